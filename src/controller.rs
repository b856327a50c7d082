//! The one trait a controller implements to be compared: [`Controller`].
//!
//! A controller is its settings: a plain struct with public fields and a `Default`, as Rapier's
//! `KinematicCharacterController` is. Over a level it builds a [`Controller::Mover`] (whatever
//! it keeps while it runs: its colliders, its characters) and steps it. Five items are
//! required (its name, the level features it models, how to build over a level, a step and a
//! character's state); everything else the harness asks has a default that a richer controller
//! overrides. One line registers it: `Registry::builtin().with::<MyController>()`.
//!
//! The harness drives every controller through the type-erased views
//! [`crate::backend::BackendSettings`] and [`crate::backend::Backend`], which this module
//! implements for every [`Controller`]; nobody implements those by hand.

use std::marker::PhantomData;

use glam::Vec2;

use crate::backend::{
    Backend, BackendError, BackendSettings, Capabilities, CharacterId, CharacterSpec,
    CharacterState, DeclaredContact, Precision, SharedGeometry, ShownByDefault,
};
use crate::config::RunConfig;
use crate::config::Setting;
use crate::level::{Features, Level};
use crate::motion::{Input, MotionParams};
use crate::shape::CharacterShape;

/// What a controller is built over: the level, the motion parameters of the run, the characters
/// to place (already checked: finite spawns and velocities, positive sizes) and geometry shared
/// with other configurations on the same level.
pub struct Setup<'a> {
    /// The level, in level coordinates (tiles); [`Level::origin`] is where a controller places it
    /// in its world.
    pub level: &'a Level,
    /// Motion parameters of the run (speeds, gravity, jump height, climb limit).
    pub params: &'a MotionParams,
    /// The characters, in id order: character `k` gets `inputs[k]` and is read as `state(k)`.
    pub characters: &'a [CharacterSpec],
    /// Geometry built once per level and shared by the configurations and scenarios run on it
    /// (optional: a controller may build its own every time).
    pub shared: &'a mut SharedGeometry,
}

