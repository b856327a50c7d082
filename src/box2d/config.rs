//! The Box2D backend's settings: the sample's mover with its values as defaults (collider
//! building, the pogo spring and shape, the solve loop), their ranges, and the capsule a
//! character's box becomes.

use glam::Vec2;

use crate::backend::{invalid, BackendError};

use super::{CharacterShape, ColliderBuilding};

/// The sample's capsule radius, in metres (one tile is one metre, docs/box2d.md): its capsule
/// `{ { 0.0f, -0.5f }, { 0.0f, 0.5f }, 0.3f }` (`samples/sample_character.cpp`, the same in
/// Box2D 56edae79 and in the later geometric mover).
pub const SAMPLE_CAPSULE_RADIUS: f32 = 0.3;

/// The sample's capsule segment, between its two centres, in metres (the capsule above).
pub const SAMPLE_CAPSULE_SEGMENT: f32 = 1.0;

/// The height of the sample's mover, in metres: its pogo's rest length of 3 capsule radii holds
/// the lower centre 0.9 above the feet (`leg_fraction`'s source), the segment and a radius
/// stand on it: `3 r + segment + r` = 2.2.
pub const SAMPLE_HEIGHT: f32 =
    3.0 * SAMPLE_CAPSULE_RADIUS + SAMPLE_CAPSULE_SEGMENT + SAMPLE_CAPSULE_RADIUS;

/// The shape the pogo casts down, as the sample offers them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PogoShape {
    /// A ray from the capsule's lower centre.
    Point,
    /// A circle of half the capsule's radius.
    Circle,
    /// A horizontal segment 1.5 capsule radii wide: the sample's default.
    Segment,
}

/// How the mover is carried by the ground its pogo stands on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroundCarry {
    /// Not carried: the sample's mover. Its ground moves it only through the collision planes
    /// (a push of at most `platform_push_limit` per solve) and the pogo's spring, so a
    /// horizontal platform slides out from under it.
    None,
    /// The user-side carry Box2D's docs leave to the game (the mover is "a few structures and
    /// functions you can use to build a character mover", docs/character.md): while grounded,
    /// the displacement for the step of the body the pogo hit (`b2Body_GetLinearVelocity`
    /// times the step, after the world step that moved it) is added to the mover's target.
    Ground,
}

impl GroundCarry {
    /// `none` or `ground`, as in configuration labels (`carry=ground`).
    pub fn label(self) -> &'static str {
        match self {
            GroundCarry::None => "none",
            GroundCarry::Ground => "ground",
        }
    }
}

/// Settings of the Box2D backend: the sample's mover, with the sample's values as defaults.
#[derive(Clone, Debug, PartialEq)]
pub struct Box2dConfig {
    /// How solid tiles become shapes: one box per tile, or merged rectangles as chain loops
    /// (Box2D's docs: chain shapes "provide an efficient way to connect many line segments
    /// together to construct your static game worlds").
    pub colliders: ColliderBuilding,
    /// The character's shape; only [`CharacterShape::Capsule`] (Box2D's docs: "The mover is
    /// assumed to be a capsule"); any other is refused with `Unsupported`.
    pub shape: CharacterShape,
    /// Fraction of the character's height under the capsule, spanned by the pogo leg
    /// (dimensionless). Default 3/11: the sample's capsule (radius 0.3, segment 1.0) rests
    /// 0.6 above the ground on a pogo of rest length 3 radii, 0.6 of its 2.2 total height.
    pub leg_fraction: f32,
    /// The pogo spring's frequency, in Hz (the sample's `m_pogoHertz`, 5).
    pub pogo_hertz: f32,
    /// The pogo spring's damping ratio (dimensionless; the sample's `m_pogoDampingRatio`, 0.8).
    pub pogo_damping_ratio: f32,
    /// The shape the pogo casts (the sample's default: a segment).
    pub pogo_shape: PogoShape,
    /// Vertical speed (tiles/s) at or below which an airborne character whose pogo touches
    /// ground lands: the sample's "avoid snapping to ground if still going up", 0.01.
    pub land_speed: f32,
    /// Most collide-solve-cast rounds per step (the sample's loop: 5).
    pub max_iterations: u32,
    /// A round that moves less than this ends the loop, in tiles (the sample's `tolerance`,
    /// 0.01).
    pub tolerance: f32,
    /// How far a moving platform's collision plane may push the capsule per solve, in tiles:
    /// the sample's elevator `maxPush`, 0.1 ("an elevator that could otherwise push the mover
    /// through the floor", Box2D's docs). Level tiles are rigid (`f32::MAX`).
    pub platform_push_limit: f32,
    /// Whether the ground the pogo stands on carries the mover ([`GroundCarry`]). Default
    /// [`GroundCarry::None`]: neither revision of the sample carries a rider (56edae79's
    /// elevator moves only vertically and it reads the hit body only to push it down).
    pub carry: GroundCarry,
}

