//! The runner: a scenario (level + spawn + input script + duration + dt) run on one backend
//! configuration, yielding a [`Trace`].

use crate::backend::{Backend, BackendError, CharacterId, CharacterSpec, SharedGeometry};
use crate::config::RunConfig;
use crate::level::{Level, ScenarioSpec};
use crate::motion::{Input, InvalidParam, MotionParams};

pub use crate::backend::DeclaredContact;
use crate::trace::{Trace, TraceRow};

mod error;
use error::{failed, failed_at};
pub use error::{RunError, RunFailure};

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
/// step that starts at frame `round(t / dt)` (or, if an earlier event in the list takes effect
/// later, from that step: events apply in their order).
pub fn input_script(spec: &ScenarioSpec) -> Script {
    let n = step_count(spec);
    let mut changes: Vec<(usize, Input)> = Vec::new();
    if n > 0 {
        changes.push((0, Input::default()));
    }
    let mut cur = Input::default();
    let mut at = 0usize;
    for e in &spec.inputs {
        let step = ((e.t / spec.dt).round() as usize).max(at);
        if step >= n {
            break;
        }
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
        at = step;
        match changes.last_mut() {
            Some(last) if last.0 == step => last.1 = cur,
            _ => changes.push((step, cur)),
        }
    }
    Script { changes, len: n }
}

/// A scenario's held buttons for each of its steps, stored as the steps where they change, so
/// a script takes memory in its events, not its steps (a 100,000 s soak is 6,000,000 steps).
/// Read like a slice of [`Input`]: `script[k]`, `get`, `iter`.
#[derive(Clone, Debug, PartialEq)]
pub struct Script {
    /// `(first step, buttons held from it)`, by increasing step; the first at step 0.
    changes: Vec<(usize, Input)>,
    len: usize,
}

impl Script {
    /// Number of steps.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the script has no step.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Index in `changes` of the change in force at step `k < len`.
    fn change_at(&self, k: usize) -> usize {
        self.changes.partition_point(|c| c.0 <= k).saturating_sub(1)
    }

    /// The buttons held on step `k`, if the script has that step.
    pub fn get(&self, k: usize) -> Option<&Input> {
        (k < self.len).then(|| &self.changes[self.change_at(k)].1)
    }

    /// The buttons of every step, in order.
    pub fn iter(&self) -> ScriptIter<'_> {
        self.range(0..self.len)
    }

    /// The buttons of steps `range` (clipped to the script).
    pub fn range(&self, range: std::ops::Range<usize>) -> ScriptIter<'_> {
        let end = range.end.min(self.len);
        let k = range.start.min(end);
        ScriptIter {
            changes: &self.changes,
            k,
            end,
            c: if k < end { self.change_at(k) } else { 0 },
        }
    }

    /// The last step whose buttons satisfy `pred`, as `iter().rposition(pred)` would find it
    /// (without visiting every step).
    pub fn rposition(&self, pred: impl Fn(&Input) -> bool) -> Option<usize> {
        self.changes
            .iter()
            .enumerate()
            .rev()
            .filter(|(_, c)| c.0 < self.len)
            .find(|(_, c)| pred(&c.1))
            .map(|(i, _)| self.changes.get(i + 1).map_or(self.len, |c| c.0) - 1)
    }
}

impl std::ops::Index<usize> for Script {
    type Output = Input;

    fn index(&self, k: usize) -> &Input {
        match self.get(k) {
            Some(i) => i,
            None => panic!("step {k} of a script of {} steps", self.len),
        }
    }
}

/// The buttons of consecutive steps of a [`Script`].
#[derive(Clone, Debug)]
pub struct ScriptIter<'a> {
    changes: &'a [(usize, Input)],
    k: usize,
    end: usize,
    c: usize,
}

impl<'a> Iterator for ScriptIter<'a> {
    type Item = &'a Input;

