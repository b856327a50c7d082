//! Running the comparison from code: every scenario of some levels on every configuration of a
//! registry, with the traces and metrics the CLI writes, and no output of its own.
//!
//! ```no_run
//! use platbench::registry::Registry;
//! use platbench::suite::{builtin_levels, run_suite};
//!
//! let levels = builtin_levels().expect("the built-in levels parse");
//! let run = run_suite(&levels, &Registry::builtin().builtin_configs()).expect("runs");
//! println!("{} traces, {} metric rows", run.traces.len(), run.metrics.len());
//! ```

use crate::config::RunConfig;
use crate::level::{parse_level, Level, LevelError};
use crate::metrics::{evaluate_with, MetricRow};
use crate::scenario::RunError;
use crate::scenario::Runner;
use crate::trace::Trace;

/// The built-in levels (the files of `compare/levels/`), parsed.
pub fn builtin_levels() -> Result<Vec<Level>, LevelError> {
    crate::builtin::LEVELS
        .iter()
        .map(|(file, text)| parse_level(text, &format!("builtin:{file}")))
        .collect()
}

/// A configuration left out of a level it does not model.
#[derive(Clone, Debug, PartialEq)]
pub struct Skipped {
    /// The level's name.
    pub level: String,
    /// The backend's name.
    pub backend: String,
    /// The configuration's label.
    pub config: String,
    /// Why (the backend's refusal).
    pub reason: String,
}

/// What [`run_suite`] measured.
#[derive(Clone, Debug, Default)]
pub struct SuiteRun {
    /// One trace per scenario and configuration that ran, in run order (level, scenario,
    /// configuration).
    pub traces: Vec<Trace>,
    /// Every metric row, as `metrics.csv` holds them.
    pub metrics: Vec<MetricRow>,
    /// The configurations left out of a level, once per level and configuration.
    pub skipped: Vec<Skipped>,
}

/// Runs every scenario of `levels` on every configuration of `configs`, as `platbench run`
/// does: geometry is built once per level and shared, and a configuration that does not model
/// a level's features is left out of that level (listed in [`SuiteRun::skipped`]), never run on
/// part of it. Any other error of a backend stops the run.
pub fn run_suite(levels: &[Level], configs: &[RunConfig]) -> Result<SuiteRun, RunError> {
    let mut out = SuiteRun::default();
    for level in levels {
        let mut runner = Runner::new(level);
        for spec in &level.scenarios {
            for run in configs {
                match evaluate_with(&mut runner, spec, run) {
                    Err(e) if e.is_unsupported() => {
                        let skipped = Skipped {
                            level: level.name.clone(),
                            backend: run.backend.backend().to_string(),
                            config: run.label.clone(),
                            reason: e.to_string(),
                        };
                        if !out.skipped.contains(&skipped) {
                            out.skipped.push(skipped);
                        }
                    }
                    e => {
                        let e = e?;
                        out.metrics.extend(e.metrics);
                        out.traces.push(e.trace);
                    }
                }
            }
        }
    }
    Ok(out)
}
