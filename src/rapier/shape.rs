//! The character's collision shape for Rapier, fitted to the same outer box as the sweep
//! character so both backends move the same footprint.

use glam::Vec2;
use rapier2d::prelude::SharedShape;

/// The shape Rapier's controller moves.
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
    /// Label used in configs and CSV files.
    pub fn label(self) -> String {
        match self {
            CharacterShape::Cuboid => "cuboid".into(),
            CharacterShape::Capsule => "capsule".into(),
            CharacterShape::Ball => "ball".into(),
            CharacterShape::RoundCuboid { border_fraction } => {
                format!("round-cuboid{border_fraction}")
            }
        }
    }

    /// The rapier shape for a character of outer `size`, centred on its local origin.
    pub fn build(self, size: Vec2) -> SharedShape {
        let half = size * 0.5;
        match self {
            CharacterShape::Cuboid => SharedShape::cuboid(half.x, half.y),
            CharacterShape::Capsule => {
                let r = half.x.min(half.y);
                SharedShape::capsule_y(half.y - r, r)
            }
            CharacterShape::Ball => SharedShape::ball(half.y),
            CharacterShape::RoundCuboid { border_fraction } => {
                let b = (border_fraction * size.x).clamp(0.0, half.x.min(half.y));
                SharedShape::round_cuboid(half.x - b, half.y - b, b)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier2d::prelude::Pose;

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