    fn next(&mut self) -> Option<&'a Input> {
        if self.k >= self.end {
            return None;
        }
        self.c = forward(self.changes, self.c, self.k);
        self.k += 1;
        Some(&self.changes[self.c].1)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.end - self.k;
        (n, Some(n))
    }
}

impl ExactSizeIterator for ScriptIter<'_> {}

/// Index in `changes` of the change in force at step `k`, moving forward from `c`, the one in
/// force at an earlier step.
fn forward(changes: &[(usize, Input)], mut c: usize, k: usize) -> usize {
    while changes.get(c + 1).is_some_and(|next| next.0 <= k) {
        c += 1;
    }
    c
}

/// The buttons of every step of a [`Script`], owned.
#[derive(Clone, Debug)]
pub struct ScriptSteps {
    script: Script,
    k: usize,
    c: usize,
}

impl Iterator for ScriptSteps {
    type Item = Input;

    fn next(&mut self) -> Option<Input> {
        if self.k >= self.script.len {
            return None;
        }
        self.c = forward(&self.script.changes, self.c, self.k);
        self.k += 1;
        Some(self.script.changes[self.c].1)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.script.len - self.k;
        (n, Some(n))
    }
}

impl ExactSizeIterator for ScriptSteps {}

impl IntoIterator for Script {
    type Item = Input;
    type IntoIter = ScriptSteps;

    fn into_iter(self) -> ScriptSteps {
        ScriptSteps {
            script: self,
            k: 0,
            c: 0,
        }
    }
}

impl<'a> IntoIterator for &'a Script {
    type Item = &'a Input;
    type IntoIter = ScriptIter<'a>;

    fn into_iter(self) -> ScriptIter<'a> {
        self.iter()
    }
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

    /// Builds the backend of `run` with motion parameters `params` and `characters` placed,
    /// reusing built geometry. A level the configuration does not model (a feature it lacks, an
    /// origin beyond its bound, or what its `check_level` refuses) and a character that is not
    /// finite and sized are refused here, before the backend builds, whatever its build would do.
    pub fn build(
        &mut self,
        run: &RunConfig,
        params: &MotionParams,
        characters: &[CharacterSpec],
    ) -> Result<Box<dyn Backend>, RunError> {
        let settings = &*run.backend;
        crate::backend::require_supported(
            settings.backend(),
            &self.level.name,
            self.level.features,
            settings.features(),
        )?;
        crate::backend::origin_supported(settings, self.level)?;
        for c in characters {
            c.validate()?;
        }
        settings
            .check_level(self.level)
            .and_then(|()| {
                characters
                    .iter()
                    .try_for_each(|c| settings.check_character(c))
            })
            .and_then(|()| settings.build(self.level, params, characters, &mut self.shared))
            .map_err(|e| match e {
                // A refusal that names no level: name the one it was built for.
                BackendError::Unsupported {
                    backend,
                    feature,
                    level,
                    beyond_bound,
                } if level.is_empty() => BackendError::Unsupported {
                    backend,
                    feature,
                    level: self.level.name.clone(),
                    beyond_bound,
                },
                e => e,
            })
            .map_err(RunError::from)
    }

    /// Runs one scenario of the level on one configuration (see [`run_scenario`]).
    pub fn run(&mut self, spec: &ScenarioSpec, run: &RunConfig) -> Result<Trace, RunError> {
        check_dt(spec)?;
        let mut rows = Vec::with_capacity(step_count(spec) + 1);
        let mut trace = self.record(spec, run, &mut |r| rows.push(r))?;
        trace.rows = rows;
        Ok(trace)
    }

    /// Runs one scenario of the level on one configuration, handing each row to `sink` as it is
    /// made (row 0 the spawn state, row `k` the state after `k` steps), and returns the trace's
    /// labels with no rows: a run of any length, streamed (see [`crate::trace::RowStore`]).
    pub fn record(
        &mut self,
        spec: &ScenarioSpec,
        run: &RunConfig,
        sink: &mut dyn FnMut(TraceRow),
    ) -> Result<Trace, RunError> {
        let params = effective_params(&run.params, spec);
        let backend = self
            .build(run, &params, &[CharacterSpec::of(spec)])
            .map_err(|e| failed_at(e, self.level, spec, run))?;
        drive(&self.level.name, spec, run, backend, sink)
    }
}

