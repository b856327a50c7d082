//! What a controller exchanges with the harness (a character's spec and state, its declared
//! contact, its errors), and the type-erased views the harness drives every
//! [`crate::controller::Controller`] through ([`Backend`], [`BackendSettings`]; the registry lists [`crate::controller::BackendKind`]).
//!
//! Both backends are driven identically: same level, same [`MotionParams`], same per-frame
//! [`Input`] per character, same `dt`. A step moves every character (then, once levels have
//! them, every moving platform). Anything a metric needs is in [`CharacterState`]; no metric
//! reaches into a backend.

use glam::Vec2;

use crate::level::{Features, Level};
use crate::motion::{Input, MotionParams};
use crate::shape::CharacterShape;

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
    /// The character of scenario `spec`: its spawn, size and initial velocity.
    pub fn of(spec: &crate::level::ScenarioSpec) -> Self {
        CharacterSpec {
            spawn: spec.spawn,
            size: spec.size,
            velocity: spec.velocity,
        }
    }

    /// Checks that the spawn and velocity are finite and the size positive: the harness's check
    /// of its own input, made before any controller is built.
    pub fn validate(&self) -> Result<(), crate::motion::InvalidParam> {
        let invalid = |name, value: Vec2, expected| crate::motion::InvalidParam {
            name,
            value: format!("{value:?}"),
            expected,
        };
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
    /// The level contains something this backend does not model yet, or (`beyond_bound`) lies
    /// beyond a bound the configuration keeps on purpose (how far from the world's origin it
    /// places a level, [`origin_supported`]).
    #[error(
        "the {backend} backend {} (level {level})",
        if *beyond_bound { format!("refuses {feature}: a bound it keeps by design") } else { format!("does not support {feature} yet") }
    )]
    Unsupported {
        /// Backend name.
        backend: &'static str,
        /// What it lacks, or what lies beyond its bound.
        feature: String,
        /// The level's name.
        level: String,
        /// Whether it is a deliberate bound (a level placed too far out), not a missing feature.
        beyond_bound: bool,
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
    /// An external controller's process failed before its first step: it could not start, or
    /// broke the step protocol, crashed or timed out in its handshake or its `run` reply
    /// (docs/protocol.md). The run ends; the rest of the command's runs go on.
    #[error("the external controller {backend} failed: {message}")]
    External {
        /// Backend name.
        backend: &'static str,
        /// What went wrong, with the process's exit status and last stderr lines if it has them.
        message: String,
    },
}

impl From<crate::motion::InvalidParam> for BackendError {
    fn from(e: crate::motion::InvalidParam) -> Self {
        BackendError::InvalidParameter {
            name: e.name,
            value: e.value,
            expected: e.expected,
        }
    }
}

/// Refuses a level whose features a backend does not support: never ignore part of a level.
pub(crate) fn require_supported(
    backend: &'static str,
    level_name: &str,
    has: Features,
    supported: Features,
) -> Result<(), BackendError> {
    let names = has.missing_from(supported).names();
    if names.is_empty() {
        Ok(())
    } else {
        Err(BackendError::Unsupported {
            backend,
            feature: names.join(", "),
            level: level_name.to_string(),
            beyond_bound: false,
        })
    }
}

