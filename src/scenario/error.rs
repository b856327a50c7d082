//! Why a run did not happen or did not finish: [`RunError`], and [`RunFailure`], a run a
//! controller's failure ended.

use crate::backend::BackendError;
use crate::config::RunConfig;
use crate::level::{Level, ScenarioSpec};
use crate::motion::InvalidParam;

/// Why a run did not happen: the controller refused the level or failed to build over it (its
/// own [`BackendError`]), or the harness refused the scenario's input (a character or a time
/// step outside the documented ranges) before building anything.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunError {
    /// The controller's error.
    #[error(transparent)]
    Controller(#[from] BackendError),
    /// The scenario's input is outside the documented ranges.
    #[error(transparent)]
    Input(#[from] InvalidParam),
    /// The controller failed during the run (an external controller's process crashed, hung,
    /// printed garbage, replied out of order or with non-finite numbers, or timed out): this
    /// run ends, and the command's other runs go on.
    #[error(transparent)]
    Failed(Box<RunFailure>),
}

/// A run that a controller's failure ended ([`RunError::Failed`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "{backend}/{config} failed on {level}.{scenario} {}: {message}",
    step.map_or_else(|| "before its first step".to_string(), |k| format!("at step {k}"))
)]
pub struct RunFailure {
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// Level name.
    pub level: String,
    /// Scenario name.
    pub scenario: String,
    /// The step (frame, from 0) it failed on, or `None` before the first.
    pub step: Option<usize>,
    /// What went wrong.
    pub message: String,
}

/// A [`RunError::Failed`] of `run` on `spec` of `level`.
pub(super) fn failed(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    step: Option<usize>,
    message: String,
) -> RunError {
    RunError::Failed(Box::new(RunFailure {
        backend: run.backend.backend().to_string(),
        config: run.label.clone(),
        level: level.name.clone(),
        scenario: spec.name.clone(),
        step,
        message,
    }))
}

/// `e`, or for an external controller's failure to start, the [`RunError::Failed`] naming the
/// scenario.
pub(super) fn failed_at(
    e: RunError,
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
) -> RunError {
    match e {
        RunError::Controller(BackendError::External { message, .. }) => {
            failed(level, spec, run, None, message)
        }
        e => e,
    }
}

impl RunError {
    /// Whether the controller failed during the run ([`RunError::Failed`]): the command says so,
    /// goes on with its other runs, and exits with an error at the end.
    pub fn is_failure(&self) -> bool {
        matches!(self, RunError::Failed(_))
    }

    /// Whether the controller does not model something the level has or holds it beyond a
    /// bound it keeps (the run is skipped, not failed).
    pub fn is_unsupported(&self) -> bool {
        matches!(self, RunError::Controller(BackendError::Unsupported { .. }))
    }
}
