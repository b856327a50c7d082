//! The step protocol's messages (docs/protocol.md): one JSON object per line, `type` naming the
//! message. [`Request`] is what platbench writes on the controller's stdin, [`Reply`] what the
//! controller prints on its stdout. Every length is in tiles, every speed in tiles/s, times in
//! seconds, y up, positions of a character its feet (bottom centre of its box).

use serde::{Deserialize, Serialize};

use crate::level::{Level, PlatformMotion, Slope, Tile};
use crate::motion::{Input, MotionParams};

/// The protocol version this build speaks; a controller answering another is refused.
pub const VERSION: u32 = 1;

/// A 2D vector as a JSON pair `[x, y]`.
pub(crate) type Pair = [f32; 2];

/// A box as `[x0, y0, x1, y1]` (lower-left and upper-right corners, level coordinates).
pub(crate) type Rect = [f32; 4];

/// What platbench writes, one per line.
#[derive(Debug, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub(crate) enum Request<'a> {
    /// The first message: which protocol and which mode platbench runs the controller in.
    Hello {
        /// [`VERSION`].
        protocol: u32,
        /// `collision` or `whole` (the controller file's mode).
        mode: &'a str,
    },
    /// Build over a level: the configuration picked, the level, the motion, the characters.
    Run(Box<RunRequest<'a>>),
    /// One step of every character.
    Step(&'a StepRequest),
    /// The run is over: the controller exits (its stdin closes next).
    End,
}

/// The `run` message.
#[derive(Debug, Serialize)]
pub(crate) struct RunRequest<'a> {
    /// The label of the configuration (one of those the handshake offered).
    pub(crate) config: &'a str,
    /// The level.
    pub(crate) level: LevelMessage,
    /// The motion parameters (the scenario's overrides applied).
    pub(crate) params: ParamsMessage,
    /// The characters, in id order.
    pub(crate) characters: Vec<CharacterMessage>,
}

/// The level as platbench holds it.
#[derive(Debug, Serialize)]
pub(crate) struct LevelMessage {
    /// The level's name.
    pub(crate) name: String,
    /// Width and height, in tiles.
    pub(crate) width: u32,
    /// Height, in tiles.
    pub(crate) height: u32,
    /// Where the level's corner sits in the world, in tiles (a controller adds it if it wants
    /// world coordinates; every other position here is in level coordinates).
    pub(crate) origin: [f64; 2],
    /// Solid tiles, one `[i, j]` cell each (column, row from the bottom); tile `[i, j]` is the
    /// box `[i, j, i + 1, j + 1]`.
    pub(crate) solid_tiles: Vec<[i64; 2]>,
    /// The same solid tiles merged into boxes (each tile in exactly one).
    pub(crate) solid_boxes: Vec<Rect>,
    /// Sloped tiles.
    pub(crate) slopes: Vec<SlopeMessage>,
    /// One-way tiles' boxes: they block only from above, at their top edge `y1`.
    pub(crate) one_way: Vec<Rect>,
    /// Ladder tiles' boxes.
    pub(crate) ladders: Vec<Rect>,
    /// Moving platforms, in index order (a reply's `platform` is an index here).
    pub(crate) platforms: Vec<PlatformMessage>,
    /// What the level contains beyond solid tiles.
    pub(crate) features: FeaturesMessage,
}

/// A sloped tile.
#[derive(Debug, Serialize)]
pub(crate) struct SlopeMessage {
    /// Its cell `[i, j]`.
    pub(crate) cell: [i64; 2],
    /// Its solid part as a polygon, counter-clockwise, level coordinates.
    pub(crate) polygon: Vec<Pair>,
    /// Its surface as a polyline, left to right, level coordinates.
    pub(crate) surface: Vec<Pair>,
    /// A line slope's heights at the tile's left and right edges (tiles above its bottom).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) line: Option<Pair>,
    /// A height-array slope's 16 column heights, in sixteenths of a tile.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) heights: Option<[u8; 16]>,
}

/// A moving platform.
#[derive(Debug, Serialize)]
pub(crate) struct PlatformMessage {
    /// Lower-left corner at t = 0.
    pub(crate) start: Pair,
    /// Width and height.
    pub(crate) size: Pair,
    /// Whether it blocks from above only.
    pub(crate) one_way: bool,
    /// How it moves (each step also gives its position).
    pub(crate) motion: MotionMessage,
}

/// A platform's path.
#[derive(Debug, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub(crate) enum MotionMessage {
    /// Visits `points` in order and back at `speed` tiles/s.
    Waypoints {
        /// Corner positions, the first the start.
        points: Vec<Pair>,
        /// Speed along the path.
        speed: f32,
    },
    /// `start + amplitude * sin(2 pi t / period)`.
    Sine {
        /// Largest offset.
        amplitude: Pair,
        /// Period, s.
        period: f32,
    },
    /// `start + radius * (cos a - 1, sin a)`, `a = 2 pi t / period`.
    Circle {
        /// Radius.
        radius: f32,
        /// Period, s.
        period: f32,
    },
}

