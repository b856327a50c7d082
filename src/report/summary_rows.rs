//! The metric rows the summary needs, kept from a stream of runs, so that a run of many
//! scenarios prints the summary [`super::summary_table`] would print from every row without
//! holding every row.
//!
//! The summary shows, per metric and configuration, the worst row (the last of the largest
//! `|error|`, as `Iterator::max_by` picks it), judged over all scenarios and over the scenarios
//! each other configuration ran; it counts the scenarios each configuration ran; it prints each
//! metric's reference from its first row; and the notes look for a row above or below a
//! threshold. A configuration runs every scenario of a level or none of it, so runs are put in
//! groups (the levels that the same configurations model), within which every scenario was run
//! by the same configurations. Kept, in their original order:
//!
//! - the first row of every metric (its unit and reference);
//! - per group, metric and configuration: the worst row, the lowest value and the highest value;
//!
//! and, as a [`Coverage`], how many scenarios each configuration ran and which groups it ran.
//! That is at most three rows per group, metric and configuration and one entry per level,
//! however many runs: memory does not grow with the number of scenarios (issue 24).

use std::collections::{BTreeMap, HashMap, HashSet};

use super::{badness, column, Coverage};
use crate::metrics::MetricRow;

/// A kept row and its position in the stream.
type Kept = (u64, MetricRow);

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

/// Rows gathered run by run; [`SummaryRows::into_rows`] gives those the summary needs.
#[derive(Default)]
pub struct SummaryRows {
    /// Rows seen so far.
    seq: u64,
    /// The first row of each metric.
    always: Vec<Kept>,
    /// The scenarios each configuration ran.
    coverage: Coverage,
    /// The (level, scenario) of the last run: runs of one scenario come together (level names
    /// are unique in a run, scenario names within a level), so a new one is a new scenario.
    last: Option<(String, String)>,
    /// The metrics seen so far.
    metrics: HashSet<&'static str>,
    /// Per (group, metric, configuration column).
    extremes: HashMap<(usize, &'static str, String), Extremes>,
}

impl SummaryRows {
    /// Adds the rows of one run; `group` names the run's group: levels modelled by different
    /// sets of configurations must be in different groups (levels modelled by the same set may
    /// share one; one group per level is always right, one per set of configurations keeps
    /// fewer rows).
    pub fn push_run(&mut self, group: usize, rows: Vec<MetricRow>) {
        if let Some(r) = rows.first() {
            let key = (r.level.as_str(), r.scenario.as_str());
            let first = self
                .last
                .as_ref()
                .is_none_or(|(l, s)| (l.as_str(), s.as_str()) != key);
            if first {
                self.last = Some((r.level.clone(), r.scenario.clone()));
            }
            self.coverage.add_run(&r.level, group, column(r), first);
        }
        for r in rows {
            let seq = self.seq;
            self.seq += 1;
            if self.metrics.insert(r.metric) {
                self.always.push((seq, r.clone()));
            }
            let e = self
                .extremes
                .entry((group, r.metric, column(&r)))
                .or_default();
            let b = badness(&r);
            if e.worst
                .as_ref()
                .is_none_or(|(_, w)| b.total_cmp(&badness(w)).is_ge())
            {
                e.worst = Some((seq, r.clone()));
            }
            if e.min.as_ref().is_none_or(|(_, m)| r.value < m.value) {
                e.min = Some((seq, r.clone()));
            }
            if e.max.as_ref().is_none_or(|(_, m)| r.value > m.value) {
                e.max = Some((seq, r));
            }
        }
    }

    /// The kept rows, each once, in the order they came, and the scenarios each configuration
    /// ran: [`super::summary_table_in`] of the two is [`super::summary_table`] of every row.
    pub fn into_parts(self) -> (Vec<MetricRow>, Coverage) {
        let mut kept: BTreeMap<u64, MetricRow> = self.always.into_iter().collect();
        for e in self.extremes.into_values() {
            for (seq, r) in [e.worst, e.min, e.max].into_iter().flatten() {
                kept.insert(seq, r);
            }
        }
        (kept.into_values().collect(), self.coverage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{summary_table, summary_table_in};

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
        for (g, rows) in runs {
            all.extend(rows.iter().cloned());
            kept.push_run(g, rows);
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