/// A character controller platbench can run and score.
///
/// Implement it on your controller's settings struct. A minimal mover that stands on the
/// lowest floor of the level (no walls, no slopes, nothing else):
///
/// ```
/// use platbench::backend::{BackendError, CharacterId, CharacterState};
/// use platbench::controller::{Controller, Setup};
/// use platbench::level::Features;
/// use platbench::motion::{Contacts, Input, MotionParams, MotionState};
///
/// /// Floats `hover` tiles above the level's floor.
/// #[derive(Clone, Debug, Default, PartialEq)]
/// pub struct Floater {
///     /// Height above the floor, in tiles.
///     pub hover: f32,
/// }
///
/// pub struct FloaterMover {
///     params: MotionParams,
///     floor: f32,
///     chars: Vec<(glam::Vec2, MotionState)>,
/// }
///
/// impl Controller for Floater {
///     type Mover = FloaterMover;
///     const NAME: &'static str = "floater";
///
///     fn features(&self) -> Features {
///         Features::default() // solid tiles only: levels with more are skipped for it
///     }
///
///     fn build(&self, setup: Setup<'_>) -> Result<FloaterMover, BackendError> {
///         Ok(FloaterMover {
///             params: setup.params.clone(),
///             floor: 1.0 + self.hover,
///             chars: setup
///                 .characters
///                 .iter()
///                 .map(|c| (c.spawn, MotionState::with_velocity(c.velocity)))
///                 .collect(),
///         })
///     }
///
///     fn step(&self, m: &mut FloaterMover, inputs: &[Input], dt: f32) {
///         for (k, (pos, motion)) in m.chars.iter_mut().enumerate() {
///             let input = inputs.get(k).copied().unwrap_or_default();
///             *pos += motion.integrate(&m.params, &input, dt);
///             let ground = pos.y <= m.floor;
///             pos.y = pos.y.max(m.floor);
///             let contacts = Contacts { ground, ..Default::default() };
///             motion.apply_contacts(&m.params, &input, contacts);
///         }
///     }
///
///     fn state(&self, m: &FloaterMover, id: CharacterId) -> CharacterState {
///         let (pos, motion) = &m.chars[id];
///         CharacterState {
///             pos: *pos,
///             vel: motion.vel,
///             grounded: motion.grounded,
///             ..Default::default()
///         }
///     }
/// }
///
/// // One line puts it beside the built-in controllers:
/// let registry = platbench::registry::Registry::builtin().with::<Floater>();
/// assert!(registry.get("floater").is_some());
/// ```
pub trait Controller:
    Clone + std::fmt::Debug + PartialEq + Default + Send + Sync + 'static
{
    /// What the controller keeps while it runs over a level (colliders, characters).
    type Mover: 'static;
    /// Short name, as in CSV files, tables and `--backend` (lower case, no spaces).
    const NAME: &'static str;

    /// The level features this configuration models. A level with any other is skipped for it
    /// before anything is built (never run half-modelled).
    fn features(&self) -> Features;
    /// Builds the controller's state over `setup.level` with `setup.characters` placed.
    fn build(&self, setup: Setup<'_>) -> Result<Self::Mover, BackendError>;
    /// Advances every character by `dt` seconds; `inputs[id]` is character `id`'s input.
    fn step(&self, mover: &mut Self::Mover, inputs: &[Input], dt: f32);
    /// The state of character `id` after the last step, in level coordinates.
    fn state(&self, mover: &Self::Mover, id: CharacterId) -> CharacterState;

    /// One line on what it is, for `--help` and the report. Default: none.
    fn description() -> &'static str {
        ""
    }
    /// The configurations it adds to the built-in comparison, with their labels. Default: its
    /// `Default` settings, labelled `default`.
    fn configs() -> Vec<RunConfig> {
        vec![RunConfig::new("default", Self::default())]
    }
    /// The configurations `platbench stress` checks. Default: the first of
    /// [`Controller::configs`].
    fn stress_configs() -> Vec<RunConfig> {
        Self::configs().into_iter().take(1).collect()
    }
    /// The settings `platbench sweep` measures. Default: [`Controller::configs`], each at its
    /// scenarios' own time step.
    fn tradeoff_settings() -> Vec<Setting> {
        Self::configs()
            .into_iter()
            .map(|run| Setting {
                label: run.label.clone(),
                run,
                dt: None,
            })
            .collect()
    }
    /// The character shapes it offers (`--shape` picks among them). Default: the shapes of
    /// [`Controller::configs`].
    fn shapes() -> Vec<CharacterShape> {
        let mut shapes: Vec<CharacterShape> = Vec::new();
        for run in Self::configs() {
            if !shapes.contains(&run.shape()) {
                shapes.push(run.shape());
            }
        }
        shapes
    }
    /// Configurations with a colour of their own in the report's replays: `(config label, CSS
    /// colour)`. Default: none (they get palette colours).
    fn drawn() -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
    /// Which of its configurations a replay shows before the reader picks. Default: the best
    /// and the worst on that scenario.
    fn shown_by_default() -> ShownByDefault {
        ShownByDefault::BestAndWorst
    }
    /// Its colour in charts (a CSS colour). Default: `None`, a colour of the report's palette
    /// that no other controller has.
    fn colour() -> Option<&'static str> {
        None
    }

    /// The character's collision shape. Default: a box ([`CharacterShape::Cuboid`]).
    fn shape(&self) -> CharacterShape {
        CharacterShape::Cuboid
    }
    /// Refuses a level its features allow but this configuration still cannot run (a bound it
    /// keeps: a size, a grid that cannot hold the level), saying why; the harness asks before
    /// building, so a run's counts leave the level out. Default: none refused.
    fn check_level(&self, level: &Level) -> Result<(), BackendError> {
        let _ = level;
        Ok(())
    }
    /// Refuses a character it cannot run (a size below what it models), saying why; the harness
    /// asks before building, so a run's counts leave that scenario out. Default: none refused
    /// (the harness itself refuses a non-finite spawn or velocity and a size that is not
    /// positive).
    fn check_character(&self, character: &CharacterSpec) -> Result<(), BackendError> {
        let _ = character;
        Ok(())
    }
    /// The contact it promises to keep, for a character of outer `size` (tiles) with climb limit
    /// `max_climb_angle` (radians), so a metric scores it on keeping its own promise. Default:
    /// flush contact, no gap and no tolerance.
    fn declared_contact(&self, size: Vec2, max_climb_angle: f32) -> DeclaredContact {
        let _ = (size, max_climb_angle);
        DeclaredContact::default()
    }
    /// The contact declared for a run with `params` stepped by `dt` seconds. Default:
    /// [`Controller::declared_contact`].
    fn declared_contact_in(&self, size: Vec2, params: &MotionParams, dt: f32) -> DeclaredContact {
        let _ = dt;
        self.declared_contact(size, params.max_climb_angle)
    }
    /// The penetration `platbench stress` holds it to for a character of outer `size` (tiles).
    /// Default: the larger of its declared gap and overlap tolerance.
    fn contact_tolerance(&self, size: Vec2) -> f64 {
        let d = self.declared_contact(size, 0.0);
        d.gap.max(d.overlap_tolerance) as f64
    }
    /// The outer size of the box it really moves for a requested `size` (tiles). Default: `size`.
    fn moved_size(&self, size: Vec2) -> Vec2 {
        size
    }
    /// Its overlap tolerance (tiles), if `--epsilon` and the stress may vary one. Default: none.
    fn epsilon(&self) -> Option<f32> {
        None
    }
    /// These settings with the overlap tolerance set to `epsilon`, if it has one.
    fn with_epsilon(&self, epsilon: f32) -> Option<Self> {
        let _ = epsilon;
        None
    }
    /// The precision it keeps world positions in. Default: f32.
    fn precision(&self) -> Precision {
        Precision::F32
    }
    /// What it declares it can do beyond the level features it models (pushing dynamic bodies,
    /// positions on a grid, determinism across machines), from its documentation: shown in the
    /// capability table, never measured. Default: nothing declared.
    fn capabilities(&self) -> Capabilities {
        Capabilities::default()
    }
    /// These settings built in `precision`, if it offers that precision besides its own.
    fn with_precision(&self, precision: Precision) -> Option<Self> {
        let _ = precision;
        None
    }
    /// How far from the world's origin it places a level, in tiles on each axis. Default: by
    /// precision ([`crate::backend::max_origin_in`]).
    fn max_origin(&self) -> f64 {
        crate::backend::max_origin_in(self.precision())
    }
    /// How far from the world's origin everything of a level must lie, if it is exact only that
    /// far ([`Level::reach`]). Default: none.
    fn max_reach(&self) -> Option<f64> {
        None
    }
}

