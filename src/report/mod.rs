//! Terminal tables over metric rows: a per-metric summary (the worst scenario of each
//! configuration, side by side, with the better one named) and a per-scenario detail table.
//! Tables are Markdown-style ASCII so they read the same in a terminal, a CI log and a PR.

pub(crate) mod check;
pub(crate) mod cost;
pub mod diff;
pub mod html;
mod html_colours;
mod html_nav;
mod html_replay_data;
mod html_sections;
pub(crate) use html_sections::GridShape;
pub(crate) mod manifest;
pub mod notes;
pub mod profile;
pub mod replay;
mod replay_drawn;
pub(crate) mod review_page;
pub mod rules;
pub mod summary_rows;
pub mod verdict;

use comfy_table::{presets, CellAlignment, Table};

use std::collections::HashMap;

use crate::metrics::{registry, MetricRow};

// A setting value is written as the stress matrix writes it (its concern, one layer down).
pub use crate::stress::format_setting;

/// Formats a metric value compactly: integers as integers, small magnitudes in scientific form.
pub(crate) fn format_value(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else if v == 0.0 {
        "0".into()
    } else if v.fract() == 0.0 && v.abs() < 1e9 {
        format!("{v:.0}")
    } else if v.abs() >= 1e-3 && v.abs() < 1e5 {
        format!("{v:.4}")
    } else {
        format!("{v:.2e}")
    }
}

/// Formats a value of a metric in `unit`: a timing (ns) to three significant figures (its
/// noise makes any more digits meaningless), anything else as [`format_value`].
pub(crate) fn format_metric(v: f64, unit: &str) -> String {
    if unit == "ns" {
        crate::metrics::timing::three_figures(v)
    } else {
        format_value(v)
    }
}

/// A configuration as a column label: the backend, then its configuration unless default.
pub(crate) fn column(r: &MetricRow) -> String {
    if r.config == "default" {
        r.backend.clone()
    } else {
        format!("{} {}", r.backend, r.config)
    }
}

/// How far a row is from ideal (larger is worse).
fn badness(r: &MetricRow) -> f64 {
    let e = r.error.abs();
    if e.is_nan() {
        f64::INFINITY
    } else {
        e
    }
}

fn new_table(header: Vec<String>) -> Table {
    let mut t = Table::new();
    t.load_style(presets::ASCII_MARKDOWN);
    t.set_header(header);
    t
}

/// The summary: one table per group of metrics ([`registry::SUMMARY_GROUPS`]), each with one row
/// per configuration and one column per metric; each cell is the configuration's worst value
/// over the scenarios it ran (farthest from ideal), `*` marks the best configuration of each
/// metric (compared with each other configuration over the scenarios both ran), a configuration
/// that ran fewer scenarios than the others says "over N of M", and the first row gives the
/// ideal value.
pub fn summary_table(rows: &[MetricRow]) -> String {
    summary_table_in(rows, &Coverage::of(rows))
}

/// [`summary_table`] of `rows` with the scenarios each configuration ran given by `coverage`
/// (the rows may then be only those [`summary_rows::SummaryRows`] kept).
pub fn summary_table_in(rows: &[MetricRow], coverage: &Coverage) -> String {
    let mut out = String::new();
    for title in registry::SUMMARY_GROUPS {
        let in_group =
            |m: &str| registry::get(m).is_some_and(|d| d.behaviour.summary_group() == title);
        if !rows.iter().any(|r| in_group(r.metric)) {
            continue;
        }
        if !out.is_empty() {
            out.push_str("\n\n");
        }
        out.push_str(&format!("{title}:\n"));
        out.push_str(&group_table(&worst_matrix_in(rows, coverage, in_group)));
    }
    let unknown = |m: &str| registry::get(m).is_none();
    if rows.iter().any(|r| unknown(r.metric)) {
        out.push_str("\n\n");
        out.push_str(&group_table(&worst_matrix_in(rows, coverage, unknown)));
    }
    out
}

