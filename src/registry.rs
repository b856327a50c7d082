//! The backend kinds the CLI and every command iterate.
//!
//! [`Registry::builtin`] holds the controllers this crate ships; a user's crate adds its own
//! [`crate::controller::Controller`] with [`Registry::with`] and hands the registry to
//! [`crate::cli::main_with`] (or runs the suite from code with [`crate::suite`]). Adding a
//! backend to the crate is its module and one line in [`Registry::builtin`].

use std::sync::Arc;

use crate::config::RunConfig;
use crate::config::Setting;
use crate::controller::{BackendKind, Controller, Kind};

/// Colours for controllers without one of their own, told apart from the built-in ones (the
/// sweep's blue, Rapier's green, Box2D's teal) and from each other.
pub const PALETTE: [&str; 6] = [
    "#6a1b9a", "#ad1457", "#5d4037", "#283593", "#9e9d24", "#37474f",
];

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

    /// The controllers this crate ships: the sweep, then Rapier, then Box2D's mover (each of the
    /// last two when its Cargo feature, `rapier` or `box2d`, is on, as by default).
    pub fn builtin() -> Self {
        let registry = Registry::new().with::<crate::sweep::SweepConfig>();
        #[cfg(feature = "rapier")]
        let registry = registry.with::<crate::rapier::RapierConfig>();
        #[cfg(feature = "box2d")]
        let registry = registry.with::<crate::box2d::Box2dConfig>();
        registry
    }

    /// This registry with controller `C` added after the others (one of the same name is
    /// replaced in place).
    ///
    /// ```
    /// use platbench::registry::Registry;
    /// use platbench::sweep::SweepConfig;
    ///
    /// let registry = Registry::new().with::<SweepConfig>();
    /// assert_eq!(registry.names(), ["sweep"]);
    /// ```
    pub fn with<C: Controller>(mut self) -> Self {
        self.register(Arc::new(Kind::<C>::new()));
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

    /// The configurations with a colour of their own in the report's replays: `(backend,
    /// config, colour)`.
    pub fn drawn(&self) -> Vec<(&'static str, &'static str, &'static str)> {
        self.kinds
            .iter()
            .flat_map(|k| k.drawn().into_iter().map(|(c, col)| (k.name(), c, col)))
            .collect()
    }

    /// The chart colour of backend `name`: its kind's own, else a colour of [`PALETTE`] that no
    /// kind before it in this registry has (grey for a name no kind has).
    pub fn colour(&self, name: &str) -> &'static str {
        let mut taken: Vec<&'static str> = self.kinds.iter().filter_map(|k| k.colour()).collect();
        for k in &self.kinds {
            let own = k.colour().unwrap_or_else(|| {
                let free = PALETTE.iter().find(|c| !taken.contains(c)).copied();
                let c = free.unwrap_or(PALETTE[taken.len() % PALETTE.len()]);
                taken.push(c);
                c
            });
            if k.name() == name {
                return own;
            }
        }
        "#757575"
    }
}
