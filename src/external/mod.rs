//! External controllers: a program in any language that speaks the step protocol (JSON lines on
//! its stdin and stdout, docs/protocol.md), named by a controller file (a small TOML,
//! [`ControllerFile`]) and run as a backend like any other: same metrics, report, traces and
//! diff. [`load`] reads the file and asks the program what it offers (the handshake); each run
//! then starts the program afresh, so a run that fails ends alone.

mod config;
pub mod godot3;
mod process;
mod protocol;
mod running;

use std::path::Path;
use std::sync::Arc;

use glam::Vec2;

pub use config::{ControllerFile, Mode, Transport};
pub use protocol::VERSION;

use crate::backend::{
    Backend, BackendError, BackendSettings, Capabilities, CharacterSpec, DeclaredContact,
    Precision, SharedGeometry, ShownByDefault,
};
use crate::config::{RunConfig, Setting};
use crate::controller::BackendKind;
use crate::level::{Features, Level};
use crate::motion::MotionParams;
use crate::shape::CharacterShape;

/// Why a controller file could not be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExternalError {
    /// The file is not a valid controller file.
    #[error("{file}:{line}:{column}: {message}")]
    File {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// What was found and what was expected.
        message: String,
    },
    /// The file could not be read.
    #[error("cannot read controller file {file}: {message}")]
    Read {
        /// The file.
        file: String,
        /// Why.
        message: String,
    },
    /// The program did not start or did not answer the handshake as the protocol says.
    #[error("{file}: controller {name}: the handshake failed: {message}")]
    Handshake {
        /// The file.
        file: String,
        /// The controller's name in the file.
        name: String,
        /// What went wrong.
        message: String,
    },
}

/// An external controller as the registry lists it: its file and the configurations its
/// handshake offered.
#[derive(Debug)]
pub(crate) struct ExternalKind {
    name: &'static str,
    description: &'static str,
    configs: Vec<Arc<ExternalSettings>>,
}

/// One configuration of an external controller.
#[derive(Debug)]
pub(crate) struct ExternalSettings {
    name: &'static str,
    file: Arc<ControllerFile>,
    label: String,
    shape: CharacterShape,
    features: Features,
    contact: DeclaredContact,
    capabilities: Capabilities,
    why: String,
}

/// Reads the controller file at `path`, starts its program and asks what it offers: the kind to
/// register ([`crate::registry::Registry::register`]). Its name and description are leaked, once
/// per file (the registry's names are `&'static str`).
pub fn load(path: &Path) -> Result<Arc<dyn BackendKind>, ExternalError> {
    load_file(config::read(path)?)
}

/// [`load`] for a controller file already read.
fn load_file(file: ControllerFile) -> Result<Arc<dyn BackendKind>, ExternalError> {
    let file = Arc::new(file);
    let fail = |message: String| ExternalError::Handshake {
        file: file.source.clone(),
        name: file.name.clone(),
        message,
    };
    let hello = running::handshake(&file).map_err(fail)?;
    let name: &'static str = Box::leak(file.name.clone().into_boxed_str());
    let mut configs = Vec::new();
    for c in hello.configs {
        if c.label.is_empty() || c.label.chars().any(|ch| ch.is_whitespace() || ch == '/') {
            return Err(fail(format!(
                "configuration label {:?}: expected a non-empty label without spaces or `/`",
                c.label
            )));
        }
        if configs
            .iter()
            .any(|k: &Arc<ExternalSettings>| k.label == c.label)
        {
            return Err(fail(format!("configuration {:?} offered twice", c.label)));
        }
        let shape = CharacterShape::from_label(&c.shape).ok_or_else(|| {
            fail(format!(
                "configuration {:?}: shape {:?}: expected cuboid, capsule, ball or round-cuboid",
                c.label, c.shape
            ))
        })?;
        let k = c.contact;
        let contact = DeclaredContact {
            gap: k.gap,
            overlap_tolerance: k.overlap_tolerance,
            gap_tolerance: k.gap_tolerance,
            slope_overhang: k.slope_overhang,
            stance_half_width: k.stance_half_width,
            stance_sink: k.stance_sink,
            surface_grid: k.surface_grid,
        };
        let lengths = [
            k.gap,
            k.overlap_tolerance,
            k.gap_tolerance,
            k.slope_overhang,
            k.stance_half_width,
            k.stance_sink,
        ];
        if !lengths.iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err(fail(format!(
                "configuration {:?}: its contact's lengths must be finite and 0 or more (tiles)",
                c.label
            )));
        }
        let why = format!(
            "{} mode over the step protocol ({}): {}",
            file.mode.label(),
            hello.name,
            if c.why.is_empty() {
                &hello.description
            } else {
                &c.why
            }
        );
        configs.push(Arc::new(ExternalSettings {
            name,
            file: file.clone(),
            label: c.label,
            shape,
            features: c.features.into(),
            contact,
            capabilities: Capabilities {
                pushes_bodies: c.capabilities.pushes_bodies,
                integer_positions: c.capabilities.integer_positions,
                cross_platform_determinism: c.capabilities.cross_platform_determinism,
                no_rider_carry: c.capabilities.no_rider_carry,
                no_climb_limit: c.capabilities.no_climb_limit,
            },
            why,
        }));
    }
    if configs.is_empty() {
        return Err(fail("it offers no configuration".into()));
    }
    let description = format!(
        "{} (external, {} mode, {}): {}",
        hello.name,
        file.mode.label(),
        file.source,
        hello.description
    );
    Ok(Arc::new(ExternalKind {
        name,
        description: Box::leak(description.into_boxed_str()),
        configs,
    }))
}