/// The worst value of each metric for each configuration: what the summary and the report's
/// tables show.
pub(crate) struct WorstMatrix {
    /// Configuration labels (`backend config`), in first-seen order.
    pub configs: Vec<String>,
    /// Per configuration: how many scenarios it ran, and how many any configuration ran.
    pub coverage: Vec<(usize, usize)>,
    /// Metrics in catalog order: name, unit, ideal value.
    pub metrics: Vec<(&'static str, &'static str, f64)>,
    /// `cells[config][metric]`: the worst value, and whether it is the best of its metric
    /// (marked only when the configurations do not all tie).
    pub cells: Vec<Vec<Option<(f64, bool)>>>,
}

impl WorstMatrix {
    /// A configuration's label with its coverage when it ran fewer scenarios than the set:
    /// `sweep positions=integer/32 (over 39 of 62)`.
    pub fn label(&self, config: usize) -> String {
        let (n, m) = self.coverage[config];
        if n < m {
            format!("{} (over {n} of {m})", self.configs[config])
        } else {
            self.configs[config].clone()
        }
    }
}

/// One scenario's row of a metric for a configuration: (level, scenario), badness, value.
type Cell<'a> = ((&'a str, &'a str), f64, f64);

/// Which scenarios each configuration ran: what the summary counts ("over N of M") and judges
/// "best" within. [`Coverage::of`] reads it off every row; [`summary_rows::SummaryRows`] keeps it
/// as counts and groups of scenarios (by the set of configurations that ran them), placing only
/// the scenarios of the rows it keeps, in memory that does not grow with the number of runs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Configuration columns in the order they first ran, each with the scenarios it ran.
    configs: Vec<(String, usize)>,
    /// Scenarios any configuration ran.
    all: usize,
    /// Per group: which configurations (by index in `configs`) ran its scenarios.
    groups: Vec<Vec<bool>>,
    /// The group of a scenario, by level, then scenario.
    placed: HashMap<String, HashMap<String, usize>>,
}

impl Coverage {
    /// The coverage of `rows`, every row of a run.
    pub fn of(rows: &[MetricRow]) -> Self {
        let mut c = Coverage::default();
        let mut seen: HashMap<(&str, &str), Vec<String>> = HashMap::new();
        let mut order: Vec<(&str, &str)> = Vec::new();
        for r in rows {
            let col = column(r);
            c.config(&col);
            let key = (r.level.as_str(), r.scenario.as_str());
            let ran = seen.entry(key).or_insert_with(|| {
                order.push(key);
                Vec::new()
            });
            if !ran.contains(&col) {
                ran.push(col);
            }
        }
        for key in order {
            let g = c.add_scenario(&seen[&key]);
            c.place(key.0, key.1, g);
        }
        c
    }

    /// The index of configuration column `column`, added if new.
    fn config(&mut self, column: &str) -> usize {
        match self.configs.iter().position(|(c, _)| c == column) {
            Some(i) => i,
            None => {
                self.configs.push((column.to_string(), 0));
                self.configs.len() - 1
            }
        }
    }

    /// Counts one scenario run by the configuration columns `columns`; returns its group.
    pub(crate) fn add_scenario(&mut self, columns: &[String]) -> usize {
        let mut set = Vec::new();
        for c in columns {
            let ci = self.config(c);
            self.configs[ci].1 += 1;
            if set.len() <= ci {
                set.resize(ci + 1, false);
            }
            set[ci] = true;
        }
        self.all += 1;
        // Configurations first seen later are false in earlier groups: compare up to the longer.
        let same = |g: &Vec<bool>| {
            (0..g.len().max(set.len()))
                .all(|i| g.get(i).copied().unwrap_or(false) == set.get(i).copied().unwrap_or(false))
        };
        match self.groups.iter().position(same) {
            Some(g) => g,
            None => {
                self.groups.push(set);
                self.groups.len() - 1
            }
        }
    }

    /// Records that scenario `scenario` of `level` is in group `group`.
    pub(crate) fn place(&mut self, level: &str, scenario: &str, group: usize) {
        self.placed
            .entry(level.to_string())
            .or_default()
            .insert(scenario.to_string(), group);
    }

    /// Whether configuration `config` ran scenario `key` (level, scenario).
    fn ran(&self, config: usize, key: (&str, &str)) -> bool {
        self.placed
            .get(key.0)
            .and_then(|s| s.get(key.1))
            .is_some_and(|&g| self.groups[g].get(config).copied().unwrap_or(false))
    }
}

