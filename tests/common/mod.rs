//! Shared helpers for the integration tests: the built-in levels and runs over them.
#![allow(dead_code)]

#[path = "../../compare/builtin.rs"]
mod builtin;

use platbench::config::RunConfig;
use platbench::level::{parse_level, Level};
use platbench::metrics::{evaluate, Evaluation, MetricRow};

/// Every built-in level, parsed.
pub fn builtin_levels() -> Vec<Level> {
    builtin::LEVELS
        .iter()
        .map(|(f, t)| parse_level(t, f).expect("built-in level parses"))
        .collect()
}

/// One built-in level by name.
pub fn level(name: &str) -> Level {
    builtin_levels()
        .into_iter()
        .find(|l| l.name == name)
        .unwrap_or_else(|| panic!("no built-in level {name}"))
}

/// Runs every scenario of `levels` on `run`.
pub fn evaluate_all(levels: &[Level], run: &RunConfig) -> Vec<(String, Evaluation)> {
    let mut out = Vec::new();
    for l in levels {
        for s in &l.scenarios {
            let e = evaluate(l, s, run).expect("scenario runs");
            out.push((format!("{}.{}", l.name, s.name), e));
        }
    }
    out
}

/// All rows of metric `m`, which must exist: a loop over them asserts nothing if there are none,
/// so a metric that stopped being measured fails here instead of passing silently.
pub fn some_rows<'a>(evals: &'a [(String, Evaluation)], m: &str) -> Vec<&'a MetricRow> {
    let r = rows(evals, m);
    assert!(!r.is_empty(), "no {m} rows measured");
    r
}

/// All rows of metric `m`.
pub fn rows<'a>(evals: &'a [(String, Evaluation)], m: &str) -> Vec<&'a MetricRow> {
    evals
        .iter()
        .flat_map(|(_, e)| e.metrics.iter())
        .filter(|r| r.metric == m)
        .collect()
}

/// The `platbench` binary, to run as a user does.
pub fn platbench() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_platbench"))
}

/// Fails the test with the command's stderr unless it exited successfully.
pub fn assert_success(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The value of metric `metric` on the scenario named `scenario`.
pub fn value(evals: &[(String, Evaluation)], scenario: &str, metric: &str) -> f64 {
    rows(evals, metric)
        .into_iter()
        .find(|r| r.scenario == scenario)
        .unwrap_or_else(|| panic!("{metric} on {scenario}"))
        .value
}

/// An outside program a test needs (`name` on the PATH, or the path in the variable `env`), or
/// `None` after one loud line on stderr saying the test is skipped, why and how to install it.
/// With `PLATBENCH_REQUIRE_PROGRAMS=1` (set by `.ci/run`, which installs every such program) a
/// missing program fails the test instead, so CI never skips it.
#[allow(dead_code)]
pub fn outside_program(
    test: &str,
    name: &str,
    env: &str,
    install: &str,
) -> Option<std::path::PathBuf> {
    if let Some(p) = std::env::var_os(env) {
        return Some(std::path::PathBuf::from(p));
    }
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join(name))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        let why = format!("no `{name}` on the PATH (nor ${env}); install it with `{install}`");
        if std::env::var("PLATBENCH_REQUIRE_PROGRAMS").is_ok_and(|v| v == "1") {
            panic!("{test} needs {name} (PLATBENCH_REQUIRE_PROGRAMS=1): {why}");
        }
        let msg = format!(
            "SKIPPED {test}: {why} to run this test (.ci/run does, and sets \
             PLATBENCH_REQUIRE_PROGRAMS=1 so that it is never skipped there)"
        );
        // Straight to the process's stderr: the test harness captures `eprintln!` of a test
        // that passes, and this line must be seen.
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), "\n*** {msg}\n");
    }
    found
}

/// A toy controller for the report's statements: the default sweep, but its grounded flag is
/// reported one frame late (grounded only on a step that started grounded), so it lands a frame
/// after the integrator's landing frame. Everything else is the sweep's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LateLander(
    /// The sweep it wraps, with its settings.
    pub platbench::sweep::SweepConfig,
);

/// What [`LateLander`] keeps: the sweep's mover and, per character, whether it was grounded
/// before the last step.
pub struct LateMover {
    inner: <platbench::sweep::SweepConfig as platbench::controller::Controller>::Mover,
    before: Vec<bool>,
}

impl platbench::controller::Controller for LateLander {
    type Mover = LateMover;
    const NAME: &'static str = "late_lander";

    fn features(&self) -> platbench::level::Features {
        self.0.features()
    }
    fn build(
        &self,
        setup: platbench::controller::Setup<'_>,
    ) -> Result<LateMover, platbench::backend::BackendError> {
        let before = vec![false; setup.characters.len()];
        Ok(LateMover {
            inner: self.0.build(setup)?,
            before,
        })
    }
    fn step(&self, m: &mut LateMover, inputs: &[platbench::motion::Input], dt: f32) {
        for (id, b) in m.before.iter_mut().enumerate() {
            *b = self.0.state(&m.inner, id).grounded;
        }
        self.0.step(&mut m.inner, inputs, dt);
    }
    fn state(
        &self,
        m: &LateMover,
        id: platbench::backend::CharacterId,
    ) -> platbench::backend::CharacterState {
        let mut s = self.0.state(&m.inner, id);
        s.grounded &= m.before[id];
        s
    }
    fn declared_contact(
        &self,
        size: glam::Vec2,
        max_climb_angle: f32,
    ) -> platbench::backend::DeclaredContact {
        self.0.declared_contact(size, max_climb_angle)
    }
    fn declared_contact_in(
        &self,
        size: glam::Vec2,
        params: &platbench::motion::MotionParams,
        dt: f32,
    ) -> platbench::backend::DeclaredContact {
        self.0.declared_contact_in(size, params, dt)
    }
}