/// Refuses a level placed farther from the world's origin than `settings` holds
/// ([`BackendSettings::max_origin`]: an f32 configuration's positions there move in whole
/// tiles or more, so nothing it does means anything; its f64 build places the level exactly).
pub fn origin_supported(settings: &dyn BackendSettings, level: &Level) -> Result<(), BackendError> {
    let max = settings.max_origin();
    if level.origin.abs().max_element() > max {
        return Err(BackendError::Unsupported {
            backend: settings.backend(),
            feature: format!(
                "a level origin of ({}, {}) tiles in {} (this configuration holds to {max} tiles \
                 from the world's origin; an f64 build places any origin to {} tiles exactly: \
                 --precision f64)",
                level.origin.x,
                level.origin.y,
                settings.precision().label(),
                crate::limits::MAX_ORIGIN
            ),
            level: level.name.clone(),
            beyond_bound: true,
        });
    }
    if let Some(max) = settings.max_reach() {
        let reach = level.reach();
        if reach > max {
            return Err(BackendError::Unsupported {
                backend: settings.backend(),
                feature: format!(
                    "a level reaching {reach} tiles from the world's origin, its origin ({}, {}) \
                     plus its size and its platforms' paths (this configuration places a level \
                     exactly within {max} tiles of the world's origin)",
                    level.origin.x, level.origin.y,
                ),
                level: level.name.clone(),
                beyond_bound: true,
            });
        }
    }
    Ok(())
}

/// How far from the world's origin a configuration in `precision` places a level by default, in
/// tiles ([`BackendSettings::max_origin`]).
pub fn max_origin_in(precision: Precision) -> f64 {
    match precision {
        Precision::F32 => crate::limits::MAX_F32_ORIGIN,
        Precision::F64 => crate::limits::MAX_ORIGIN,
    }
}

/// Whether `settings` runs `level`: its features are among the configuration's
/// ([`BackendSettings::features`]), the configuration takes it ([`BackendSettings::check_level`])
/// and holds its origin ([`origin_supported`]); the same checks, in the same order, as
/// [`crate::scenario::Runner::build`] makes before building, so a run counts what will run.
pub fn runs(settings: &dyn BackendSettings, level: &Level) -> bool {
    // (A scenario's character is asked separately: [`runs_scenario`].)
    level.features.within(settings.features())
        && origin_supported(settings, level).is_ok()
        && settings.check_level(level).is_ok()
}

/// Whether `settings` runs scenario `spec` of `level`: [`runs`], and its character is one the
/// configuration takes ([`BackendSettings::check_character`]).
pub(crate) fn runs_scenario(
    settings: &dyn BackendSettings,
    level: &Level,
    spec: &crate::level::ScenarioSpec,
) -> bool {
    runs(settings, level) && settings.check_character(&CharacterSpec::of(spec)).is_ok()
}

/// A controller built over one level with its characters placed: what the runner steps
/// (implemented for every [`crate::controller::Controller`]).
pub trait Backend {
    /// Short backend name, as in CSV files (`sweep`, `rapier`).
    fn name(&self) -> &'static str;
    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    fn step(&mut self, inputs: &[Input], dt: f32);
    /// The state of character `id` after the last step.
    fn state(&self, id: CharacterId) -> CharacterState;
    /// Why the backend stopped, if a step failed (an external controller's process crashed,
    /// hung, or broke the protocol): the runner ends the run there with this message. Steps
    /// after a failure do nothing. Default: never fails.
    fn failure(&self) -> Option<String> {
        None
    }
    /// The time the controller itself reports its steps took since it was built, in
    /// nanoseconds, if it reports one (an external controller measures its own step; the
    /// runner's wall clock would also count the pipe). Default: none, the runner times the
    /// steps itself.
    fn reported_ns(&self) -> Option<f64> {
        None
    }
}

