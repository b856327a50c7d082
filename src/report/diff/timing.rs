//! How a diff judges a timing (`ns_per_character_step`): a change counts only beyond the
//! measured noise of both runs and beyond the least change that counts (criterion's "no change
//! detected" idea), so that two runs of the same code on a loaded machine compare the same.

use super::compare::{Change, Tolerance};

/// The least change of a timing that counts, whatever its spread: 1 ns, and 60% of the
/// baseline's median.
///
/// Measured on the shared 2-core machine this was written on (docs/speed.md, "How timings are
/// measured"): over three identical `platbench run --timing` runs of the built-in set under
/// other builds' load (six ordered pairs of 1,472 timings), a scenario's median moved by a
/// ratio of 0.58 to 1.72, and no move beyond 60% had the two interquartile ranges apart; a
/// 2-times slowdown (+100%) is beyond 60% with room for that noise.
pub(super) const TIMING_TOLERANCE: Tolerance = Tolerance { abs: 1.0, rel: 0.6 };

/// A timing's median and quartiles, in ns per character step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Spread {
    /// The median of the samples (the `metrics.csv` value).
    pub(super) median: f64,
    /// The first quartile (the median itself when the file has none).
    pub(super) q1: f64,
    /// The third quartile (the median itself when the file has none).
    pub(super) q3: f64,
}

/// Whether timing `new` is worse (slower), better or the same as `base`: worse only when the
/// new run's interquartile range lies wholly above the baseline's (`new.q1 > base.q3`: the
/// medians are further apart than the halves of the two ranges that face each other) **and**
/// the new median exceeds the baseline's by more than `tol.abs + tol.rel * base.median`;
/// better the same way down. Anything else is within the noise: the same.
pub(super) fn classify_timing(base: &Spread, new: &Spread, tol: Tolerance) -> Change {
    let (b, n) = (base.median, new.median);
    if b.to_bits() == n.to_bits() || (b.is_nan() && n.is_nan()) {
        return Change::Same;
    }
    // A NaN is a difference, as for any metric.
    if n.is_nan() {
        return Change::Worse;
    }
    if b.is_nan() {
        return Change::Better;
    }
    let least = tol.abs + tol.rel * b.abs();
    if new.q1 > base.q3 && n > b + least {
        Change::Worse
    } else if new.q3 < base.q1 && n < b - least {
        Change::Better
    } else {
        Change::Same
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(q1: f64, median: f64, q3: f64) -> Spread {
        Spread { median, q1, q3 }
    }

    #[test]
    fn a_timing_is_worse_only_beyond_both_spreads_and_the_least_change() {
        let t = TIMING_TOLERANCE;
        let base = s(95.0, 100.0, 110.0);
        // Twice as slow, ranges apart: worse.
        assert_eq!(
            classify_timing(&base, &s(190.0, 200.0, 215.0), t),
            Change::Worse
        );
        // Twice as slow but the new range reaches down into the baseline's: within the noise.
        assert_eq!(
            classify_timing(&base, &s(105.0, 200.0, 215.0), t),
            Change::Same
        );
        // Ranges apart but by less than the least change that counts.
        assert_eq!(
            classify_timing(&base, &s(120.0, 130.0, 140.0), t),
            Change::Same
        );
        // Four times as fast: better (the least change is 60% of the baseline's median both
        // ways, so twice as fast, -50%, is within it).
        assert_eq!(
            classify_timing(&base, &s(20.0, 25.0, 30.0), t),
            Change::Better
        );
        assert_eq!(
            classify_timing(&base, &s(40.0, 50.0, 55.0), t),
            Change::Same
        );
        // A baseline written before the quartiles: its spread is its value.
        let old = s(100.0, 100.0, 100.0);
        assert_eq!(
            classify_timing(&old, &s(190.0, 200.0, 215.0), t),
            Change::Worse
        );
        assert_eq!(
            classify_timing(&old, &s(110.0, 120.0, 130.0), t),
            Change::Same
        );
        // A NaN is a difference.
        assert_eq!(
            classify_timing(&base, &s(f64::NAN, f64::NAN, f64::NAN), t),
            Change::Worse
        );
    }
}
