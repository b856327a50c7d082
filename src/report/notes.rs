//! What the summary says beside its tables, the same way for every configuration: each
//! configuration's one-line design with its source ([`why_lines`], from
//! [`crate::config::RunConfig::why`], else its controller's description), and the notes that
//! explain what a metric's number means where the measurements call for it, in the same words
//! for any configuration, naming no controller ([`notes`]); [`RunNotes`] gathers the notes from
//! a stream of runs.

use std::collections::HashSet;

use super::Coverage;
use crate::config::RunConfig;
use crate::metrics::MetricRow;
use crate::registry::Registry;

/// Notes on what the numbers in `rows` mean, each made only when the measurements show what it
/// explains, in the same words whichever configuration shows it (the tables say which): none
/// names a controller or explains one's design, which is each configuration's [`why_lines`].
pub fn notes(rows: &[MetricRow]) -> Vec<String> {
    let mut out = Vec::new();
    // A rest off touching that keeps the configuration's declared contact: a promise kept.
    let kept: HashSet<RunKey> = rows
        .iter()
        .filter(|d| d.metric == "rest_gap_declared" && d.value.abs() <= 1e-4)
        .map(run_key)
        .collect();
    if rows
        .iter()
        .any(|r| r.metric == "rest_gap" && r.value.abs() > 1e-3 && kept.contains(&run_key(r)))
    {
        out.push("rest_gap off 0 where rest_gap_declared is 0 (within 1e-4 tiles on the same run) is the gap or overlap the configuration declares, a promise kept; its design line says why.".into());
    }
    if rows
        .iter()
        .any(|r| r.metric == "slope_overlap" && r.value > 1e-3)
    {
        out.push("slope_overlap is counted in max_penetration, rest_gap and slope_gap_max too, as any shape inside a slope is; penetration_beyond_declared and the other *_declared metrics leave out what the configuration declares.".into());
    }
    out
}

/// A run: level, scenario, backend, configuration.
type RunKey<'a> = (&'a str, &'a str, &'a str, &'a str);

/// The run a row is of.
fn run_key(r: &MetricRow) -> RunKey<'_> {
    (&r.level, &r.scenario, &r.backend, &r.config)
}

/// Each configuration that ran (`coverage`, in run order) as its column label, with why it
/// behaves as it does: its own [`RunConfig::why`] when one of `configs` has its label, else
/// its controller's description in `registry`
/// ([`crate::controller::Controller::description`]); a configuration with neither is left out.
pub fn why_lines(
    coverage: &Coverage,
    configs: &[RunConfig],
    registry: &Registry,
) -> Vec<(String, String)> {
    coverage
        .configs
        .iter()
        .filter_map(|(label, _)| {
            let own = configs
                .iter()
                .find(|c| column_of(c) == *label)
                .map(|c| c.why.clone())
                .filter(|w| !w.is_empty());
            let why = own.or_else(|| {
                let backend = label.split(' ').next().unwrap_or_default();
                registry
                    .get(backend)
                    .map(|k| k.description().to_string())
                    .filter(|d| !d.is_empty())
            })?;
            Some((label.clone(), why))
        })
        .collect()
}

/// A configuration's column label, as [`super::column`] labels its rows.
fn column_of(c: &RunConfig) -> String {
    if c.label == "default" {
        c.backend.backend().to_string()
    } else {
        format!("{} {}", c.backend.backend(), c.label)
    }
}

/// The notes of a stream of runs without holding every row: each run's rows are read as they
/// come and the rows of the first run that calls for each note are kept. A note is about the
/// rows of one run (a row past a threshold, or two rows of the same run), so the notes of the
/// kept runs are [`notes`] of every row, in the same order. Memory: one run's rows per distinct
/// note.
#[derive(Default)]
pub struct RunNotes {
    seen: HashSet<String>,
    rows: Vec<MetricRow>,
}

