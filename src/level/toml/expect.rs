//! A scenario's `expect` table (`[scenario.expect]`): what the level says should happen — a
//! region to reach by a time or frame, grounded or not at the end, a lowest height, staying in
//! the map, a moving platform to land on — each checked against the scenario it belongs to and
//! the level it runs on, with errors at the file's line and column.

use glam::Vec2;
use serde::Deserialize;
use toml::Spanned;

use crate::level::{Deadline, Expectations, Level, Reach, ScenarioSpec};
use crate::limits;

use super::error::{LevelError, Locator};
use super::numbers::{coord, finite};

/// The `expect` table as the file gives it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawExpect {
    reach: Option<Spanned<RawReach>>,
    grounded_at_end: Option<bool>,
    min_y: Option<Spanned<f64>>,
    stay_in_map: Option<bool>,
    land_on: Option<Spanned<toml::Value>>,
}

/// `reach = { x = [left, right], y = [bottom, top], by = seconds }` (or `by_frame = N`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawReach {
    #[serde(default, deserialize_with = "super::exact::opt_spanned")]
    x: Option<Spanned<[f64; 2]>>,
    #[serde(default, deserialize_with = "super::exact::opt_spanned")]
    y: Option<Spanned<[f64; 2]>>,
    by: Option<Spanned<f64>>,
    by_frame: Option<Spanned<u32>>,
}

/// Checks and converts scenario `spec`'s `expect` table against `level`.
pub(super) fn parse_expect(
    loc: &Locator,
    level: &Level,
    spec: &ScenarioSpec,
    raw: &Spanned<RawExpect>,
) -> Result<Expectations, LevelError> {
    let e = raw.get_ref();
    let reach = e
        .reach
        .as_ref()
        .map(|r| parse_reach(loc, spec, r))
        .transpose()?;
    let min_y = e
        .min_y
        .as_ref()
        .map(|v| coord(loc, &v.span(), "expect.min_y", *v.get_ref()))
        .transpose()?;
    let land_on = e
        .land_on
        .as_ref()
        .map(|p| platform_number(loc, level, p))
        .transpose()?;
    Ok(Expectations {
        reach,
        grounded_at_end: e.grounded_at_end,
        min_y,
        stay_in_map: e.stay_in_map.unwrap_or(false),
        land_on,
    })
}

/// `land_on`: the number of one of the level's platforms (from 0, in file order, as `ride`).
fn platform_number(
    loc: &Locator,
    level: &Level,
    v: &Spanned<toml::Value>,
) -> Result<u32, LevelError> {
    let n = level.platforms.len();
    let expected = if n == 0 {
        "the level has no moving platform to land on".to_string()
    } else {
        format!("expected a platform's number, 0 <= land_on < {n} (numbered from 0 in file order, as for `ride`)")
    };
    match v.get_ref() {
        toml::Value::Integer(i) if (0..n as i64).contains(i) => Ok(*i as u32),
        toml::Value::Integer(i) => Err(loc.at(
            &v.span(),
            format!("expect.land_on = {i} names no platform; {expected}"),
        )),
        other => Err(loc.at(
            &v.span(),
            format!("expect.land_on is {} {other}; {expected}", other.type_str()),
        )),
    }
}

/// One axis of a region: `[low, high]` in tiles, low <= high; open (infinite) when not given.
fn bounds(
    loc: &Locator,
    v: Option<&Spanned<[f64; 2]>>,
    what: &str,
) -> Result<(f32, f32), LevelError> {
    let Some(v) = v else {
        return Ok((f32::NEG_INFINITY, f32::INFINITY));
    };
    let [a, b] = *v.get_ref();
    let lo = coord(loc, &v.span(), what, a)?;
    let hi = coord(loc, &v.span(), what, b)?;
    if lo > hi {
        return Err(loc.at(
            &v.span(),
            format!("{what} is [{lo}, {hi}]; expected [low, high] with low <= high (tiles)"),
        ));
    }
    Ok((lo, hi))
}

fn parse_reach(
    loc: &Locator,
    spec: &ScenarioSpec,
    raw: &Spanned<RawReach>,
) -> Result<Reach, LevelError> {
    let r = raw.get_ref();
    if r.x.is_none() && r.y.is_none() {
        return Err(loc.at(
            &raw.span(),
            "expect.reach states no region; expected x = [left, right] and/or y = [bottom, top] (tiles, feet position)",
        ));
    }
    let (x0, x1) = bounds(loc, r.x.as_ref(), "expect.reach x")?;
    let (y0, y1) = bounds(loc, r.y.as_ref(), "expect.reach y")?;
    let by = match (&r.by, &r.by_frame) {
        (Some(_), Some(f)) => {
            return Err(loc.at(
                &f.span(),
                "expect.reach has both `by` (seconds) and `by_frame`; expected one deadline",
            ))
        }
        (Some(s), None) => {
            let t = finite(loc, &s.span(), "expect.reach by", *s.get_ref())?;
            if !(0.0..=spec.duration).contains(&t) {
                return Err(loc.at(
                    &s.span(),
                    format!(
                        "expect.reach by = {t} is outside the scenario; expected 0 <= by <= duration ({}) seconds",
                        spec.duration
                    ),
                ));
            }
            Deadline::Seconds(t)
        }
        (None, Some(f)) => {
            let last = limits::frames(spec.duration as f64, spec.dt as f64);
            if *f.get_ref() as f64 > last {
                return Err(loc.at(
                    &f.span(),
                    format!(
                        "expect.reach by_frame = {} is after the scenario's last frame; expected 0 <= by_frame <= {last} (duration / dt)",
                        f.get_ref()
                    ),
                ));
            }
            Deadline::Frame(*f.get_ref())
        }
        (None, None) => Deadline::End,
    };
    Ok(Reach {
        min: Vec2::new(x0, y0),
        max: Vec2::new(x1, y1),
        by,
    })
}
