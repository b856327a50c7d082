//! The level's static geometry as rapier2d colliders, in a `ColliderSet` kept in rapier's
//! `BroadPhaseBvh`. Compiled once per precision (`super::precision`): on rapier2d for
//! [`crate::rapier`], on rapier2d-f64 for [`crate::rapier::double`].

use super::precision::{engine, level_origin, top_bits, top_from_bits, v, Real, Vect};
use engine::prelude::{
    BroadPhaseBvh, Collider, ColliderBuilder, ColliderHandle, ColliderSet, IntegrationParameters,
    RigidBodySet,
};

pub use crate::level::outlines::ColliderBuilding;
use crate::level::outlines::{one_way_rects, slope_outlines, solid_rects};
use crate::level::Level;
use parry2d::bounding_volume::Aabb;

/// The level's static colliders and the broad phase that holds them. Built once per level and
/// collider building, and shared by every character shape and scenario run on it.
#[derive(Clone)]
pub struct StaticWorld {
    /// Empty: static colliders are parentless, and no rigid body is simulated.
    pub bodies: RigidBodySet,
    /// One cuboid collider per tile or per merged rectangle.
    pub colliders: ColliderSet,
    /// rapier's BVH broad phase, updated once after insertion so queries see every collider.
    pub broad_phase: BroadPhaseBvh,
}

impl StaticWorld {
    /// Builds the colliders for `level` and runs one broad-phase update, which is what makes
    /// them visible to queries (before it the broad phase is empty and a character falls
    /// through the floor). The level's corner is placed at `level.origin` in Rapier's world.
    pub fn new(level: &Level, building: ColliderBuilding) -> Self {
        let origin = level_origin(level);
        let mut colliders = ColliderSet::new();
        let mut handles: Vec<ColliderHandle> = solid_boxes(level, building)
            .map(|r| {
                let half = v(r.half_extents());
                colliders.insert(
                    ColliderBuilder::cuboid(half.x, half.y)
                        .translation(v(r.center()) + origin)
                        .build(),
                )
            })
            .collect();
        for r in one_way_rects(level, building) {
            let half = v(r.half_extents());
            let top = v(r.maxs).y + origin.y;
            handles.push(
                colliders.insert(
                    ColliderBuilder::cuboid(half.x, half.y)
                        .translation(v(r.center()) + origin)
                        .user_data(one_way_tag(top))
                        .build(),
                ),
            );
        }
        for points in slope_outlines(level, building) {
            let pts: Vec<Vect> = points.iter().map(|p| v(*p) + origin).collect();
            let builder = match building {
                // A line slope's tile: its convex polygon.
                ColliderBuilding::PerTile if pts.len() <= 5 => ColliderBuilder::convex_hull(&pts),
                _ => None,
            }
            .unwrap_or_else(|| ColliderBuilder::polyline(pts, None));
            handles.push(colliders.insert(builder.build()));
        }
        let mut world = StaticWorld {
            bodies: RigidBodySet::new(),
            colliders,
            broad_phase: BroadPhaseBvh::new(),
        };
        world.update_broad_phase(&handles);
        world
    }

    /// Inserts a static collider and makes it visible to queries.
    pub fn insert(&mut self, collider: Collider) -> ColliderHandle {
        let h = self.colliders.insert(collider);
        self.update_broad_phase(&[h]);
        h
    }

    /// Runs rapier's broad-phase update for the given new or modified colliders.
    fn update_broad_phase(&mut self, modified: &[ColliderHandle]) {
        let mut events = Vec::new();
        self.broad_phase.update(
            &IntegrationParameters::default(),
            &self.colliders,
            &self.bodies,
            modified,
            &[],
            &mut events,
        );
    }
}

/// The level's solid boxes as [`solid_rects`] gives them, in its order, without collecting a
/// per-tile world's boxes first (16 bytes a tile held beside the colliders while they are
/// built).
fn solid_boxes(level: &Level, building: ColliderBuilding) -> Box<dyn Iterator<Item = Aabb> + '_> {
    match building {
        ColliderBuilding::PerTile => Box::new(level.solid_boxes()),
        ColliderBuilding::Merged => Box::new(solid_rects(level, building).into_iter()),
    }
}

/// `user_data` bit marking a one-way collider; the low 32 bits (64 in f64) hold its top (world
/// y, the bits of the float).
pub const ONE_WAY: u128 = 1 << 64;

/// The `user_data` of a one-way collider whose top is at world height `top`.
pub(crate) fn one_way_tag(top: Real) -> u128 {
    ONE_WAY | top_bits(top)
}

/// The top of a one-way collider (world y), or `None` for any other collider. Moving one-way
/// platforms carry only the flag; their top is read from where the collider is.
pub fn one_way_top(collider: &Collider) -> Option<Real> {
    let data = collider.user_data;
    if data & ONE_WAY == 0 {
        None
    } else if collider.parent().is_some() {
        Some(collider.compute_aabb().maxs.y)
    } else {
        Some(top_from_bits(data))
    }
}
