//! The runner: a scenario (level + spawn + input script + duration + dt) run on one backend
//! configuration, yielding a [`Trace`].

use crate::backend::{Backend, BackendError, BackendSettings, CharacterSpec, SharedGeometry};
use crate::level::{Level, ScenarioSpec};
use crate::motion::{Input, MotionParams};
use crate::registry::Registry;
use std::sync::Arc;

pub use crate::backend::DeclaredContact;
use crate::shape::CharacterShape;
use crate::trace::{Trace, TraceRow};

/// Which controller to run, with its settings: any backend's [`BackendSettings`].
pub type BackendConfig = Arc<dyn BackendSettings>;

/// One column of a comparison: a backend configuration and the motion parameters it runs with.
#[derive(Clone, Debug)]
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

impl PartialEq for RunConfig {
    fn eq(&self, other: &Self) -> bool {
        self.label == other.label
            && self.backend.same_as(other.backend.as_ref())
            && self.params == other.params
            && self.substeps == other.substeps
    }
}

impl RunConfig {
    /// A configuration of `settings` labelled `label`, with the default motion parameters and
    /// one step per frame.
    pub fn new(label: impl Into<String>, settings: impl BackendSettings) -> Self {
        RunConfig {
            label: label.into(),
            backend: Arc::new(settings),
            params: MotionParams::default(),
            substeps: 1,
        }
    }

    /// The character's collision shape in this configuration.
    pub fn shape(&self) -> CharacterShape {
        self.backend.shape()
    }

    /// The built-in comparison set: every configuration of [`Registry::builtin`], in order.
    pub fn builtin_set() -> Vec<RunConfig> {
        Registry::builtin().builtin_configs()
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
/// between configurations and scenarios (see [`SharedGeometry`]).
pub struct Runner<'a> {
    level: &'a Level,
    shared: SharedGeometry,
}

impl<'a> Runner<'a> {
    /// A runner for `level` with nothing built yet.
    pub fn new(level: &'a Level) -> Self {
        Runner {
            level,
            shared: SharedGeometry::default(),
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
        crate::backend::origin_supported(&*run.backend, self.level)?;
        run.backend.build(self.level, params, &mut self.shared)
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
