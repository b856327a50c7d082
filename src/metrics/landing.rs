//! Landing and resting: when the character lands, how it rests (gap, jitter, penetration) and
//! whether its grounded flag tells the truth.

use super::ground::Ground;
use super::pushers::Pushers;
use super::{pos, predicted_landing_frame, standing, Context, Measure, Peak};
use crate::level::Tile;
use crate::scenario::input_script;
use crate::trace::{Frames, TraceRow};

/// Idle time at the end of a scenario needed for the rest metrics, in seconds.
pub const REST_WINDOW: f32 = 0.5;
/// How far below the feet the ground may be for a grounded-to-airborne switch to count as a
/// flicker rather than leaving the ground, in tiles. Larger than Rapier's default offset
/// (1% of a 0.9-tile character) so a controller that keeps a skin gap is not penalised.
pub const FLICKER_SUPPORT_TOLERANCE: f32 = 0.1;

/// `max_penetration`: deepest overlap of the character's shape with the level's solid geometry
/// (solid tiles' squares and slope tiles' true solid parts, nothing left out) over the whole run,
/// in tiles, from parry's contact query (not from a backend's contacts); on grounded frames
/// standing on a one-way top (platform or ladder top), how far it is sunk below that top.
///
/// Frame: the first frame at the deepest overlap.
pub fn max_penetration(g: &Ground, rows: Frames) -> Measure {
    let mut worst = Peak::new(0.0);
    for r in rows.iter() {
        worst.push(r.frame, g.penetration(pos(&r), r.t as f64, standing(&r)));
    }
    Measure {
        metric: "max_penetration",
        value: worst.value as f64,
        reference: 0.0,
        frame: worst.frame,
    }
}

/// `land_frame_error`: first grounded frame minus the frame the discrete integrator predicts,
/// for a character that starts in the air, above ground, with no horizontal velocity and no
/// input before it should land.
///
/// Frame: the first grounded frame (the landing); the last frame if it never landed (still in
/// the air, or fallen through, at the end).
pub fn land_frame_error(ctx: &Context, rows: Frames) -> Option<Measure> {
    let spec = ctx.spec;
    if spec.velocity.x != 0.0 {
        return None;
    }
    let half = spec.size.x * 0.5;
    let top =
        ctx.level
            .support_below(spec.spawn.x - half, spec.spawn.x + half, spec.spawn.y, 0.0)?;
    // Only onto flat solid ground: no slope between the feet and that top under the centre.
    let flat = ctx
        .level
        .surface_at(spec.spawn.x, spec.spawn.y, spec.spawn.y - top + 0.5)
        .is_some_and(|(h, slope)| slope.is_none() && h == top);
    // Not onto a moving platform (the prediction reads the static level).
    let over_platform = ctx.level.platforms.iter().any(|p| {
        let b = p.aabb(0.0);
        b.maxs.y <= spec.spawn.y && b.maxs.x > spec.spawn.x - half && b.mins.x < spec.spawn.x + half
    });
    if spec.spawn.y <= top || !flat || over_platform {
        return None;
    }
    let predicted = predicted_landing_frame(
        (spec.spawn.y - top) as f64,
        spec.velocity.y as f64,
        ctx.params.gravity as f64,
        spec.dt as f64,
    )?;
    let script = input_script(spec);
    if script
        .iter()
        .take(predicted)
        .any(|i| *i != crate::motion::Input::default())
    {
        return None;
    }
    let landed = rows
        .iter()
        .skip(1)
        .find(|r| r.is_grounded())
        .map(|r| r.frame);
    let value = landed.map_or(f64::INFINITY, |f| f as f64 - predicted as f64);
    Some(Measure {
        metric: "land_frame_error",
        value,
        reference: 0.0,
        frame: landed.or_else(|| rows.last().map(|r| r.frame)),
    })
}

