//! The rapier2d backend: `KinematicCharacterController::move_shape` over the level's colliders,
//! set up the way Rapier's docs and examples do it.
//!
//! Each frame, per character: the shared motion integrates the velocity (gravity accumulates
//! while airborne), the desired translation `v * dt` goes to `move_shape` through the broad
//! phase's `QueryPipeline`, the returned translation is added to the position, and the result is
//! fed back as Rapier's examples do: when grounded the vertical velocity is reset. A ceiling hit
//! that blocked a rising move also resets it (as any platformer must, or the character sticks
//! under the ceiling until gravity wins). A wall that blocked the horizontal move goes through
//! the same shared rule as the sweep's: it stops a coasting character, while held input keeps
//! driving one steered into it. That rule matters for Rapier: its controller reports the
//! internal edges of a per-tile floor as wall contacts, and a walker that lost its speed on each
//! of them would pay our acceleration ramp on top of Rapier's snag. No rigid-body simulation
//! runs: the level has only static colliders.
//!
//! The backend is built in either precision from the same source: `backend.rs`,
//! `colliders.rs` and `platforms.rs` are compiled here on rapier2d and parry2d (f32, this
//! module) and again in [`double`] on rapier2d-f64 and parry2d-f64, each against its own
//! `precision` module (the engine crate, the scalar and vector types, and the conversions from
//! the harness's f32 level coordinates, identities in f32). The settings ([`RapierConfig`]) are
//! one type for both; [`RapierConfig::precision`] picks the build.

mod backend;
pub mod colliders;
pub mod double;
pub mod kind;
pub mod platforms;
mod presets;

pub use crate::backend::Precision;
use crate::motion::MotionParams;
pub use crate::shape::CharacterShape;
pub use backend::{controller, pose, Move, RapierBackend};
pub use colliders::{one_way_top, ColliderBuilding, StaticWorld};
pub use platforms::Platforms;

/// The f32 build: rapier2d and parry2d, glam's `Vec2`.
mod precision {
    use glam::Vec2;

    pub use ::rapier2d as engine;
    /// The engine's scalar.
    pub type Real = f32;
    /// The engine's vector.
    pub type Vect = Vec2;
    /// The backend's name in this precision.
    pub const NAME: &str = "rapier";

    /// A vector of the harness (f32) in the engine's type.
    #[inline]
    pub fn v(x: Vec2) -> Vect {
        x
    }
    /// A vector of the engine in the harness's f32.
    #[inline]
    pub fn back(x: Vect) -> Vec2 {
        x
    }
    /// A scalar of the harness (f32) in the engine's type.
    #[inline]
    pub fn s(x: f32) -> Real {
        x
    }
    /// Where `level`'s corner sits in the engine's world: its f64 origin rounded to the nearest
    /// f32 ([`crate::level::Level::origin_f32`]).
    #[inline]
    pub fn level_origin(level: &crate::level::Level) -> Vect {
        level.origin_f32()
    }
    /// A one-way top's bits, for a collider's `user_data`.
    pub fn top_bits(top: Real) -> u128 {
        top.to_bits() as u128
    }
    /// A one-way top from a collider's `user_data`.
    pub fn top_from_bits(data: u128) -> Real {
        Real::from_bits(data as u32)
    }
    /// [`crate::ladder::enter`] in world coordinates.
    pub fn ladder_enter(
        level: &crate::level::Level,
        origin: Vect,
        m: &mut crate::motion::MotionState,
        pos: &mut Vect,
        size: Vec2,
        input: &crate::motion::Input,
    ) {
        crate::ladder::enter(level, origin, m, pos, size, input)
    }
    /// [`crate::ladder::leave`] in world coordinates.
    pub fn ladder_leave(
        level: &crate::level::Level,
        origin: Vect,
        m: &mut crate::motion::MotionState,
        pos: Vect,
        size: Vec2,
        input: &crate::motion::Input,
    ) {
        crate::ladder::leave(level, origin, m, pos, size, input)
    }
}

/// Added to [`MotionParams::max_climb_angle`] for Rapier's climb and slide angles, in radians.
/// Rapier calls a slope at exactly its limit a wall (`angle >= max_slope_climb_angle`) and
/// slides on one past it, while the shared limit is the steepest walkable, non-slipping slope.
/// Rapier's own climb test puts 0.001 rad around its limit, on exact rotated cuboids; on a
/// merged polyline the contact normals of a 45-degree ramp scatter by about 0.003 rad, so with
/// 0.001 rad the ramp tips past the slide limit on some steps and a resting character creeps
/// down it. 0.01 rad (0.57 degrees) clears that scatter.
pub const CLIMB_LIMIT_MARGIN: f32 = 1e-2;

/// How far beyond its offset Rapier's controller looks for ground, in tiles: its
/// `predict_ground` adds this absolute 0.05 to the offset (rapier2d 0.36.1).
pub(crate) const GROUND_PREDICTION: f32 = 0.05;