impl RunNotes {
    /// No run read yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Reads the rows of one run.
    pub fn push_run(&mut self, rows: &[MetricRow]) {
        let mut new = false;
        for n in notes(rows) {
            new |= self.seen.insert(n);
        }
        if new {
            self.rows.extend_from_slice(rows);
        }
    }

    /// The notes of every run read.
    pub fn notes(&self) -> Vec<String> {
        notes(&self.rows)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(backend: &str, scenario: &str, metric: &'static str, value: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: scenario.into(),
            backend: backend.into(),
            config: "default".into(),
            metric,
            value,
            unit: "tiles",
            reference: 0.0,
            error: value,
            frame: None,
            q1: None,
            q3: None,
        }
    }

    #[test]
    fn the_notes_of_the_kept_runs_are_the_notes_of_every_row() {
        // The rest_gap note needs a rest_gap row and a rest_gap_declared row of the same run;
        // here the run that has both comes between runs that have one of them, or both apart.
        let runs = [
            vec![
                r("a", "s1", "rest_gap", 0.0),
                r("a", "s1", "rest_gap_declared", 0.0),
            ],
            vec![
                r("b", "s1", "rest_gap", 0.2),
                r("b", "s1", "rest_gap_declared", 0.2),
            ],
            vec![
                r("b", "s2", "rest_gap", 0.009),
                r("b", "s2", "rest_gap_declared", 1e-5),
            ],
            vec![r("a", "s3", "rest_gap", 0.3)],
            vec![r("b", "s3", "rest_gap_declared", 0.0)],
        ];
        let all: Vec<MetricRow> = runs.iter().flatten().cloned().collect();
        let mut kept = RunNotes::new();
        for run in &runs {
            kept.push_run(run);
        }
        let expected = notes(&all);
        assert_eq!(expected.len(), 1, "{expected:?}");
        assert!(expected[0].starts_with("rest_gap off 0"), "{expected:?}");
        assert_eq!(kept.notes(), expected);
        // Only the run that called for the note is kept.
        assert_eq!(kept.rows.len(), 2);
    }

    #[test]
    fn a_note_names_no_controller_and_reads_the_same_for_any() {
        // The same measurements under two names give the same notes.
        let of = |name: &str| {
            notes(&[
                r(name, "s", "rest_gap", 0.01),
                r(name, "s", "rest_gap_declared", 0.0),
                r(name, "s", "slope_overlap", 0.2),
            ])
        };
        let (a, b) = (of("sweep"), of("box2d"));
        assert_eq!(a.len(), 2, "{a:?}");
        assert_eq!(a, b);
        for n in &a {
            for word in ["sweep", "rapier", "box2d", "seed", "by design"] {
                assert!(!n.to_lowercase().contains(word), "{word:?} in {n:?}");
            }
        }
    }

    #[test]
    fn every_configuration_that_ran_gets_its_why_or_its_controllers_description() {
        let registry = Registry::builtin();
        let configs = registry.builtin_configs();
        // Every built-in configuration states its design.
        for c in &configs {
            assert!(
                !c.why.is_empty(),
                "{} {} has no why",
                c.backend.backend(),
                c.label
            );
        }
        let rows: Vec<MetricRow> = ["default", "jump=continuous", "no-such-preset"]
            .iter()
            .map(|config| MetricRow {
                config: config.to_string(),
                ..r("sweep", "s", "rest_gap", 0.0)
            })
            .collect();
        let whys = why_lines(&Coverage::of(&rows), &configs, &registry);
        let labels: Vec<&str> = whys.iter().map(|(l, _)| l.as_str()).collect();
        assert_eq!(
            labels,
            ["sweep", "sweep jump=continuous", "sweep no-such-preset"]
        );
        let own = |label: &str| &configs.iter().find(|c| c.label == label).unwrap().why;
        assert_eq!(&whys[0].1, own("default"));
        assert_eq!(&whys[1].1, own("jump=continuous"));
        assert_ne!(whys[0].1, whys[1].1);
        // No configuration of that label: the controller's description.
        use crate::controller::Controller as _;
        assert_eq!(whys[2].1, crate::sweep::SweepConfig::description());
    }
}