/// The frames over which the character should be at rest: from its first settled frame (grounded
/// on real ground, moving less than 1% of the run speed) within the final idle window (or the window's last [`REST_WINDOW`] seconds if it never lands there)
/// to the end. `None` if the scenario does not end with such a window.
pub(super) fn rest_frames(
    ctx: &Context,
    g: &Ground,
    rows: Frames,
) -> Option<std::ops::Range<usize>> {
    let script = input_script(ctx.spec);
    let idle = crate::motion::Input::default();
    let n = script.len();
    let first_idle_step = script.rposition(|i| *i != idle).map_or(0, |k| k + 1);
    // Step k produces row k + 1; the idle window's rows are first_idle_step + 1 ..= n.
    let window_rows = n.saturating_sub(first_idle_step);
    let needed = (REST_WINDOW / ctx.spec.dt).ceil() as usize;
    // A rider rests on a moving platform: its height is the platform's business.
    if window_rows < needed || rows.len() != n + 1 || ctx.spec.ride.is_some() {
        return None;
    }
    let start = first_idle_step + 1;
    // At rest: grounded on real ground and no longer sliding (moving less than 1% of the run
    // speed), so deceleration along a slope is not counted as jitter.
    let still = ctx.params.run_speed * ctx.spec.dt * 0.01;
    let landed = (start..=n).find(|&k| {
        let r = rows.at(k);
        r.is_grounded() && supported(ctx, g, &r) && (r.x - rows.at(k - 1).x).abs() < still
    });
    let from = landed.unwrap_or(n + 1 - needed);
    Some(from..n + 1)
}

/// `rest_gap`: signed gap from the character's shape down to the ground at the last frame
/// (negative: sunk into a solid), in tiles; see [`Ground::gap`]. Frame: that last frame.
pub(super) fn rest_gap(ctx: &Context, g: &Ground, rows: Frames) -> Measure {
    let last = rows.last().map_or(ctx.spec.spawn, |r| pos(&r));
    Measure {
        metric: "rest_gap",
        value: rows.last().map_or(g.gap_at(last, 0.0, false), |r| {
            g.gap_at(last, r.t as f64, standing(&r))
        }) as f64,
        reference: 0.0,
        frame: rows.last().map(|r| r.frame),
    }
}

/// `rest_gap_declared`: the `rest_gap` minus the gap of the stance the configuration declares
/// (so 0 is a promise kept, positive farther than promised, negative closer or deeper): its
/// declared gap along the normal of the ground a straight drop meets (Rapier's `offset`:
/// `offset / cos(angle)` vertically on a slope), or, for a controller that stands a box on the
/// surface under its centre (the seed), the gap of that stance (inside a slope by its overhang;
/// on integer positions, on the surface rounded up to its subpixel, [`crate::scenario::DeclaredContact::stance_height`]),
/// or, for a controller standing on a flat foot (Box2D's segment pogo,
/// `DeclaredContact::stance_half_width`), the gap of its shape with the feet on the highest
/// surface under the foot, plus its declared gap. Frame: the last frame, as `rest_gap`'s.
pub(super) fn rest_gap_declared(ctx: &Context, g: &Ground, rows: Frames) -> Measure {
    let rest = rest_gap(ctx, g, rows);
    let feet = rows.last().map_or(ctx.spec.spawn, |r| pos(&r));
    Measure {
        metric: "rest_gap_declared",
        value: gap_beyond_declared(ctx, g, feet, rest.value),
        reference: 0.0,
        frame: rest.frame,
    }
}

