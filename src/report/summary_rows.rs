//! The metric rows the summary needs, kept from a stream of runs, so that a run of many
//! scenarios prints the summary [`super::summary_table`] would print from every row without
//! holding every row.
//!
//! The summary shows, per metric and configuration, the worst row (the last of the largest
//! `|error|`, as `Iterator::max_by` picks it), judged over all scenarios and over the scenarios
//! each other configuration ran; it counts the scenarios each configuration ran; it prints each
//! metric's reference from its first row; and the notes look for a row above or below a
//! threshold. Scenarios are put in groups by the set of configurations that ran them (a
//! configuration may skip a whole level or, refusing a character, one scenario), so that within
//! a group every scenario was run by the same configurations. Kept, in their original order:
//!
//! - the first row of every metric (its unit and reference);
//! - per group, metric and configuration: the worst row, the lowest value and the highest value;
//!
//! and, as a [`Coverage`], how many scenarios each configuration ran and, for each kept row, its
//! group. That is at most three rows per group, metric and configuration, and one scenario's
//! rows waiting to be grouped, however many runs: memory does not grow with the number of
//! scenarios.

use std::collections::{BTreeMap, HashMap, HashSet};

use super::{badness, column, Coverage};
use crate::metrics::MetricRow;

/// A kept row, its position in the stream and its group.
type Kept = (u64, usize, MetricRow);

/// The rows kept for one group, metric and configuration.
#[derive(Default)]
struct Extremes {
    /// The last row of the largest badness.
    worst: Option<Kept>,
    /// The first row of the lowest value.
    min: Option<Kept>,
    /// The first row of the highest value.
    max: Option<Kept>,
}

/// Rows gathered run by run; [`SummaryRows::into_parts`] gives those the summary needs.
#[derive(Default)]
pub struct SummaryRows {
    /// Rows seen so far.
    seq: u64,
    /// The first row of each metric.
    always: Vec<Kept>,
    /// The scenarios each configuration ran.
    coverage: Coverage,
    /// The runs of the current scenario, grouped once its last run is in: the runs of one
    /// scenario come together (level names are unique in a run, scenario names within a level).
    pending: Vec<Vec<MetricRow>>,
    /// The metrics seen so far.
    metrics: HashSet<&'static str>,
    /// Per (group, metric, configuration column).
    extremes: HashMap<(usize, &'static str, String), Extremes>,
}

impl SummaryRows {
    /// Adds the rows of one run (a run with no row counts for nothing). Runs must come scenario
    /// by scenario, as `platbench run` makes them.
    pub fn push_run(&mut self, rows: Vec<MetricRow>) {
        let Some(r) = rows.first() else {
            return;
        };
        let same = self
            .pending
            .first()
            .and_then(|p| p.first())
            .is_some_and(|p| {
                (p.level.as_str(), p.scenario.as_str()) == (r.level.as_str(), r.scenario.as_str())
            });
        if !same {
            self.flush();
        }
        self.pending.push(rows);
    }

    /// Groups the pending scenario by the configurations that ran it and keeps its rows.
    fn flush(&mut self) {
        if self.pending.is_empty() {
            return;
        }
        let runs = std::mem::take(&mut self.pending);
        let columns: Vec<String> = runs.iter().map(|rows| column(&rows[0])).collect();
        let group = self.coverage.add_scenario(&columns);
        for r in runs.into_iter().flatten() {
            let seq = self.seq;
            self.seq += 1;
            if self.metrics.insert(r.metric) {
                self.always.push((seq, group, r.clone()));
            }
            let e = self
                .extremes
                .entry((group, r.metric, column(&r)))
                .or_default();
            let b = badness(&r);
            if e.worst
                .as_ref()
                .is_none_or(|(_, _, w)| b.total_cmp(&badness(w)).is_ge())
            {
                e.worst = Some((seq, group, r.clone()));
            }
            if e.min.as_ref().is_none_or(|(_, _, m)| r.value < m.value) {
                e.min = Some((seq, group, r.clone()));
            }
            if e.max.as_ref().is_none_or(|(_, _, m)| r.value > m.value) {
                e.max = Some((seq, group, r));
            }
        }
    }

