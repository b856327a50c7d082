//! The comparison rules of a diff: how far a metric may move (per-unit tolerances) and which way
//! is better (distance from ideal), where a trace diverges, and which changes fail the diff.

use serde::Serialize;

use crate::trace::TraceRow;

/// How much a metric may move before the move counts: `abs + rel * |base distance from ideal|`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Absolute tolerance, in the metric's unit.
    pub abs: f64,
    /// Relative tolerance, as a fraction of the baseline's distance from ideal.
    pub rel: f64,
}

/// Default tolerance by unit: lengths in tiles and ratios move with f32 rounding (1e-5 and 1%
/// of the distance from ideal); counts, frames and booleans are exact.
pub fn default_tolerance(unit: &str) -> Tolerance {
    match unit {
        "tiles" | "ratio" | "tiles/s" => Tolerance {
            abs: 1e-5,
            rel: 0.01,
        },
        // Timings: the least change that counts beyond their measured spread (see
        // `timing::TIMING_TOLERANCE`, measured on a loaded machine).
        "ns" => super::timing::TIMING_TOLERANCE,
        _ => Tolerance { abs: 0.0, rel: 0.0 },
    }
}

/// What happened to one metric.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Change {
    /// Within tolerance.
    Same,
    /// Closer to ideal beyond tolerance.
    Better,
    /// Farther from ideal beyond tolerance.
    Worse,
    /// In the new run only.
    Added,
    /// In the baseline only.
    Missing,
}

/// One metric's comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MetricDiff {
    /// `level.scenario`.
    pub scenario: String,
    /// `backend config`.
    pub config: String,
    /// Metric name.
    pub metric: String,
    /// Baseline value.
    pub base: Option<f64>,
    /// New value.
    pub new: Option<f64>,
    /// The verdict.
    pub change: Change,
    /// The trace frame of the baseline value, if its `metrics.csv` gives one (shown, never
    /// compared).
    pub base_frame: Option<u32>,
    /// The trace frame of the new value, if its `metrics.csv` gives one (shown, never compared).
    pub new_frame: Option<u32>,
    /// A timing's first quartile in the baseline, if its `metrics.csv` gives one.
    pub base_q1: Option<f64>,
    /// A timing's third quartile in the baseline, if its `metrics.csv` gives one.
    pub base_q3: Option<f64>,
    /// A timing's first quartile in the new run, if its `metrics.csv` gives one.
    pub new_q1: Option<f64>,
    /// A timing's third quartile in the new run, if its `metrics.csv` gives one.
    pub new_q3: Option<f64>,
}

/// What happened to one trace.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TraceChange {
    /// A position differs beyond the tolerance (a NaN where the other has a number counts).
    Diverged,
    /// One trace ends before the other (every frame before agrees).
    Truncated,
    /// In the baseline only.
    Missing,
    /// In the new run only.
    Added,
}

/// One trace's comparison.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TraceDiff {
    /// Trace file name.
    pub file: String,
    /// The verdict.
    pub change: TraceChange,
    /// First frame whose position differs beyond the tolerance (or where one trace ends), if
    /// any.
    pub frame: Option<u32>,
    /// Baseline feet position at that frame.
    pub base: Option<(f32, f32)>,
    /// New feet position at that frame.
    pub new: Option<(f32, f32)>,
}

/// How many metrics got each verdict, timings (`ns_per_character_step`) apart: only
/// `--fail-on-timing` fails on them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ChangeCounts {
    /// By whether the metric is a timing, then by [`Change`] (in its declared order).
    counts: [[usize; 5]; 2],
}

impl ChangeCounts {
    /// Counts one verdict.
    pub fn add(&mut self, m: &MetricDiff) {
        self.counts[usize::from(m.metric == "ns_per_character_step")][m.change as usize] += 1;
    }

    /// How many metrics got `change`, timings included.
    pub fn of(&self, change: Change) -> usize {
        self.counts[0][change as usize] + self.counts[1][change as usize]
    }