/// A gap `gap` (tiles) measured with the feet at `feet`, less the gap of the stance the
/// configuration declares there, beyond the declared tolerance (signed; 0: promise kept). See
/// [`rest_gap_declared`].
pub(super) fn gap_beyond_declared(ctx: &Context, g: &Ground, feet: glam::Vec2, gap: f64) -> f64 {
    // A gap kept along the normal of the ground the shape rests on reads vertically as
    // gap / cos(angle) (the normal a straight drop meets; a wall's is clamped at 84 degrees).
    let n = g.ground_normal(feet).unwrap_or(glam::Vec2::Y);
    let vertical = |along_normal: f32| (along_normal / n.y.max(0.1)) as f64;
    // Vertical for every controller: the drop to the ground less the declared stance's, or,
    // for the seed's centre-column stance over a slope, the feet's height less the stance's
    // (its box overlaps the ramp there, and a depth along the ramp's normal would read a lift
    // cos(angle) smaller than the drop another controller's lift reads).
    let off = match stance_over_slope(ctx, feet) {
        Some(stance) => (feet.y - stance) as f64,
        None => match flat_foot_stance(ctx, feet) {
            // A flat foot (Box2D's segment pogo) stands on the highest surface under it: the
            // shape's gap with the feet there, plus the declared gap.
            Some(stance) => {
                gap - (g.gap(glam::Vec2::new(feet.x, stance)) as f64 + vertical(ctx.declared.gap)
                    - ctx.declared.stance_sink as f64)
            }
            None => gap - (vertical(ctx.declared.gap) - ctx.declared.stance_sink as f64),
        },
    };
    // Within the declared tolerance of the promise counts as keeping it; beyond, the excess.
    let tolerance = vertical(ctx.declared.gap_tolerance);
    off.signum() * (off.abs() - tolerance).max(0.0)
}

/// For a controller that declares a flat foot (`stance_half_width > 0`: Box2D's segment pogo),
/// the height its feet declare they stand at when the ground under their centre (from half a
/// tile above to one tile below) is a slope: the highest surface under the foot. `None`
/// otherwise.
pub(super) fn flat_foot_stance(ctx: &Context, feet: glam::Vec2) -> Option<f32> {
    let w = ctx.declared.stance_half_width;
    if w <= 0.0 {
        return None;
    }
    match ctx.level.surface_at(feet.x, feet.y + 0.5, 1.5) {
        Some((h, Some(_))) => Some(
            [feet.x - w, feet.x + w]
                .into_iter()
                .filter_map(|x| ctx.level.surface_at(x, feet.y + 0.5, 1.5))
                .fold(h, |top, (s, _)| top.max(s)),
        ),
        _ => None,
    }
}

/// For a controller that declares the seed's centre-column stance (`slope_overhang > 0`), the
/// height its feet declare they stand at when the ground under their centre (from half a tile
/// above to one tile below) is a slope: that surface, on its grid. `None` otherwise.
pub(super) fn stance_over_slope(ctx: &Context, feet: glam::Vec2) -> Option<f32> {
    if ctx.declared.slope_overhang <= 0.0 {
        return None;
    }
    match ctx.level.surface_at(feet.x, feet.y + 0.5, 1.5) {
        Some((h, Some(_))) => Some(ctx.declared.stance_height(h)),
        _ => None,
    }
}

/// `penetration_beyond_declared`: over the run, the deepest overlap with the level beyond what
/// the configuration declares it may overlap, in tiles: its overlap tolerance (the sweep's
/// epsilon) everywhere, plus, for a controller that declares the seed's centre-column stance
/// (`slope_overhang > 0`), the overlap its shape has when its feet stand on the surface under
/// its centre: the designed overhang into a ramp (or the ground that continues it) at that very
/// place, measured the same way as the overlap itself. Sunk below that stance, the difference
/// counts. A controller keeping its promise scores 0.
///
/// Frame: the first frame at the deepest overlap beyond the declared one.
pub(super) fn penetration_beyond_declared(ctx: &Context, g: &Ground, rows: Frames) -> Measure {
    let mut worst = Peak::new(0.0);
    for r in rows.iter() {
        worst.push(r.frame, beyond_declared(ctx, g, &r));
    }
    Measure {
        metric: "penetration_beyond_declared",
        value: worst.value as f64,
        reference: 0.0,
        frame: worst.frame,
    }
}

