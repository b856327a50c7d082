//! The sweep-and-snap controller of the seed slides.
//!
//! One step per character: the shared motion integrates the velocity (symplectic Euler with a
//! force accumulator, [`crate::motion`]), then [`resolve`] moves the box along x, then along
//! y, each time snapping flush to the closest obstacle found through the parry2d broadphase
//! ([`broadphase`]); the blocked axis loses its velocity and the other gets friction.

pub mod broadphase;
pub mod resolve;

use glam::Vec2;

use crate::backend::{
    require_supported, Backend, BackendError, CharacterId, CharacterSpec, CharacterState,
};
use crate::level::{Features, Level};
use crate::motion::{Contacts, Input, MotionParams, MotionState};
use broadphase::StaticTiles;
use resolve::{move_axis, Axis};

/// Settings of the sweep controller.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepConfig {
    /// The seed's overlap tolerance, in tiles: an overlap smaller than this is not a collision,
    /// so rounding after a snap never reads as a new hit. The seed: "try 0.001, and lower until
    /// unstable".
    pub epsilon: f32,
}

impl Default for SweepConfig {
    fn default() -> Self {
        SweepConfig { epsilon: 0.001 }
    }
}

struct Character {
    /// Feet position in world coordinates.
    pos: Vec2,
    size: Vec2,
    motion: MotionState,
}

/// The sweep backend over one level.
pub struct SweepBackend {
    tiles: StaticTiles,
    /// The level's corner in the world.
    origin: Vec2,
    params: MotionParams,
    config: SweepConfig,
    characters: Vec<Character>,
}

impl SweepBackend {
    /// What this backend models today.
    pub const SUPPORTED: Features = Features::NONE;

    /// Builds the backend for `level`; refuses levels with features it does not model.
    pub fn new(
        level: &Level,
        params: MotionParams,
        config: SweepConfig,
    ) -> Result<Self, BackendError> {
        require_supported("sweep", &level.name, level.features, Self::SUPPORTED)?;
        if !(config.epsilon.is_finite() && config.epsilon >= 0.0) {
            return Err(BackendError::InvalidParameter {
                name: "epsilon",
                value: config.epsilon.to_string(),
                expected: "a finite number >= 0 (tiles)",
            });
        }
        Ok(SweepBackend {
            tiles: StaticTiles::new(level),
            origin: level.origin,
            params,
            config,
            characters: Vec::new(),
        })
    }

    /// Moves one character by one step.
    fn step_character(&mut self, id: usize, input: &Input, dt: f32) {
        let eps = self.config.epsilon;
        let c = &mut self.characters[id];
        let delta = c.motion.integrate(&self.params, input, dt);
        let wall = move_axis(&self.tiles, &mut c.pos, c.size, Axis::X, delta.x, eps);
        let hit_y = move_axis(&self.tiles, &mut c.pos, c.size, Axis::Y, delta.y, eps);
        let contacts = Contacts {
            wall,
            ground: hit_y && delta.y < 0.0,
            ceiling: hit_y && delta.y > 0.0,
        };
        c.motion.apply_contacts(&self.params, input, contacts);
    }
}

impl Backend for SweepBackend {
    fn name(&self) -> &'static str {
        "sweep"
    }

    fn add_character(&mut self, spec: CharacterSpec) -> CharacterId {
        self.characters.push(Character {
            pos: spec.spawn + self.origin,
            size: spec.size,
            motion: MotionState::with_velocity(spec.velocity),
        });
        self.characters.len() - 1
    }

    fn step(&mut self, inputs: &[Input], dt: f32) {
        for id in 0..self.characters.len() {
            let input = inputs.get(id).copied().unwrap_or_default();
            self.step_character(id, &input, dt);
        }
    }

    fn state(&self, id: CharacterId) -> CharacterState {
        let c = &self.characters[id];
        CharacterState {
            pos: c.pos - self.origin,
            vel: c.motion.vel,
            grounded: c.motion.grounded,
            ground_normal: if c.motion.grounded {
                Vec2::Y
            } else {
                Vec2::ZERO
            },
            platform: None,
            ladder: false,
        }
    }
}
