//! Moving platforms for the Rapier backend: kinematic position-based bodies, moved to the shared
//! platform motion's next position with `set_next_kinematic_translation` and one physics step
//! each frame after the characters have moved (the same order as the sweep). The step integrates
//! only these kinematic bodies (the levels have no dynamic body) and updates the broad phase;
//! it also gives each body the velocity Rapier's character controller reads to carry riders.
//! Compiled once per precision (`super::precision`).

use super::precision::{engine, level_origin, s, v, Vect};
use engine::prelude::{
    CCDSolver, ColliderBuilder, ImpulseJointSet, IntegrationParameters, IslandManager,
    MultibodyJointSet, NarrowPhase, PhysicsPipeline, RigidBodyBuilder, RigidBodyHandle,
    SoftBodySet,
};

use super::colliders::{StaticWorld, ONE_WAY};
use crate::level::{Level, Platform};

/// The platforms' bodies and the pipeline that moves them.
pub struct Platforms {
    specs: Vec<Platform>,
    origin: Vect,
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
            let b = p.aabb(0.0);
            let (mins, maxs) = (
                v(b.mins) + level_origin(level),
                v(b.maxs) + level_origin(level),
            );
            let body = world.bodies.insert(
                RigidBodyBuilder::kinematic_position_based()
                    .translation(mins.midpoint(maxs))
                    .build(),
            );
            let half = (maxs - mins) * 0.5;
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
            origin: level_origin(level),
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
    fn center(&self, i: usize, t: f64) -> Vect {
        let b = self.specs[i].aabb(t);
        (v(b.mins) + self.origin).midpoint(v(b.maxs) + self.origin)
    }

    /// Platform `i`'s displacement from `t0` to `t1`.
    pub fn displacement(&self, i: usize, t0: f64, t1: f64) -> Vect {
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
        self.params.dt = s(dt);
        self.pipeline.step(
            Vect::ZERO,
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