/// Level features, as [`crate::level::Features`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct FeaturesMessage {
    /// Sloped tiles.
    pub(crate) slopes: bool,
    /// One-way platforms.
    pub(crate) one_way: bool,
    /// Ladders.
    pub(crate) ladders: bool,
    /// Moving platforms.
    pub(crate) moving_platforms: bool,
}

impl From<crate::level::Features> for FeaturesMessage {
    fn from(f: crate::level::Features) -> Self {
        FeaturesMessage {
            slopes: f.slopes,
            one_way: f.one_way,
            ladders: f.ladders,
            moving_platforms: f.moving_platforms,
        }
    }
}

impl From<FeaturesMessage> for crate::level::Features {
    fn from(f: FeaturesMessage) -> Self {
        crate::level::Features {
            slopes: f.slopes,
            one_way: f.one_way,
            ladders: f.ladders,
            moving_platforms: f.moving_platforms,
        }
    }
}

/// The motion parameters, as [`MotionParams`].
#[derive(Debug, Serialize)]
pub(crate) struct ParamsMessage {
    gravity: f32,
    run_speed: f32,
    run_accel: f32,
    jump_height: f32,
    jump_mode: &'static str,
    ground_friction: f32,
    stop_speed: f32,
    wall_friction: f32,
    max_climb_angle: f32,
    ladder_speed: f32,
}

impl From<&MotionParams> for ParamsMessage {
    fn from(p: &MotionParams) -> Self {
        ParamsMessage {
            gravity: p.gravity,
            run_speed: p.run_speed,
            run_accel: p.run_accel,
            jump_height: p.jump_height,
            jump_mode: p.jump_mode.label(),
            ground_friction: p.ground_friction,
            stop_speed: p.stop_speed,
            wall_friction: p.wall_friction,
            max_climb_angle: p.max_climb_angle,
            ladder_speed: p.ladder_speed,
        }
    }
}

/// A character to place.
#[derive(Debug, Serialize)]
pub(crate) struct CharacterMessage {
    /// Feet position.
    pub(crate) spawn: Pair,
    /// Width and height of its box.
    pub(crate) size: Pair,
    /// Initial velocity.
    pub(crate) velocity: Pair,
    /// Its shape's label (`cuboid`, `capsule`, `ball`, `round-cuboid`).
    pub(crate) shape: String,
}

/// The `step` message.
#[derive(Debug, Default, Serialize)]
pub(crate) struct StepRequest {
    /// The step's number, from 0; the reply repeats it.
    pub(crate) step: u64,
    /// The time at the end of this step, in seconds.
    pub(crate) time: f64,
    /// The step's length, in seconds.
    pub(crate) dt: f32,
    /// Per character, in id order.
    pub(crate) characters: Vec<StepCharacter>,
    /// Each moving platform's lower-left corner at the end of the step.
    pub(crate) platforms: Vec<Pair>,
}

/// One character's part of a `step`.
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub(crate) struct StepCharacter {
    /// The buttons held.
    pub(crate) input: InputMessage,
    /// Collision mode: the velocity the shared motion asks for this step (move by
    /// `desired * dt`); absent in whole mode.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) desired: Option<Pair>,
    /// Collision mode: drop through one-way platforms this step (down + jump on one).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(crate) drop_through: bool,
}

/// The buttons held, as [`Input`].
#[derive(Clone, Copy, Debug, Default, Serialize)]
pub(crate) struct InputMessage {
    left: bool,
    right: bool,
    up: bool,
    down: bool,
    jump: bool,
}

impl From<&Input> for InputMessage {
    fn from(i: &Input) -> Self {
        InputMessage {
            left: i.left,
            right: i.right,
            up: i.up,
            down: i.down,
            jump: i.jump,
        }
    }
}

/// What the controller prints, one per line.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub(crate) enum Reply {
    /// The handshake's answer.
    Hello {
        /// The protocol version it speaks.
        protocol: u32,
        /// Its own name (shown in descriptions; the controller file's `name` names its rows).
        name: String,
        /// One line on what it is.
        #[serde(default)]
        description: String,
        /// The configurations it offers, at least one.
        configs: Vec<ConfigMessage>,
    },
    /// Built over the level: steps follow.
    Ready,
    /// It does not run this level (or character): skipped, and the reason said.
    Refuse {
        /// Why, in a few words ("slopes").
        reason: String,
    },
    /// The characters' states after a step.
    State(StateReply),
}

/// A configuration the controller offers.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ConfigMessage {
    /// Its label (lower case, no spaces).
    pub(crate) label: String,
    /// The character shape it moves (`cuboid` if absent).
    #[serde(default = "cuboid")]
    pub(crate) shape: String,
    /// The level features it models (none if absent: solid tiles only).
    #[serde(default)]
    pub(crate) features: FeaturesMessage,
    /// The contact it declares (flush if absent).
    #[serde(default)]
    pub(crate) contact: ContactMessage,
    /// What it declares beyond its features.
    #[serde(default)]
    pub(crate) capabilities: CapabilitiesMessage,
    /// One line: its design and source.
    #[serde(default)]
    pub(crate) why: String,
}