/// A controller and what it built over a level: the erased [`Backend`] the runner steps.
struct Running<C: Controller> {
    controller: C,
    mover: C::Mover,
}

impl<C: Controller> Backend for Running<C> {
    fn name(&self) -> &'static str {
        C::NAME
    }
    fn step(&mut self, inputs: &[Input], dt: f32) {
        self.controller.step(&mut self.mover, inputs, dt);
    }
    fn state(&self, id: CharacterId) -> CharacterState {
        self.controller.state(&self.mover, id)
    }
}

impl<C: Controller> BackendSettings for C {
    fn backend(&self) -> &'static str {
        C::NAME
    }
    fn shape(&self) -> CharacterShape {
        Controller::shape(self)
    }
    fn features(&self) -> Features {
        Controller::features(self)
    }
    fn supports(&self, level: &Level) -> bool {
        level.features.within(Controller::features(self)) && self.check_level(level).is_ok()
    }
    fn check_level(&self, level: &Level) -> Result<(), BackendError> {
        Controller::check_level(self, level)
    }
    fn check_character(&self, character: &CharacterSpec) -> Result<(), BackendError> {
        Controller::check_character(self, character)
    }
    fn declared_contact(&self, size: Vec2, max_climb_angle: f32) -> DeclaredContact {
        Controller::declared_contact(self, size, max_climb_angle)
    }
    fn declared_contact_in(&self, size: Vec2, params: &MotionParams, dt: f32) -> DeclaredContact {
        Controller::declared_contact_in(self, size, params, dt)
    }
    fn contact_tolerance(&self, size: Vec2) -> f64 {
        Controller::contact_tolerance(self, size)
    }
    fn moved_size(&self, size: Vec2) -> Vec2 {
        Controller::moved_size(self, size)
    }
    fn epsilon(&self) -> Option<f32> {
        Controller::epsilon(self)
    }
    fn with_epsilon(&self, epsilon: f32) -> Option<std::sync::Arc<dyn BackendSettings>> {
        Controller::with_epsilon(self, epsilon).map(|c| std::sync::Arc::new(c) as _)
    }
    fn precision(&self) -> Precision {
        Controller::precision(self)
    }
    fn capabilities(&self) -> Capabilities {
        Controller::capabilities(self)
    }
    fn max_origin(&self) -> f64 {
        Controller::max_origin(self)
    }
    fn max_reach(&self) -> Option<f64> {
        Controller::max_reach(self)
    }
    fn with_precision(&self, precision: Precision) -> Option<std::sync::Arc<dyn BackendSettings>> {
        Controller::with_precision(self, precision).map(|c| std::sync::Arc::new(c) as _)
    }
    fn build(
        &self,
        level: &Level,
        params: &MotionParams,
        characters: &[CharacterSpec],
        shared: &mut SharedGeometry,
    ) -> Result<Box<dyn Backend>, BackendError> {
        let mover = Controller::build(
            self,
            Setup {
                level,
                params,
                characters,
                shared,
            },
        )?;
        Ok(Box::new(Running {
            controller: self.clone(),
            mover,
        }))
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn same_as(&self, other: &dyn BackendSettings) -> bool {
        other.as_any().downcast_ref::<C>() == Some(self)
    }
}