impl Default for Box2dConfig {
    fn default() -> Self {
        Box2dConfig {
            colliders: ColliderBuilding::PerTile,
            shape: CharacterShape::Capsule,
            leg_fraction: 3.0 / 11.0,
            pogo_hertz: 5.0,
            pogo_damping_ratio: 0.8,
            pogo_shape: PogoShape::Segment,
            land_speed: 0.01,
            max_iterations: 5,
            tolerance: 0.01,
            platform_push_limit: 0.1,
            carry: GroundCarry::None,
        }
    }
}

impl Box2dConfig {
    /// Short label for tables and file names: the collider building and the shape, then
    /// `carry=ground` and `pogo=<f>Hz` where they differ from the sample's.
    pub fn label(&self) -> String {
        let mut label = format!("{} {}", self.colliders.label(), self.shape.label());
        if self.carry != GroundCarry::None {
            label += " carry=";
            label += self.carry.label();
        }
        if self.pogo_hertz != Box2dConfig::default().pogo_hertz {
            // Whole hertz as the trade-off grid writes them (`pogo=20Hz`), else one decimal.
            let hz = self.pogo_hertz;
            label += &if hz.fract() == 0.0 {
                format!(" pogo={hz}Hz")
            } else {
                format!(" pogo={hz:.1}Hz")
            };
        }
        label
    }

    /// The sample's pogo frequency scaled to a character `height` tiles tall, in Hz: under the
    /// same gravity a dynamically similar spring scales its time by the square root of the
    /// length ratio, so its frequency by `sqrt(SAMPLE_HEIGHT / height)` ([`SAMPLE_HEIGHT`]);
    /// 7.82 Hz for the built-in 0.9-tile character.
    pub fn scaled_pogo_hertz(height: f32) -> f32 {
        Box2dConfig::default().pogo_hertz * (SAMPLE_HEIGHT / height).sqrt()
    }

    /// Checks every field's range.
    pub fn validate(&self) -> Result<(), BackendError> {
        if !(self.leg_fraction >= 0.0 && self.leg_fraction < 1.0) {
            return Err(invalid("leg_fraction", self.leg_fraction, "0 <= f < 1"));
        }
        if !(self.pogo_hertz.is_finite() && self.pogo_hertz >= 0.0) {
            return Err(invalid("pogo_hertz", self.pogo_hertz, "finite, >= 0 (Hz)"));
        }
        if !(self.pogo_damping_ratio.is_finite() && self.pogo_damping_ratio >= 0.0) {
            return Err(invalid(
                "pogo_damping_ratio",
                self.pogo_damping_ratio,
                "finite, >= 0",
            ));
        }
        if !self.land_speed.is_finite() {
            return Err(invalid("land_speed", self.land_speed, "finite (tiles/s)"));
        }
        if self.max_iterations == 0 {
            return Err(invalid("max_iterations", self.max_iterations, ">= 1"));
        }
        if !(self.tolerance.is_finite() && self.tolerance >= 0.0) {
            return Err(invalid("tolerance", self.tolerance, "finite, >= 0 (tiles)"));
        }
        if self.platform_push_limit.is_nan() || self.platform_push_limit < 0.0 {
            return Err(invalid(
                "platform_push_limit",
                self.platform_push_limit,
                ">= 0 (tiles)",
            ));
        }
        Ok(())
    }

    /// The capsule for a character of outer `size`: `(radius, lower centre height, upper
    /// centre height)` above the feet, in tiles. The capsule fills the box above the leg, as
    /// wide as the box where its height allows (else a circle as wide as it is tall).
    pub fn capsule(&self, size: Vec2) -> (f32, f32, f32) {
        let leg = self.leg_fraction * size.y;
        let body = size.y - leg;
        let r = (0.5 * size.x).min(0.5 * body);
        (r, leg + r, size.y - r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn capsule_fills_the_box_above_the_leg() {
        let c = Box2dConfig::default();
        // A 0.8 x 2.2 box: the leg is 3/11 of 2.2 = 0.6, the capsule radius half the width.
        let (r, c1, c2) = c.capsule(Vec2::new(0.8, 2.2));
        assert!((r - 0.4).abs() < 1e-6);
        assert!((c1 - 1.0).abs() < 1e-6);
        assert!((c2 - 1.8).abs() < 1e-6);
    }
}
