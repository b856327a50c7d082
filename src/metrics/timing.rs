//! The cost metric, `ns_per_character_step`: how a scenario's time per character step is
//! sampled and summarised (median and interquartile range of [`SAMPLES`] whole runs), and its
//! `metrics.csv` row.

use crate::level::{Level, ScenarioSpec};

use super::{registry, MetricRow};

/// Whole runs timed per scenario and configuration by `platbench run --timing`, one per round
/// over every run (see [`time_rounds`]).
///
/// Eleven: the median is then a sample (the 6th), the quartiles fall between the 3rd and 4th
/// and the 8th and 9th, so a single disturbed run (a context switch, another build's burst)
/// moves none of them, and two moves at most one quartile. More samples narrow the estimates
/// slowly (as 1/sqrt(n)) while the run's time grows with them; eleven keeps a timed run of the
/// built-in set within about twice the minimum-of-5 run it replaces (docs/speed.md says the
/// measured times).
pub(crate) const SAMPLES: usize = 11;

/// Times every scenario of `levels` on every configuration of `configs` [`SAMPLES`] times, in
/// rounds: each round times each (scenario, configuration) once, in run order (level, scenario,
/// configuration), so that a scenario's samples are spread over the whole timing and a burst of
/// load on the machine disturbs one sample of many scenarios, not every sample of a few. Each
/// sample is a whole run right after an untimed one of the same run, so that a configuration's
/// time depends far less on which ran before it in the round (docs/speed.md gives what is left:
/// a few percent after an engine's run). The
/// samples of run `i` (in that order) are `out[i]`; a run its configuration does not model, or
/// that fails (the measured run says why), has NaN samples. `progress` is told each round's
/// start.
pub(crate) fn time_rounds(
    levels: &[Level],
    configs: &[crate::config::RunConfig],
    mut progress: impl FnMut(usize),
) -> Vec<[f64; SAMPLES]> {
    let runs: usize = levels.iter().map(|l| l.scenarios.len()).sum::<usize>() * configs.len();
    let mut out = vec![[f64::NAN; SAMPLES]; runs];
    for round in 0..SAMPLES {
        progress(round);
        // The runs' sample arrays in run order, one taken per (scenario, configuration).
        let mut slots = out.iter_mut();
        for level in levels {
            let mut runner = crate::scenario::Runner::new(level);
            for spec in &level.scenarios {
                for run in configs {
                    let Some(slot) = slots.next() else {
                        unreachable!("one slot per run, counted above")
                    };
                    if crate::backend::runs_scenario(&*run.backend, level, spec) {
                        // Two whole runs, the first untimed: the sample is the second, with this
                        // configuration's code, branch history and data warmer whatever ran
                        // before it in the round (measured first after another controller, a
                        // sweep configuration took about 1.2x its time measured second; 1.03x
                        // with this run before it).
                        let mut two = [f64::NAN; 2];
                        if crate::scenario::time_samples(&mut runner, spec, run, &mut two).is_ok() {
                            slot[round] = two[1];
                        }
                    }
                }
            }
        }
    }
    out
}

/// A timing summarised: the median of the samples and their quartiles (the interquartile
/// range `q3 - q1` is the spread), in nanoseconds per character step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Timing {
    /// The median sample.
    pub(crate) median: f64,
    /// The first quartile.
    pub(crate) q1: f64,
    /// The third quartile.
    pub(crate) q3: f64,
}

/// The `p`-quantile of sorted `v` (not empty), interpolated linearly between the two nearest
/// order statistics (what R's default type 7 and numpy's `quantile` do).
pub(crate) fn quantile(v: &[f64], p: f64) -> f64 {
    let h = (v.len() - 1) as f64 * p.clamp(0.0, 1.0);
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    v[lo] + (h - lo as f64) * (v[hi] - v[lo])
}

impl Timing {
    /// The median and quartiles of `samples` (sorted in place); `None` when there are none or
    /// one is not a finite number.
    pub(crate) fn of(samples: &mut [f64]) -> Option<Timing> {
        if samples.is_empty() || samples.iter().any(|x| !x.is_finite()) {
            return None;
        }
        samples.sort_by(f64::total_cmp);
        Some(Timing {
            median: quantile(samples, 0.5),
            q1: quantile(samples, 0.25),
            q3: quantile(samples, 0.75),
        })
    }
}

/// The `ns_per_character_step` row of a timed scenario: the median as its value, the quartiles
/// in its `q1` and `q3` columns (see [`crate::scenario::time_samples`]).
pub(crate) fn timing_row(
    level: &Level,
    spec: &ScenarioSpec,
    run: &crate::config::RunConfig,
    t: Timing,
) -> MetricRow {
    MetricRow {
        level: level.name.clone(),
        scenario: spec.name.clone(),
        backend: run.backend.backend().to_string(),
        config: run.label.clone(),
        metric: "ns_per_character_step",
        value: t.median,
        unit: registry::unit("ns_per_character_step"),
        reference: 0.0,
        error: t.median,
        // A timing comes from repeated whole runs, no frame.
        frame: None,
        q1: Some(t.q1),
        q3: Some(t.q3),
    }
}

/// `v` to three significant figures, as timings are printed: `1234.5` is `1230`, `0.012345`
/// is `0.0123`; an integer part longer than three digits is rounded, never written in
/// scientific form.
pub(crate) fn three_figures(v: f64) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let digits = |x: f64| x.abs().log10().floor() as i32;
    let unit = 10f64.powi(digits(v) - 2);
    // Rounded first: 99.96 rounds to 100, which has one digit more and no decimal.
    let r = (v / unit).round() * unit;
    format!("{r:.*}", (2 - digits(r)).max(0) as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_and_quartiles_of_eleven_samples_are_order_statistics_or_between() {
        let mut s: Vec<f64> = (1..=11).rev().map(f64::from).collect();
        let t = Timing::of(&mut s).unwrap();
        assert_eq!((t.q1, t.median, t.q3), (3.5, 6.0, 8.5));
        // One wild sample moves neither the median nor a quartile.
        let mut s: Vec<f64> = (1..=10).map(f64::from).chain([1e9]).collect();
        assert_eq!(Timing::of(&mut s).unwrap(), t);
        assert_eq!(Timing::of(&mut []), None);
        assert_eq!(Timing::of(&mut [1.0, f64::NAN]), None);
        assert_eq!(Timing::of(&mut [4.0]).unwrap().q1, 4.0);
    }

    #[test]
    fn timings_print_to_three_significant_figures() {
        assert_eq!(three_figures(1234.5), "1230");
        assert_eq!(three_figures(123.45), "123");
        assert_eq!(three_figures(12.345), "12.3");
        assert_eq!(three_figures(1.0), "1.00");
        assert_eq!(three_figures(0.012345), "0.0123");
        assert_eq!(three_figures(99.96), "100");
        assert_eq!(three_figures(0.0), "0");
    }
}