/// A kind of backend: a controller the harness knows. One [`crate::registry::Registry`] lists
/// the kinds; the CLI and every command iterate it and never name a backend. Implemented for
/// every [`Controller`] type (whose functions of the same names document
/// these); register one with [`crate::registry::Registry::with`].
pub trait BackendKind: Send + Sync {
    /// The backend's short name, as in CSV files and `--backend`.
    fn name(&self) -> &'static str;
    /// One line on what it is, for `--help` and the report.
    fn description(&self) -> &'static str;
    /// The character shapes it offers (`--shape` picks among them when there is a choice).
    fn shapes(&self) -> Vec<CharacterShape>;
    /// The configurations it adds to the built-in comparison, with their labels.
    fn builtin_configs(&self) -> Vec<RunConfig>;
    /// The configurations `platbench stress` checks.
    fn stress_configs(&self) -> Vec<RunConfig>;
    /// The settings `platbench sweep` measures.
    fn tradeoff_settings(&self) -> Vec<Setting>;
    /// Configurations with a colour of their own in the report's scenario replays.
    fn drawn(&self) -> Vec<(&'static str, &'static str)>;
    /// Which of its configurations a scenario's replay shows before the reader picks others.
    fn shown_by_default(&self) -> ShownByDefault;
    /// Its own colour in charts (a CSS colour), if it has one.
    fn colour(&self) -> Option<&'static str>;
}

/// The harness's view of a [`Controller`] type as a kind of backend (what the registry lists).
pub(crate) struct Kind<C>(PhantomData<fn() -> C>);

impl<C> Kind<C> {
    pub(crate) fn new() -> Self {
        Kind(PhantomData)
    }
}

impl<C: Controller> BackendKind for Kind<C> {
    fn name(&self) -> &'static str {
        C::NAME
    }
    fn description(&self) -> &'static str {
        C::description()
    }
    fn shapes(&self) -> Vec<CharacterShape> {
        C::shapes()
    }
    fn builtin_configs(&self) -> Vec<RunConfig> {
        C::configs()
    }
    fn stress_configs(&self) -> Vec<RunConfig> {
        C::stress_configs()
    }
    fn tradeoff_settings(&self) -> Vec<Setting> {
        C::tradeoff_settings()
    }
    fn drawn(&self) -> Vec<(&'static str, &'static str)> {
        C::drawn()
    }
    fn shown_by_default(&self) -> ShownByDefault {
        C::shown_by_default()
    }
    fn colour(&self) -> Option<&'static str> {
        C::colour()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::runs;
    use crate::level::parse_level;

    /// Models solid tiles only, and refuses no level of its own accord.
    #[derive(Clone, Debug, Default, PartialEq)]
    struct Eager;

    impl Controller for Eager {
        type Mover = ();
        const NAME: &'static str = "eager";
        fn features(&self) -> Features {
            Features::NONE
        }
        fn build(&self, _: Setup<'_>) -> Result<(), BackendError> {
            Ok(())
        }
        fn step(&self, _: &mut (), _: &[Input], _: f32) {}
        fn state(&self, _: &(), _: CharacterId) -> CharacterState {
            CharacterState::default()
        }
    }

    #[test]
    fn a_level_with_a_feature_it_does_not_model_is_not_counted() {
        let level =
            |map: &str| parse_level(&format!("name = \"l\"\nmap = \"\"\"\n{map}\"\"\"\n"), "l");
        let slope = level("../\n###\n").unwrap();
        assert!(slope.features.slopes);
        assert!(!runs(&Eager, &slope));
        let flat = level("...\n###\n").unwrap();
        assert!(runs(&Eager, &flat));
    }
}
