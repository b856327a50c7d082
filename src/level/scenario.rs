//! A scenario as a level states it ([`ScenarioSpec`]): one character, its spawn, its input
//! script ([`InputEvent`]) and its changes to the motion ([`MotionOverrides`]); the default
//! character and time step, and which names a level or scenario may have ([`valid_name`]).

use glam::Vec2;

/// One timed change of the held buttons in a scenario's input script. Buttons not named keep
/// their previous state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InputEvent {
    /// Time at which the change takes effect, in seconds from the start.
    pub t: f32,
    /// New state of the left button, if it changes.
    pub left: Option<bool>,
    /// New state of the right button, if it changes.
    pub right: Option<bool>,
    /// New state of the up button, if it changes.
    pub up: Option<bool>,
    /// New state of the down button, if it changes.
    pub down: Option<bool>,
    /// New state of the jump button, if it changes.
    pub jump: Option<bool>,
}

/// Per-scenario changes to the run's motion parameters.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MotionOverrides {
    /// Replaces the jump height, in tiles.
    pub jump_height: Option<f32>,
    /// Replaces the run speed, in tiles/s.
    pub run_speed: Option<f32>,
    /// Replaces the gravity, in tiles/s².
    pub gravity: Option<f32>,
}

/// A scenario as the level file states it: one character, its spawn and its input script.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenarioSpec {
    /// Name, unique within the level.
    pub name: String,
    /// Spawn position of the character's feet (bottom centre of its box), in tiles.
    pub spawn: Vec2,
    /// Width and height of the character's box, in tiles.
    pub size: Vec2,
    /// Initial velocity, in tiles/s.
    pub velocity: Vec2,
    /// Length of the run, in seconds.
    pub duration: f32,
    /// Time step, in seconds.
    pub dt: f32,
    /// Input changes, in time order.
    pub inputs: Vec<InputEvent>,
    /// Changes to the motion parameters for this scenario.
    pub motion: MotionOverrides,
    /// Where the character's feet should end (y, in tiles), for scenarios whose outcome is a
    /// place: which side of a one-way platform, or the top of a ladder.
    pub expect_y: Option<f32>,
    /// The moving platform (index in the level's list) this scenario rides, for the carry
    /// metrics.
    pub ride: Option<u32>,
}

impl ScenarioSpec {
    /// A scenario with the default character, time step and motion, from rest, no expected end
    /// place and no platform ridden: the fields other code then sets what it needs of.
    pub fn new(name: String, spawn: Vec2, duration: f32, inputs: Vec<InputEvent>) -> Self {
        ScenarioSpec {
            name,
            spawn,
            size: DEFAULT_CHARACTER_SIZE,
            velocity: Vec2::ZERO,
            duration,
            dt: DEFAULT_DT,
            inputs,
            motion: MotionOverrides::default(),
            expect_y: None,
            ride: None,
        }
    }
}

/// Whether `name` can name a level or scenario: non-empty ASCII letters, digits, '_' or '-',
/// since it names output files (and '.' separates the parts of a trace file's name).
pub fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Default character box: 0.8 x 0.9 tiles, the size of the reference measurements.
pub const DEFAULT_CHARACTER_SIZE: Vec2 = Vec2::new(0.8, 0.9);
/// Default time step: 1/60 s.
pub const DEFAULT_DT: f32 = 1.0 / 60.0;
