//! A third controller built only on platbench's public API: a collide-and-slide mover in the
//! style of Godot 4's `CharacterBody2D.move_and_slide()` in its grounded mode. Its settings and
//! their defaults are the Godot 4.3 class docs' properties of `CharacterBody2D`; its slide rules
//! are read from Godot's source, `CharacterBody2D::_move_and_slide_grounded` in
//! `scene/2d/physics/character_body_2d.cpp` (`scene/2d/physics_body_2d.cpp` before 4.3).
//!
//! Each step: the shared motion ([`MotionState::integrate`]) turns the input into the desired
//! displacement, gravity included (as a Godot script adds gravity to `velocity` every frame).
//! The mover casts the character's shape (parry2d shape casts) along it against the level's
//! colliders, stops `safe_margin` short of the first hit and decides what the rest does, up to
//! `max_slides` times, by Godot's rules:
//!
//! - A hit whose normal is within `floor_max_angle` of up is a floor, within it of down a
//!   ceiling, anything else a wall; each stays set for the rest of the step.
//! - `floor_stop_on_slope`: a move straight down onto a floor ends there; and the first hit of a
//!   step does not slide while on a floor: its rest is cast again unchanged, and sliding starts
//!   with the second hit (the first-slide rule; off with `floor_stop_on_slope` off).
//! - `floor_block_on_wall`: a wall hit by a move with a horizontal part into it does not turn
//!   into a climb. Walked off the floor into it, the move ends and a snap down (a wall counting
//!   as floor) keeps the character stood; still on the floor, the rest is cast again unslid; in
//!   the air, only the rest's vertical part slides along the wall.
//! - `floor_constant_speed`: once a step, on a floor only, the rest goes along the slope for the
//!   horizontal distance left; walking down a slope a snap would stand on, the first move is
//!   redone along the previous floor at flat-ground speed.
//! - Otherwise the rest slides along the surface, unless the slide turns against the velocity.
//!
//! A character that was on the floor, is not rising and found no floor is then snapped down
//! onto one within `floor_snap_length`. Last, it is pushed out to `safe_margin` from anything
//! closer (the recovery), and a floor within the margin is stood on. One-way platforms follow
//! the rule the built-in backends use: one counts only for a character whose feet were on or
//! above its top at the start of the step, not climbing a ladder and not dropping through it.
//!
//! Not modelled, by design or for simplicity:
//! - Moving platforms: the kind declares it, and the harness skips those levels.
//! - Godot's recovery order: Godot recovers first, in every `move_and_collide`
//!   (`GodotSpace2D::test_body_motion` in `modules/godot_physics_2d/godot_space_2d.cpp`, "STEP
//!   1"), by 40% of the depth a pass, and counts a contact within the margin as a collision;
//!   here the casts stop the margin short and one exact recovery comes after the moves, so
//!   Godot's undoing of a travel within the margin (its recovery's push) has nothing to undo.
//! - Velocity: the shared motion's contact rule replaces what `move_and_slide` does to
//!   `velocity` (a blocked axis loses its speed; held input keeps driving the feet).
//! - `slide_on_ceiling` off, `wall_min_slide_angle` (floating mode), the snap's up-axis-only
//!   travel and its `max(floor_snap_length, safe_margin)` length (a 0 snap is off here).
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
            "a box: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes, blocks on walls (Godot 4.3 CharacterBody2D docs)",
            "a capsule: 0.005-tile safe_margin gap, 1 px floor snap, stops on slopes, blocks on walls (Godot 4.3 CharacterBody2D docs)",
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
