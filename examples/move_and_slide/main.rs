//! A third controller built only on platbench's public API: a collide-and-slide mover in the
//! style of Godot's `CharacterBody2D.move_and_slide()` (reference: the Godot 4.3 class docs of
//! `CharacterBody2D`, whose property defaults the config below takes) and of the kinematic
//! character examples of Rust physics crates.
//!
//! Each step: the shared motion ([`MotionState::integrate`]) turns the input into the desired
//! displacement; the mover first recovers from any overlap, then casts the character's shape
//! (parry2d shape casts) along the displacement against the level's colliders, stops
//! `safe_margin` short of the first hit, and slides the rest along the surface it hit, up to
//! `max_slides` times. A hit whose normal is within `floor_max_angle` of up is a floor. A
//! character that was on the floor and is not rising is snapped down onto a floor within
//! `floor_snap_length`. With `floor_stop_on_slope`, a character standing on a slope with no
//! horizontal move does not slide down it; with `floor_constant_speed`, it walks up and down
//! slopes at its flat-ground speed. One-way platforms follow the rule the built-in backends
//! use: one counts only for a character whose feet were on or above its top at the start of
//! the step, not climbing a ladder and not dropping through it. Moving platforms are not
//! modelled: the kind declares it, and the harness skips those levels.
//!
//! Written from Godot's documented behaviour, not its source; where Godot's code does what the
//! docs do not say (recovery iterations, exact floor snapping), this does the simple thing.
//!
//! `cargo run --release --example move_and_slide` runs the built-in comparison with it as extra
//! rows; every platbench command takes it (`-- report --out DIR`; docs/move-and-slide.md).

mod colliders;
mod config;
mod mover;

use glam::Vec2;
use platbench::prelude::*;

use colliders::LevelColliders;
pub use config::MoveAndSlideConfig;
use mover::{Character, MoveAndSlide};

/// The backend's name, as in CSV files.
pub const NAME: &str = "move_and_slide";

impl Controller for MoveAndSlideConfig {
    type Mover = MoveAndSlide;
    const NAME: &'static str = NAME;

    fn features(&self) -> Features {
        MoveAndSlide::SUPPORTED
    }

    fn build(&self, setup: Setup<'_>) -> Result<MoveAndSlide, BackendError> {
        let level = setup.level;
        let colliders = setup
            .shared
            .get_or_build(NAME, || LevelColliders::new(level));
        let mut mover = MoveAndSlide::new(level, colliders, setup.params.clone(), self.clone())?;
        // The characters (the harness has checked their spawns, sizes and velocities).
        let origin = mover.origin;
        mover
            .characters
            .extend(setup.characters.iter().map(|spec| Character {
                pos: spec.spawn + origin,
                size: spec.size,
                shape: self.shape.build(spec.size),
                motion: MotionState::with_velocity(spec.velocity),
                ground_normal: Vec2::ZERO,
                one_way_ground: None,
                drop_top: None,
            }));
        Ok(mover)
    }

    fn step(&self, m: &mut MoveAndSlide, inputs: &[Input], dt: f32) {
        for id in 0..m.characters.len() {
            let input = inputs.get(id).copied().unwrap_or_default();
            m.step_character(id, &input, dt);
        }
    }

    fn state(&self, m: &MoveAndSlide, id: CharacterId) -> CharacterState {
        let c = &m.characters[id];
        CharacterState {
            pos: c.pos - m.origin,
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            ground_normal: c.ground_normal,
            platform: None,
            ladder: c.motion.on_ladder,
            crushed: false,
        }
    }

    fn description() -> &'static str {
        "Godot-style collide-and-slide over parry2d shape casts (examples/move_and_slide/)"
    }

    /// Godot's defaults with a box and with a capsule, the box with constant speed on floors,
    /// and the box with a floor snap of 4 px (0.25 tiles); each with its design and source.
    fn configs() -> Vec<RunConfig> {
        let configs = [
            MoveAndSlideConfig::default(),
            MoveAndSlideConfig {
                shape: CharacterShape::Capsule,
                ..Default::default()
            },
            MoveAndSlideConfig {
                floor_constant_speed: true,
                ..Default::default()
            },
            // What a Godot user raises to keep walking down a 45-degree ramp at run speed: the
            // ground drops run_speed * dt = 0.1 tiles a step there, more than the 1 px default.
            MoveAndSlideConfig {
                floor_snap_length: 0.25,
                ..Default::default()
            },
        ];
        let whys = [
            "a box: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes (Godot 4.3 CharacterBody2D docs)",
            "a capsule: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes (Godot 4.3 CharacterBody2D docs)",
            "floor_constant_speed: run speed along slopes, not slower up and faster down (Godot 4.3 CharacterBody2D docs)",
            "a 4 px floor snap: stays grounded down a 45-degree ramp at run speed (Godot 4.3 CharacterBody2D docs)",
        ];
        configs
            .into_iter()
            .zip(whys)
            .map(|(c, why)| RunConfig::new(c.label(), c).with_why(why))
            .collect()
    }

    fn drawn() -> Vec<(&'static str, &'static str)> {
        vec![("cuboid", "#6a1b9a")]
    }

    fn shape(&self) -> CharacterShape {
        self.shape
    }

    /// The safe margin, kept to everything it touches (and the stress holds it to it).
    fn declared_contact(&self, _size: Vec2, _max_climb_angle: f32) -> DeclaredContact {
        DeclaredContact {
            gap: self.safe_margin,
            ..DeclaredContact::default()
        }
    }
}

/// The registry of the built-in backends with this one added.
pub fn registry() -> platbench::registry::Registry {
    platbench::registry::Registry::builtin().with::<MoveAndSlideConfig>()
}

#[allow(dead_code)]
fn main() -> std::process::ExitCode {
    platbench::cli::main_with(registry())
}