/// The contact a configuration promises to keep with the level (see
/// [`BackendSettings::declared_contact`]); all lengths in tiles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DeclaredContact {
    /// Gap kept to obstacles along their normal: Rapier's `offset` ("must not be zero"), 0 for
    /// a controller that snaps flush.
    pub gap: f32,
    /// Overlap tolerated before a contact counts: the sweep's epsilon (the seed's "overlap
    /// tolerance").
    pub overlap_tolerance: f32,
    /// How far a rest may sit from `gap`, along the normal, and still keep the promise:
    /// Rapier's normal nudge (1e-4 tiles by default), which it adds after each cast hit, so its
    /// rest settles between the offset and one nudge beyond; the sweep's epsilon.
    pub gap_tolerance: f32,
    /// How far the character's shape may overhang into a slope, vertically: the seed's
    /// centre-column rule stands a box on the surface under its centre, so its corner may be
    /// half its width times the climb gradient inside a walkable ramp. The metrics allow no
    /// more: into a ramp, at most this overhang's depth along the normal of a ramp at the climb
    /// limit; into a flat top that continues the ground, this overhang (a box standing at the
    /// foot of a too-steep slope is charged for the part of it deeper inside).
    pub slope_overhang: f32,
    /// Half-width of a flat foot the controller stands on, in tiles: on a slope it stands on
    /// the highest surface under the foot (Box2D's segment pogo, 0.75 capsule radius either
    /// side, rests on its uphill end), so its feet are above the surface under their centre by
    /// design; 0 for a controller that stands by its shape or its centre.
    pub stance_half_width: f32,
    /// How far below the ground's top the controller's feet rest by design, vertically, in
    /// tiles: Box2D's pogo spring, fed gravity every step as the sample feeds it, settles where
    /// its push balances gravity (a sag set by gravity, the step and the spring); 0 for a
    /// controller that stands on its contact.
    pub stance_sink: f32,
    /// Subpixels per tile to which the controller rounds the surface height under its centre
    /// (integer positions: up to the next subpixel, [`crate::level::round_height_up`]); 0 for a
    /// controller that stands on the exact surface.
    pub surface_grid: u32,
}

impl DeclaredContact {
    /// The height at which the controller declares it stands on a surface at height `h`
    /// (tiles): `h` itself, or `h` rounded the controller's way onto its grid.
    pub fn stance_height(&self, h: f32) -> f32 {
        match self.surface_grid {
            0 => h,
            n => (crate::level::round_height_up(h, n as i64) as f64 / n as f64) as f32,
        }
    }
}

/// What a configuration declares it can do beyond the level features it models
/// ([`Features`]): facts from its documentation that the built-in scenarios do not measure,
/// shown beside the measurements so a game profile that needs one of them reads the
/// declaration instead of a guess.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Capabilities {
    /// It pushes dynamic rigid bodies it walks into (Rapier's
    /// `solve_character_collision_impulses`). No built-in level has a dynamic body, so this is
    /// declared, not measured. Default: false.
    pub pushes_bodies: bool,
    /// Its positions lie on a fixed grid (whole pixels or fractions of a tile), so a rest
    /// height is exact by construction. Default: false.
    pub integer_positions: bool,
    /// Its documentation promises bit-identical results across machines and platforms (the
    /// harness itself checks only the same machine: the same inputs give bit-identical
    /// traces). Default: false.
    pub cross_platform_determinism: bool,
    /// It declares that it carries no rider: a moving platform moves it only through collision
    /// (Box2D's Mover sample, "carries no rider"), so `platbench hunt` does not hold it to the
    /// carry invariant. Default: false (a platform carries its rider).
    pub no_rider_carry: bool,
    /// It declares no climb limit: it walks up any slope (Box2D's Mover sample, "no slope
    /// limit"), so `platbench hunt` does not hold it to the climb invariant. Default: false
    /// (it keeps `max_climb_angle`).
    pub no_climb_limit: bool,
}

/// The floating-point type a configuration keeps world positions in: what decides how far from
/// the world's origin it can place a level before a position's spacing swallows a step.
/// Whatever the precision, [`CharacterState`] and the traces are in level coordinates (f32, a
/// few hundred tiles at most), so an f64 configuration keeps its precision in what it reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Precision {
    /// `f32` world coordinates (rapier2d, parry2d, Box2D, the sweep's float mode).
    #[default]
    F32,
    /// `f64` world coordinates (rapier2d-f64 and parry2d-f64; the sweep's double mode).
    F64,
}

impl Precision {
    /// Both precisions, f32 first.
    pub const ALL: [Precision; 2] = [Precision::F32, Precision::F64];

