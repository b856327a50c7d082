//! Walking over tile seams: distance covered against distance commanded, and steps stuck on
//! open ground.

use super::slopes::steep_columns;
use super::{commanded_distance, commanded_steps, pos, Context, Measure};
use crate::level::{character_box, Tile};
use crate::scenario::input_script;
use crate::trace::{Frames, TraceRow};
use glam::Vec2;
use parry2d::bounding_volume::Aabb;

/// How far above a floor a walker may spawn for `progress_ratio` to apply, in tiles: enough
/// to let a controller settle at its own rest height, too little to matter to the distance.
pub(crate) const PROGRESS_SPAWN_HEIGHT: f32 = 0.05;

/// `progress_ratio`: distance walked over distance commanded, for a walk that starts on the
/// ground with the whole commanded path flat, supported and free of obstacles.
///
/// Frame: the last frame (where the distance walked is read).
pub fn progress_ratio(ctx: &Context, rows: Frames) -> Option<Measure> {
    let spec = ctx.spec;
    let script = input_script(spec);
    if spec.velocity != Vec2::ZERO || script.iter().all(|i| i.horizontal() == 0.0 || i.jump) {
        return None;
    }
    if script.iter().any(|i| i.jump || i.up || i.down) {
        return None;
    }
    let d = commanded_distance(ctx.params, &script, spec.velocity.x, spec.dt);
    if d.abs() < 1e-6 {
        return None;
    }
    // The path: the character's box swept over the commanded distance, from the floor it
    // starts on (spawned on it, or up to PROGRESS_SPAWN_HEIGHT above it).
    let half = spec.size.x * 0.5;
    let x0 = spec.spawn.x as f64;
    let y0 = spec.spawn.y.floor();
    let lo = (x0 - half as f64 + d.min(0.0)) as f32;
    let hi = (x0 + half as f64 + d.max(0.0)) as f32;
    if spec.spawn.y - y0 > PROGRESS_SPAWN_HEIGHT {
        return None;
    }
    let path = Aabb::new(Vec2::new(lo, y0), Vec2::new(hi, y0 + spec.size.y));
    // Cells outside the map are empty: only the map's cells under the path are looked at.
    let (i0, i1) = ctx
        .level
        .clip_columns(lo.floor() as i64, (hi.ceil() as i64).saturating_sub(1));
    let (j0, j1) = ctx.level.clip_rows(
        y0 as i64,
        ((y0 + spec.size.y).ceil() as i64).saturating_sub(1),
    );
    let open = (i0..=i1).all(|i| (j0..=j1).all(|j| ctx.level.tile(i, j) == Tile::Empty));
    if ctx.level.solids_overlapping(&path).next().is_some() || !open {
        return None;
    }
    let row = y0 as i64 - 1;
    let flat = (lo.floor() as i64..hi.ceil() as i64).all(|i| ctx.level.tile(i, row) == Tile::Solid);
    if !flat {
        return None;
    }
    let last = rows.last()?;
    let walked = last.x as f64 - x0;
    Some(Measure {
        metric: "progress_ratio",
        value: walked / d,
        reference: 1.0,
        frame: Some(last.frame),
    })
}

/// Below this fraction of the commanded step a commanded move counts as stuck.
pub const STUCK_FRACTION: f64 = 0.01;
/// Height above the feet below which a solid ahead is the floor (or a seam in it), not an
/// obstacle, for `stuck_frames`, in tiles: larger than Rapier's offset and a snapped step.
pub(crate) const STUCK_FLOOR_BAND: f32 = 0.05;

/// `stuck_frames`: steps in which the character was commanded to move horizontally, was
/// grounded, and moved less than [`STUCK_FRACTION`] of the commanded step, while nothing in the
/// level blocked that step (a wall being pushed against is not "stuck").
///
/// Frame: the frame the first stuck step ends on (`None` if none was stuck).
pub fn stuck_frames(ctx: &Context, rows: Frames) -> Measure {
    let (count, first) = super::landing::first_and_count(
        stuck_steps(ctx, rows)
            .enumerate()
            .filter(|(_, s)| *s)
            .map(|(k, _)| rows.at(k + 1).frame),
    );
    Measure {
        metric: "stuck_frames",
        value: count as f64,
        reference: 0.0,
        frame: first,
    }
}

/// Per step `k` (from row `k` to row `k + 1`), whether it was stuck as [`stuck_frames`] counts
/// it; one entry per step the script and the rows both cover, computed as it is read.
pub(crate) fn stuck_steps<'a>(
    ctx: &'a Context,
    rows: Frames<'a>,
) -> impl Iterator<Item = bool> + 'a {
    let mut judge = stuck_judge(ctx);
    (0..rows.len().saturating_sub(1)).map_while(move |k| judge(&rows.at(k), &rows.at(k + 1)))
}

/// [`stuck_steps`] a step at a time, for rows read as they come: called with rows `k` and
/// `k + 1` for `k = 0, 1, ...` in turn, whether step `k` was stuck, or `None` once the script
/// has no step `k`.
pub(crate) fn stuck_judge<'a>(
    ctx: &'a Context,
) -> impl FnMut(&TraceRow, &TraceRow) -> Option<bool> + 'a {
    let script = input_script(ctx.spec);
    let size = ctx.spec.size;
    let commanded = commanded_steps(ctx.params, script.clone(), ctx.spec.velocity.x, ctx.spec.dt);
    let mut steps = script.into_iter().zip(commanded);
    move |before, after| {
        let (input, step) = steps.next()?;
        let step = &step;
        let stuck = input.horizontal() != 0.0
            && after.is_grounded()
            && step.abs() >= 1e-9
            && ((after.x - before.x) as f64).abs() < STUCK_FRACTION * step.abs()
            && {
                // The box moved by the commanded step, lifted out of the floor band.
                let mut ahead = character_box(pos(before) + Vec2::new(*step as f32, 0.0), size);
                ahead.mins.y += STUCK_FLOOR_BAND;
                let dir = step.signum() as f32;
                let steep_ahead = steep_columns(ctx, dir)
                    .any(|i| (i as f32) < ahead.maxs.x && (i as f32 + 1.0) > ahead.mins.x);
                ctx.level.solids_overlapping(&ahead).next().is_none() && !steep_ahead
            };
        Some(stuck)
    }
}
