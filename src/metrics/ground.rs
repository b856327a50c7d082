//! Where the ground is under a character, for every shape: how far the shape can drop before it
//! touches the level's geometry (solid tiles as squares, slope tiles as their solid part, and
//! one-way platforms and ladder tops for a shape above them). Used
//! by the metrics that ask whether a character stands on something and how far above it.
//!
//! The sweep stands the centre of its box on a slope and lets the box overhang the ground by up
//! to half its width times the climb gradient (the seed's model); an overlap with a ramp (a
//! slope tile's solid part, a solid tile carrying a slope, or a solid whose top is within that
//! overhang above the slope under the centre) therefore reads as touching (gap 0), while an
//! overlap with any other solid tile reads as sinking (negative gap, its depth).

use std::collections::HashMap;

use glam::Vec2;
use parry2d::math::Pose;
use parry2d::query::{cast_shapes, contact, ShapeCastOptions};
use parry2d::shape::{Cuboid, SharedShape};

use crate::level::{character_box, Level, Slope, Tile};
use crate::shape::CharacterShape;

/// How far below the feet the ground is looked for, in tiles.
pub const GROUND_SEARCH: f32 = 2.0;

/// The level's ground geometry for one character shape.
pub struct Ground<'a> {
    level: &'a Level,
    shape: SharedShape,
    size: Vec2,
    slopes: HashMap<(i64, i64), SharedShape>,
    tile: Cuboid,
    /// How far a box standing on a slope overhangs the ground: half its width times the
    /// climb gradient.
    overhang: f32,
}

/// A slope tile's solid part as a parry shape, in tile-local coordinates: the convex polygon
/// under a line, or for a height array the seed's 16 columns exactly.
fn slope_shape(s: &Slope) -> Option<SharedShape> {
    match s {
        Slope::Line { .. } => {
            // A line that never rises above the tile's bottom leaves no solid part.
            let outline = s.outline();
            (outline.len() >= 3)
                .then(|| SharedShape::convex_hull(&outline))
                .flatten()
        }
        Slope::Heights(h) => {
            let parts: Vec<(Pose, SharedShape)> = h
                .iter()
                .enumerate()
                .filter(|(_, v)| **v > 0)
                .map(|(i, v)| {
                    let (w, ht) = (1.0 / 16.0, *v as f32 / 16.0);
                    (
                        Pose::from_translation(Vec2::new((i as f32 + 0.5) * w, ht * 0.5)),
                        SharedShape::cuboid(w * 0.5, ht * 0.5),
                    )
                })
                .collect();
            (!parts.is_empty()).then(|| SharedShape::compound(parts))
        }
    }
}

impl<'a> Ground<'a> {
    /// The ground of `level` for a character of `shape` and outer `size`.
    pub fn new(level: &'a Level, shape: CharacterShape, size: Vec2, max_climb_angle: f32) -> Self {
        let slopes = level
            .slopes()
            .filter_map(|(i, j, s)| slope_shape(&s).map(|sh| ((i, j), sh)))
            .collect();
        Ground {
            level,
            shape: shape.build(size),
            size,
            slopes,
            tile: Cuboid::new(Vec2::splat(0.5)),
            overhang: size.x * 0.5 * max_climb_angle.tan(),
        }
    }

    /// Deepest overlap of the shape with a solid tile that carries no slope, in tiles (0 if
    /// none).
    pub fn solid_penetration(&self, feet: Vec2) -> f32 {
        let pose = CharacterShape::pose(feet, self.size);
        let slope_under = self
            .level
            .surface_at(feet.x, feet.y + self.overhang, self.overhang + 1.0)
            .and_then(|(h, slope)| slope.map(|_| h));
        self.level
            .solids_overlapping(&character_box(feet, self.size))
            .filter(|t| !self.level.supports_slope(t.mins.x as i64, t.mins.y as i64))
            .filter(|t| !slope_under.is_some_and(|h| t.maxs.y <= h + self.overhang + 1e-3))
            .map(|t| {
                let tile_pose = Pose::from_translation(t.center());
                match contact(&pose, &*self.shape, &tile_pose, &self.tile, 0.0) {
                    Ok(Some(c)) if c.dist < 0.0 => -c.dist,
                    _ => 0.0,
                }
            })
            .fold(0.0, f32::max)
    }

