//! The level's static geometry as rapier2d colliders, in a `ColliderSet` kept in rapier's
//! `BroadPhaseBvh`.

use rapier2d::prelude::{
    BroadPhaseBvh, Collider, ColliderBuilder, ColliderHandle, ColliderSet, IntegrationParameters,
    RigidBodySet,
};

use crate::level::Level;

/// How solid tiles become colliders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColliderBuilding {
    /// One cuboid per solid tile: what a naive tile-map import does. Every tile edge is a
    /// seam a sliding shape can catch on.
    PerTile,
    /// Adjacent solid tiles merged into rectangles (row runs grown upward): far fewer
    /// colliders and no seams inside a merged floor.
    Merged,
}

impl ColliderBuilding {
    /// Label used in configs and CSV files.
    pub fn label(self) -> &'static str {
        match self {
            ColliderBuilding::PerTile => "per-tile",
            ColliderBuilding::Merged => "merged",
        }
    }
}

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
        let rects = match building {
            ColliderBuilding::PerTile => level.solid_boxes().collect::<Vec<_>>(),
            ColliderBuilding::Merged => level.merged_solid_rects(),
        };
        let mut colliders = ColliderSet::new();
        let handles: Vec<ColliderHandle> = rects
            .iter()
            .map(|r| {
                let half = r.half_extents();
                colliders.insert(
                    ColliderBuilder::cuboid(half.x, half.y)
                        .translation(r.center() + level.origin)
                        .build(),
                )
            })
            .collect();
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
