//! The backend kinds the CLI and every command iterate.
//!
//! [`Registry::builtin`] holds the controllers this crate ships; a user's crate adds its own
//! [`crate::controller::Controller`] with [`Registry::with`] and hands the registry to
//! [`crate::cli::main_with`] (or runs the suite from code with [`crate::suite`]). Adding a
//! backend to the crate is its module and one line in [`Registry::builtin`].

use std::sync::Arc;

use crate::backend::{BackendKind, ShownByDefault};
use crate::controller::{Controller, Kind};
use crate::metrics::MetricRow;
use crate::scenario::RunConfig;
use crate::tradeoff::Setting;

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

    /// The configurations a scenario's replay in the report shows before the reader picks,
    /// from `rows`, that scenario's metric rows: per kind in order, what its
    /// [`BackendKind::shown_by_default`] asks for among the configurations that ran it. Each
    /// entry is `(backend, config label)`.
    pub fn shown_by_default(&self, rows: &[MetricRow]) -> Vec<(String, String)> {
        let mut out = Vec::new();
        for k in &self.kinds {
            let mut configs: Vec<&str> = Vec::new();
            for r in rows.iter().filter(|r| r.backend == k.name()) {
                if !configs.contains(&r.config.as_str()) {
                    configs.push(&r.config);
                }
            }
            let picked: Vec<&str> = match k.shown_by_default() {
                ShownByDefault::Listed(labels) => {
                    labels.into_iter().filter(|l| configs.contains(l)).collect()
                }
                ShownByDefault::BestAndWorst => {
                    let scored: Vec<(&str, f64)> = configs
                        .iter()
                        .map(|c| {
                            let own: Vec<MetricRow> = rows
                                .iter()
                                .filter(|r| r.backend == k.name() && r.config == *c)
                                .cloned()
                                .collect();
                            (*c, crate::tradeoff::error_score(&own))
                        })
                        .collect();
                    // The first of equals is the best; the last of equals the worst.
                    let best = scored.iter().reduce(|a, b| if b.1 < a.1 { b } else { a });
                    let worst = scored.iter().reduce(|a, b| if b.1 >= a.1 { b } else { a });
                    let mut p: Vec<&str> = best.into_iter().chain(worst).map(|x| x.0).collect();
                    p.dedup();
                    p
                }
            };
            out.extend(
                picked
                    .into_iter()
                    .map(|c| (k.name().to_string(), c.to_string())),
            );
        }
        out
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

    /// Every kind's notes on `rows`, then the notes about no one backend
    /// ([`crate::report::notes`]).
    pub fn notes(&self, rows: &[MetricRow]) -> Vec<String> {
        let mut out: Vec<String> = self.kinds.iter().flat_map(|k| k.notes(rows)).collect();
        out.extend(crate::report::notes(rows));
        out
    }
}

/// The notes of a stream of runs without holding every row: each run's rows are read as they
/// come and the rows of the first run that calls for each note are kept. A note is about the
/// rows of one run (a row past a threshold, or two rows of the same run), so the notes of the
/// kept runs are [`Registry::notes`] of every row, in the same order. Memory: one run's rows per
/// distinct note.
pub struct RunNotes<'r> {
    registry: &'r Registry,
    seen: std::collections::HashSet<String>,
    rows: Vec<MetricRow>,
}

impl<'r> RunNotes<'r> {
    /// No run read yet.
    pub fn new(registry: &'r Registry) -> Self {
        RunNotes {
            registry,
            seen: Default::default(),
            rows: Vec::new(),
        }
    }

    /// Reads the rows of one run.
    pub fn push_run(&mut self, rows: &[MetricRow]) {
        let mut new = false;
        for n in self.registry.notes(rows) {
            new |= self.seen.insert(n);
        }
        if new {
            self.rows.extend_from_slice(rows);
        }
    }

    /// The notes of every run read.
    pub fn notes(&self) -> Vec<String> {
        self.registry.notes(&self.rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(backend: &str, config: &str, stuck: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: "s".into(),
            backend: backend.into(),
            config: config.into(),
            metric: "stuck_frames",
            value: stuck,
            unit: "frames",
            reference: 0.0,
            error: stuck,
        }
    }

    #[test]
    fn the_notes_of_the_kept_runs_are_the_notes_of_every_row() {
        // The sweep's note on a too-steep slope needs a penetration row and a steep_blocked row
        // of the same run; here the run that has both comes between two that do not, and its
        // steep_blocked value is neither the lowest nor the highest (the summary drops it).
        let r = |scenario: &str, metric: &'static str, value: f64| MetricRow {
            scenario: scenario.into(),
            metric,
            value,
            error: value,
            ..row("sweep", "default", 0.0)
        };
        let runs = [
            vec![
                r("a", "penetration_beyond_declared", 0.0),
                r("a", "steep_blocked", 0.0),
            ],
            vec![
                r("b", "penetration_beyond_declared", 0.07),
                r("b", "steep_blocked", 0.5),
            ],
            vec![r("c", "penetration_beyond_declared", 0.2)],
            vec![r("d", "steep_blocked", 1.0)],
        ];
        let registry = Registry::builtin();
        let all: Vec<MetricRow> = runs.iter().flatten().cloned().collect();
        let mut notes = RunNotes::new(&registry);
        for run in &runs {
            notes.push_run(run);
        }
        let expected = registry.notes(&all);
        assert!(
            expected.iter().any(|n| n.contains("too-steep slope")),
            "{expected:?}"
        );
        assert_eq!(notes.notes(), expected);
        // Only the run that called for a note is kept.
        assert_eq!(notes.rows.len(), 2);
    }

    #[test]
    #[cfg(all(feature = "rapier", feature = "box2d"))]
    fn replays_show_the_listed_reference_and_each_other_kinds_best_and_worst() {
        // stuck_frames weighs 1 in the default score, min(1, |error| / 1 frame): below one frame
        // (fractions, for the test), more is worse; at one and above every value scores 1.
        let rows = [
            row("sweep", "jump=continuous", 0.0),
            row("sweep", "default", 9.0),
            row("rapier", "a", 0.25),
            row("rapier", "b", 0.0),
            row("rapier", "c", 0.75),
            row("rapier", "d", 0.5),
        ];
        let shown = Registry::builtin().shown_by_default(&rows);
        let pair = |b: &str, c: &str| (b.to_string(), c.to_string());
        assert_eq!(
            shown,
            [
                pair("sweep", "default"),
                pair("rapier", "b"),
                pair("rapier", "c")
            ]
        );
        // One configuration is both its kind's best and worst: shown once.
        let one = Registry::builtin().shown_by_default(&rows[2..3]);
        assert_eq!(one, [pair("rapier", "a")]);
    }
}