fn cuboid() -> String {
    "cuboid".into()
}

/// As [`crate::backend::DeclaredContact`], in tiles.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct ContactMessage {
    pub(crate) gap: f32,
    pub(crate) overlap_tolerance: f32,
    pub(crate) gap_tolerance: f32,
    pub(crate) slope_overhang: f32,
    pub(crate) stance_half_width: f32,
    pub(crate) stance_sink: f32,
    pub(crate) surface_grid: u32,
}

/// As [`crate::backend::Capabilities`].
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct CapabilitiesMessage {
    pub(crate) pushes_bodies: bool,
    pub(crate) integer_positions: bool,
    pub(crate) cross_platform_determinism: bool,
    pub(crate) no_rider_carry: bool,
    pub(crate) no_climb_limit: bool,
}

/// The `state` reply.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct StateReply {
    /// The step it answers.
    pub(crate) step: u64,
    /// Per character, in id order.
    pub(crate) characters: Vec<CharacterReply>,
    /// The controller's own time for the step (all characters), in nanoseconds.
    pub(crate) ns: f64,
}

/// One character's state after a step.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CharacterReply {
    /// Feet position.
    pub(crate) position: Pair,
    /// Velocity (whole mode; in collision mode the shared motion's is recorded).
    pub(crate) velocity: Pair,
    /// Standing on something.
    pub(crate) grounded: bool,
    /// Normal of the ground (`[0, 0]` when airborne).
    #[serde(default)]
    pub(crate) ground_normal: Pair,
    /// Collision mode: the horizontal move was blocked by a wall.
    #[serde(default)]
    pub(crate) wall: bool,
    /// Collision mode: the upward move was blocked by a ceiling.
    #[serde(default)]
    pub(crate) ceiling: bool,
    /// Collision mode: the ground is a one-way platform.
    #[serde(default)]
    pub(crate) on_one_way: bool,
    /// Index of the moving platform ridden, or null.
    #[serde(default)]
    pub(crate) platform: Option<u32>,
    /// In the ladder state.
    #[serde(default)]
    pub(crate) ladder: bool,
    /// A moving platform pushed it into the level this step.
    #[serde(default)]
    pub(crate) crushed: bool,
}

impl CharacterReply {
    /// Whether every number is finite.
    pub(crate) fn is_finite(&self) -> bool {
        [self.position, self.velocity, self.ground_normal]
            .iter()
            .flatten()
            .all(|v| v.is_finite())
    }
}

fn rect(b: &parry2d::bounding_volume::Aabb) -> Rect {
    [b.mins.x, b.mins.y, b.maxs.x, b.maxs.y]
}

/// The level as the `run` message carries it.
pub(crate) fn level_message(level: &Level) -> LevelMessage {
    let (mut solid_tiles, mut slopes, mut one_way, mut ladders) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for j in 0..level.height as i64 {
        for i in 0..level.width as i64 {
            let at = |p: glam::Vec2| [p.x + i as f32, p.y + j as f32];
            match level.tile(i, j) {
                Tile::Solid => solid_tiles.push([i, j]),
                Tile::OneWay => one_way.push(rect(&Level::tile_box(i, j))),
                Tile::Ladder => ladders.push(rect(&Level::tile_box(i, j))),
                Tile::Slope(s) => slopes.push(SlopeMessage {
                    cell: [i, j],
                    polygon: s.outline().into_iter().map(at).collect(),
                    surface: s.surface_points().into_iter().map(at).collect(),
                    line: match s {
                        Slope::Line { left, right } => Some([left, right]),
                        Slope::Heights(_) => None,
                    },
                    heights: match s {
                        Slope::Heights(h) => Some(h),
                        Slope::Line { .. } => None,
                    },
                }),
                Tile::Empty => {}
            }
        }
    }
    let pair = |v: glam::Vec2| [v.x, v.y];
    LevelMessage {
        name: level.name.clone(),
        width: level.width,
        height: level.height,
        origin: [level.origin.x, level.origin.y],
        solid_tiles,
        solid_boxes: level.merged_solid_rects().iter().map(rect).collect(),
        slopes,
        one_way,
        ladders,
        platforms: level
            .platforms
            .iter()
            .map(|p| PlatformMessage {
                start: pair(p.start),
                size: pair(p.size),
                one_way: p.one_way,
                motion: match &p.motion {
                    PlatformMotion::Waypoints { points, speed } => MotionMessage::Waypoints {
                        points: points.iter().copied().map(pair).collect(),
                        speed: *speed,
                    },
                    PlatformMotion::Sine { amplitude, period } => MotionMessage::Sine {
                        amplitude: pair(*amplitude),
                        period: *period,
                    },
                    PlatformMotion::Circle { radius, period } => MotionMessage::Circle {
                        radius: *radius,
                        period: *period,
                    },
                },
            })
            .collect(),
        features: level.features.into(),
    }
}