    /// How many metrics got `change`, timings only when `timing` is set.
    pub fn failing(&self, change: Change, timing: bool) -> usize {
        self.counts[0][change as usize]
            + if timing {
                self.counts[1][change as usize]
            } else {
                0
            }
    }
}

/// The comparison of two runs.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct RunDiff {
    /// The metrics that are not `Same`: the first [`crate::limits::MAX_LISTED_CHANGES`] of each
    /// change, in the order found ([`RunDiff::push`]); `counts` counts every one.
    pub metrics: Vec<MetricDiff>,
    /// How many metrics got each verdict, listed or not.
    pub counts: ChangeCounts,
    /// How many metrics were compared.
    pub compared: usize,
    /// Every trace that diverges, is missing or was added.
    pub traces: Vec<TraceDiff>,
    /// How many traces were compared.
    pub traces_compared: usize,
    /// How many of the metrics compared were timings found in both runs.
    pub timings_compared: usize,
}

/// What fails a diff, beyond a metric that got worse (which always does, timings aside).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FailOn {
    /// A timing (`ns_per_character_step`) that got worse fails too.
    pub timing: bool,
    /// A metric or trace in the baseline only does not fail (it is still listed).
    pub allow_missing: bool,
    /// A trace that diverges or ends early does not fail (it is still listed).
    pub allow_divergence: bool,
}

impl RunDiff {
    /// Counts a metric's verdict, and lists it if fewer than
    /// [`crate::limits::MAX_LISTED_CHANGES`] of its change are listed: what the diff shows stays
    /// in proportion to that, not to the files compared.
    pub fn push(&mut self, m: MetricDiff) {
        self.counts.add(&m);
        if self.counts.of(m.change) <= crate::limits::MAX_LISTED_CHANGES {
            self.metrics.push(m);
        }
    }

    /// How many metrics were counted but not listed.
    pub fn unlisted(&self) -> usize {
        let all: usize = [
            Change::Worse,
            Change::Better,
            Change::Missing,
            Change::Added,
        ]
        .iter()
        .map(|&c| self.counts.of(c))
        .sum();
        all.saturating_sub(self.metrics.len())
    }

    /// Whether a metric got worse (or went missing): the regression that fails CI. Timings
    /// (`ns_per_character_step`) count only when `timing_fails` is set: they are reported, but
    /// a shared machine's noise must not fail a build by default.
    pub fn regressed(&self, timing_fails: bool) -> bool {
        !self
            .failures(FailOn {
                timing: timing_fails,
                ..FailOn::default()
            })
            .is_empty()
    }

    /// Why the diff fails under `fail_on`, one line per kind of failure (empty: it passes): a
    /// metric worse beyond its tolerance, a metric or trace missing from the new run, a trace
    /// that diverges beyond the position tolerance or ends early.
    pub fn failures(&self, fail_on: FailOn) -> Vec<String> {
        let worse = self.counts.failing(Change::Worse, fail_on.timing);
        let missing_metrics = self.counts.failing(Change::Missing, fail_on.timing);
        let count = |c: TraceChange| self.traces.iter().filter(|t| t.change == c).count();
        let mut out = Vec::new();
        if worse > 0 {
            out.push(format!(
                "{worse} metric(s) got worse beyond their tolerance"
            ));
        }
        if !fail_on.allow_missing {
            if missing_metrics > 0 {
                out.push(format!(
                    "{missing_metrics} metric(s) of the baseline are missing from the new run (--allow-missing accepts that)"
                ));
            }
            if count(TraceChange::Missing) > 0 {
                out.push(format!(
                    "{} trace(s) of the baseline are missing from the new run (--allow-missing accepts that)",
                    count(TraceChange::Missing)
                ));
            }
        }
        if !fail_on.allow_divergence {
            for (c, what) in [
                (TraceChange::Diverged, "diverge beyond --position-tolerance"),
                (
                    TraceChange::Truncated,
                    "end before the baseline's or run past it",
                ),
            ] {
                if count(c) > 0 {
                    out.push(format!(
                        "{} trace(s) {what} (--allow-divergence accepts that)",
                        count(c)
                    ));
                }
            }
        }
        out
    }
}

