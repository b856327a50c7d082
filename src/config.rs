//! A configuration: a controller's settings under a label, with the motion parameters and the
//! steps per frame it runs with ([`RunConfig`]), and a point of the speed-against-accuracy grid
//! ([`Setting`]). Controllers declare theirs as data; the runner, the stress and the trade-off
//! read them.

use std::sync::Arc;

use crate::backend::BackendSettings;
use crate::motion::MotionParams;
use crate::shape::CharacterShape;

/// A configuration: one column of a comparison, a controller's settings under a label with the
/// motion parameters and steps per frame it runs with. The one name for a configuration; a
/// controller's settings struct is the controller itself (`SweepConfig`, `RapierConfig`, yours),
/// and a trade-off [`Setting`] is a configuration with a time step.
#[derive(Clone, Debug)]
pub struct RunConfig {
    /// Label of this configuration in tables and CSV files (`config` column).
    pub label: String,
    /// The controller and its settings, through the harness's erased view of any
    /// [`crate::controller::Controller`].
    pub backend: Arc<dyn BackendSettings>,
    /// Motion parameters (scenarios may override some of them).
    pub params: MotionParams,
    /// Steps the backend takes per frame, each of `dt / substeps` (1: one step per frame).
    /// Traces keep one row per frame.
    pub substeps: u32,
    /// Why this configuration behaves as it does: its documented design in one line, with its
    /// source (the paper, docs or sample it follows), printed beside its row by `platbench run`
    /// and the report, the same way for every configuration. Set by its controller's presets
    /// ([`RunConfig::with_why`]); empty from [`RunConfig::new`], and then the report uses the
    /// controller's [`crate::controller::Controller::description`]. Not compared by `==`: it
    /// describes the settings, it is not one.
    pub why: String,
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
            why: String::new(),
        }
    }

    /// This configuration with `why` as its one-line design and source ([`RunConfig::why`]).
    pub fn with_why(mut self, why: impl Into<String>) -> Self {
        self.why = why.into();
        self
    }

    /// The character's collision shape in this configuration.
    pub fn shape(&self) -> CharacterShape {
        self.backend.shape()
    }
}

/// One setting of the trade-off grid (`platbench sweep`): a configuration and, optionally, a time step for every scenario.
#[derive(Clone, Debug)]
pub struct Setting {
    /// Label in `tradeoff.csv`.
    pub label: String,
    /// The configuration.
    pub run: RunConfig,
    /// The time step (seconds) every scenario runs with, if not its own.
    pub dt: Option<f32>,
}

impl Setting {
    /// A setting labelled `label`: `settings` with `substeps` steps per frame and every scenario
    /// at `dt` seconds (its own if `None`), the default motion parameters otherwise.
    pub fn new(
        label: &str,
        settings: impl BackendSettings,
        substeps: u32,
        dt: Option<f32>,
    ) -> Self {
        Setting {
            label: label.into(),
            run: RunConfig {
                substeps,
                ..RunConfig::new(label, settings)
            },
            dt,
        }
    }
}