/// Cost of one character-step of `spec` on `run`, in nanoseconds: the scenario's steps timed in
/// process (building the backend and recording the trace are not timed), the minimum over
/// `repeats` runs, which is the least disturbed by the rest of the machine.
pub(crate) fn time_scenario(
    runner: &mut Runner,
    spec: &ScenarioSpec,
    run: &RunConfig,
    repeats: usize,
) -> Result<f64, RunError> {
    let mut samples = vec![0.0; repeats.max(1)];
    time_samples(runner, spec, run, &mut samples)?;
    Ok(samples.iter().copied().fold(f64::INFINITY, f64::min))
}

/// Times `samples.len()` whole runs of `spec` on `run`, one after the other, writing each run's
/// nanoseconds per character step (its steps' time on the thread's CPU clock,
/// [`thread_ns`], over its frames; building the backend is not timed)
/// into `samples`, in run order.
pub(crate) fn time_samples(
    runner: &mut Runner,
    spec: &ScenarioSpec,
    run: &RunConfig,
    samples: &mut [f64],
) -> Result<(), RunError> {
    check_dt(spec)?;
    let params = effective_params(&run.params, spec);
    let script = input_script(spec);
    for sample in samples.iter_mut() {
        let mut backend = runner
            .build(run, &params, &[CharacterSpec::of(spec)])
            .map_err(|e| failed_at(e, runner.level(), spec, run))?;
        let mut input = [Input::default()];
        let start = thread_ns();
        for (k, i) in script.iter().enumerate() {
            input[0] = *i;
            for _ in 0..run.substeps.max(1) {
                backend.step(&input, spec.dt / run.substeps.max(1) as f32);
            }
            if let Some(message) = backend.failure() {
                return Err(failed(runner.level(), spec, run, Some(k), message));
            }
        }
        let spent = thread_ns().saturating_sub(start) as f64;
        // A controller that reports its own step time is charged that, not the pipe's.
        *sample = backend.reported_ns().unwrap_or(spent) / script.len().max(1) as f64;
    }
    Ok(())
}

/// Time spent by this thread, in nanoseconds, on its CPU clock where the system gives one (Unix:
/// `CLOCK_THREAD_CPUTIME_ID`): what a step costs, without the time the thread waited for a core
/// while other processes ran (on a loaded machine most of the wall clock's noise). Elsewhere, or
/// if the clock fails, the wall clock since an arbitrary start.
pub(crate) fn thread_ns() -> u64 {
    #[cfg(unix)]
    {
        let mut t = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: `t` is a valid, writable timespec for the call's duration, the only memory
        // clock_gettime touches.
        if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0 {
            return (t.tv_sec as u64)
                .saturating_mul(1_000_000_000)
                .saturating_add(t.tv_nsec as u64);
        }
    }
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_nanos() as u64
}

/// Runs one scenario on one configuration. Row 0 of the trace is the spawn state; row `k` is
/// the state after `k` steps.
pub fn run_scenario(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
) -> Result<Trace, RunError> {
    Runner::new(level).run(spec, run)
}