    /// `f32` or `f64`, as in `--precision` and configuration labels.
    pub fn label(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }

    /// The precision a label of [`Precision::label`] names.
    pub fn from_label(label: &str) -> Option<Precision> {
        Self::ALL.into_iter().find(|p| p.label() == label)
    }

    /// The spacing of stored positions at world coordinate `x` (tiles): the distance from |x| to
    /// the next larger value of this type, the smallest move a position there can make.
    pub fn spacing(self, x: f64) -> f64 {
        match self {
            Precision::F32 => {
                let x = (x as f32).abs();
                (f32::from_bits(x.to_bits() + 1) - x) as f64
            }
            Precision::F64 => {
                let x = x.abs();
                f64::from_bits(x.to_bits() + 1) - x
            }
        }
    }

    /// A point `local` (level coordinates, tiles) as a backend of this precision places it in the
    /// world at `origin` (an f32 backend at `origin` rounded to the nearest f32, as
    /// [`Level::origin_f32`]) and reads it back in level coordinates: rounded to this type's
    /// spacing at the world position.
    pub fn placed(self, local: glam::DVec2, origin: glam::DVec2) -> glam::DVec2 {
        match self {
            Precision::F32 => {
                let o = origin.as_vec2();
                ((local.as_vec2() + o) - o).as_dvec2()
            }
            Precision::F64 => (local + origin) - origin,
        }
    }
}

/// Level geometry a backend built once and shares between the configurations and scenarios a
/// [`crate::scenario::Runner`] runs on one level (Rapier's colliders, built once per collider
/// building whatever the character shape). Entries are keyed by a string the backend chooses
/// (prefix it with the backend's name) and hold any type.
#[derive(Default)]
pub struct SharedGeometry {
    entries: Vec<(String, std::rc::Rc<dyn std::any::Any>)>,
}

impl SharedGeometry {
    /// The entry under `key`, built by `build` the first time it is asked for. An entry of
    /// another type under the same key is replaced.
    pub fn get_or_build<T: 'static>(
        &mut self,
        key: &str,
        build: impl FnOnce() -> T,
    ) -> std::rc::Rc<T> {
        if let Some((_, e)) = self.entries.iter().find(|(k, _)| k == key) {
            if let Ok(t) = e.clone().downcast::<T>() {
                return t;
            }
        }
        let t = std::rc::Rc::new(build());
        self.entries.retain(|(k, _)| k != key);
        self.entries.push((key.to_string(), t.clone()));
        t
    }
}

