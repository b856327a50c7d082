//! The runner: a scenario (level + spawn + input script + duration + dt) run on one backend
//! configuration, yielding a [`Trace`].

use crate::backend::{Backend, BackendError, CharacterSpec};
use crate::level::{Level, ScenarioSpec};
use crate::motion::{Input, JumpMode, MotionParams};
use glam::Vec2;
use std::rc::Rc;

use crate::rapier::{ColliderBuilding, GroundedMove, RapierBackend, RapierConfig, StaticWorld};
use crate::shape::CharacterShape;
use crate::sweep::{SweepBackend, SweepConfig};
use crate::trace::{Trace, TraceRow};

/// Which controller to run, with its settings.
#[derive(Clone, Debug, PartialEq)]
pub enum BackendConfig {
    /// The sweep-and-snap controller.
    Sweep(SweepConfig),
    /// rapier2d's kinematic character controller.
    Rapier(RapierConfig),
}

impl BackendConfig {
    /// The backend's short name, as in CSV files.
    pub fn name(&self) -> &'static str {
        match self {
            BackendConfig::Sweep(_) => "sweep",
            BackendConfig::Rapier(_) => "rapier",
        }
    }

    /// The character's collision shape on this backend.
    pub fn shape(&self) -> CharacterShape {
        match self {
            BackendConfig::Sweep(_) => CharacterShape::Cuboid,
            BackendConfig::Rapier(c) => c.shape,
        }
    }

    /// Whether this backend models `level`: its features, and for integer positions its
    /// origin. A level it does not model is refused by its build (and skipped by the CLI), so a
    /// run can count what it will run beforehand.
    pub fn supports(&self, level: &Level) -> bool {
        let supported = match self {
            BackendConfig::Sweep(c) => match c.positions {
                crate::sweep::Positions::Float => SweepBackend::SUPPORTED,
                crate::sweep::Positions::Integer { per_tile } => {
                    if crate::sweep::grid::Grid::new(per_tile, level.origin, &level.name).is_err() {
                        return false;
                    }
                    crate::sweep::INTEGER_SUPPORTED
                }
            },
            BackendConfig::Rapier(_) => RapierBackend::SUPPORTED,
        };
        crate::backend::require_supported(self.name(), "", level.features, supported).is_ok()
    }

    /// The contact this configuration declares it keeps, for a character of outer `size`
    /// (tiles) with climb limit `max_climb_angle` (radians): what its documentation promises,
    /// so a metric can score it on keeping that promise.
    pub fn declared_contact(&self, size: Vec2, max_climb_angle: f32) -> DeclaredContact {
        match self {
            BackendConfig::Sweep(c) => match c.positions {
                crate::sweep::Positions::Float => DeclaredContact {
                    gap: 0.0,
                    overlap_tolerance: c.epsilon,
                    gap_tolerance: c.epsilon,
                    slope_overhang: size.x * 0.5 * max_climb_angle.tan(),
                    surface_grid: 0,
                },
                // No gap and no tolerance (it snaps exactly), and the seed's centre-column stance
                // on slopes for the box it really moves.
                crate::sweep::Positions::Integer { per_tile } => DeclaredContact {
                    slope_overhang: self.moved_size(size).x * 0.5 * max_climb_angle.tan(),
                    surface_grid: per_tile,
                    ..DeclaredContact::default()
                },
            },
            BackendConfig::Rapier(c) => DeclaredContact {
                gap: c.offset.eval(size.y),
                // Rapier adds its normal nudge along the contact normal after each cast hit, so
                // a rest settles at the offset or up to one nudge further out.
                gap_tolerance: c.normal_nudge_factor,
                ..DeclaredContact::default()
            },
        }
    }

    /// The outer size of the box the configuration really moves for a character of requested
    /// `size` (tiles): integer positions round it up to whole subpixels (0.8 x 0.9 tiles at 32
    /// per tile is 26 x 29 subpixels, 0.8125 x 0.90625 tiles), so the metrics measure that box.
    pub fn moved_size(&self, size: Vec2) -> Vec2 {
        match self {
            BackendConfig::Sweep(SweepConfig {
                positions: crate::sweep::Positions::Integer { per_tile },
                ..
            }) => {
                let n = crate::sweep::grid::subpixel_size(size, *per_tile as i64);
                n.as_vec2() / *per_tile as f32
            }
            _ => size,
        }
    }

    /// Builds the backend over `level`.
    pub fn build(
        &self,
        level: &Level,
        params: &MotionParams,
    ) -> Result<Box<dyn Backend>, BackendError> {
        match self {
            BackendConfig::Sweep(c) => Ok(Box::new(SweepBackend::new(
                level,
                params.clone(),
                c.clone(),
            )?)),
            BackendConfig::Rapier(c) => Ok(Box::new(RapierBackend::new(
                level,
                params.clone(),
                c.clone(),
            )?)),
        }
    }
}

