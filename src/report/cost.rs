//! The closing lines of a timed run, in hyperfine's manner: how many times cheaper the cheapest
//! configuration is than each other one, with the spread of that ratio over the scenarios.
//!
//! The ratio of configurations A and B on a scenario both timed is B's median time per
//! character step over A's. The line gives the median of those per-scenario ratios and, after
//! `±`, half their interquartile range: half the scenarios both timed lie within about that
//! much of the median (the spread says how much the ratio depends on the scenario, which on a
//! shared machine is larger than any one timing's noise). The cheapest configuration is the one
//! whose median, over the scenarios it timed, of its time over that scenario's cheapest time
//! is least (it need not have timed every scenario).

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::metrics::timing::{quantile, three_figures};
use crate::metrics::MetricRow;

/// The timings of a run, one median per (scenario, configuration), kept as the rows come.
#[derive(Clone, Debug, Default)]
pub(crate) struct CostRows {
    /// Configuration columns ([`super::column`]), in the order first timed.
    configs: Vec<String>,
    /// Scenario index by (level, scenario).
    scenarios: HashMap<(String, String), usize>,
    /// `level.scenario` by scenario index.
    names: Vec<String>,
    /// (scenario, configuration, median ns per character step) of every timing row.
    times: Vec<(usize, usize, f64)>,
}

impl CostRows {
    /// Keeps the timing rows (`ns_per_character_step`, finite and above 0) of one run's rows.
    pub(crate) fn push_run(&mut self, rows: &[MetricRow]) {
        for r in rows
            .iter()
            .filter(|r| r.metric == "ns_per_character_step" && r.value.is_finite() && r.value > 0.0)
        {
            let col = super::column(r);
            let c = match self.configs.iter().position(|x| *x == col) {
                Some(c) => c,
                None => {
                    self.configs.push(col);
                    self.configs.len() - 1
                }
            };
            let next = self.scenarios.len();
            let s = *self
                .scenarios
                .entry((r.level.clone(), r.scenario.clone()))
                .or_insert_with(|| {
                    self.names.push(format!("{}.{}", r.level, r.scenario));
                    next
                });
            self.times.push((s, c, r.value));
        }
    }

    /// The closing lines: one per configuration but the cheapest (under it, the scenarios of its
    /// least and greatest ratio), from the least median ratio to the
    /// greatest (see the module's doc); none when fewer than two configurations were timed.
    pub(crate) fn closing_lines(&self) -> Vec<String> {
        let (nc, ns) = (self.configs.len(), self.scenarios.len());
        if nc < 2 {
            return Vec::new();
        }
        let mut grid: Vec<Vec<Option<f64>>> = vec![vec![None; nc]; ns];
        for &(s, c, t) in &self.times {
            grid[s][c] = Some(t);
        }
        // Per configuration: its time over the scenario's cheapest, over the scenarios it timed.
        let relative = |c: usize| {
            let mut v: Vec<f64> = grid
                .iter()
                .filter_map(|row| {
                    let least = row.iter().flatten().copied().fold(f64::INFINITY, f64::min);
                    row[c].map(|t| t / least)
                })
                .collect();
            v.sort_by(f64::total_cmp);
            (!v.is_empty()).then(|| quantile(&v, 0.5))
        };
        let Some(cheapest) = (0..nc)
            .filter_map(|c| relative(c).map(|r| (c, r)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(c, _)| c)
        else {
            return Vec::new();
        };
        let mut lines: Vec<(f64, String)> = (0..nc)
            .filter(|&o| o != cheapest)
            .filter_map(|o| {
                let mut ratios: Vec<(f64, usize)> = grid
                    .iter()
                    .enumerate()
                    .filter_map(|(s, row)| Some((row[o]? / row[cheapest]?, s)))
                    .collect();
                if ratios.is_empty() {
                    return None;
                }
                ratios.sort_by(|x, y| x.0.total_cmp(&y.0));
                let (least, most) = (ratios[0], ratios[ratios.len() - 1]);
                let ratios: Vec<f64> = ratios.into_iter().map(|(r, _)| r).collect();
                let r = quantile(&ratios, 0.5);
                let half_iqr = (quantile(&ratios, 0.75) - quantile(&ratios, 0.25)) / 2.0;
                let (a, b) = (&self.configs[cheapest], &self.configs[o]);
                let n = ratios.len();
                let scenarios = if n == 1 { "scenario" } else { "scenarios" };
                let mut line = if r >= 1.0 {
                    format!(
                        "{a} is {} × cheaper than {b} (median over {n} {scenarios})",
                        with_spread(r, half_iqr)
                    )
                } else {
                    format!(
                        "{a} costs {} × what {b} costs (median over {n} {scenarios})",
                        with_spread(r, half_iqr)
                    )
                };
                if n > 1 {
                    // The scenarios where the gap is least and greatest, to trace the extremes.
                    let _ = write!(
                        line,
                        "\n    least {} × on {}, greatest {} × on {}",
                        three_figures(least.0),
                        self.names[least.1],
                        three_figures(most.0),
                        self.names[most.1]
                    );
                }
                Some((r, line))
            })
            .collect();
        lines.sort_by(|a, b| a.0.total_cmp(&b.0));
        lines.into_iter().map(|(_, l)| l).collect()
    }
}

/// `r ± s`, `r` to three significant figures and `s` to as many decimals.
fn with_spread(r: f64, s: f64) -> String {
    let r = three_figures(r);
    let decimals = r.split_once('.').map_or(0, |(_, d)| d.len());
    format!("{r} ± {s:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn timing(level: &str, scenario: &str, backend: &str, value: f64) -> MetricRow {
        MetricRow {
            level: level.into(),
            scenario: scenario.into(),
            backend: backend.into(),
            config: "default".into(),
            metric: "ns_per_character_step",
            value,
            unit: "ns",
            reference: 0.0,
            error: value,
            frame: None,
            q1: Some(value),
            q3: Some(value),
        }
    }

    #[test]
    fn the_closing_line_is_the_median_ratio_with_half_its_interquartile_range() {
        let mut c = CostRows::default();
        // b costs 2, 3, 4 and 5 times a's on four scenarios; c only ran the first, at 1.5 times.
        for (s, k) in [("s1", 2.0), ("s2", 3.0), ("s3", 4.0), ("s4", 5.0)] {
            c.push_run(&[timing("l", s, "a", 100.0), timing("l", s, "b", 100.0 * k)]);
        }
        c.push_run(&[timing("l", "s1", "c", 150.0)]);
        let lines = c.closing_lines();
        // Ratios of b: 2, 3, 4, 5: median 3.5, quartiles 2.75 and 4.25, half the range 0.75.
        assert_eq!(
            lines,
            [
                "a is 1.50 ± 0.00 × cheaper than c (median over 1 scenario)",
                "a is 3.50 ± 0.75 × cheaper than b (median over 4 scenarios)\n    least 2.00 × on l.s1, greatest 5.00 × on l.s4",
            ]
        );
        // One configuration: no line.
        let mut one = CostRows::default();
        one.push_run(&[timing("l", "s1", "a", 100.0)]);
        assert!(one.closing_lines().is_empty());
    }

    #[test]
    fn a_ratio_and_its_spread_print_to_the_same_decimals() {
        assert_eq!(with_spread(3.1034, 0.2117), "3.10 ± 0.21");
        assert_eq!(with_spread(12.34, 1.56), "12.3 ± 1.6");
        assert_eq!(with_spread(123.4, 10.2), "123 ± 10");
    }
}