/// How much deeper than it declares the character of row `r` is inside the level's solid
/// geometry, in tiles (see `penetration_beyond_declared`; 0 when it keeps its promise).
///
/// Tile by tile: each tile's overlap less what the declared stance allows with that very tile.
/// A controller declaring the seed's centre-column stance (`slope_overhang > 0`) stands on the
/// surface under its centre (`stance_surface`: a box sunk below it is measured against the
/// true surface, however deep), and is allowed the overlap it has there with slope
/// tiles and with the solid tiles that continue the ground (tops at most `slope_overhang` above
/// the stance), never with a tile beside its body: a box pushed into a wall is charged, as
/// any other controller's would be. A one-way top it stands sunk below is never allowed.
pub(crate) fn beyond_declared(ctx: &Context, g: &Ground, r: &TraceRow) -> f32 {
    let d = ctx.declared;
    let p = pos(r);
    let stance = (d.slope_overhang > 0.0)
        .then(|| stance_surface(ctx, p, d.slope_overhang))
        .flatten()
        .map(|h| glam::Vec2::new(p.x, d.stance_height(h)));
    // The design allows at most what a walkable ramp gives (`DeclaredContact::slope_overhang`
    // is half the width times the climb gradient, vertically): into a ramp, that overhang along
    // a ramp at the climb limit's normal (the deepest a walkable ramp takes the box corner);
    // into a flat top continuing the ground, the overhang itself. A box standing by its centre
    // at the foot of a too-steep slope has its leading half deeper inside it than that, and the
    // excess is charged (the seed: run into the higher side, "collide like solid box").
    let ramp_cap = d.slope_overhang * ctx.params.max_climb_angle.cos();
    let allowed = |(i, j): (i64, i64)| match stance {
        Some(s) => {
            let cap = match ctx.level.tile(i, j) {
                Tile::Solid if (j + 1) as f32 <= s.y + d.slope_overhang + 1e-4 => d.slope_overhang,
                Tile::Solid => return 0.0,
                _ => ramp_cap,
            };
            g.tile_overlap(s, i, j).min(cap + 1e-4)
        }
        // A stance declared sunk (Box2D's pogo sag) allows that sink into the ground under the
        // feet only, never into a wall or a ceiling: a tile whose top is at or above the feet
        // and below mid-body (the floor, however deep the feet are in it, not a wall beside the
        // body), or a ramp that starts below mid-body (the ramp ahead of feet walking up it).
        None if d.stance_sink > 0.0 => {
            let mid = p.y + 0.5 * ctx.spec.size.y;
            let under = match ctx.level.tile(i, j) {
                Tile::Solid => {
                    let top = (j + 1) as f32;
                    top >= p.y - 1e-4 && top <= mid
                }
                Tile::Slope(_) => (j as f32) <= mid,
                _ => false,
            };
            if under {
                d.stance_sink
            } else {
                0.0
            }
        }
        None => 0.0,
    };
    let mut worst = (g.sunk_on_one_way(p, r.t as f64, standing(r)) - d.stance_sink).max(0.0);
    g.each_overlap(p, true, true, |tile, depth| {
        worst = worst.max(depth - allowed(tile));
    });
    (worst - d.overlap_tolerance).max(0.0)
}

/// The surface in the centre column that feet at `p` stand on or in, in tiles: where the feet
/// are inside the ground (a solid tile, or a slope tile below its surface), the top of that
/// ground, climbing the column at most the character's height; elsewhere the surface within
/// `overhang` above or below the feet. `None` if there is none (or the feet are buried deeper
/// than the character's height: then nothing is allowed).
fn stance_surface(ctx: &Context, p: glam::Vec2, overhang: f32) -> Option<f32> {
    let level = ctx.level;
    let i = p.x.floor() as i64;
    let first = p.y.floor() as i64;
    let limit = (p.y + ctx.spec.size.y).floor() as i64;
    let mut j = first;
    while j <= limit {
        match level.tile(i, j) {
            Tile::Solid => j += 1,
            Tile::Slope(s) => {
                let h = j as f32 + s.height_at(p.x - i as f32);
                if h >= p.y {
                    return Some(h);
                }
                break;
            }
            _ if j > first => return Some(j as f32),
            _ => break,
        }
    }
    if j > limit {
        return None;
    }
    level
        .surface_at(p.x, p.y + overhang, 2.0 * overhang)
        .map(|(h, _)| h)
}