/// Steps `backend` (built with the scenario's character as character 0) through the scenario's
/// script, handing each row to `sink` as it is made, and returns the trace's labels with no rows.
fn drive(
    level: &str,
    spec: &ScenarioSpec,
    run: &RunConfig,
    mut backend: Box<dyn Backend>,
    sink: &mut dyn FnMut(TraceRow),
) -> Result<Trace, RunError> {
    check_dt(spec)?;
    let id: CharacterId = 0;
    let script = input_script(spec);
    let initial = crate::backend::CharacterState {
        pos: spec.spawn,
        vel: spec.velocity,
        ..Default::default()
    };
    sink(TraceRow::from_state(0, 0.0, id as u32, &initial));
    let mut input = [Input::default()];
    for (k, step_input) in script.iter().enumerate() {
        input[0] = *step_input;
        for _ in 0..run.substeps.max(1) {
            backend.step(&input, spec.dt / run.substeps.max(1) as f32);
        }
        if let Some(message) = backend.failure() {
            return Err(RunError::Failed(Box::new(RunFailure {
                backend: backend.name().to_string(),
                config: run.label.clone(),
                level: level.to_string(),
                scenario: spec.name.clone(),
                step: Some(k),
                message,
            })));
        }
        let frame = (k + 1) as u32;
        sink(TraceRow::from_state(
            frame,
            frame as f32 * spec.dt,
            id as u32,
            &backend.state(id),
        ));
    }
    Ok(Trace {
        level: level.to_string(),
        scenario: spec.name.clone(),
        backend: backend.name().to_string(),
        config: run.label.clone(),
        rows: Vec::new(),
    })
}

/// Refuses a time step or duration outside the ranges of [`crate::limits`]: the frames a run
/// takes (and the trace it records) are bounded before it starts.
fn check_dt(spec: &ScenarioSpec) -> Result<(), InvalidParam> {
    match crate::limits::check_timing(spec.duration as f64, spec.dt as f64) {
        Ok(_) => Ok(()),
        Err(message) => Err(InvalidParam {
            name: "dt",
            // Quoted as the value of a parameter error always is (its Debug form).
            value: format!("{:?}", message.to_string()),
            expected:
                "a time step 1e-6..=1 s and a duration of 1 to 10,000,000 frames (crate::limits)",
        }),
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
            expect: Default::default(),
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

    /// The script as a vector, one entry a step, read the plain way: the reference the compact
    /// [`Script`] must match (events applied in their order, each from its frame).
    fn naive(s: &ScenarioSpec) -> Vec<Input> {
        let n = step_count(s);
        let mut out = Vec::new();
        let mut cur = Input::default();
        let mut events = s.inputs.iter().peekable();
        for k in 0..n {
            while let Some(e) = events.next_if(|e| (e.t / s.dt).round() as usize <= k) {
                cur.left = e.left.unwrap_or(cur.left);
                cur.right = e.right.unwrap_or(cur.right);
                cur.up = e.up.unwrap_or(cur.up);
                cur.down = e.down.unwrap_or(cur.down);
                cur.jump = e.jump.unwrap_or(cur.jump);
            }
            out.push(cur);
        }
        out
    }

    #[test]
    fn the_compact_script_reads_as_one_input_per_step() {
        let ev = |t: f32, right: bool, jump: Option<bool>| InputEvent {
            t,
            right: Some(right),
            jump,
            ..Default::default()
        };
        // In order, out of order (an earlier event later in the list), two on one frame, one
        // before 0, one past the end, one on the last step.
        let cases = [
            vec![],
            vec![ev(0.0, true, None)],
            vec![ev(0.03, true, None), ev(0.01, false, Some(true))],
            vec![
                ev(0.02, true, None),
                ev(0.02, false, Some(true)),
                ev(0.05, true, None),
            ],
            vec![
                ev(-1.0, true, None),
                ev(0.09, false, None),
                ev(0.5, true, None),
            ],
        ];
        for inputs in cases {
            let s = spec(inputs);
            let (script, plain) = (input_script(&s), naive(&s));
            assert_eq!(script.len(), plain.len());
            assert_eq!(script.iter().copied().collect::<Vec<_>>(), plain);
            for (k, i) in plain.iter().enumerate() {
                assert_eq!(script[k], *i);
                assert_eq!(
                    script.range(k..plain.len()).copied().collect::<Vec<_>>(),
                    plain[k..]
                );
            }
            assert_eq!(script.get(plain.len()), None);
            for pred in [
                |i: &Input| i.right,
                |i: &Input| i.jump,
                |i: &Input| *i != Input::default(),
            ] {
                assert_eq!(script.rposition(pred), plain.iter().rposition(pred));
            }
        }
    }
}
