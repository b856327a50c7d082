//! Moving platforms: carrying a rider, and pushing (or crushing) a character.

use super::ground::Ground;
use super::pushers::{CrushRule, Pushers};
use super::{pos, Context, Measure, Peak};
use crate::scenario::input_script;
use crate::trace::{Frames, TraceRow};

/// Platform `p`'s box at frame `k`, where the configuration places it: on its exact path, or
/// rounded to the subpixel grid a configuration on integer positions moves it on
/// ([`crate::level::Platform::placed_aabb`]), so the carry and push are measured against the
/// platform the controller really moves, as the character's box is the one it moves.
pub(super) fn placed(
    ctx: &Context,
    p: &crate::level::Platform,
    k: usize,
) -> parry2d::bounding_volume::Aabb {
    p.placed_aabb(k as f64 * ctx.spec.dt as f64, ctx.declared.surface_grid)
}

/// Deepest overlap of row `r`'s shape (frame `k`) with a platform that is not one-way, where
/// the configuration places it (`placed`), in tiles.
pub(crate) fn platform_depth(ctx: &Context, g: &Ground, r: &TraceRow, k: usize) -> f32 {
    ctx.level
        .platforms
        .iter()
        .filter(|p| !p.one_way)
        .map(|p| g.box_penetration(pos(r), &placed(ctx, p, k)))
        .fold(0.0f32, f32::max)
}

/// How close above a platform's top the feet count as on it, for the carry metrics, in tiles:
/// above Rapier's offset.
pub(crate) const ON_PLATFORM: f32 = 0.05;

/// The frames of the ride: from the first frame the character stands on the scenario's platform
/// (grounded, feet within [`ON_PLATFORM`] of its top, overlapping it in x) with idle input and no
/// velocity of its own, to the end of that idle input (or the end); from the first step if it
/// never stands on it. `None` if the scenario names no platform.
pub(super) fn ride_frames(ctx: &Context, rows: Frames) -> Option<std::ops::Range<usize>> {
    let p = ctx.level.platforms.get(ctx.spec.ride? as usize)?;
    let script = input_script(ctx.spec);
    let half = ctx.spec.size.x * 0.5;
    let on = |k: usize| {
        let r = rows.at(k);
        let b = placed(ctx, p, k);
        r.is_grounded()
            && (r.y - b.maxs.y).abs() <= ON_PLATFORM
            && r.x + half > b.mins.x
            && r.x - half < b.maxs.x
    };
    let idle = |k: usize| {
        k == 0
            || script
                .get(k - 1)
                .is_none_or(|i| *i == crate::motion::Input::default())
    };
    // From the first step's result (the spawn row has no contact yet) at which it stands on the
    // platform, idle and not moving on its own (no walk or slide left over).
    // A controller that never stands on it is measured over the whole run.
    let start = (1..rows.len())
        .find(|&k| on(k) && idle(k) && rows.at(k).vx.abs() < 1e-3)
        .unwrap_or(1.min(rows.len()));
    let end = (start..rows.len())
        .find(|&k| !idle(k))
        .unwrap_or(rows.len());
    Some(start..end)
}

/// `carry_drift`: over the idle part of the ride, the largest change of the character's position
/// relative to its platform, in tiles. Frame: the first frame at the largest change.
pub fn carry_drift(ctx: &Context, rows: Frames, ride: &std::ops::Range<usize>) -> Measure {
    let p = &ctx.level.platforms[ctx.spec.ride.unwrap_or(0) as usize];
    let rel = |k: usize| pos(&rows.at(k)) - placed(ctx, p, k).mins;
    let first = rel(ride.start);
    let mut drift = Peak::new(0.0);
    for k in ride.clone() {
        drift.push(rows.at(k).frame, (rel(k) - first).length());
    }
    Measure {
        metric: "carry_drift",
        value: drift.value as f64,
        reference: 0.0,
        frame: drift.frame,
    }
}

/// `carry_airborne_frames`: frames airborne during the idle part of the ride. Frame: the first
/// of them (`None` if there is none).
pub fn carry_airborne_frames(rows: Frames, ride: &std::ops::Range<usize>) -> Measure {
    let (count, first) = super::landing::first_and_count(
        ride.clone()
            .map(|k| rows.at(k))
            .filter(|r| !r.is_grounded())
            .map(|r| r.frame),
    );
    Measure {
        metric: "carry_airborne_frames",
        value: count as f64,
        reference: 0.0,
        frame: first,
    }
}

/// `push_penetration`: on a level with moving platforms, the deepest overlap of the character's
/// shape with a platform that is not one-way, over the run, in tiles (parry's penetration depth,
/// [`Ground::box_penetration`], against the platform where the configuration places it). The
/// frames of a crush by design ([`CrushRule`]: from a frame a platform squeezes the character
/// against the level while it stays in contact) are left out: there the overlap is the crush,
/// which `crush_count` judges by its own rule.
/// Frame: the first frame at the deepest overlap.
pub(crate) fn push_penetration(
    ctx: &Context,
    g: &Ground,
    pushers: &Pushers,
    rows: Frames,
) -> Option<Measure> {
    if ctx.level.platforms.is_empty() {
        return None;
    }
    let mut deepest = Peak::new(0.0);
    let mut rule = CrushRule::new();
    for (k, r) in rows.iter().enumerate() {
        rule.push(pushers, rows, k, false);
        if !rule.crushing {
            deepest.push(r.frame, platform_depth(ctx, g, &r, k));
        }
    }
    Some(Measure {
        metric: "push_penetration",
        value: deepest.value as f64,
        reference: 0.0,
        frame: deepest.frame,
    })
}

/// Overlap with a moving platform beyond which the character counts as crushed (or run
/// through), in tiles: far beyond any contact tolerance.
pub const CRUSH_DEPTH: f32 = 0.25;

/// `crush_count`: on a level with moving platforms, how many times the character's shape ended
/// up inside a (not one-way) platform by more than [`CRUSH_DEPTH`] against the crush rule
/// ([`CrushRule`]): run through by a platform that had room to push it. A squeeze against the
/// level is the crush the scenario designs, not counted, whether the controller reports it (the
/// sweep's `crushed` column) or has no crush event (Rapier, Box2D): read from the geometry
/// alone, alike for every controller.
///
/// Frame: the frame of the first crush counted (`None` if there is none).
pub(crate) fn crush_count(
    ctx: &Context,
    g: &Ground,
    pushers: &Pushers,
    rows: Frames,
) -> Option<Measure> {
    if ctx.level.platforms.is_empty() {
        return None;
    }
    let inside = |k: usize| platform_depth(ctx, g, &rows.at(k), k) > CRUSH_DEPTH;
    let mut rule = CrushRule::new();
    let (mut count, mut first) = (0, None);
    let mut was_inside = !rows.is_empty() && inside(0);
    let mut add = |(n, f): (usize, Option<u32>)| {
        count += n;
        first = match (first, f) {
            (Some(a), Some(b)) => Some(std::cmp::min(a, b)),
            (a, b) => a.or(b),
        };
    };
    for k in 0..rows.len() {
        let now = inside(k);
        add(rule.push(pushers, rows, k, k > 0 && now && !was_inside));
        was_inside = now;
    }
    add(rule.end());
    Some(Measure {
        metric: "crush_count",
        value: count as f64,
        reference: 0.0,
        frame: first,
    })
}