/// `bounce_frames`: in the final idle span (no input, as [`rest_frames`] finds it), the frames
/// the character spends airborne after it first touched ground: a landing that bounces or lifts
/// off again. `rest_jitter` judges only the settled rest and `land_frame_error` only the first
/// grounded frame, so without this a bounce after landing would be charged nowhere. Frames a
/// moving platform shoves ([`super::pushers::shoved`]: in contact with the character, or airborne
/// since without having landed) are the platform's doing and are left out: they neither count
/// nor are the touch it counts from.
///
/// Frame: the first of those airborne frames (`None` if there is none).
pub(super) fn bounce_frames(ctx: &Context, pushers: &Pushers, rows: Frames) -> Measure {
    let script = input_script(ctx.spec);
    let idle = crate::motion::Input::default();
    let first_idle_row = script.rposition(|i| *i != idle).map_or(0, |k| k + 1) + 1;
    let span = first_idle_row.min(rows.len())..rows.len();
    let (count, first) = first_and_count(
        super::pushers::shoved(pushers, rows, span)
            .filter(|(_, shoved)| !shoved)
            .map(|(r, _)| r)
            .skip_while(|r| !r.is_grounded())
            .filter(|r| !r.is_grounded())
            .map(|r| r.frame),
    );
    Measure {
        metric: "bounce_frames",
        value: count as f64,
        reference: 0.0,
        frame: first,
    }
}

/// The settled part of the rest frames `rest`: its last [`REST_WINDOW`] seconds, as `stress`
/// judges a stable rest (a landing and its settling are `land_frame_error`'s business, so a
/// landing is charged once).
pub(super) fn settled(ctx: &Context, rest: std::ops::Range<usize>) -> std::ops::Range<usize> {
    let needed = (REST_WINDOW / ctx.spec.dt).ceil() as usize;
    rest.start.max(rest.end.saturating_sub(needed))..rest.end
}

/// `rest_jitter`: max minus min of y over the settled resting frames `settled` (see
/// [`settled`]), in tiles, leaving out the frames a moving platform shoves
/// ([`super::pushers::shoved`]): a character a block lifts or drops is not jittering (0 when
/// every settled frame is shoved).
///
/// Frame: the frame at which the range reached its final width (the later of the lowest and
/// the highest frame, each the first at its height).
pub(super) fn rest_jitter(
    pushers: &Pushers,
    rows: Frames,
    settled: std::ops::Range<usize>,
) -> Measure {
    let (mut lo, mut hi, mut frame) = (f32::INFINITY, f32::NEG_INFINITY, None);
    for (r, shoved) in super::pushers::shoved(pushers, rows, settled) {
        if shoved {
            continue;
        }
        if r.y < lo || r.y > hi {
            frame = Some(r.frame);
        }
        (lo, hi) = (lo.min(r.y), hi.max(r.y));
    }
    Measure {
        metric: "rest_jitter",
        value: if frame.is_none() {
            0.0
        } else {
            (hi - lo) as f64
        },
        reference: 0.0,
        frame,
    }
}

/// Whether the character's shape is within [`FLICKER_SUPPORT_TOLERANCE`] of the ground (or in
/// it).
pub fn supported(ctx: &Context, g: &Ground, r: &TraceRow) -> bool {
    // A moving platform under the shape holds it, whatever slope lies below the platform (the
    // stances below are of the level's own surface).
    if g.platform_gap(pos(r), r.t as f64) <= FLICKER_SUPPORT_TOLERANCE {
        return true;
    }
    // The seed's box stands by its centre over a slope with its corners inside the ramp, so its
    // shape touches the ramp until it hovers by the overhang: over a slope it is judged by its
    // feet against its declared stance instead, as a touching shape is judged by its gap.
    if let Some(stance) = stance_over_slope(ctx, pos(r)) {
        if r.y - stance > FLICKER_SUPPORT_TOLERANCE && !on_flat_top(ctx, r) {
            return false;
        }
    }
    let gap = g.gap_at(pos(r), r.t as f64, standing(r));
    // A flat foot (Box2D's segment pogo) stands on the highest surface under it over a slope,
    // its shape that far above the ramp under its centre by design: it is judged by its gap
    // beyond that declared stance (with its declared gap and sink), as `rest_gap_declared`
    // judges it.
    if flat_foot_stance(ctx, pos(r)).is_some() {
        let beyond = gap_beyond_declared(ctx, g, pos(r), gap as f64);
        return beyond <= FLICKER_SUPPORT_TOLERANCE as f64;
    }
    gap <= FLICKER_SUPPORT_TOLERANCE
}