    /// Signed gap from the shape down to the ground at time `t` (moving platforms included), in
    /// tiles: the distance it can drop before touching (0 when touching or resting its corners in
    /// a slope), minus the depth it has sunk into a solid tile. Infinite if no ground is within
    /// [`GROUND_SEARCH`].
    pub fn gap_at(&self, feet: Vec2, t: f64) -> f32 {
        let mut best = self.gap(feet);
        if best <= 0.0 {
            return best;
        }
        let pose = CharacterShape::pose(feet, self.size);
        let half = self.size.x * 0.5;
        for p in &self.level.platforms {
            let b = p.aabb(t);
            // Under the shape: its top at most half the character's height above the feet (a
            // rider that sank into it stands on it; one whose middle it reaches is beside it).
            let top_limit = feet.y + self.size.y * 0.5;
            if b.maxs.x <= feet.x - half || b.mins.x >= feet.x + half || b.maxs.y > top_limit {
                continue;
            }
            let half_extents = b.half_extents();
            let options = ShapeCastOptions::with_max_time_of_impact(GROUND_SEARCH);
            if let Ok(Some(hit)) = cast_shapes(
                &pose,
                Vec2::NEG_Y,
                &*self.shape,
                &Pose::from_translation(b.center()),
                Vec2::ZERO,
                &Cuboid::new(half_extents),
                options,
            ) {
                best = best.min(hit.time_of_impact);
            }
        }
        best
    }

    /// Signed gap from the shape down to the level's static ground (see [`Ground::gap_at`]).
    pub fn gap(&self, feet: Vec2) -> f32 {
        let sunk = self.solid_penetration(feet);
        if sunk > 0.0 {
            return -sunk;
        }
        let pose = CharacterShape::pose(feet, self.size);
        let half = self.size.x * 0.5;
        // Columns the shape spans (a wall touching its side is not under it), rows from mid-body
        // down to the search depth.
        let i0 = (feet.x - half + 1e-4).floor() as i64;
        let i1 = (feet.x + half - 1e-4).floor() as i64;
        let j_top = (feet.y + self.size.y * 0.5).floor() as i64;
        let j_low = (feet.y - GROUND_SEARCH).floor() as i64;
        let mut best = f32::INFINITY;
        for i in i0..=i1 {
            for j in (j_low..=j_top).rev() {
                let origin = Vec2::new(i as f32, j as f32);
                // One-way tops (platforms, ladder tops) are ground for a shape above them.
                let one_way_below = self.level.is_one_way(i, j) && feet.y >= j as f32 + 1.0 - 1e-3;
                let (tile_pose, tile_shape): (Pose, &dyn parry2d::shape::Shape) =
                    match self.level.tile(i, j) {
                        _ if one_way_below => (
                            Pose::from_translation(origin + Vec2::splat(0.5)),
                            &self.tile,
                        ),
                        Tile::Solid => (
                            Pose::from_translation(origin + Vec2::splat(0.5)),
                            &self.tile,
                        ),
                        Tile::Slope(_) => match self.slopes.get(&(i, j)) {
                            Some(s) => (Pose::from_translation(origin), &**s),
                            None => continue,
                        },
                        _ => continue,
                    };
                let options = ShapeCastOptions::with_max_time_of_impact(GROUND_SEARCH);
                if let Ok(Some(hit)) = cast_shapes(
                    &pose,
                    Vec2::NEG_Y,
                    &*self.shape,
                    &tile_pose,
                    Vec2::ZERO,
                    tile_shape,
                    options,
                ) {
                    best = best.min(hit.time_of_impact);
                }
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::parse_level;

    #[test]
    fn gap_is_shape_aware_on_floors_and_slopes() {
        let level = parse_level("map = \"\"\"\n.....\n../##\n#####\n\"\"\"\n", "g.toml").unwrap();
        let size = Vec2::new(0.8, 0.9);
        let boxy = Ground::new(
            &level,
            CharacterShape::Cuboid,
            size,
            std::f32::consts::FRAC_PI_4,
        );
        assert!((boxy.gap(Vec2::new(0.5, 1.25)) - 0.25).abs() < 1e-4);
        assert!((boxy.gap(Vec2::new(0.5, 0.97)) + 0.03).abs() < 1e-4);
        // The box's centre on the '/' surface at x = 2.5 (height 1.5): its right corner
        // overhangs the slope, which reads as touching.
        assert_eq!(boxy.gap(Vec2::new(2.5, 1.5)), 0.0);
        // A ball of radius 0.45 above the 45-degree surface rests where its bottom point is
        // r (sqrt 2 - 1) above the surface under its centre.
        let ball = Ground::new(
            &level,
            CharacterShape::Ball,
            size,
            std::f32::consts::FRAC_PI_4,
        );
        let lift = 0.45 * (2f32.sqrt() - 1.0);
        assert!(ball.gap(Vec2::new(2.5, 1.5 + lift + 0.1)) - 0.1 < 1e-3);
        assert!(boxy.gap(Vec2::new(0.5, 5.0)).is_infinite());
    }
}
