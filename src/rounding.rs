//! Rounding to whole numbers without a call into the C maths library.
//!
//! On x86-64's baseline (SSE2, no SSE4.1 `roundss`) `f32::floor`, `ceil` and `round` are calls
//! to libm, and the sweep's per-step rules round a few times per character step (the column
//! under the centre, the ladder rows, the subpixel moves). These give the very same bits as the
//! standard functions for every input (NaN stays NaN, infinities and values already whole are
//! returned as they are, and the result keeps the input's sign, as IEEE rounding does, so
//! `-0.3` floors to `-1` and rounds to `-0.0`), from one truncating conversion and a compare.

/// 2^23: every f32 at least this large in magnitude is a whole number.
const F32_WHOLE: f32 = 8_388_608.0;
/// 2^52: every f64 at least this large in magnitude is a whole number.
const F64_WHOLE: f64 = 4_503_599_627_370_496.0;

/// Generates the three roundings for one float type: `$whole` is the magnitude from which
/// every value is whole, `$int` an integer type holding every smaller whole value; `$unused`
/// marks a type's floor and ceil when no caller needs them (f32's: they stay, with their
/// tests, beside the round the crate uses).
macro_rules! roundings {
    ($float:ty, $whole:expr, $int:ty, $floor:ident, $ceil:ident, $round:ident $(, #[$unused:meta])?) => {
        /// `x.floor()`, bit for bit.
        #[inline]
        $(#[$unused])?
        pub(crate) fn $floor(x: $float) -> $float {
            if x.is_nan() || x.abs() >= $whole {
                return x;
            }
            let t = x as $int as $float;
            (if t > x { t - 1.0 } else { t }).copysign(x)
        }

        /// `x.ceil()`, bit for bit.
        #[inline]
        $(#[$unused])?
        pub(crate) fn $ceil(x: $float) -> $float {
            if x.is_nan() || x.abs() >= $whole {
                return x;
            }
            let t = x as $int as $float;
            (if t < x { t + 1.0 } else { t }).copysign(x)
        }

        /// `x.round()` (halves away from zero), bit for bit.
        #[inline]
        pub(crate) fn $round(x: $float) -> $float {
            if x.is_nan() || x.abs() >= $whole {
                return x;
            }
            let t = x as $int as $float;
            // x - t is exact: both lie within one unit of each other below 2^mantissa.
            let d = x - t;
            let r = if d >= 0.5 {
                t + 1.0
            } else if d <= -0.5 {
                t - 1.0
            } else {
                t
            };
            r.copysign(x)
        }
    };
}

// The f32 floor and ceil: every caller now wants a column or row index, which
// `floor_to_i64` and `ceil_to_i64` give without rounding in float first.
roundings!(f32, F32_WHOLE, i32, floor32, ceil32, round32, #[cfg_attr(not(test), allow(dead_code))]);
roundings!(f64, F64_WHOLE, i64, floor64, ceil64, round64);

/// `floor32(x) as i64` (so `x.floor() as i64`), bit for bit, without rounding in float first:
/// the truncating conversion (saturating, NaN to 0) and one step down for a negative fraction.
/// A column's or row's index from a coordinate.
#[inline]
pub(crate) fn floor_to_i64(x: f32) -> i64 {
    let t = x as i64;
    // Below 2^23 in magnitude `t` is exact in f32; above, `x` is whole and `t` is `x` (or the
    // saturated bound, which only a value beyond it exceeds: then the bound is the answer).
    if (t as f32) > x && t != i64::MIN {
        t - 1
    } else {
        t
    }
}

/// `ceil32(x) as i64` (so `x.ceil() as i64`), bit for bit: [`floor_to_i64`]'s way, one step up
/// for a positive fraction. A row's end index from a coordinate.
#[inline]
pub(crate) fn ceil_to_i64(x: f32) -> i64 {
    let t = x as i64;
    // As in `floor_to_i64`: only a value beyond the saturated bound exceeds it.
    if (t as f32) < x && t != i64::MAX {
        t + 1
    } else {
        t
    }
}

/// `round64(x) as i64` (so `x.round() as i64`), bit for bit, without rounding in float
/// first: below 2^52 in magnitude, the truncating conversion and one step away from zero for
/// a fraction of a half or more (`x - t` is exact there); anything else as the standard does.
#[inline]
pub(crate) fn round_to_i64(x: f64) -> i64 {
    if x.is_nan() || x.abs() >= F64_WHOLE {
        return round64(x) as i64;
    }
    let t = x as i64;
    let d = x - t as f64;
    if d >= 0.5 {
        t + 1
    } else if d <= -0.5 {
        t - 1
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values where rounding goes wrong when done naively: signed zeros, halves, the largest
    /// float below a half, neighbours of whole numbers, the whole-number threshold, huge values,
    /// infinities.
    fn edges32() -> Vec<f32> {
        let mut v = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            0.499_999_97,
            -0.499_999_97,
            F32_WHOLE,
            F32_WHOLE - 0.5,
            F32_WHOLE * 2.0,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1e-45,
            -1e-45,
        ];
        for k in -40..40 {
            let w = k as f32;
            v.extend([w, w.next_up(), w.next_down(), w + 0.5, (w + 0.5).next_up()]);
            v.extend([(w + 0.5).next_down()]);
        }
        v
    }

    /// Whether two results are the same bits (any NaN matches any NaN).
    fn same32(a: f32, b: f32) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    fn same64(a: f64, b: f64) -> bool {
        a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
    }

    #[test]
    fn f32_roundings_are_the_standard_ones_bit_for_bit() {
        // A deterministic spread over every magnitude (each of 2^32 bit patterns stepped by a
        // prime) plus the edges above.
        let spread = (0..200_000u64).map(|k| f32::from_bits((k * 21_473) as u32));
        for x in spread.chain(edges32()).chain([f32::NAN, -f32::NAN]) {
            assert!(same32(floor32(x), x.floor()), "floor {x:e}");
            assert!(same32(ceil32(x), x.ceil()), "ceil {x:e}");
            assert!(same32(round32(x), x.round()), "round {x:e}");
            assert_eq!(floor_to_i64(x), x.floor() as i64, "floor to i64 {x:e}");
            assert_eq!(ceil_to_i64(x), x.ceil() as i64, "ceil to i64 {x:e}");
        }
        for x in [-9.3e18f32, -9.223372e18, -1e30, 9.3e18, 9.223372e18, 1e30] {
            assert_eq!(floor_to_i64(x), x.floor() as i64, "floor to i64 {x:e}");
            assert_eq!(ceil_to_i64(x), x.ceil() as i64, "ceil to i64 {x:e}");
        }
    }

    #[test]
    fn f64_roundings_are_the_standard_ones_bit_for_bit() {
        let spread = (0..200_000u64).map(|k| f64::from_bits(k.wrapping_mul(92_233_720_368_547)));
        let edges = edges32().into_iter().map(f64::from).chain([
            F64_WHOLE,
            F64_WHOLE - 0.5,
            0.499_999_999_999_999_94,
            -0.499_999_999_999_999_94,
            f64::MAX,
            f64::NAN,
        ]);
        for x in spread.chain(edges) {
            assert!(same64(floor64(x), x.floor()), "floor {x:e}");
            assert!(same64(ceil64(x), x.ceil()), "ceil {x:e}");
            assert!(same64(round64(x), x.round()), "round {x:e}");
            assert_eq!(round_to_i64(x), x.round() as i64, "round to i64 {x:e}");
        }
    }
}