/// Computes the worst-per-configuration matrix of the metrics `keep` selects. Scenario coverage
/// is counted over all of `rows` (every metric), so pass the whole run.
pub(crate) fn worst_matrix(rows: &[MetricRow], keep: impl Fn(&str) -> bool) -> WorstMatrix {
    worst_matrix_in(rows, &Coverage::of(rows), keep)
}

/// [`worst_matrix`] with the scenarios each configuration ran given by `coverage`.
pub(crate) fn worst_matrix_in(
    rows: &[MetricRow],
    cov: &Coverage,
    keep: impl Fn(&str) -> bool,
) -> WorstMatrix {
    let configs: Vec<String> = cov.configs.iter().map(|(c, _)| c.clone()).collect();
    let mut metrics: Vec<(&'static str, &'static str, f64)> = Vec::new();
    for r in rows {
        if keep(r.metric) && !metrics.iter().any(|(m, _, _)| *m == r.metric) {
            metrics.push((r.metric, r.unit, r.reference));
        }
    }
    metrics.sort_by_key(|(m, _, _)| registry::position(m));
    let config_index: std::collections::HashMap<String, usize> = configs
        .iter()
        .enumerate()
        .map(|(i, c)| (c.clone(), i))
        .collect();
    // per_metric[metric][config]: (scenario, badness) of each row.
    let mut per_metric: Vec<Vec<Vec<Cell>>> = vec![vec![Vec::new(); configs.len()]; metrics.len()];
    for r in rows {
        if let Some(mi) = metrics.iter().position(|(m, _, _)| *m == r.metric) {
            let ci = config_index[&column(r)];
            per_metric[mi][ci].push(((r.level.as_str(), r.scenario.as_str()), badness(r), r.value));
        }
    }
    // Worst of a configuration's rows over the scenarios `within` ran (all if None).
    let worst_over = |cells: &[Cell], within: Option<usize>| {
        cells
            .iter()
            .filter(|(k, _, _)| within.is_none_or(|d| cov.ran(d, *k)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|&(_, b, v)| (b, v))
    };
    let best: Vec<Vec<bool>> = per_metric
        .iter()
        .map(|pm| {
            // A configuration is best when no other beats it over the scenarios both ran.
            (0..configs.len())
                .map(|c| {
                    !pm[c].is_empty()
                        && (0..configs.len()).filter(|&d| d != c).all(|d| {
                            match (worst_over(&pm[c], Some(d)), worst_over(&pm[d], Some(c))) {
                                (Some((bc, _)), Some((bd, _))) => bc <= bd + TIE_TOLERANCE,
                                _ => true,
                            }
                        })
                })
                .collect()
        })
        .collect();
    let cells = (0..configs.len())
        .map(|ci| {
            (0..metrics.len())
                .map(|mi| {
                    let measured = per_metric[mi].iter().filter(|c| !c.is_empty()).count();
                    let marked = best[mi].iter().filter(|b| **b).count();
                    // Every measured configuration best: they all tie, nothing is marked.
                    let all_tie = marked == measured;
                    worst_over(&per_metric[mi][ci], None)
                        .map(|(_, v)| (v, best[mi][ci] && !all_tie))
                })
                .collect()
        })
        .collect();
    let coverage = cov.configs.iter().map(|(_, n)| (*n, cov.all)).collect();
    WorstMatrix {
        configs,
        coverage,
        metrics,
        cells,
    }
}

/// One summary table of a matrix.
fn group_table(m: &WorstMatrix) -> String {
    let mut header = vec!["configuration".to_string()];
    header.extend(
        m.metrics
            .iter()
            .map(|(name, unit, _)| format!("{}\n({unit})", name.replace('_', "\n"))),
    );
    let mut table = new_table(header);
    // A cost has no ideal (its reference 0 is no controller's aim): no ideal row for timings.
    if m.metrics.iter().any(|(_, unit, _)| *unit != "ns") {
        let mut ideal = vec!["ideal".to_string()];
        ideal.extend(m.metrics.iter().map(|(_, unit, r)| {
            if *unit == "ns" {
                "-".to_string()
            } else {
                format_value(*r)
            }
        }));
        table.add_row(ideal);
    }
    for (ci, row) in m.cells.iter().enumerate() {
        if row.iter().all(|c| c.is_none()) {
            continue;
        }
        let mut cells = vec![m.label(ci)];
        cells.extend(
            row.iter()
                .zip(&m.metrics)
                .map(|(cell, (_, unit, _))| match cell {
                    None => "-".into(),
                    Some((v, best)) => format!(
                        "{}{}",
                        format_metric(*v, unit),
                        if *best { "*" } else { "" }
                    ),
                }),
        );
        table.add_row(cells);
    }
    let metrics = &m.metrics;
    for i in 1..=metrics.len() {
        if let Some(c) = table.column_mut(i) {
            c.set_cell_alignment(CellAlignment::Right);
        }
    }
    table.to_string()
}

/// Distance from ideal below which two configurations tie: f32 rounding of positions of a few
/// tiles (ulp 2.4e-7 to 9.5e-7 for 2 to 8 tiles) accumulates to about this much.
pub(crate) const TIE_TOLERANCE: f64 = 1e-6;

/// Every metric of every scenario, configurations side by side.
pub(crate) fn detail_table(rows: &[MetricRow]) -> String {
    let mut columns: Vec<String> = Vec::new();
    let mut keys: Vec<(String, String, &'static str)> = Vec::new();
    for r in rows {
        let c = column(r);
        if !columns.contains(&c) {
            columns.push(c);
        }
        let k = (r.level.clone(), r.scenario.clone(), r.metric);
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    let mut header = vec!["scenario".to_string(), "metric".to_string()];
    header.extend(columns.iter().cloned());
    let mut table = new_table(header);
    for (level, scenario, metric) in &keys {
        let mut cells = vec![format!("{level}.{scenario}"), metric.to_string()];
        for c in &columns {
            let v = rows.iter().find(|r| {
                r.level == *level
                    && r.scenario == *scenario
                    && r.metric == *metric
                    && column(r) == *c
            });
            cells.push(v.map_or("-".into(), |r| format_metric(r.value, r.unit)));
        }
        table.add_row(cells);
    }
    table.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(config: &str, scenario: &str, value: f64) -> MetricRow {
        MetricRow {
            level: "l".into(),
            scenario: scenario.into(),
            backend: "sweep".into(),
            config: config.into(),
            metric: "apex_error",
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
    fn summary_shows_worst_per_configuration_and_marks_the_best() {
        let rows = vec![
            row("a", "s1", 1e-6),
            row("a", "s2", -2e-5),
            row("b", "s1", -0.1),
            row("b", "s2", 0.01),
        ];
        let t = summary_table(&rows);
        let line = |label: &str| {
            t.lines()
                .find(|l| l.starts_with(&format!("| {label} ")))
                .unwrap()
                .to_string()
        };
        assert!(line("sweep a").contains("-2.00e-5*"), "{t}");
        assert!(line("sweep b").contains("-0.1000 "), "{t}");
        assert!(!line("sweep b").contains('*'), "{t}");
    }

    #[test]
    fn a_configuration_is_compared_only_over_the_scenarios_it_ran() {
        // b ran only s1, where a is exact: over that shared scenario a is better, although a's
        // worst over everything it ran (s2, 0.5) is worse than b's (0.1).
        let mut b1 = row("b", "s1", 0.1);
        b1.backend = "sweep".into();
        let rows = vec![row("a", "s1", 0.0), row("a", "s2", 0.5), b1];
        let t = summary_table(&rows);
        let line = |label: &str| {
            t.lines()
                .find(|l| l.starts_with(&format!("| {label}")))
                .unwrap()
                .to_string()
        };
        assert!(line("sweep a ").contains("0.5000*"), "{t}");
        assert!(line("sweep b (over 1 of 2)").contains("0.1000 "), "{t}");
    }

    #[test]
    fn values_format_compactly() {
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(3.0), "3");
        assert_eq!(format_value(0.25), "0.2500");
        assert_eq!(format_value(1.5e-7), "1.50e-7");
        assert_eq!(format_value(f64::INFINITY), "inf");
    }
}