/// Whether `new` is better, worse or the same as `base`, by distance from `reference`.
pub(super) fn classify(base: f64, new: f64, reference: f64, tol: Tolerance) -> Change {
    if reference.is_nan() && !(base.is_nan() && new.is_nan()) {
        // No reference (a damaged file) cannot say which way is better: a change beyond the
        // tolerance, or a NaN on one side only, is a difference, and a difference fails.
        let moved = (new - base).abs();
        return if base.to_bits() == new.to_bits() || moved <= tol.abs + tol.rel * base.abs() {
            Change::Same
        } else {
            Change::Worse
        };
    }
    let (db, dn) = ((base - reference).abs(), (new - reference).abs());
    if base.to_bits() == new.to_bits()
        || (db.is_infinite() && dn.is_infinite())
        || (db.is_nan() && dn.is_nan())
    {
        return Change::Same;
    }
    // A NaN is a difference: one that appears is worse, one that goes is better.
    if dn.is_nan() {
        return Change::Worse;
    }
    if db.is_nan() {
        return Change::Better;
    }
    let allowed = tol.abs + tol.rel * if db.is_finite() { db } else { 0.0 };
    if dn > db + allowed {
        Change::Worse
    } else if dn < db - allowed {
        Change::Better
    } else {
        Change::Same
    }
}

/// Whether two coordinates differ by more than `tol`: a NaN against a number does, two NaNs
/// do not.
fn differs(a: f32, b: f32, tol: f32) -> bool {
    if a.is_nan() || b.is_nan() {
        return a.is_nan() != b.is_nan();
    }
    a != b && (a - b).abs() > tol
}

/// The first frame where two traces' positions differ by more than a tolerance (or one ends
/// before the other), found as their rows are given in pairs: it holds the first divergence and
/// a count, never the rows, so a trace of any length compares in constant memory.
pub(super) struct Divergence {
    tol: f32,
    /// Pairs of rows given so far.
    rows: u64,
    found: Option<TraceDiff>,
}

impl Divergence {
    /// Nothing compared yet; positions may differ by `tol` tiles.
    pub(super) fn new(tol: f32) -> Self {
        Divergence {
            tol,
            rows: 0,
            found: None,
        }
    }

    /// The next row of each trace: a diverged position (or frame number) is kept if it is the
    /// first.
    pub(super) fn pair(&mut self, rb: &TraceRow, rn: &TraceRow) {
        let tol = self.tol;
        self.rows += 1;
        if self.found.is_none()
            && (differs(rb.x, rn.x, tol) || differs(rb.y, rn.y, tol) || rb.frame != rn.frame)
        {
            self.found = Some(TraceDiff {
                file: String::new(),
                change: TraceChange::Diverged,
                frame: Some(rb.frame),
                base: Some((rb.x, rb.y)),
                new: Some((rn.x, rn.y)),
            });
        }
    }

    /// One trace (or both) ended: `rb` or `rn` is the row of the other that has no partner.
    /// A trace that ends first is truncated at the count of rows both have, if nothing
    /// diverged before.
    pub(super) fn end(&mut self, rb: Option<&TraceRow>, rn: Option<&TraceRow>) {
        if self.found.is_some() || (rb.is_none() && rn.is_none()) {
            return;
        }
        self.found = Some(TraceDiff {
            file: String::new(),
            change: TraceChange::Truncated,
            frame: Some(u32::try_from(self.rows).unwrap_or(u32::MAX)),
            base: rb.map(|r| (r.x, r.y)),
            new: rn.map(|r| (r.x, r.y)),
        });
    }

    /// The first divergence, if any.
    pub(super) fn finish(self) -> Option<TraceDiff> {
        self.found
    }
}