/// One configuration of a backend: its settings, and what the harness needs to know of them
/// to build it, skip the levels it does not model and score it fairly. A configuration is held
/// as `Arc<dyn BackendSettings>` in [`crate::config::RunConfig`]. Implemented for every
/// [`crate::controller::Controller`] (whose methods document these); implement that instead.
pub trait BackendSettings: std::fmt::Debug + Send + Sync + 'static {
    /// The backend's short name, as in CSV files (the name of its [`crate::controller::BackendKind`]).
    fn backend(&self) -> &'static str;
    /// The character's collision shape in this configuration.
    fn shape(&self) -> CharacterShape;
    /// The level features this configuration models.
    fn features(&self) -> Features;
    /// Whether this configuration models `level` (its features, and
    /// [`BackendSettings::check_level`]). A level it does not model is skipped by the harness
    /// before anything is built, so a run can count what it will run beforehand.
    fn supports(&self, level: &Level) -> bool;
    /// Why this configuration refuses `level` beyond its features, if it does.
    fn check_level(&self, level: &Level) -> Result<(), BackendError>;
    /// Why this configuration refuses `character`, if it does.
    fn check_character(&self, character: &CharacterSpec) -> Result<(), BackendError>;
    /// The contact this configuration declares it keeps, for a character of outer `size`
    /// (tiles) with climb limit `max_climb_angle` (radians): what its documentation promises,
    /// so a metric can score it on keeping that promise.
    fn declared_contact(&self, size: Vec2, max_climb_angle: f32) -> DeclaredContact;
    /// The contact declared for a run with motion `params` stepped by `dt` seconds (a substep
    /// where the run substeps): [`BackendSettings::declared_contact`], unless the promise
    /// depends on the motion (Box2D's pogo rests sunk by a sag set by gravity and the step).
    fn declared_contact_in(&self, size: Vec2, params: &MotionParams, dt: f32) -> DeclaredContact;
    /// The penetration `platbench stress` holds this configuration to for a character of outer
    /// `size` (tiles): its own contact tolerance.
    fn contact_tolerance(&self, size: Vec2) -> f64;
    /// The outer size of the box the configuration really moves for a character of requested
    /// `size` (tiles); the metrics measure that box. Default: `size`.
    fn moved_size(&self, size: Vec2) -> Vec2;
    /// The overlap tolerance (tiles) this configuration has, if it has one that `--epsilon` and
    /// the stress's epsilon dimension may vary. Default: none.
    fn epsilon(&self) -> Option<f32>;
    /// This configuration with its overlap tolerance set to `epsilon` (tiles), if it has one.
    fn with_epsilon(&self, epsilon: f32) -> Option<std::sync::Arc<dyn BackendSettings>>;
    /// The precision this configuration keeps world positions in. Default: f32.
    fn precision(&self) -> Precision;
    /// What this configuration declares it can do beyond its features. Default: nothing.
    fn capabilities(&self) -> Capabilities;
    /// How far from the world's origin this configuration places a level, in tiles on each axis
    /// (a level farther out is refused, [`origin_supported`]). Default: by
    /// [`BackendSettings::precision`], [`crate::limits::MAX_F32_ORIGIN`] in f32 (beyond it an
    /// f32 position moves in whole tiles), [`crate::limits::MAX_ORIGIN`] in f64 (every origin a
    /// level can have).
    fn max_origin(&self) -> f64;
    /// How far from the world's origin everything of a level placed by this configuration must
    /// lie, in tiles on each axis ([`Level::reach`]: its tile faces and its platforms' paths), if
    /// the configuration is exact only that far (a level reaching farther is refused,
    /// [`origin_supported`]). Default: none (the origin's bound, [`BackendSettings::max_origin`],
    /// is the only one).
    fn max_reach(&self) -> Option<f64>;
    /// This configuration built in `precision`, if it offers that precision besides its own
    /// (`None` otherwise: a caller keeps the configuration itself for its own precision).
    /// Default: none.
    fn with_precision(&self, precision: Precision) -> Option<std::sync::Arc<dyn BackendSettings>>;
    /// Builds the backend over `level` with `params` and `characters` placed, reusing geometry
    /// from `shared` where another configuration already built it.
    fn build(
        &self,
        level: &Level,
        params: &MotionParams,
        characters: &[CharacterSpec],
        shared: &mut SharedGeometry,
    ) -> Result<Box<dyn Backend>, BackendError>;
    /// The settings as `Any`, for a caller that knows the concrete type.
    fn as_any(&self) -> &dyn std::any::Any;
    /// Whether `other` is the same configuration (same backend, equal settings).
    fn same_as(&self, other: &dyn BackendSettings) -> bool;
}

impl PartialEq for dyn BackendSettings {
    fn eq(&self, other: &Self) -> bool {
        self.same_as(other)
    }
}

/// Which of a kind's configurations the report's replay of a scenario shows by default (the
/// reader can pick any other).
#[derive(Clone, Debug, PartialEq)]
pub enum ShownByDefault {
    /// These configuration labels, whatever they measure: the reference every other kind is
    /// watched against.
    Listed(Vec<&'static str>),
    /// The kind's best and worst configuration on the scenario by the error score of its metrics
    /// ([`crate::tradeoff::error_score`]): the range a user of that kind can expect.
    BestAndWorst,
}
