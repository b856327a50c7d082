//! Rapier as a kind of backend: what the harness needs to know of it (its name, shapes,
//! declared offset, features, built-in configurations and its `platbench sweep` grid), on the
//! public API of [`RapierBackend`] and [`RapierConfig`] only.

use std::rc::Rc;

use glam::Vec2;

use super::{CharacterShape, ColliderBuilding, RapierBackend, RapierConfig, StaticWorld};
use crate::backend::{
    BackendError, Capabilities, CharacterId, CharacterState, DeclaredContact, Precision,
};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::controller::{Controller, Setup};
use crate::level::Features;
use crate::motion::Input;

/// The backend's name, as in CSV files.
pub const NAME: &str = "rapier";

/// Rapier built over a level in the configuration's precision: rapier2d (f32) or rapier2d-f64.
pub enum RapierMover {
    /// On rapier2d and parry2d.
    F32(RapierBackend),
    /// On rapier2d-f64 and parry2d-f64.
    F64(super::double::RapierBackend),
}

impl Controller for RapierConfig {
    type Mover = RapierMover;
    const NAME: &'static str = NAME;

    fn shape(&self) -> CharacterShape {
        self.shape
    }

    fn features(&self) -> Features {
        RapierBackend::SUPPORTED
    }

    /// The gap of its `offset`.
    fn declared_contact(&self, size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        DeclaredContact {
            gap: self.offset.eval(size.y),
            // Rapier adds its normal nudge along the contact normal after each cast hit, so a
            // rest settles at the offset or up to one nudge further out.
            gap_tolerance: self.normal_nudge_factor,
            ..DeclaredContact::default()
        }
    }

    /// 1% of the character's height, Rapier's default offset.
    fn contact_tolerance(&self, size: Vec2) -> f64 {
        0.01 * size.y as f64
    }

    fn precision(&self) -> Precision {
        self.precision
    }

    /// Rapier's character controller pushes the dynamic bodies it hits
    /// (`KinematicCharacterController::solve_character_collision_impulses`, in its character
    /// controller guide). Rapier is deterministic only on one machine unless built with its
    /// `enhanced-determinism` feature (rapier.rs, "Determinism"), which this build does not
    /// enable.
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            pushes_bodies: true,
            ..Capabilities::default()
        }
    }

    /// Every Rapier configuration has a build in both precisions.
    fn with_precision(&self, precision: Precision) -> Option<RapierConfig> {
        Some(RapierConfig {
            precision,
            ..self.clone()
        })
    }

    /// Builds over the level's colliders for `self.colliders` in `self.precision`, built once
    /// per level, collider building and precision whatever the character shape.
    fn build(&self, setup: Setup<'_>) -> Result<RapierMover, BackendError> {
        let Setup {
            level,
            params,
            characters,
            shared,
        } = setup;
        let key = format!("{NAME}:{}", self.colliders.label());
        Ok(match self.precision {
            Precision::F32 => {
                let world: Rc<StaticWorld> =
                    shared.get_or_build(&key, || StaticWorld::new(level, self.colliders));
                let mut r = RapierBackend::with_world(level, world, params.clone(), self.clone())?;
                for c in characters {
                    r.add_character(*c)?;
                }
                RapierMover::F32(r)
            }
            Precision::F64 => {
                use super::double;
                let world: Rc<double::StaticWorld> = shared
                    .get_or_build(&format!("{key}:f64"), || {
                        double::StaticWorld::new(level, self.colliders)
                    });
                let mut r =
                    double::RapierBackend::with_world(level, world, params.clone(), self.clone())?;
                for c in characters {
                    r.add_character(*c)?;
                }
                RapierMover::F64(r)
            }
        })
    }

    fn step(&self, mover: &mut RapierMover, inputs: &[Input], dt: f32) {
        match mover {
            RapierMover::F32(r) => r.step(inputs, dt),
            RapierMover::F64(r) => r.step(inputs, dt),
        }
    }

    fn state(&self, mover: &RapierMover, id: CharacterId) -> CharacterState {
        match mover {
            RapierMover::F32(r) => r.state(id),
            RapierMover::F64(r) => r.state(id),
        }
    }

    fn description() -> &'static str {
        "rapier2d's KinematicCharacterController, set up as Rapier's docs and examples advise"
    }

    fn shapes() -> Vec<CharacterShape> {
        CharacterShape::ALL.to_vec()
    }

    fn configs() -> Vec<RunConfig> {
        super::presets::configs()
    }

    fn stress_configs() -> Vec<RunConfig> {
        super::presets::stress_configs()
    }

    fn tradeoff_settings() -> Vec<Setting> {
        super::presets::tradeoff_settings()
    }

    fn drawn() -> Vec<(&'static str, &'static str)> {
        vec![
            ("per-tile capsule", "#2e7d32"),
            ("merged capsule", "#9e9d24"),
            ("per-tile cuboid", "#c62828"),
            ("merged cuboid", "#ef6c00"),
        ]
    }

    fn colour() -> Option<&'static str> {
        Some("#2e7d32")
    }
}

/// Rapier with its default settings, the given collider building and character shape.
pub fn run(colliders: ColliderBuilding, shape: CharacterShape) -> RunConfig {
    run_with(RapierConfig {
        colliders,
        shape,
        ..Default::default()
    })
}

/// Rapier with `config`, labelled by [`RapierConfig::label`].
pub fn run_with(config: RapierConfig) -> RunConfig {
    RunConfig::new(config.label(), config)
}
