//! The checks of a level file's numbers: finite, positive, within a range of
//! [`crate::limits`] (coordinates, periods, an origin in f64), each error naming the quantity,
//! the value found and the range expected.

use std::ops::Range;

use glam::Vec2;
use toml::Spanned;

use crate::limits;

use super::error::{LevelError, Locator};

pub(super) fn finite(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
) -> Result<f32, LevelError> {
    if !v.is_finite() {
        return Err(loc.at(
            span,
            format!("{what} is {}; expected a finite number", limits::show(v)),
        ));
    }
    if v.abs() > f32::MAX as f64 {
        // Finite, but beyond what the f32 the level holds can represent.
        return Err(loc.at(
            span,
            format!(
                "{what} is {}; expected a number the level's f32 can hold (at most {:e} in size)",
                limits::show(v),
                f32::MAX
            ),
        ));
    }
    Ok(v as f32)
}

pub(super) fn positive(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
) -> Result<f32, LevelError> {
    let x = finite(loc, span, what, v)?;
    if x <= 0.0 {
        return Err(loc.at(
            span,
            format!("{what} is {}; expected a number > 0", limits::show(v)),
        ));
    }
    Ok(x)
}

/// A number within `range` (inclusive), in `unit`.
pub(super) fn ranged(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
    range: (f64, f64),
    unit: &str,
) -> Result<f32, LevelError> {
    ranged_f64(loc, span, what, v, range, unit).map(|v| v as f32)
}

/// [`ranged`] kept in f64 (a level's origin, exact far beyond what an f32 holds).
pub(super) fn ranged_f64(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
    range: (f64, f64),
    unit: &str,
) -> Result<f64, LevelError> {
    if !limits::within(v, range) {
        let lo = if range.0 == f64::MIN_POSITIVE {
            "0 < ".to_string()
        } else {
            format!("{} <= ", range.0)
        };
        return Err(loc.at(
            span,
            format!(
                "{what} is {}; expected {lo}{what} <= {} ({unit})",
                limits::show(v),
                range.1
            ),
        ));
    }
    Ok(v)
}

/// A coordinate or length within [`limits::MAX_COORD`] of zero, in tiles.
pub(super) fn coord(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
) -> Result<f32, LevelError> {
    ranged(
        loc,
        span,
        what,
        v,
        (-limits::MAX_COORD, limits::MAX_COORD),
        "tiles",
    )
}

/// A platform's period, in seconds.
pub(super) fn period(
    loc: &Locator,
    span: &Range<usize>,
    what: &str,
    v: f64,
) -> Result<f32, LevelError> {
    ranged(
        loc,
        span,
        what,
        v,
        (limits::MIN_PERIOD, limits::MAX_DURATION),
        "seconds",
    )
}

pub(super) fn vec2(
    loc: &Locator,
    v: &Spanned<[f64; 2]>,
    what: &str,
    must_be_positive: bool,
) -> Result<Vec2, LevelError> {
    let span = v.span();
    let [a, b] = *v.get_ref();
    let check = if must_be_positive { positive } else { finite };
    Ok(Vec2::new(
        check(loc, &span, what, a)?,
        check(loc, &span, what, b)?,
    ))
}
