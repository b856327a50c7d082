//! What a level says should happen, and the one thing that should never happen: the
//! `expect_*` rows check a scenario's stated expectations ([`crate::level::Expectations`])
//! against its trace; `left_level`, on every scenario, flags a character that fell out of the
//! level or walked off the side of its map. Each is 0 (pass) or 1 (fail), with the frame that
//! decided it.

use super::platforms::{placed, ON_PLATFORM};
use super::{Context, Measure};
use crate::level::{Level, Tile};
use crate::trace::{Frames, TraceRow};

/// The height below which nothing of `level` can catch a falling character, in tiles: the bottom
/// of its lowest row holding a tile that is not empty, or of the lowest box a moving platform
/// sweeps, whichever is lower; the map's bottom (0) when it holds neither.
pub(crate) fn level_bottom(level: &Level) -> f32 {
    let rows = (0..level.height as i64)
        .find(|&j| (0..level.width as i64).any(|i| !matches!(level.tile(i, j), Tile::Empty)));
    let platforms = level
        .platforms
        .iter()
        .map(|p| p.reach().0.y as f32)
        .fold(f32::INFINITY, f32::min);
    let tiles = rows.map_or(f32::INFINITY, |j| j as f32);
    let b = tiles.min(platforms);
    if b.is_finite() {
        b
    } else {
        0.0
    }
}

/// Whether row `r` (a box `size.x` wide, `size.y` high, feet at its bottom centre) has left the
/// level whose bottom is `bottom` ([`level_bottom`]): its feet below the bottom while falling
/// (`vy < 0`), or its box wholly beside the map (right of its width or left of 0) or wholly
/// below it. Above the map is not leaving it: gravity brings a character back from the sky.
pub(crate) fn outside_level(level: &Level, bottom: f32, size: glam::Vec2, r: &TraceRow) -> bool {
    let half = size.x * 0.5;
    (r.y < bottom && r.vy < 0.0)
        || r.x + half < 0.0
        || r.x - half > level.width as f32
        || r.y + size.y < 0.0
}

/// `left_level`: 1 if the character left the level at any frame, else 0: its feet below the
/// level's bottom (the lowest non-empty tile row or platform reach) while falling, or its box
/// wholly beside or below the map.
/// Frame: the first frame it was outside (`None` if never).
pub fn left_level(ctx: &Context, rows: Frames) -> Measure {
    let bottom = level_bottom(ctx.level);
    let at = rows
        .iter()
        .find(|r| outside_level(ctx.level, bottom, ctx.spec.size, r))
        .map(|r| r.frame);
    fail_at("left_level", at)
}

/// A pass/fail row: failed at `frame` when it is `Some`.
fn fail_at(metric: &'static str, frame: Option<u32>) -> Measure {
    Measure {
        metric,
        value: frame.is_some() as u8 as f64,
        reference: 0.0,
        frame,
    }
}

/// A pass/fail row decided at `frame` either way.
fn judged(metric: &'static str, failed: bool, frame: u32) -> Measure {
    Measure {
        metric,
        value: failed as u8 as f64,
        reference: 0.0,
        frame: Some(frame),
    }
}

/// `expect_reach`: 1 if the feet were never inside the scenario's region (bounds inclusive) at a
/// frame up to its deadline, else 0. Frame: the first frame inside it (a pass), or the deadline's
/// frame (a fail). `None` when the scenario states no region.
pub fn expect_reach(ctx: &Context, rows: Frames) -> Option<Measure> {
    let reach = ctx.spec.expect.reach?;
    let last = rows.iter().next_back()?.frame;
    let deadline = reach.by.frame(ctx.spec.dt, last);
    let inside = rows.iter().take_while(|r| r.frame <= deadline).find(|r| {
        (reach.min.x..=reach.max.x).contains(&r.x) && (reach.min.y..=reach.max.y).contains(&r.y)
    });
    Some(match inside {
        Some(r) => judged("expect_reach", false, r.frame),
        None => judged("expect_reach", true, deadline),
    })
}

/// `expect_grounded_at_end`: 1 if the last frame's grounded flag (the controller's report) is not
/// the one the scenario expects, else 0. Frame: the last frame. `None` when not stated.
pub fn expect_grounded_at_end(ctx: &Context, rows: Frames) -> Option<Measure> {
    let want = ctx.spec.expect.grounded_at_end?;
    let r = rows.iter().next_back()?;
    Some(judged(
        "expect_grounded_at_end",
        r.is_grounded() != want,
        r.frame,
    ))
}

/// `expect_min_y`: 1 if the feet went below the scenario's lowest height at any frame, else 0.
/// Frame: the first frame below it (`None` on a pass). `None` when not stated.
pub fn expect_min_y(ctx: &Context, rows: Frames) -> Option<Measure> {
    let min_y = ctx.spec.expect.min_y?;
    let below = rows.iter().find(|r| r.y < min_y).map(|r| r.frame);
    Some(fail_at("expect_min_y", below))
}

/// `expect_stay_in_map`: 1 if the feet were outside the map (0 <= x <= width, 0 <= y <= height)
/// at any frame, else 0. Frame: the first frame outside (`None` on a pass). `None` when the
/// scenario does not ask for it.
pub fn expect_stay_in_map(ctx: &Context, rows: Frames) -> Option<Measure> {
    if !ctx.spec.expect.stay_in_map {
        return None;
    }
    let (w, h) = (ctx.level.width as f32, ctx.level.height as f32);
    let out = rows
        .iter()
        .find(|r| !((0.0..=w).contains(&r.x) && (0.0..=h).contains(&r.y)))
        .map(|r| r.frame);
    Some(fail_at("expect_stay_in_map", out))
}

/// `expect_land_on`: 1 if the character never stood on the scenario's platform, else 0. Standing
/// on it, as the carry metrics read it: grounded, feet within 0.05 tiles of the top of the
/// platform where the configuration places it at that frame, the box overlapping it in x.
/// Frame: the first frame on it (a pass), or the last frame (a fail). `None` when not stated.
pub fn expect_land_on(ctx: &Context, rows: Frames) -> Option<Measure> {
    let p = ctx.level.platforms.get(ctx.spec.expect.land_on? as usize)?;
    let half = ctx.spec.size.x * 0.5;
    let on = rows.iter().enumerate().skip(1).find(|(k, r)| {
        let b = placed(ctx, p, *k);
        r.is_grounded()
            && (r.y - b.maxs.y).abs() <= ON_PLATFORM
            && r.x + half > b.mins.x
            && r.x - half < b.maxs.x
    });
    let last = rows.iter().next_back()?.frame;
    Some(match on {
        Some((_, r)) => judged("expect_land_on", false, r.frame),
        None => judged("expect_land_on", true, last),
    })
}

#[cfg(test)]
#[path = "expect_tests.rs"]
mod tests;
