//! The character's collision shape, fitted to the same outer box as the sweep's AABB so every
//! backend moves the same footprint. The sweep always moves the box; Rapier moves any of these;
//! metrics use the shape to measure overlap with the level.

use glam::Vec2;
use parry2d::math::Pose;
use parry2d::shape::SharedShape;

/// A character's collision shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CharacterShape {
    /// A cuboid with the character's width and height: the same box as the sweep's AABB.
    Cuboid,
    /// A vertical capsule: radius half the width, segment so that the outer height matches.
    /// A character narrower than tall becomes a ball of radius half the width.
    Capsule,
    /// A ball of radius half the character's height (Rapier's own ground-detection test uses
    /// a ball); it is as wide as it is tall.
    Ball,
    /// A cuboid with rounded corners: the same outer box, with a border radius of
    /// `border_fraction` times the width (the reference figures use 1/16: 0.05 on 0.8).
    RoundCuboid {
        /// Border radius as a fraction of the character's width (dimensionless, 0..0.5).
        border_fraction: f32,
    },
}

impl CharacterShape {
    /// The round cuboid of the reference measurements: border 1/16 of the width.
    pub const ROUND_CUBOID: CharacterShape = CharacterShape::RoundCuboid {
        border_fraction: 1.0 / 16.0,
    };

    /// Every shape a Rapier user would pick, in table order.
    pub const ALL: [CharacterShape; 4] = [
        CharacterShape::Capsule,
        CharacterShape::Cuboid,
        CharacterShape::Ball,
        CharacterShape::ROUND_CUBOID,
    ];

    /// Label used in configs and CSV files (`round-cuboid` for the default border).
    pub fn label(self) -> String {
        match self {
            CharacterShape::Cuboid => "cuboid".into(),
            CharacterShape::Capsule => "capsule".into(),
            CharacterShape::Ball => "ball".into(),
            CharacterShape::RoundCuboid { border_fraction } => {
                if self == Self::ROUND_CUBOID {
                    "round-cuboid".into()
                } else {
                    format!("round-cuboid{border_fraction}")
                }
            }
        }
    }

    /// The shape a label of [`CharacterShape::label`] names (default border for the round
    /// cuboid), if any.
    pub fn from_label(label: &str) -> Option<CharacterShape> {
        Self::ALL.into_iter().find(|s| s.label() == label)
    }

    /// The pose of the shape's centre for a character whose feet (bottom centre) are at `feet`.
    pub fn pose(feet: Vec2, size: Vec2) -> Pose {
        Pose::from_translation(feet + Vec2::new(0.0, size.y * 0.5))
    }

    /// The dimensions of the shape for a character of outer `size` (tiles), from which every
    /// engine builds it in its own precision.
    pub fn params(self, size: Vec2) -> ShapeParams {
        let half = size * 0.5;
        match self {
            CharacterShape::Cuboid => ShapeParams::Cuboid { half },
            CharacterShape::Capsule => {
                let r = half.x.min(half.y);
                ShapeParams::Capsule {
                    half_segment: half.y - r,
                    radius: r,
                }
            }
            CharacterShape::Ball => ShapeParams::Ball { radius: half.y },
            CharacterShape::RoundCuboid { border_fraction } => {
                let b = (border_fraction * size.x).clamp(0.0, half.x.min(half.y));
                ShapeParams::RoundCuboid {
                    half: half - Vec2::splat(b),
                    border: b,
                }
            }
        }
    }

    /// The parry shape for a character of outer `size`, centred on its local origin.
    pub fn build(self, size: Vec2) -> SharedShape {
        match self.params(size) {
            ShapeParams::Cuboid { half } => SharedShape::cuboid(half.x, half.y),
            ShapeParams::Capsule {
                half_segment,
                radius,
            } => SharedShape::capsule_y(half_segment, radius),
            ShapeParams::Ball { radius } => SharedShape::ball(radius),
            ShapeParams::RoundCuboid { half, border } => {
                SharedShape::round_cuboid(half.x, half.y, border)
            }
        }
    }
}

/// A character shape's dimensions, in tiles, centred on its local origin
/// ([`CharacterShape::params`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeParams {
    /// A box of half extents `half`.
    Cuboid {
        /// Half width and half height.
        half: Vec2,
    },
    /// A vertical capsule: a segment of half length `half_segment` swept by a ball of `radius`.
    Capsule {
        /// Half the segment's length.
        half_segment: f32,
        /// The radius.
        radius: f32,
    },
    /// A ball.
    Ball {
        /// The radius.
        radius: f32,
    },
    /// A box of half extents `half` with a border of radius `border` around it.
    RoundCuboid {
        /// Half extents of the inner box.
        half: Vec2,
        /// Border radius.
        border: f32,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shape_fits_the_outer_box() {
        let size = Vec2::new(0.8, 0.9);
        for s in [
            CharacterShape::Cuboid,
            CharacterShape::Capsule,
            CharacterShape::RoundCuboid {
                border_fraction: 1.0 / 16.0,
            },
        ] {
            let aabb = s.build(size).compute_aabb(&Pose::IDENTITY);
            assert!(
                (aabb.extents() - size).abs().max_element() < 1e-6,
                "{s:?}: {aabb:?}"
            );
        }
        let ball = CharacterShape::Ball
            .build(size)
            .compute_aabb(&Pose::IDENTITY);
        assert!((ball.extents().y - 0.9).abs() < 1e-6);
    }
}