/// How far below a one-way platform's top the feet may start a move and still land on it, in
/// tiles: rounding only (Rapier keeps its offset above the top when standing on it).
pub const ONE_WAY_TOLERANCE: f32 = 1e-3;

/// A length that is either absolute (tiles) or relative to the character's height, as Rapier's
/// `CharacterLength`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// In tiles.
    Absolute(f32),
    /// As a fraction of the character's height.
    Relative(f32),
}

impl Length {
    /// The length in tiles for a character `height` tiles tall (Rapier evaluates relative
    /// lengths against the height of the shape's bounding box, which is the box's here).
    pub fn eval(self, height: f32) -> f32 {
        match self {
            Length::Absolute(v) => v,
            Length::Relative(v) => v * height,
        }
    }
}

/// How a grounded step's vertical move is fed to the controller. Rapier leaves this to its
/// users, and its own examples differ; the choice decides whether a box sticks on a long merged
/// floor (rapier #613: a cast at a glancing angle can miss the offset band).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GroundedMove {
    /// Gravity every step: the shared motion's vertical velocity, reset to 0 when grounded, so
    /// each grounded step asks to move down by `g * dt²`. What a game that integrates its own
    /// gravity and hands the controller `v * dt` does (Rapier's docs leave the vertical move to
    /// the user); the set-up docs/rapier-reference.md records.
    Gravity,
    /// No vertical move while grounded (a jump still rises): the official bevy_rapier character
    /// example (`bevy_rapier3d/examples/character_controller3.rs`) zeroes its vertical movement
    /// when the controller reports grounded and only then adds gravity for the next frame.
    /// Snap-to-ground follows the ground down slopes. The controller's own carry on a moving
    /// platform stops with it: Rapier carries a rider only after a cast hit.
    None,
    /// As [`GroundedMove::None`], except on a moving platform (a kinematic body), where
    /// gravity is fed so that the controller's cast hits the platform and its carry runs.
    NoneExceptOnPlatforms,
    /// A constant push down while grounded, in tiles/s (the step asks for `speed * dt`), for
    /// trying speeds other than [`GroundedMove::Testbed`]'s.
    Constant(f32),
    /// Rapier's own 2D testbed feed (dimforge/rapier, `examples2d/utils/character.rs`, lines
    /// 50-85 and 132 at commit ccd01cd2): `character_movement_from_inputs(gfx, speed, true)`
    /// scales the arrow keys' direction by `speed`, "the speed applied each simulation tick"
    /// (0.1 per tick by default, `CharacterControlMode::Kinematic(0.1)` in
    /// `examples2d/character_controller2.rs`), then, its "artificial gravity", subtracts
    /// `Vector::Y * speed`: every step asks to move down by one walking step. Here, while
    /// grounded, the step asks for `MotionParams::run_speed * dt` down (6 tiles/s: 0.1 tiles a
    /// step at 60 Hz, the testbed's 0.1 per tick for its capsule, which is 0.9 tall as this
    /// character is). Airborne, the shared motion's gravity still applies (the testbed's
    /// character falls at that constant speed instead). The push reaches any ground within
    /// one walking step, so the controller's cast hits a descending platform and its carry runs.
    Testbed,
    /// As [`GroundedMove::None`] on static ground (the bevy_rapier example's feed), and as
    /// [`GroundedMove::Testbed`] on a moving platform (a kinematic body): the controller
    /// carries a rider only after its cast hits the platform, and the testbed's push reaches
    /// one that descends faster than gravity's `g * dt²` a step does.
    NoneExceptTestbedOnPlatforms,
}

impl GroundedMove {
    /// Short label for configuration names.
    pub fn label(self) -> String {
        match self {
            GroundedMove::Gravity => "gravity".into(),
            GroundedMove::None => "none".into(),
            GroundedMove::NoneExceptOnPlatforms => "none-but-platforms".into(),
            GroundedMove::Constant(v) => format!("push{v}"),
            GroundedMove::Testbed => "testbed".into(),
            GroundedMove::NoneExceptTestbedOnPlatforms => "none-but-testbed-on-platforms".into(),
        }
    }
}

/// When moving platforms move within a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlatformOrder {
    /// After every character has moved: the seed's order, the sweep's.
    AfterCharacters,
    /// Before the characters move: the platform's velocity the controller carries with is then
    /// the one of this step's displacement, not the step before's.
    BeforeCharacters,
}

/// How a rider is carried by a moving platform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlatformCarry {
    /// What Rapier's controller does by itself: it adds the velocity of the kinematic body it
    /// stands on to the move (its kinematic friction). The reference measured this to carry a
    /// horizontal rider exactly.
    Controller,
    /// The controller's carry plus the platform's displacement added to the desired
    /// translation when grounded on it, as Rapier users often bolt on. The reference measured it
    /// to over-carry (1.35x horizontally) and to sink into a descending elevator.
    ControllerPlusDisplacement,
}