impl BackendKind for ExternalKind {
    fn name(&self) -> &'static str {
        self.name
    }
    fn description(&self) -> &'static str {
        self.description
    }
    fn shapes(&self) -> Vec<CharacterShape> {
        let mut shapes = Vec::new();
        for c in &self.configs {
            if !shapes.contains(&c.shape) {
                shapes.push(c.shape);
            }
        }
        shapes
    }
    fn builtin_configs(&self) -> Vec<RunConfig> {
        self.configs
            .iter()
            .map(|c| RunConfig {
                label: c.label.clone(),
                backend: c.clone(),
                params: MotionParams::default(),
                substeps: 1,
                why: c.why.clone(),
            })
            .collect()
    }
    fn stress_configs(&self) -> Vec<RunConfig> {
        self.builtin_configs().into_iter().take(1).collect()
    }
    fn tradeoff_settings(&self) -> Vec<Setting> {
        self.builtin_configs()
            .into_iter()
            .map(|run| Setting {
                label: run.label.clone(),
                run,
                dt: None,
            })
            .collect()
    }
    fn drawn(&self) -> Vec<(&'static str, &'static str)> {
        Vec::new()
    }
    fn shown_by_default(&self) -> ShownByDefault {
        ShownByDefault::BestAndWorst
    }
    fn colour(&self) -> Option<&'static str> {
        None
    }
}

impl BackendSettings for ExternalSettings {
    fn backend(&self) -> &'static str {
        self.name
    }
    fn shape(&self) -> CharacterShape {
        self.shape
    }
    fn features(&self) -> Features {
        self.features
    }
    fn supports(&self, level: &Level) -> bool {
        level.features.within(self.features)
    }
    fn check_level(&self, _: &Level) -> Result<(), BackendError> {
        Ok(())
    }
    fn check_character(&self, _: &CharacterSpec) -> Result<(), BackendError> {
        Ok(())
    }
    fn declared_contact(&self, _: Vec2, _: f32) -> DeclaredContact {
        self.contact
    }
    fn declared_contact_in(&self, _: Vec2, _: &MotionParams, _: f32) -> DeclaredContact {
        self.contact
    }
    fn contact_tolerance(&self, _: Vec2) -> f64 {
        self.contact.gap.max(self.contact.overlap_tolerance) as f64
    }
    fn moved_size(&self, size: Vec2) -> Vec2 {
        size
    }
    fn epsilon(&self) -> Option<f32> {
        None
    }
    fn with_epsilon(&self, _: f32) -> Option<Arc<dyn BackendSettings>> {
        None
    }
    fn precision(&self) -> Precision {
        Precision::F32
    }
    fn capabilities(&self) -> Capabilities {
        self.capabilities
    }
    fn max_origin(&self) -> f64 {
        crate::backend::max_origin_in(Precision::F32)
    }
    fn max_reach(&self) -> Option<f64> {
        None
    }
    fn with_precision(&self, _: Precision) -> Option<Arc<dyn BackendSettings>> {
        None
    }
    fn build(
        &self,
        level: &Level,
        params: &MotionParams,
        characters: &[CharacterSpec],
        _: &mut SharedGeometry,
    ) -> Result<Box<dyn Backend>, BackendError> {
        running::start(self, level, params, characters).map(|b| Box::new(b) as Box<dyn Backend>)
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn same_as(&self, other: &dyn BackendSettings) -> bool {
        other
            .as_any()
            .downcast_ref::<ExternalSettings>()
            .is_some_and(|o| o.name == self.name && o.label == self.label)
    }
}
