//! A scenario as a level states it ([`ScenarioSpec`]): one character, its spawn, its input
//! script ([`InputEvent`]) and its changes to the motion ([`MotionOverrides`]); the default
//! character and time step, what it says should happen ([`Expectations`]), and which names a
//! level or scenario may have ([`valid_name`]).

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
    /// What the level says should happen (its `[scenario.expect]` table), each checked against
    /// the trace and reported as an `expect_*` metric row; none by default.
    pub expect: Expectations,
}

/// What a scenario says should happen to its character: each stated expectation is checked
/// against the trace and reported as a pass (0) or fail (1) metric row. Positions are of the
/// feet (bottom centre of the box), in level tiles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Expectations {
    /// A box the feet must be inside at some frame up to a deadline (`expect_reach`).
    pub reach: Option<Reach>,
    /// Whether the character must end grounded (`true`) or airborne (`false`), as its
    /// controller reports it on the last frame (`expect_grounded_at_end`).
    pub grounded_at_end: Option<bool>,
    /// The lowest the feet may ever be, in tiles (`expect_min_y`).
    pub min_y: Option<f32>,
    /// Whether the feet must stay inside the map, 0 <= x <= width and 0 <= y <= height in tiles,
    /// on every frame (`expect_stay_in_map`).
    pub stay_in_map: bool,
    /// The moving platform (index in the level's list, from 0) the character must stand on at
    /// some frame (`expect_land_on`).
    pub land_on: Option<u32>,
}

impl Expectations {
    /// Whether the scenario states no expectation.
    pub fn is_empty(&self) -> bool {
        *self == Expectations::default()
    }
}

/// A region to reach: a box in level tiles (bounds inclusive) and the deadline to reach it by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// Lower-left corner of the box, in tiles (`-inf` on an axis the level leaves open).
    pub min: Vec2,
    /// Upper-right corner of the box, in tiles (`+inf` on an axis the level leaves open).
    pub max: Vec2,
    /// When the feet must be in the box by.
    pub by: Deadline,
}

/// The last moment an expectation may be met at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Deadline {
    /// The scenario's last frame.
    End,
    /// A time, in seconds from the start: the last frame at or before it (`floor(seconds /
    /// dt)`, a quotient within a thousandth of a frame of a whole number being that frame).
    Seconds(f32),
    /// A frame number (the trace's 0-based `frame` column; the last frame if beyond it).
    Frame(u32),
}

impl Deadline {
    /// The deadline's frame in a run of `last` + 1 frames of `dt` seconds.
    pub fn frame(self, dt: f32, last: u32) -> u32 {
        match self {
            Deadline::End => last,
            Deadline::Seconds(s) => {
                let f = s as f64 / dt as f64;
                // A time on a frame's own time is that frame, though f32 time steps make the
                // quotient a hair off (3 s at 1/60 s is 179.99999): as `round(duration / dt)`
                // counts a scenario's frames.
                let near = f.round();
                let f = if (f - near).abs() <= 1e-3_f64.max(f * 1e-6) {
                    near
                } else {
                    f.floor()
                };
                if f.is_finite() && f >= 0.0 {
                    f.min(last as f64) as u32
                } else {
                    last
                }
            }
            Deadline::Frame(f) => f.min(last),
        }
    }
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
            expect: Expectations::default(),
        }
    }
}

/// Whether `name` can name a level or scenario: 1 to 64 ASCII letters, digits, '_' or '-',
/// since it names output files (and '.' separates the parts of a trace file's name).
pub fn valid_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= crate::limits::MAX_NAME_BYTES
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Default character box: 0.8 x 0.9 tiles, the size of the reference measurements.
pub const DEFAULT_CHARACTER_SIZE: Vec2 = Vec2::new(0.8, 0.9);
/// Default time step: 1/60 s.
pub const DEFAULT_DT: f32 = 1.0 / 60.0;