/// Whether the feet stand on the flat top of a solid or one-way tile under the character's box
/// (within [`FLICKER_SUPPORT_TOLERANCE`]): a box over a slope held up by the tile beside it,
/// higher than the slope's stance under its centre.
fn on_flat_top(ctx: &Context, r: &TraceRow) -> bool {
    let half = ctx.spec.size.x * 0.5;
    // The row whose top is nearest the feet.
    let j = r.y.round() as i64 - 1;
    let top = (j + 1) as f32;
    // Columns outside the map hold nothing: only the map's are looked at.
    let (i0, i1) = ctx.level.clip_columns(
        (r.x - half).floor() as i64,
        ((r.x + half).ceil() as i64).saturating_sub(1),
    );
    (r.y - top).abs() <= FLICKER_SUPPORT_TOLERANCE
        && (i0..=i1).any(|i| {
            let (lo, hi) = (i as f32, i as f32 + 1.0);
            hi > r.x - half
                && lo < r.x + half
                && matches!(
                    ctx.level.tile(i, j),
                    crate::level::Tile::Solid | crate::level::Tile::OneWay
                )
        })
}

/// `false_grounded`: frames reported grounded with the ground farther than
/// [`FLICKER_SUPPORT_TOLERANCE`] below the shape (standing on air, or on a wall's side). Not in
/// DESIGN.md's catalog: added because a controller that calls itself grounded mid-air resets
/// its fall and can jump from there.
///
/// Frame: the first such frame (`None` if there is none).
pub fn false_grounded(ctx: &Context, g: &Ground, rows: Frames) -> Measure {
    let (count, first) = first_and_count(
        rows.iter()
            .filter(|r| r.is_grounded() && !supported(ctx, g, r))
            .map(|r| r.frame),
    );
    Measure {
        metric: "false_grounded",
        value: count as f64,
        reference: 0.0,
        frame: first,
    }
}

/// `grounded_flicker`: grounded-to-airborne switches that no jump explains while the ground is
/// still within [`FLICKER_SUPPORT_TOLERANCE`] under the feet.
///
/// Frame: the first airborne frame of the first such switch (`None` if there is none).
pub fn grounded_flicker(ctx: &Context, g: &Ground, rows: Frames) -> Measure {
    let script = input_script(ctx.spec);
    let mut count = 0u32;
    let mut first = None;
    for k in 1..rows.len() {
        let (prev, cur) = (rows.at(k - 1), rows.at(k));
        if !prev.is_grounded() || cur.is_grounded() {
            continue;
        }
        // Step k-1 produced row k: a jump pressed on that step explains leaving the ground.
        let jumped = script.get(k - 1).is_some_and(|i| i.jump)
            && (k < 2 || script.get(k - 2).is_none_or(|i| !i.jump));
        if !jumped && supported(ctx, g, &cur) {
            count += 1;
            first = first.or(Some(cur.frame));
        }
    }
    Measure {
        metric: "grounded_flicker",
        value: count as f64,
        reference: 0.0,
        frame: first,
    }
}

/// How many frames `frames` yields, and the first of them.
pub(super) fn first_and_count(frames: impl Iterator<Item = u32>) -> (usize, Option<u32>) {
    frames.fold((0, None), |(n, first), f| (n + 1, first.or(Some(f))))
}
