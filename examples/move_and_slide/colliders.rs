//! The level as the mover sees it: static parry2d colliders in world coordinates.

use glam::Vec2;
use parry2d::bounding_volume::Aabb;
use parry2d::math::Pose;
use parry2d::shape::SharedShape;

use platbench::level::outlines::{one_way_rects, solid_rects, ColliderBuilding};
use platbench::prelude::*;

/// A static collider of the level: its shape, where it is, and the top of a one-way platform.
pub(crate) struct Obstacle {
    pub(crate) shape: SharedShape,
    pub(crate) pose: Pose,
    pub(crate) aabb: Aabb,
    /// The top (world y) of a one-way platform; `None` for a solid.
    pub(crate) one_way_top: Option<f32>,
}

/// The level's colliders, in world coordinates: solid tiles merged into rectangles, one-way
/// tiles (and ladder tops), and each slope tile's outline (a convex polygon for a line slope, a
/// polyline for a height array).
pub struct LevelColliders {
    pub(crate) obstacles: Vec<Obstacle>,
}

impl LevelColliders {
    /// Builds the colliders of `level`.
    pub fn new(level: &Level) -> Self {
        let mut obstacles = Vec::new();
        let o = level.origin_f32();
        let mut push = |shape: SharedShape, pose: Pose, one_way_top| {
            let aabb = shape.compute_aabb(&pose);
            obstacles.push(Obstacle {
                shape,
                pose,
                aabb,
                one_way_top,
            });
        };
        for r in solid_rects(level, ColliderBuilding::Merged) {
            let half = r.half_extents();
            push(
                SharedShape::cuboid(half.x, half.y),
                Pose::from_translation(r.center() + o),
                None,
            );
        }
        // The shared one-way boxes, one per tile.
        for r in one_way_rects(level, ColliderBuilding::PerTile) {
            let half = r.half_extents();
            push(
                SharedShape::cuboid(half.x, half.y),
                Pose::from_translation(r.center() + o),
                Some(r.maxs.y + o.y),
            );
        }
        // Each slope in its tile's frame (the outline the shared outlines place in the level).
        for (i, j, slope) in level.slopes() {
            let pts: Vec<Vec2> = slope.outline();
            if pts.len() < 2 {
                continue;
            }
            let shape = SharedShape::convex_hull(&pts).filter(|_| pts.len() <= 5);
            let shape = shape.unwrap_or_else(|| SharedShape::polyline(pts, None));
            let corner = Vec2::new(i as f32, j as f32) + o;
            push(shape, Pose::from_translation(corner), None);
        }
        LevelColliders { obstacles }
    }
}