/// The contact a configuration promises to keep with the level (see
/// [`BackendConfig::declared_contact`]); all lengths in tiles.
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
    /// half its width times the climb gradient inside a walkable ramp.
    pub slope_overhang: f32,
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

/// One column of a comparison: a backend configuration and the motion parameters it runs with.
#[derive(Clone, Debug, PartialEq)]
pub struct RunConfig {
    /// Label of this configuration in tables and CSV files (`config` column).
    pub label: String,
    /// The backend and its settings.
    pub backend: BackendConfig,
    /// Motion parameters (scenarios may override some of them).
    pub params: MotionParams,
    /// Steps the backend takes per frame, each of `dt / substeps` (1: one step per frame).
    /// Traces keep one row per frame.
    pub substeps: u32,
}

impl RunConfig {
    /// The default sweep configuration.
    pub fn sweep_default() -> Self {
        RunConfig {
            label: "default".into(),
            backend: BackendConfig::Sweep(SweepConfig::default()),
            params: MotionParams::default(),
            substeps: 1,
        }
    }

    /// The sweep on integer positions, `per_tile` subpixels per tile.
    pub fn sweep_integer(per_tile: u32) -> Self {
        RunConfig {
            label: format!("positions=integer/{per_tile}"),
            backend: BackendConfig::Sweep(SweepConfig {
                positions: crate::sweep::Positions::Integer { per_tile },
                ..Default::default()
            }),
            params: MotionParams::default(),
            substeps: 1,
        }
    }

    /// The character's collision shape in this configuration.
    pub fn shape(&self) -> CharacterShape {
        self.backend.shape()
    }

    /// Rapier with its default settings, the given collider building and character shape.
    pub fn rapier(colliders: ColliderBuilding, shape: CharacterShape) -> Self {
        Self::rapier_with(RapierConfig {
            colliders,
            shape,
            ..Default::default()
        })
    }

    /// Rapier with `config`, labelled by [`RapierConfig::label`].
    pub fn rapier_with(config: RapierConfig) -> Self {
        RunConfig {
            label: config.label(),
            backend: BackendConfig::Rapier(config),
            params: MotionParams::default(),
            substeps: 1,
        }
    }

    /// The built-in comparison set: the default sweep; the sweep with the seed's continuous
    /// jump formula, so the two jump modes' apex errors stand side by side; the sweep on integer
    /// positions (32 subpixels per tile; levels it does not model are skipped); and Rapier with
    /// every character shape its users pick, each on one collider per tile and on merged
    /// colliders; and per shape, Rapier as its docs and examples advise for a character that
    /// gets stuck: no vertical move while grounded except on a moving platform
    /// ([`GroundedMove::NoneExceptOnPlatforms`], the feed of the official bevy_rapier
    /// character example), on per-tile colliders, which `examples/rapier_setups.rs` measured
    /// to leave the fewest stuck frames for every shape. (Rapier's docs also advise a larger
    /// offset; the same command measured it to help no shape as much, and to leave the merged
    /// cuboid stuck.)
    pub fn builtin_set() -> Vec<RunConfig> {
        let continuous = RunConfig {
            label: "jump=continuous".into(),
            params: MotionParams {
                jump_mode: JumpMode::Continuous,
                ..Default::default()
            },
            ..Self::sweep_default()
        };
        let mut set = vec![Self::sweep_default(), continuous, Self::sweep_integer(32)];
        for shape in CharacterShape::ALL {
            for building in [ColliderBuilding::PerTile, ColliderBuilding::Merged] {
                set.push(Self::rapier(building, shape));
            }
        }
        for shape in CharacterShape::ALL {
            set.push(Self::rapier_with(RapierConfig {
                shape,
                grounded_move: GroundedMove::NoneExceptOnPlatforms,
                ..Default::default()
            }));
        }
        set
    }
}