    /// The kept rows, each once, in the order they came, and the scenarios each configuration
    /// ran: [`super::summary_table_in`] of the two is [`super::summary_table`] of every row.
    pub fn into_parts(mut self) -> (Vec<MetricRow>, Coverage) {
        self.flush();
        let mut kept: BTreeMap<u64, (usize, MetricRow)> = self
            .always
            .into_iter()
            .map(|(seq, g, r)| (seq, (g, r)))
            .collect();
        for e in self.extremes.into_values() {
            for (seq, g, r) in [e.worst, e.min, e.max].into_iter().flatten() {
                kept.insert(seq, (g, r));
            }
        }
        let mut coverage = self.coverage;
        let rows = kept
            .into_values()
            .map(|(g, r)| {
                coverage.place(&r.level, &r.scenario, g);
                r
            })
            .collect();
        (rows, coverage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{summary_table, summary_table_in};

    #[test]
    fn a_scenario_one_configuration_refused_is_judged_without_it() {
        // Level l1: y refused scenario s2 (a character it cannot build), so s2 is not in the
        // scenarios both ran. Over s1 and s3, x (worst 0.01) beats y (worst 0.03); counting s2
        // as y's too, x's 0.5 there would hand the mark to y. y ran 2 of 3 scenarios.
        let r = |s: &str, c: &str, v: f64| row("l1", s, c, "max_penetration", v);
        let runs = vec![
            vec![r("s1", "x", 0.01)],
            vec![r("s1", "y", 0.02)],
            vec![r("s2", "x", 0.5)],
            vec![r("s3", "x", 0.0)],
            vec![r("s3", "y", 0.03)],
        ];
        let all: Vec<MetricRow> = runs.iter().flatten().cloned().collect();
        let mut kept = SummaryRows::default();
        for run in runs {
            kept.push_run(run);
        }
        let (rows, coverage) = kept.into_parts();
        let table = summary_table(&all);
        assert!(table.contains("b y (over 2 of 3)"), "{table}");
        assert!(table.contains("0.5000*"), "{table}");
        assert_eq!(summary_table_in(&rows, &coverage), table);
    }

    fn row(level: &str, scenario: &str, config: &str, metric: &'static str, v: f64) -> MetricRow {
        MetricRow {
            level: level.into(),
            scenario: scenario.into(),
            backend: "b".into(),
            config: config.into(),
            metric,
            value: v,
            unit: crate::metrics::registry::unit(metric),
            reference: 0.0,
            error: v,
            frame: None,
            q1: None,
            q3: None,
        }
    }

    #[test]
    fn the_summary_of_the_kept_rows_is_the_summary_of_all() {
        // Two levels: "l1" run by configurations x and y, "l2" by x only (group 1). Values
        // chosen so that x is worst on l2, which y did not run: judged over the scenarios both
        // ran, x beats y, which marks it best only if l2's rows stay out of that comparison.
        let mut all = Vec::new();
        let mut kept = SummaryRows::default();
        let runs: Vec<(usize, Vec<MetricRow>)> = vec![
            (
                0,
                vec![
                    row("l1", "s1", "x", "max_penetration", 0.01),
                    row("l1", "s1", "x", "tunneled", 0.0),
                ],
            ),
            (
                0,
                vec![
                    row("l1", "s1", "y", "max_penetration", 0.02),
                    row("l1", "s1", "y", "tunneled", 0.0),
                ],
            ),
            (
                0,
                vec![
                    row("l1", "s2", "x", "max_penetration", 0.0),
                    row("l1", "s2", "x", "tunneled", 1.0),
                ],
            ),
            (
                0,
                vec![
                    row("l1", "s2", "y", "max_penetration", 0.03),
                    row("l1", "s2", "y", "tunneled", 0.0),
                ],
            ),
            (
                1,
                vec![
                    row("l2", "s1", "x", "max_penetration", 0.5),
                    row("l2", "s1", "x", "tunneled", 0.0),
                ],
            ),
            (
                1,
                vec![
                    row("l2", "s2", "x", "max_penetration", -0.5),
                    row("l2", "s2", "x", "tunneled", 0.0),
                ],
            ),
            (
                1,
                vec![
                    row("l2", "s3", "x", "max_penetration", 0.2),
                    row("l2", "s3", "x", "tunneled", 0.0),
                ],
            ),
        ];
        for (_, rows) in runs {
            all.extend(rows.iter().cloned());
            kept.push_run(rows);
        }
        let (kept, coverage) = kept.into_parts();
        assert!(kept.len() < all.len(), "nothing was left out");
        assert_eq!(summary_table_in(&kept, &coverage), summary_table(&all));
        // The lowest and highest values survive, for the notes.
        for v in [-0.5, 0.5] {
            assert!(kept.iter().any(|r| r.value == v));
        }
    }
}
