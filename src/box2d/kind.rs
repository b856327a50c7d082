//! Box2D's mover as a kind of backend: what the harness needs to know of it (its name, shape,
//! declared contact, features, built-in configurations and its `platbench sweep` grid), on the
//! public API of [`Box2dBackend`] and [`Box2dConfig`] only.

use glam::Vec2;

use super::{Box2dBackend, Box2dConfig, CharacterShape, PogoShape, LINEAR_SLOP};
use crate::backend::{
    BackendError, Capabilities, CharacterId, CharacterSpec, CharacterState, DeclaredContact,
};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::controller::{Controller, Setup};
use crate::level::{Features, Level};
use crate::motion::{Input, MotionParams};

/// The backend's name, as in CSV files.
pub const NAME: &str = "box2d";

impl Controller for Box2dConfig {
    type Mover = Box2dBackend;
    const NAME: &'static str = NAME;

    fn shape(&self) -> CharacterShape {
        self.shape
    }

    fn features(&self) -> Features {
        Box2dBackend::SUPPORTED
    }

    /// Box2D v3 promises cross-platform determinism (its v3.1 release notes; the docs'
    /// "Determinism" section). The mover pushes nothing: it "is not a rigid body and does not
    /// exist in the simulation world" (docs/character.md); pushing is left to the game.
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            cross_platform_determinism: true,
            no_rider_carry: self.carry == super::GroundCarry::None,
            no_climb_limit: true,
            ..Capabilities::default()
        }
    }

    /// The sample's capsule (the only shape it offers), on a level within
    /// [`super::MAX_LEVEL_EXTENT`] tiles on a side.
    fn check_level(&self, level: &Level) -> Result<(), BackendError> {
        if self.shape != CharacterShape::Capsule {
            return Err(BackendError::Unsupported {
                backend: NAME,
                feature: format!(
                    "a {} character (the sample's mover is a capsule, the only shape it offers)",
                    self.shape.label()
                ),
                level: level.name.clone(),
                beyond_bound: false,
            });
        }
        super::check_extent(level)
    }

    /// A capsule radius over twice Box2D's linear slop ([`super::check_radius`]).
    fn check_character(&self, character: &CharacterSpec) -> Result<(), BackendError> {
        super::check_radius(self, character.size)
    }

    /// The pogo at its rest length: the feet one linear slop off the ground (the pogo's cast
    /// stops that short of a surface, and `b2SolvePlanes` keeps the capsule that far off every
    /// plane: "add slop to prevent jitter"). The sample's default pogo is a segment 0.75
    /// capsule radius either side of the feet, which stands on its uphill end on a ramp; a
    /// point stands at the centre, and a circle's stance on a ramp is not modelled (declared
    /// flat).
    fn declared_contact(&self, size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        let stance_half_width = match self.pogo_shape {
            PogoShape::Segment => 0.75 * self.capsule(size).0,
            PogoShape::Point | PogoShape::Circle => 0.0,
        };
        DeclaredContact {
            gap: LINEAR_SLOP,
            gap_tolerance: LINEAR_SLOP,
            // Box2D's collision tolerance: "a small length used as a collision and constraint
            // tolerance ... visually insignificant" (b2_linearSlop); contacts within it are
            // contacts (contact_tolerance below, which stress holds it to).
            overlap_tolerance: LINEAR_SLOP,
            stance_half_width,
            ..DeclaredContact::default()
        }
    }

    /// As [`Controller::declared_contact`], with the pogo's sag: the sample feeds gravity
    /// every step and the spring (`b2SpringDamper`, `pogo_hertz`, `pogo_damping_ratio`) rests
    /// where its push balances it, `g dt (2 zeta + omega dt) / omega` below the pogo's rest
    /// length (0.0338 tiles at 60 Hz; `tests/controllers/box2d.rs` derives it and finds the feet there, less
    /// the cast's linear slop). The feet stand that far down by design, so the metrics declare
    /// that stance and allow that sink into the ground under the feet (never into a wall or a
    /// ceiling), as Rapier's offset is declared.
    fn declared_contact_in(&self, size: Vec2, params: &MotionParams, dt: f32) -> DeclaredContact {
        let omega = 2.0 * std::f64::consts::PI * self.pogo_hertz as f64;
        let (g, dt) = (params.gravity as f64, dt as f64);
        let sag = if omega > 0.0 {
            g * dt * (2.0 * self.pogo_damping_ratio as f64 + omega * dt) / omega
        } else {
            0.0
        };
        let sag = (sag as f32).max(0.0);
        DeclaredContact {
            stance_sink: sag,
            ..self.declared_contact(size, params.max_climb_angle)
        }
    }

    /// Box2D's linear slop: its collision tolerance.
    fn contact_tolerance(&self, _size: Vec2) -> f64 {
        LINEAR_SLOP as f64
    }

    /// The capsule is as wide as the box where the height above the pogo leg allows, else
    /// narrower (a circle); the leg makes up the rest of the height.
    fn moved_size(&self, size: Vec2) -> Vec2 {
        let (r, _, _) = self.capsule(size);
        Vec2::new(2.0 * r, size.y)
    }

    /// Builds the backend's own world (moving platforms mutate it, so it is not shared).
    fn build(&self, setup: Setup<'_>) -> Result<Box2dBackend, BackendError> {
        let mut b = Box2dBackend::new(setup.level, setup.params.clone(), self.clone())?;
        for c in setup.characters {
            b.add_character(*c)?;
        }
        Ok(b)
    }

    fn step(&self, mover: &mut Box2dBackend, inputs: &[Input], dt: f32) {
        mover.step(inputs, dt);
    }

    fn state(&self, mover: &Box2dBackend, id: CharacterId) -> CharacterState {
        mover.state(id)
    }

    fn description() -> &'static str {
        "Box2D v3's character mover (cast, collide, solve planes, clip velocity, pogo), driven as Box2D's Mover sample drives it"
    }

    fn shapes() -> Vec<CharacterShape> {
        vec![CharacterShape::Capsule]
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
            ("per-tile capsule", "#00838f"),
            ("merged capsule", "#4dd0e1"),
        ]
    }

    fn colour() -> Option<&'static str> {
        Some("#00838f")
    }
}

/// Box2D with `config`, labelled by [`Box2dConfig::label`].
pub fn run_with(config: Box2dConfig) -> RunConfig {
    RunConfig::new(config.label(), config)
}