/// The run's motion parameters with the scenario's overrides applied.
pub fn effective_params(base: &MotionParams, spec: &ScenarioSpec) -> MotionParams {
    let mut p = base.clone();
    let o = &spec.motion;
    if let Some(v) = o.jump_height {
        p.jump_height = v;
    }
    if let Some(v) = o.run_speed {
        p.run_speed = v;
    }
    if let Some(v) = o.gravity {
        p.gravity = v;
    }
    p
}

/// Number of steps a scenario runs.
pub fn step_count(spec: &ScenarioSpec) -> usize {
    (spec.duration / spec.dt).round() as usize
}

/// The held buttons for each step `0..step_count`: an event at time `t` takes effect from the
/// step that starts at frame `round(t / dt)`.
pub fn input_script(spec: &ScenarioSpec) -> Vec<Input> {
    let n = step_count(spec);
    let mut out = Vec::with_capacity(n);
    let mut cur = Input::default();
    let mut events = spec.inputs.iter().peekable();
    for k in 0..n {
        while let Some(e) = events.next_if(|e| (e.t / spec.dt).round() as usize <= k) {
            let set = |b: &mut bool, v: Option<bool>| {
                if let Some(v) = v {
                    *b = v;
                }
            };
            set(&mut cur.left, e.left);
            set(&mut cur.right, e.right);
            set(&mut cur.up, e.up);
            set(&mut cur.down, e.down);
            set(&mut cur.jump, e.jump);
        }
        out.push(cur);
    }
    out
}

/// Runs scenarios of one level, building each backend's level geometry once and sharing it
/// between configurations and scenarios (Rapier's colliders are built once per collider
/// building, whatever the character shape).
pub struct Runner<'a> {
    level: &'a Level,
    rapier_worlds: Vec<(ColliderBuilding, Rc<StaticWorld>)>,
}

impl<'a> Runner<'a> {
    /// A runner for `level` with nothing built yet.
    pub fn new(level: &'a Level) -> Self {
        Runner {
            level,
            rapier_worlds: Vec::new(),
        }
    }

    /// The level this runner runs.
    pub fn level(&self) -> &'a Level {
        self.level
    }

    /// Builds the backend of `run` with motion parameters `params`, reusing built geometry.
    pub fn build(
        &mut self,
        run: &RunConfig,
        params: &MotionParams,
    ) -> Result<Box<dyn Backend>, BackendError> {
        match &run.backend {
            BackendConfig::Rapier(c) => {
                let world = match self.rapier_worlds.iter().find(|(b, _)| *b == c.colliders) {
                    Some((_, w)) => w.clone(),
                    None => {
                        let w = Rc::new(StaticWorld::new(self.level, c.colliders));
                        self.rapier_worlds.push((c.colliders, w.clone()));
                        w
                    }
                };
                Ok(Box::new(RapierBackend::with_world(
                    self.level,
                    world,
                    params.clone(),
                    c.clone(),
                )?))
            }
            other => other.build(self.level, params),
        }
    }

    /// Runs one scenario of the level on one configuration (see [`run_scenario`]).
    pub fn run(&mut self, spec: &ScenarioSpec, run: &RunConfig) -> Result<Trace, BackendError> {
        let params = effective_params(&run.params, spec);
        let backend = self.build(run, &params)?;
        drive(self.level, spec, run, backend)
    }
}

