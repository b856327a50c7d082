//! The interface both controllers implement, and what a character exposes after a step.
//!
//! Both backends are driven identically: same level, same [`MotionParams`], same per-frame
//! [`Input`] per character, same `dt`. A step moves every character (then, once levels have
//! them, every moving platform). Anything a metric needs is in [`CharacterState`]; no metric
//! reaches into a backend.

use glam::Vec2;

use crate::level::Features;
use crate::motion::Input;
#[cfg(doc)]
use crate::motion::MotionParams;

/// Index of a character within one backend instance.
pub type CharacterId = usize;

/// How a character starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CharacterSpec {
    /// Position of the feet (bottom centre of the box), in tiles.
    pub spawn: Vec2,
    /// Width and height of the character's box, in tiles.
    pub size: Vec2,
    /// Initial velocity, in tiles/s.
    pub velocity: Vec2,
}

impl CharacterSpec {
    /// Checks that the spawn and velocity are finite and the size positive.
    pub fn validate(&self) -> Result<(), BackendError> {
        let finite = |v: Vec2| v.is_finite();
        if !finite(self.spawn) {
            return Err(invalid("spawn", self.spawn, "finite coordinates (tiles)"));
        }
        if !(finite(self.size) && self.size.min_element() > 0.0) {
            return Err(invalid(
                "size",
                self.size,
                "a finite width and height > 0 (tiles)",
            ));
        }
        if !finite(self.velocity) {
            return Err(invalid(
                "velocity",
                self.velocity,
                "finite components (tiles/s)",
            ));
        }
        Ok(())
    }
}

/// An [`BackendError::InvalidParameter`].
pub fn invalid(
    name: &'static str,
    value: impl std::fmt::Debug,
    expected: &'static str,
) -> BackendError {
    BackendError::InvalidParameter {
        name,
        value: format!("{value:?}"),
        expected,
    }
}

/// A character's state after a step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CharacterState {
    /// Position of the feet (bottom centre of the box), in tiles.
    pub pos: Vec2,
    /// Velocity after the step, in tiles/s.
    pub vel: Vec2,
    /// Whether the character stands on something.
    pub grounded: bool,
    /// Normal of the surface it stands on (zero when airborne).
    pub ground_normal: Vec2,
    /// Index of the moving platform it rides, if any.
    pub platform: Option<u32>,
    /// Whether it is in the ladder state.
    pub ladder: bool,
    /// Whether a moving platform pushed it into the level during the step (it could not make
    /// room): the crush event, left to the scenario to judge.
    pub crushed: bool,
}

/// Why a backend could not be built for a level.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BackendError {
    /// The level contains something this backend does not model yet.
    #[error("the {backend} backend does not support {feature} yet (level {level})")]
    Unsupported {
        /// Backend name.
        backend: &'static str,
        /// What it lacks.
        feature: String,
        /// The level's name.
        level: String,
    },
    /// A parameter is out of its valid range.
    #[error("invalid parameter {name} = {value}: {expected}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value, printed.
        value: String,
        /// What was expected.
        expected: &'static str,
    },
}

/// Refuses a level whose features a backend does not support: never ignore part of a level.
pub fn require_supported(
    backend: &'static str,
    level_name: &str,
    has: Features,
    supported: Features,
) -> Result<(), BackendError> {
    let missing = Features {
        slopes: has.slopes && !supported.slopes,
        one_way: has.one_way && !supported.one_way,
        ladders: has.ladders && !supported.ladders,
        moving_platforms: has.moving_platforms && !supported.moving_platforms,
    };
    let names = missing.names();
    if names.is_empty() {
        Ok(())
    } else {
        Err(BackendError::Unsupported {
            backend,
            feature: names.join(", "),
            level: level_name.to_string(),
        })
    }
}

/// A character controller driving characters over one level.
pub trait Backend {
    /// Short backend name, as in CSV files (`sweep`, `rapier`).
    fn name(&self) -> &'static str;
    /// Adds a character and returns its id; refuses a non-finite spawn or velocity, or a size
    /// that is not positive.
    fn add_character(&mut self, spec: CharacterSpec) -> Result<CharacterId, BackendError>;
    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    fn step(&mut self, inputs: &[Input], dt: f32);
    /// The state of character `id` after the last step.
    fn state(&self, id: CharacterId) -> CharacterState;
}