/// Settings of the Rapier backend: every option of Rapier's `KinematicCharacterController`,
/// with Rapier's own defaults, plus how the level and the character are built.
#[derive(Clone, Debug, PartialEq)]
pub struct RapierConfig {
    /// How solid tiles become colliders.
    pub colliders: ColliderBuilding,
    /// The character's collision shape, fitted to its box. Default: a capsule, the shape of
    /// Rapier's own 2D character-controller example (`examples2d/character_controller2.rs`).
    pub shape: CharacterShape,
    /// Gap the controller keeps between the character and obstacles. Rapier's default, 1% of
    /// the character's height; Rapier's docs advise a small non-zero value for numerical
    /// stability, so `rest_gap` is about this value by design.
    pub offset: Length,
    /// Whether the character slides along what it hits (Rapier's default: on).
    pub slide: bool,
    /// Automatic stepping over small obstacles (Rapier's default: off, "computationally
    /// expensive"): maximum step height and minimum free width on top.
    pub autostep: Option<(Length, Length)>,
    /// Steepest slope the character can climb, in radians; `None` takes
    /// [`MotionParams::max_climb_angle`] plus [`CLIMB_LIMIT_MARGIN`] (Rapier's default is 45
    /// degrees, as is ours).
    pub max_slope_climb_angle: Option<f32>,
    /// Slope angle from which the character slides down, in radians; `None` takes
    /// [`MotionParams::max_climb_angle`] plus [`CLIMB_LIMIT_MARGIN`] (Rapier's default is 45
    /// degrees).
    pub min_slope_slide_angle: Option<f32>,
    /// Snap to the ground when it is closer than this below the feet (Rapier's default: 20% of
    /// the character's height); `None` disables snapping.
    pub snap_to_ground: Option<Length>,
    /// Nudge along contact normals that keeps shape casts from sticking while sliding, in
    /// tiles (Rapier's default: 1e-4).
    pub normal_nudge_factor: f32,
    /// How a rider is carried by a moving platform. Default: the controller's own carry, which
    /// the reference measured exact horizontally; adding the displacement too over-carries.
    pub platform_carry: PlatformCarry,
    /// How a grounded step's vertical move is fed (default: gravity every step).
    pub grounded_move: GroundedMove,
    /// Whether a character spawned closer than the offset above the ground is raised to the
    /// offset (default: on). Spawned flush, it would start inside the offset band, where
    /// Rapier's casts see it touching and its depenetration (which runs only for overlaps)
    /// never lifts it; a Rapier user places the character clear of the ground. Off only to
    /// reproduce a scene placed exactly, such as Rapier's own tests.
    pub lift_spawn: bool,
    /// When moving platforms move within a step. Default: before the characters, which
    /// `examples/rapier_setups.rs` measured to carry better than the seed's order (the
    /// controller carries with the platform velocity of the step it moves in, not the step
    /// before's).
    pub platform_order: PlatformOrder,
    /// The precision of the build the settings run on: f32 (rapier2d and parry2d, default) or
    /// f64 (rapier2d-f64 and parry2d-f64, [`double`]), for large or streamed worlds whose
    /// levels sit far from the world's origin.
    pub precision: Precision,
}

impl Default for RapierConfig {
    fn default() -> Self {
        let kcc = rapier2d::control::KinematicCharacterController::default();
        RapierConfig {
            colliders: ColliderBuilding::PerTile,
            shape: CharacterShape::Capsule,
            offset: Length::Relative(0.01),
            slide: kcc.slide,
            autostep: None,
            max_slope_climb_angle: None,
            min_slope_slide_angle: None,
            snap_to_ground: Some(Length::Relative(0.2)),
            normal_nudge_factor: kcc.normal_nudge_factor,
            platform_carry: PlatformCarry::Controller,
            grounded_move: GroundedMove::Gravity,
            lift_spawn: true,
            platform_order: PlatformOrder::BeforeCharacters,
            precision: Precision::F32,
        }
    }
}

impl RapierConfig {
    /// The controller these settings describe, for motion parameters `p`, on rapier2d (f32;
    /// [`double::controller`] for f64).
    pub fn controller(&self, p: &MotionParams) -> rapier2d::control::KinematicCharacterController {
        controller(self, p)
    }

    /// Short label for tables and file names: the collider building and the shape, then how
    /// a grounded step is fed when that is not gravity, then ` f64` on the f64 build.
    pub fn label(&self) -> String {
        let mut label = format!("{} {}", self.colliders.label(), self.shape.label());
        if self.grounded_move != GroundedMove::Gravity {
            label += " grounded=";
            label += &self.grounded_move.label();
        }
        if self.precision == Precision::F64 {
            label += " f64";
        }
        label
    }
}