/// Cost of one character-step of `spec` on `run`, in nanoseconds: the scenario's steps timed in
/// process (building the backend and recording the trace are not timed), the minimum over
/// `repeats` runs, which is the least disturbed by the rest of the machine.
pub fn time_scenario(
    runner: &mut Runner,
    spec: &ScenarioSpec,
    run: &RunConfig,
    repeats: usize,
) -> Result<f64, BackendError> {
    check_dt(spec)?;
    let params = effective_params(&run.params, spec);
    let script = input_script(spec);
    let mut best = f64::INFINITY;
    for _ in 0..repeats.max(1) {
        let mut backend = runner.build(run, &params)?;
        backend.add_character(CharacterSpec {
            spawn: spec.spawn,
            size: spec.size,
            velocity: spec.velocity,
        })?;
        let mut input = [Input::default()];
        let start = std::time::Instant::now();
        for i in &script {
            input[0] = *i;
            for _ in 0..run.substeps.max(1) {
                backend.step(&input, spec.dt / run.substeps.max(1) as f32);
            }
        }
        let ns = start.elapsed().as_nanos() as f64 / script.len().max(1) as f64;
        best = best.min(ns);
    }
    Ok(best)
}

/// Runs one scenario on one configuration. Row 0 of the trace is the spawn state; row `k` is
/// the state after `k` steps.
pub fn run_scenario(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
) -> Result<Trace, BackendError> {
    Runner::new(level).run(spec, run)
}

/// Steps `backend` through the scenario's script and records the trace.
fn drive(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    mut backend: Box<dyn Backend>,
) -> Result<Trace, BackendError> {
    check_dt(spec)?;
    let id = backend.add_character(CharacterSpec {
        spawn: spec.spawn,
        size: spec.size,
        velocity: spec.velocity,
    })?;
    let script = input_script(spec);
    let mut rows = Vec::with_capacity(script.len() + 1);
    let initial = crate::backend::CharacterState {
        pos: spec.spawn,
        vel: spec.velocity,
        ..Default::default()
    };
    rows.push(TraceRow::from_state(0, 0.0, id as u32, &initial));
    let mut input = [Input::default()];
    for (k, step_input) in script.iter().enumerate() {
        input[0] = *step_input;
        for _ in 0..run.substeps.max(1) {
            backend.step(&input, spec.dt / run.substeps.max(1) as f32);
        }
        let frame = (k + 1) as u32;
        rows.push(TraceRow::from_state(
            frame,
            frame as f32 * spec.dt,
            id as u32,
            &backend.state(id),
        ));
    }
    Ok(Trace {
        level: level.name.clone(),
        scenario: spec.name.clone(),
        backend: backend.name().to_string(),
        config: run.label.clone(),
        rows,
    })
}

/// Refuses a time step or duration outside the ranges of [`crate::limits`]: the frames a run
/// takes (and the trace it records) are bounded before it starts.
fn check_dt(spec: &ScenarioSpec) -> Result<(), BackendError> {
    match crate::limits::check_timing(spec.duration as f64, spec.dt as f64) {
        Ok(_) => Ok(()),
        Err(message) => Err(crate::backend::invalid(
            "dt",
            message,
            "a time step 1e-6..=1 s and a duration of 1 to 10,000,000 frames (crate::limits)",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::level::InputEvent;
    use glam::Vec2;

    fn spec(inputs: Vec<InputEvent>) -> ScenarioSpec {
        ScenarioSpec {
            name: "s".into(),
            spawn: Vec2::ZERO,
            size: Vec2::ONE,
            velocity: Vec2::ZERO,
            duration: 0.1,
            dt: 0.01,
            inputs,
            motion: Default::default(),
            expect_y: None,
            ride: None,
        }
    }

    #[test]
    fn script_applies_events_from_their_frame() {
        let s = spec(vec![
            InputEvent {
                t: 0.02,
                right: Some(true),
                ..Default::default()
            },
            InputEvent {
                t: 0.05,
                right: Some(false),
                jump: Some(true),
                ..Default::default()
            },
        ]);
        let script = input_script(&s);
        assert_eq!(script.len(), 10);
        let rights: Vec<bool> = script.iter().map(|i| i.right).collect();
        assert_eq!(
            rights,
            [false, false, true, true, true, false, false, false, false, false]
        );
        assert!(script[5].jump && !script[4].jump);
    }
}
