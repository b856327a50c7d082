//! Moving platforms for the Rapier backend: kinematic position-based bodies, moved to the shared
//! platform motion's next position with `set_next_kinematic_translation` and one physics step
//! each frame after the characters have moved (the same order as the sweep). The step integrates
//! only these kinematic bodies (the levels have no dynamic body) and updates the broad phase;
//! it also gives each body the velocity Rapier's character controller reads to carry riders.

use glam::Vec2;
use rapier2d::prelude::{
    CCDSolver, ColliderBuilder, ImpulseJointSet, IntegrationParameters, IslandManager,
    MultibodyJointSet, NarrowPhase, PhysicsPipeline, RigidBodyBuilder, RigidBodyHandle,
    SoftBodySet,
};

use super::colliders::{StaticWorld, ONE_WAY};
use crate::level::{Level, Platform};

/// How a rider is carried by a moving platform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlatformCarry {
    /// What Rapier's controller does by itself: it adds the velocity of the kinematic body it
    /// stands on to the move (its kinematic friction). The reference measured this to carry a
    /// horizontal rider exactly.
    Controller,
    /// The controller's carry plus the platform's displacement added to the desired
    /// translation when grounded on it, as Rapier users often bolt on. The reference measured it
    /// to over-carry (1.35x horizontally) and to sink into a descending elevator.
    ControllerPlusDisplacement,
}

/// The platforms' bodies and the pipeline that moves them.
pub struct Platforms {
    specs: Vec<Platform>,
    origin: Vec2,
    /// One kinematic body per platform, in the level's order.
    pub bodies: Vec<RigidBodyHandle>,
    pipeline: PhysicsPipeline,
    params: IntegrationParameters,
    islands: IslandManager,
    narrow_phase: NarrowPhase,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
}

impl Platforms {
    /// Adds the level's platforms to `world` as kinematic bodies at their t = 0 place.
    pub fn new(level: &Level, world: &mut StaticWorld) -> Self {
        let mut bodies = Vec::with_capacity(level.platforms.len());
        for p in &level.platforms {
            let b = p.aabb(0.0).translated(level.origin);
            let body = world.bodies.insert(
                RigidBodyBuilder::kinematic_position_based()
                    .translation(b.center())
                    .build(),
            );
            let half = b.half_extents();
            let mut collider = ColliderBuilder::cuboid(half.x, half.y);
            if p.one_way {
                collider = collider.user_data(ONE_WAY);
            }
            world
                .colliders
                .insert_with_parent(collider.build(), body, &mut world.bodies);
            bodies.push(body);
        }
        let mut platforms = Platforms {
            specs: level.platforms.clone(),
            origin: level.origin,
            bodies,
            pipeline: PhysicsPipeline::new(),
            params: IntegrationParameters::default(),
            islands: IslandManager::new(),
            narrow_phase: NarrowPhase::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
        };
        // One step at dt = 0 puts the new colliders in the broad phase where they stand.
        platforms.step_to(world, 0.0, 0.0);
        platforms
    }

    /// Centre of platform `i` at time `t`, in the world.
    fn center(&self, i: usize, t: f64) -> Vec2 {
        self.specs[i].aabb(t).translated(self.origin).center()
    }

    /// Platform `i`'s displacement from `t0` to `t1`.
    pub fn displacement(&self, i: usize, t0: f64, t1: f64) -> Vec2 {
        self.center(i, t1) - self.center(i, t0)
    }

    /// Moves every platform to its place at `t1` over one step of `dt`.
    pub fn step_to(&mut self, world: &mut StaticWorld, t1: f64, dt: f32) {
        for (i, h) in self.bodies.iter().enumerate() {
            let c = self.center(i, t1);
            if let Some(b) = world.bodies.get_mut(*h) {
                b.set_next_kinematic_translation(c);
            }
        }
        self.params.dt = dt;
        self.pipeline.step(
            Vec2::ZERO,
            &self.params,
            &mut self.islands,
            &mut world.broad_phase,
            &mut self.narrow_phase,
            &mut world.bodies,
            &mut world.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            &(),
            &(),
        );
    }
}