/// The first frame where the two traces' positions differ by more than `tol` (or one ends),
/// for traces held whole (tests).
#[cfg(test)]
pub(super) fn first_divergence(b: &[TraceRow], n: &[TraceRow], tol: f32) -> Option<TraceDiff> {
    let mut d = Divergence::new(tol);
    for (rb, rn) in b.iter().zip(n) {
        d.pair(rb, rn);
    }
    let k = b.len().min(n.len());
    d.end(b.get(k), n.get(k));
    d.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classify_by_distance_from_ideal() {
        let exact = Tolerance { abs: 0.0, rel: 0.0 };
        assert_eq!(classify(0.0, 0.0, 0.0, exact), Change::Same);
        assert_eq!(classify(0.0, 1.0, 0.0, exact), Change::Worse);
        assert_eq!(classify(2.0, 1.0, 0.0, exact), Change::Better);
        // A ratio getting closer to its ideal 1 is better.
        assert_eq!(classify(0.9, 0.95, 1.0, exact), Change::Better);
        let loose = Tolerance {
            abs: 1e-5,
            rel: 0.01,
        };
        assert_eq!(classify(0.1, 0.1005, 0.0, loose), Change::Same);
        assert_eq!(classify(0.1, 0.102, 0.0, loose), Change::Worse);
        assert_eq!(
            classify(f64::INFINITY, f64::INFINITY, 0.0, exact),
            Change::Same
        );
        // NaN is a difference, both ways.
        assert_eq!(classify(0.0, f64::NAN, 0.0, loose), Change::Worse);
        assert_eq!(classify(f64::NAN, 0.0, 0.0, loose), Change::Better);
        // A NaN reference: any move beyond the tolerance is worse, either way.
        assert_eq!(classify(0.0, 5.0, f64::NAN, loose), Change::Worse);
        assert_eq!(classify(5.0, 0.0, f64::NAN, loose), Change::Worse);
        assert_eq!(classify(0.1, 0.1, f64::NAN, loose), Change::Same);
        assert_eq!(classify(0.1, f64::NAN, f64::NAN, loose), Change::Worse);
        assert_eq!(classify(f64::NAN, f64::NAN, 0.0, loose), Change::Same);
    }

    #[test]
    fn a_nan_position_diverges() {
        let row = |x: f32| {
            let state = crate::backend::CharacterState {
                pos: glam::Vec2::new(x, 0.0),
                ..Default::default()
            };
            TraceRow::from_state(0, 0.0, 0, &state)
        };
        assert!(differs(0.0, f32::NAN, 1e-4));
        assert!(!differs(f32::NAN, f32::NAN, 1e-4));
        assert!(!differs(f32::INFINITY, f32::INFINITY, 1e-4));
        assert!(differs(0.0, f32::INFINITY, 1e-4));
        let d = first_divergence(&[row(1.0)], &[row(f32::NAN)], 1e-4).unwrap();
        assert_eq!(d.change, TraceChange::Diverged);
        let d = first_divergence(&[row(1.0), row(1.0)], &[row(1.0)], 1e-4).unwrap();
        assert_eq!(d.change, TraceChange::Truncated);
    }
}

#[cfg(test)]
mod timing_tests {
    use super::*;

    fn diff_of(metric: &str, change: Change) -> RunDiff {
        let mut d = RunDiff::default();
        d.push(MetricDiff {
            scenario: "l.s".into(),
            config: "sweep default".into(),
            metric: metric.into(),
            base: Some(1.0),
            new: Some(2.0),
            base_frame: None,
            new_frame: None,
            base_q1: None,
            base_q3: None,
            new_q1: None,
            new_q3: None,
            change,
        });
        d
    }

    #[test]
    fn a_slower_timing_is_reported_but_fails_only_on_request() {
        let slower = diff_of("ns_per_character_step", Change::Worse);
        assert!(!slower.regressed(false));
        assert!(slower.regressed(true));
        assert!(diff_of("rest_gap", Change::Worse).regressed(false));
        assert!(!diff_of("rest_gap", Change::Better).regressed(false));
    }
}
