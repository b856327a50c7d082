//! The runner: a scenario (level + spawn + input script + duration + dt) run on one backend
//! configuration, yielding a [`Trace`].

use crate::backend::{Backend, BackendError, CharacterSpec};
use crate::level::{Level, ScenarioSpec};
use crate::motion::{Input, JumpMode, MotionParams};
use crate::rapier::{ColliderBuilding, RapierBackend, RapierConfig};
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

/// One column of a comparison: a backend configuration and the motion parameters it runs with.
#[derive(Clone, Debug, PartialEq)]
pub struct RunConfig {
    /// Label of this configuration in tables and CSV files (`config` column).
    pub label: String,
    /// The backend and its settings.
    pub backend: BackendConfig,
    /// Motion parameters (scenarios may override some of them).
    pub params: MotionParams,
}

impl RunConfig {
    /// The default sweep configuration.
    pub fn sweep_default() -> Self {
        RunConfig {
            label: "default".into(),
            backend: BackendConfig::Sweep(SweepConfig::default()),
            params: MotionParams::default(),
        }
    }

    /// Rapier with its default settings and the given collider building.
    pub fn rapier(colliders: ColliderBuilding) -> Self {
        let config = RapierConfig {
            colliders,
            ..Default::default()
        };
        RunConfig {
            label: config.label(),
            backend: BackendConfig::Rapier(config),
            params: MotionParams::default(),
        }
    }

    /// The built-in comparison set: the default sweep; the sweep with the seed's continuous
    /// jump formula, so the two jump modes' apex errors stand side by side; and Rapier with
    /// one collider per tile and with merged colliders.
    pub fn builtin_set() -> Vec<RunConfig> {
        let continuous = RunConfig {
            label: "jump=continuous".into(),
            params: MotionParams {
                jump_mode: JumpMode::Continuous,
                ..Default::default()
            },
            ..Self::sweep_default()
        };
        vec![
            Self::sweep_default(),
            continuous,
            Self::rapier(ColliderBuilding::PerTile),
            Self::rapier(ColliderBuilding::Merged),
        ]
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

/// Runs one scenario on one configuration. Row 0 of the trace is the spawn state; row `k` is
/// the state after `k` steps.
pub fn run_scenario(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
) -> Result<Trace, BackendError> {
    let params = effective_params(&run.params, spec);
    let mut backend = run.backend.build(level, &params)?;
    let id = backend.add_character(CharacterSpec {
        spawn: spec.spawn,
        size: spec.size,
        velocity: spec.velocity,
    });
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
        backend.step(&input, spec.dt);
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
