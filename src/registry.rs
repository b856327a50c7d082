//! The backend kinds the CLI and every command iterate.
//!
//! [`Registry::builtin`] holds the controllers this crate ships; a user's crate adds its own
//! with [`Registry::with`] and hands the registry to [`crate::cli::main_with`] (or runs the
//! suite from code with [`crate::suite`]). Adding a backend to the crate is its module and one
//! line in [`Registry::builtin`].

use std::sync::Arc;

use crate::backend::BackendKind;
use crate::metrics::MetricRow;
use crate::scenario::RunConfig;
use crate::tradeoff::Setting;

/// An ordered list of backend kinds. Commands run them in this order.
#[derive(Clone, Default)]
pub struct Registry {
    kinds: Vec<Arc<dyn BackendKind>>,
}

impl std::fmt::Debug for Registry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.names()).finish()
    }
}

impl Registry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }

    /// The controllers this crate ships: the sweep, then Rapier. Box2D's mover
    /// ([`crate::box2d::kind::Box2dKind`]) is not listed yet: adding it changes the built-in
    /// comparison, so it goes in with the re-blessed baseline and README (issue 19, slice c);
    /// until then a caller adds it with [`Registry::with`].
    pub fn builtin() -> Self {
        Registry::new()
            .with(crate::sweep::kind::SweepKind)
            .with(crate::rapier::kind::RapierKind)
    }

    /// This registry with `kind` added after the others.
    pub fn with(mut self, kind: impl BackendKind + 'static) -> Self {
        self.register(Arc::new(kind));
        self
    }

    /// Adds `kind` after the others; a kind of the same name is replaced in place.
    pub fn register(&mut self, kind: Arc<dyn BackendKind>) {
        match self.kinds.iter_mut().find(|k| k.name() == kind.name()) {
            Some(k) => *k = kind,
            None => self.kinds.push(kind),
        }
    }

    /// The kinds, in order.
    pub fn kinds(&self) -> &[Arc<dyn BackendKind>] {
        &self.kinds
    }

    /// The kinds' names, in order.
    pub fn names(&self) -> Vec<&'static str> {
        self.kinds.iter().map(|k| k.name()).collect()
    }

    /// The kind named `name`.
    pub fn get(&self, name: &str) -> Option<&Arc<dyn BackendKind>> {
        self.kinds.iter().find(|k| k.name() == name)
    }

    /// The built-in comparison: every kind's configurations, in order.
    pub fn builtin_configs(&self) -> Vec<RunConfig> {
        self.kinds
            .iter()
            .flat_map(|k| k.builtin_configs())
            .collect()
    }

    /// The configurations `platbench stress` checks.
    pub fn stress_configs(&self) -> Vec<RunConfig> {
        self.kinds.iter().flat_map(|k| k.stress_configs()).collect()
    }

    /// The settings `platbench sweep` measures.
    pub fn tradeoff_settings(&self) -> Vec<Setting> {
        self.kinds
            .iter()
            .flat_map(|k| k.tradeoff_settings())
            .collect()
    }

    /// The configurations drawn in the report's pictures: `(backend, config, colour)`.
    pub fn drawn(&self) -> Vec<(&'static str, &'static str, &'static str)> {
        self.kinds
            .iter()
            .flat_map(|k| k.drawn().into_iter().map(|(c, col)| (k.name(), c, col)))
            .collect()
    }

    /// The chart colour of backend `name` (grey for a name no kind has).
    pub fn colour(&self, name: &str) -> &'static str {
        self.get(name).map_or("#757575", |k| k.colour())
    }

    /// Every kind's notes on `rows`, then the notes about no one backend
    /// ([`crate::report::notes`]).
    pub fn notes(&self, rows: &[MetricRow]) -> Vec<String> {
        let mut out: Vec<String> = self.kinds.iter().flat_map(|k| k.notes(rows)).collect();
        out.extend(crate::report::notes(rows));
        out
    }
}
