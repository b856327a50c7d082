//! Behaviour metrics, computed from a trace, the level geometry and the scenario's script, each
//! against an analytic or geometric reference (DESIGN.md, "metric catalog"). No metric reads
//! backend internals.
//!
//! A metric is reported only for scenarios where it means something: `land_frame_error` for a
//! character dropped with no input until it should land, `apex_error` for a jump with room
//! above, `progress_ratio` for a walk over flat open ground, `rest_gap` and `rest_jitter` for
//! scenarios that end with at least [`REST_WINDOW`] seconds of idle input. `max_penetration`,
//! `grounded_flicker`, `stuck_frames` and `tunneled` apply to every scenario. Only character 0
//! is measured.

pub mod ground;
mod reference;

pub use reference::{commanded_distance, commanded_steps, predicted_landing_frame};

use serde::Serialize;

use crate::level::{character_box, Level, ScenarioSpec, Tile};
use crate::motion::MotionParams;
use crate::scenario::input_script;
use crate::shape::CharacterShape;
use crate::trace::{Trace, TraceRow};
use glam::Vec2;
use ground::Ground;
use parry2d::bounding_volume::Aabb;

/// Idle time at the end of a scenario needed for the rest metrics, in seconds.
pub const REST_WINDOW: f32 = 0.5;
/// How far below the feet the ground may be for a grounded-to-airborne switch to count as a
/// flicker rather than leaving the ground, in tiles. Larger than Rapier's default offset
/// (1% of a 0.9-tile character) so a controller that keeps a skin gap is not penalised.
pub const FLICKER_SUPPORT_TOLERANCE: f32 = 0.1;

/// Every metric this version computes, in catalog order (tables list them in this order).
pub const CATALOG: &[&str] = &[
    "land_frame_error",
    "rest_gap",
    "max_penetration",
    "rest_jitter",
    "grounded_flicker",
    "false_grounded",
    "apex_error",
    "progress_ratio",
    "stuck_frames",
    "slope_airborne_frames",
    "slope_gap_max",
    "slope_speed_ratio",
    "steep_blocked",
    "oneway_result",
    "ladder_speed_error",
    "ladder_result",
    "carry_drift",
    "carry_airborne_frames",
    "push_penetration",
    "crush_count",
    "tunneled",
    "ns_per_character_step",
];

/// How far above a floor a walker may spawn for `progress_ratio` to apply, in tiles: enough
/// to let a controller settle at its own rest height, too little to matter to the distance.
pub const PROGRESS_SPAWN_HEIGHT: f32 = 0.05;

/// The catalog in the groups the summary prints as separate tables.
pub const GROUPS: &[(&str, &[&str])] = &[
    (
        "landing, jumping, walking, walls",
        &[
            "land_frame_error",
            "rest_gap",
            "max_penetration",
            "rest_jitter",
            "grounded_flicker",
            "false_grounded",
            "apex_error",
            "progress_ratio",
            "stuck_frames",
            "tunneled",
        ],
    ),
    (
        "slopes, one-way platforms, ladders",
        &[
            "slope_airborne_frames",
            "slope_gap_max",
            "slope_speed_ratio",
            "steep_blocked",
            "oneway_result",
            "ladder_speed_error",
            "ladder_result",
        ],
    ),
    (
        "moving platforms",
        &[
            "carry_drift",
            "carry_airborne_frames",
            "push_penetration",
            "crush_count",
        ],
    ),
    ("cost (run --timing)", &["ns_per_character_step"]),
];

/// One row of `metrics.csv`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MetricRow {
    /// Level name.
    pub level: String,
    /// Scenario name.
    pub scenario: String,
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// Metric name (DESIGN.md catalog).
    pub metric: &'static str,
    /// Measured value.
    pub value: f64,
    /// Unit of `value`.
    pub unit: &'static str,
    /// What an ideal controller would measure.
    pub reference: f64,
    /// `value - reference`.
    pub error: f64,
}

/// A measured metric before it is labelled with its run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measure {
    /// Metric name.
    pub metric: &'static str,
    /// Measured value.
    pub value: f64,
    /// Unit.
    pub unit: &'static str,
    /// Ideal value.
    pub reference: f64,
}

/// Everything a metric may read.
pub struct Context<'a> {
    /// The character's collision shape (the box for the sweep).
    pub shape: CharacterShape,
    /// The level the scenario ran on.
    pub level: &'a Level,
    /// The scenario.
    pub spec: &'a ScenarioSpec,
    /// The motion parameters it ran with (overrides applied).
    pub params: &'a MotionParams,
    /// The trace.
    pub trace: &'a Trace,
}

/// Computes every metric that applies to the scenario.
pub fn compute(ctx: &Context) -> Vec<MetricRow> {
    let rows: Vec<TraceRow> = ctx.trace.character(0).copied().collect();
    let ground = Ground::new(
        ctx.level,
        ctx.shape,
        ctx.spec.size,
        ctx.params.max_climb_angle,
    );
    let g = &ground;
    let mut out = Vec::new();
    let mut push = |m: Option<Measure>| {
        if let Some(m) = m {
            out.push(MetricRow {
                level: ctx.trace.level.clone(),
                scenario: ctx.trace.scenario.clone(),
                backend: ctx.trace.backend.clone(),
                config: ctx.trace.config.clone(),
                metric: m.metric,
                value: m.value,
                unit: m.unit,
                reference: m.reference,
                error: m.value - m.reference,
            });
        }
    };
    push(land_frame_error(ctx, &rows));
    let rest = rest_frames(ctx, g, &rows);
    push(rest.clone().map(|r| rest_gap(ctx, g, &rows[r])));
    push(Some(max_penetration(g, &rows)));
    push(rest.map(|r| rest_jitter(&rows[r])));
    push(Some(grounded_flicker(ctx, g, &rows)));
    push(Some(false_grounded(g, &rows)));
    push(apex_error(ctx, &rows));
    push(progress_ratio(ctx, &rows));
    push(Some(stuck_frames(ctx, &rows)));
    let on_slope = slope_frames(ctx, &rows);
    push(slope_airborne_frames(ctx, &rows, &on_slope));
    push(slope_gap_max(ctx, g, &rows, &on_slope));
    push(slope_speed_ratio(ctx, &rows, &on_slope));
    push(steep_blocked(ctx, &rows));
    push(oneway_result(ctx, &rows));
    push(ladder_speed_error(ctx, &rows));
    push(ladder_result(ctx, &rows));
    let ride = ride_frames(ctx, &rows);
    push(ride.as_ref().map(|r| carry_drift(ctx, &rows, r)));
    push(ride.as_ref().map(|r| carry_airborne_frames(&rows, r)));
    push(push_penetration(ctx, &rows));
    push(crush_count(ctx, &rows));
    push(Some(tunneled(ctx, &rows)));
    out
}

fn pos(r: &TraceRow) -> Vec2 {
    Vec2::new(r.x, r.y)
}

/// `max_penetration`: deepest overlap of the character's shape with any solid tile over the
/// whole run, in tiles, from parry's contact query between the shape and each tile's square
/// (not from a backend's contacts).
pub fn max_penetration(g: &Ground, rows: &[TraceRow]) -> Measure {
    let worst = rows
        .iter()
        .map(|r| g.solid_penetration(pos(r)))
        .fold(0.0f32, f32::max);
    Measure {
        metric: "max_penetration",
        value: worst as f64,
        unit: "tiles",
        reference: 0.0,
    }
}

/// `land_frame_error`: first grounded frame minus the frame the discrete integrator predicts,
/// for a character that starts in the air, above ground, with no horizontal velocity and no
/// input before it should land.
pub fn land_frame_error(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
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
        unit: "frames",
        reference: 0.0,
    })
}

/// The frames over which the character should be at rest: from its first settled frame (grounded
/// on real ground, moving less than 1% of the run speed) within the final idle window (or the window's last [`REST_WINDOW`] seconds if it never lands there)
/// to the end. `None` if the scenario does not end with such a window.
fn rest_frames(ctx: &Context, g: &Ground, rows: &[TraceRow]) -> Option<std::ops::Range<usize>> {
    let script = input_script(ctx.spec);
    let idle = crate::motion::Input::default();
    let n = script.len();
    let first_idle_step = script.iter().rposition(|i| *i != idle).map_or(0, |k| k + 1);
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
        rows[k].is_grounded() && supported(g, &rows[k]) && (rows[k].x - rows[k - 1].x).abs() < still
    });
    let from = landed.unwrap_or(n + 1 - needed);
    Some(from..n + 1)
}

/// `rest_gap`: signed gap from the character's shape down to the ground at the last frame
/// (negative: sunk into a solid), in tiles; see [`Ground::gap`].
fn rest_gap(ctx: &Context, g: &Ground, rows: &[TraceRow]) -> Measure {
    let last = rows.last().map(pos).unwrap_or(ctx.spec.spawn);
    Measure {
        metric: "rest_gap",
        value: g.gap_at(last, rows.last().map_or(0.0, |r| r.t as f64)) as f64,
        unit: "tiles",
        reference: 0.0,
    }
}

/// `rest_jitter`: max minus min of y over the resting frames, in tiles.
fn rest_jitter(rows: &[TraceRow]) -> Measure {
    let (lo, hi) = rows
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), r| {
            (lo.min(r.y), hi.max(r.y))
        });
    Measure {
        metric: "rest_jitter",
        value: if rows.is_empty() {
            0.0
        } else {
            (hi - lo) as f64
        },
        unit: "tiles",
        reference: 0.0,
    }
}

/// Whether the character's shape is within [`FLICKER_SUPPORT_TOLERANCE`] of the ground (or in
/// it).
fn supported(g: &Ground, r: &TraceRow) -> bool {
    g.gap_at(pos(r), r.t as f64) <= FLICKER_SUPPORT_TOLERANCE
}

/// `false_grounded`: frames reported grounded with the ground farther than
/// [`FLICKER_SUPPORT_TOLERANCE`] below the shape (standing on air, or on a wall's side). Not in
/// DESIGN.md's catalog: added because a controller that calls itself grounded mid-air resets
/// its fall and can jump from there.
pub fn false_grounded(g: &Ground, rows: &[TraceRow]) -> Measure {
    let count = rows
        .iter()
        .filter(|r| r.is_grounded() && !supported(g, r))
        .count();
    Measure {
        metric: "false_grounded",
        value: count as f64,
        unit: "frames",
        reference: 0.0,
    }
}

/// `grounded_flicker`: grounded-to-airborne switches that no jump explains while the ground is
/// still within [`FLICKER_SUPPORT_TOLERANCE`] under the feet.
pub fn grounded_flicker(ctx: &Context, g: &Ground, rows: &[TraceRow]) -> Measure {
    let script = input_script(ctx.spec);
    let mut count = 0u32;
    for k in 1..rows.len() {
        let (prev, cur) = (&rows[k - 1], &rows[k]);
        if !prev.is_grounded() || cur.is_grounded() {
            continue;
        }
        // Step k-1 produced row k: a jump pressed on that step explains leaving the ground.
        let jumped = script.get(k - 1).is_some_and(|i| i.jump)
            && (k < 2 || script.get(k - 2).is_none_or(|i| !i.jump));
        if !jumped && supported(g, cur) {
            count += 1;
        }
    }
    Measure {
        metric: "grounded_flicker",
        value: count as f64,
        unit: "count",
        reference: 0.0,
    }
}

/// `apex_error`: the rise of the feet from take-off to the apex of the first jump, minus the
/// requested jump height, in tiles. Only for a jump with no solid within the jump's reach above
/// the character.
pub fn apex_error(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    let script = input_script(ctx.spec);
    let press = script
        .iter()
        .enumerate()
        .position(|(k, i)| i.jump && (k == 0 || !script[k - 1].jump))?;
    // Down + jump is a drop through a one-way platform, not a jump.
    if script[press].down {
        return None;
    }
    let start = rows.get(press)?;
    let h = ctx.params.jump_height;
    let half = ctx.spec.size.x * 0.5;
    let reach = Aabb::new(
        Vec2::new(start.x - half, start.y + ctx.spec.size.y),
        Vec2::new(start.x + half, start.y + ctx.spec.size.y + h + 0.5),
    );
    if ctx.level.solids_overlapping(&reach).next().is_some() {
        return None;
    }
    let mut apex = start.y;
    for r in rows.iter().skip(press + 1) {
        apex = apex.max(r.y);
        if r.is_grounded() && r.frame as usize > press + 1 {
            break;
        }
    }
    Some(Measure {
        metric: "apex_error",
        value: (apex - start.y) as f64 - h as f64,
        unit: "tiles",
        reference: 0.0,
    })
}

/// `progress_ratio`: distance walked over distance commanded, for a walk that starts on the
/// ground with the whole commanded path flat, supported and free of obstacles.
pub fn progress_ratio(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
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
    let open = (lo.floor() as i64..hi.ceil() as i64).all(|i| {
        (y0 as i64..(y0 + spec.size.y).ceil() as i64).all(|j| ctx.level.tile(i, j) == Tile::Empty)
    });
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
        unit: "ratio",
        reference: 1.0,
    })
}

/// Below this fraction of the commanded step a commanded move counts as stuck.
pub const STUCK_FRACTION: f64 = 0.01;
/// Height above the feet below which a solid ahead is the floor (or a seam in it), not an
/// obstacle, for `stuck_frames`, in tiles: larger than Rapier's offset and a snapped step.
pub const STUCK_FLOOR_BAND: f32 = 0.05;

/// `stuck_frames`: steps in which the character was commanded to move horizontally, was
/// grounded, and moved less than [`STUCK_FRACTION`] of the commanded step, while nothing in the
/// level blocked that step (a wall being pushed against is not "stuck").
pub fn stuck_frames(ctx: &Context, rows: &[TraceRow]) -> Measure {
    let script = input_script(ctx.spec);
    let commanded = commanded_steps(ctx.params, &script, ctx.spec.velocity.x, ctx.spec.dt);
    let size = ctx.spec.size;
    let mut count = 0u32;
    for (k, step) in commanded.iter().enumerate() {
        let (Some(before), Some(after)) = (rows.get(k), rows.get(k + 1)) else {
            break;
        };
        if script[k].horizontal() == 0.0 || !after.is_grounded() || step.abs() < 1e-9 {
            continue;
        }
        if ((after.x - before.x) as f64).abs() >= STUCK_FRACTION * step.abs() {
            continue;
        }
        // The box moved by the commanded step, lifted out of the floor band.
        let mut ahead = character_box(pos(before) + Vec2::new(*step as f32, 0.0), size);
        ahead.mins.y += STUCK_FLOOR_BAND;
        let dir = step.signum() as f32;
        let steep_ahead = steep_columns(ctx, dir)
            .any(|i| (i as f32) < ahead.maxs.x && (i as f32 + 1.0) > ahead.mins.x);
        if ctx.level.solids_overlapping(&ahead).next().is_none() && !steep_ahead {
            count += 1;
        }
    }
    Measure {
        metric: "stuck_frames",
        value: count as f64,
        unit: "frames",
        reference: 0.0,
    }
}

/// Columns holding a slope that rises in direction `dir` (+1 right, -1 left) more steeply than
/// the climb limit somewhere in the tile.
fn steep_columns<'a>(ctx: &'a Context, dir: f32) -> impl Iterator<Item = i64> + 'a {
    let limit = ctx.params.max_climb_angle.tan() + 1e-3;
    ctx.level.slopes().filter_map(move |(i, _, s)| {
        let steep = (0..16).any(|k| {
            let (a, b) = (k as f32 / 16.0, (k + 1) as f32 / 16.0);
            (s.height_at(b) - s.height_at(a)) * 16.0 * dir > limit
        });
        steep.then_some(i)
    })
}

/// For each row, whether the ground under the character's centre (from half a tile above its
/// feet to one tile below) is a slope no steeper than the climb limit.
fn slope_frames(ctx: &Context, rows: &[TraceRow]) -> Vec<bool> {
    let limit = ctx.params.max_climb_angle.tan() + 1e-3;
    rows.iter()
        .map(|r| match ctx.level.surface_at(r.x, r.y + 0.5, 1.5) {
            Some((_, Some((i, j)))) => {
                let n = ctx.level.slope_normal(i, j, r.x);
                (n.x / n.y).abs() <= limit
            }
            _ => false,
        })
        .collect()
}

/// Whether the scenario walks (a direction held at some point) and never jumps.
fn walks_without_jumping(script: &[crate::motion::Input]) -> bool {
    script.iter().any(|i| i.horizontal() != 0.0) && !script.iter().any(|i| i.jump)
}

/// Whether the scenario's walk, as commanded, crosses a column holding a slope no steeper than
/// the climb limit: the slope metrics then apply, whatever the controller does.
fn walks_over_slopes(ctx: &Context) -> bool {
    let script = input_script(ctx.spec);
    if !walks_without_jumping(&script) {
        return false;
    }
    let d = commanded_distance(ctx.params, &script, ctx.spec.velocity.x, ctx.spec.dt) as f32;
    let half = ctx.spec.size.x * 0.5;
    let (a, b) = (ctx.spec.spawn.x, ctx.spec.spawn.x + d);
    let (x0, x1) = (a.min(b) - half, a.max(b) + half);
    let limit = ctx.params.max_climb_angle.tan() + 1e-3;
    ctx.level.slopes().any(|(i, _, s)| {
        let walkable = (0..16).any(|k| {
            let (u, v) = (k as f32 / 16.0, (k + 1) as f32 / 16.0);
            let grad = (s.height_at(v) - s.height_at(u)) * 16.0;
            grad != 0.0 && grad.abs() <= limit
        });
        walkable && (i as f32) < x1 && (i as f32 + 1.0) > x0
    })
}

/// `slope_airborne_frames`: frames airborne over a walkable slope while walking, without a jump.
pub fn slope_airborne_frames(ctx: &Context, rows: &[TraceRow], on: &[bool]) -> Option<Measure> {
    if !walks_over_slopes(ctx) {
        return None;
    }
    let script = input_script(ctx.spec);
    let count = (1..rows.len())
        .filter(|&k| on[k] && script[k - 1].horizontal() != 0.0 && !rows[k].is_grounded())
        .count();
    Some(Measure {
        metric: "slope_airborne_frames",
        value: count as f64,
        unit: "frames",
        reference: 0.0,
    })
}

/// `slope_gap_max`: the largest gap between the character's shape and the ground over a
/// walkable slope while reported grounded, in tiles (0 if it never stood on one).
pub fn slope_gap_max(ctx: &Context, g: &Ground, rows: &[TraceRow], on: &[bool]) -> Option<Measure> {
    if !(walks_over_slopes(ctx) || rest_on_slope(ctx)) {
        return None;
    }
    let gaps: Vec<f32> = rows
        .iter()
        .zip(on)
        .filter(|(r, o)| **o && r.is_grounded())
        .map(|(r, _)| g.gap(pos(r)))
        .collect();
    Some(Measure {
        metric: "slope_gap_max",
        value: gaps.iter().fold(0.0f32, |a, b| a.max(*b)) as f64,
        unit: "tiles",
        reference: 0.0,
    })
}

/// Whether the scenario drops the character onto a slope and leaves it there (no input).
fn rest_on_slope(ctx: &Context) -> bool {
    input_script(ctx.spec)
        .iter()
        .all(|i| *i == crate::motion::Input::default())
        && matches!(
            ctx.level
                .surface_at(ctx.spec.spawn.x, ctx.spec.spawn.y, ctx.spec.spawn.y),
            Some((_, Some(_)))
        )
}

/// `slope_speed_ratio`: mean horizontal speed over a walkable slope while walking at full run
/// speed, over the run speed (the horizontal speed the same input gives on flat ground).
pub fn slope_speed_ratio(ctx: &Context, rows: &[TraceRow], on: &[bool]) -> Option<Measure> {
    // A walk into a too-steep rise is steep_blocked's business, not a speed.
    if !walks_over_slopes(ctx) || steep_ahead(ctx) {
        return None;
    }
    let script = input_script(ctx.spec);
    // Steps at full commanded speed: the same direction held since the ramp-up ended.
    let ramp = (ctx.params.run_speed / (ctx.params.run_accel * ctx.spec.dt)).ceil() as usize + 1;
    let speeds: Vec<f64> = (1..rows.len())
        .filter(|&k| {
            let dir = script[k - 1].horizontal();
            dir != 0.0
                && on[k]
                && on[k - 1]
                && k > ramp
                && script[k - 1 - ramp..k]
                    .iter()
                    .all(|i| i.horizontal() == dir)
        })
        .map(|k| ((rows[k].x - rows[k - 1].x) as f64 / ctx.spec.dt as f64).abs())
        .collect();
    // Never on a slope at full speed: it did not walk the slope.
    let mean = if speeds.is_empty() {
        0.0
    } else {
        speeds.iter().sum::<f64>() / speeds.len() as f64
    };
    Some(Measure {
        metric: "slope_speed_ratio",
        value: mean / ctx.params.run_speed as f64,
        unit: "ratio",
        reference: 1.0,
    })
}

/// Whether the commanded walk reaches a slope rising more steeply than the climb limit.
fn steep_ahead(ctx: &Context) -> bool {
    let script = input_script(ctx.spec);
    let d = commanded_distance(ctx.params, &script, ctx.spec.velocity.x, ctx.spec.dt) as f32;
    let (a, b) = (ctx.spec.spawn.x, ctx.spec.spawn.x + d);
    let (x0, x1) = (a.min(b), a.max(b));
    steep_columns(ctx, d.signum()).any(|i| (i as f32) < x1 && (i as f32 + 1.0) > x0)
}

/// `steep_blocked`: for a walk toward a slope that rises more steeply than the climb limit, 1 if
/// the character never got half a tile above where it started, else 0.
pub fn steep_blocked(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    let script = input_script(ctx.spec);
    if !walks_without_jumping(&script) {
        return None;
    }
    if !steep_ahead(ctx) {
        return None;
    }
    let top = rows.iter().map(|r| r.y).fold(f32::NEG_INFINITY, f32::max);
    Some(Measure {
        metric: "steep_blocked",
        value: (top < ctx.spec.spawn.y + 0.5) as u8 as f64,
        unit: "bool",
        reference: 1.0,
    })
}

/// How close to the expected height the feet must end for `oneway_result`, in tiles: above
/// Rapier's offset, far below a tile.
pub const EXPECT_TOLERANCE: f32 = 0.05;

/// `oneway_result`: on a level with one-way platforms, 1 if the character ended where the
/// scenario says the seed's rule puts it (`expect_y`: on the platform, or below it), else 0.
pub fn oneway_result(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    ended_as_expected(ctx, rows, "oneway_result", ctx.level.features.one_way)
}

/// 1 if the last row's feet are within [`EXPECT_TOLERANCE`] of the scenario's `expect_y`, as
/// metric `metric`, when `applies` and the scenario states an `expect_y`.
fn ended_as_expected(
    ctx: &Context,
    rows: &[TraceRow],
    metric: &'static str,
    applies: bool,
) -> Option<Measure> {
    let expect = ctx.spec.expect_y.filter(|_| applies)?;
    let last = rows.last()?;
    Some(Measure {
        metric,
        value: ((last.y - expect).abs() <= EXPECT_TOLERANCE) as u8 as f64,
        unit: "bool",
        reference: 1.0,
    })
}

/// `ladder_speed_error`: on a level with ladders, for a scenario that climbs (up or down held),
/// the measured climbing speed minus the configured ladder speed, in tiles/s: the worst over the
/// steps spent on the ladder from start to end while climbing (steps entering or leaving the
/// ladder are not climbing at speed). A character that never climbed measures speed 0.
pub fn ladder_speed_error(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    let script = input_script(ctx.spec);
    if !ctx.level.features.ladders || !script.iter().any(|i| i.up || i.down) {
        return None;
    }
    let target = ctx.params.ladder_speed as f64;
    let mut worst: Option<f64> = None;
    for k in 1..rows.len() {
        let i = script[k - 1];
        if !(rows[k - 1].ladder == 1 && rows[k].ladder == 1 && i.up != i.down && !i.jump) {
            continue;
        }
        let speed = ((rows[k].y - rows[k - 1].y) as f64 / ctx.spec.dt as f64).abs();
        let err = speed - target;
        if worst.is_none_or(|w| err.abs() > w.abs()) {
            worst = Some(err);
        }
    }
    Some(Measure {
        metric: "ladder_speed_error",
        value: worst.unwrap_or(-target),
        unit: "tiles/s",
        reference: 0.0,
    })
}

/// `ladder_result`: on a level with ladders, 1 if the character ended where the scenario says
/// (`expect_y`: at the top, back at the bottom, or on the floor after jumping off), else 0. Not
/// in DESIGN.md's catalog: added so that entering and leaving a ladder is checked, not only the
/// climbing speed.
pub fn ladder_result(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    ended_as_expected(ctx, rows, "ladder_result", ctx.level.features.ladders)
}

/// How close above a platform's top the feet count as on it, for the carry metrics, in tiles:
/// above Rapier's offset.
pub const ON_PLATFORM: f32 = 0.05;

/// The frames of the ride: from the first frame the character stands on the scenario's platform
/// (grounded, feet within [`ON_PLATFORM`] of its top, overlapping it in x) with idle input and no
/// velocity of its own, to the end of that idle input (or the end); from the first step if it
/// never stands on it. `None` if the scenario names no platform.
fn ride_frames(ctx: &Context, rows: &[TraceRow]) -> Option<std::ops::Range<usize>> {
    let p = ctx.level.platforms.get(ctx.spec.ride? as usize)?;
    let script = input_script(ctx.spec);
    let dt = ctx.spec.dt as f64;
    let half = ctx.spec.size.x * 0.5;
    let on = |k: usize| {
        let r = &rows[k];
        let b = p.aabb(k as f64 * dt);
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
        .find(|&k| on(k) && idle(k) && rows[k].vx.abs() < 1e-3)
        .unwrap_or(1.min(rows.len()));
    let end = (start..rows.len())
        .find(|&k| !idle(k))
        .unwrap_or(rows.len());
    Some(start..end)
}

/// `carry_drift`: over the idle part of the ride, the largest change of the character's position
/// relative to its platform, in tiles.
pub fn carry_drift(ctx: &Context, rows: &[TraceRow], ride: &std::ops::Range<usize>) -> Measure {
    let p = &ctx.level.platforms[ctx.spec.ride.unwrap_or(0) as usize];
    let dt = ctx.spec.dt as f64;
    let rel = |k: usize| pos(&rows[k]) - p.position(k as f64 * dt);
    let first = rel(ride.start);
    let drift = ride
        .clone()
        .map(|k| (rel(k) - first).length())
        .fold(0.0f32, f32::max);
    Measure {
        metric: "carry_drift",
        value: drift as f64,
        unit: "tiles",
        reference: 0.0,
    }
}

/// `carry_airborne_frames`: frames airborne during the idle part of the ride.
pub fn carry_airborne_frames(rows: &[TraceRow], ride: &std::ops::Range<usize>) -> Measure {
    Measure {
        metric: "carry_airborne_frames",
        value: ride.clone().filter(|&k| !rows[k].is_grounded()).count() as f64,
        unit: "frames",
        reference: 0.0,
    }
}

/// `push_penetration`: on a level with moving platforms, the deepest overlap of the character's
/// box with a platform that is not one-way, over the run, in tiles.
pub fn push_penetration(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    if ctx.level.platforms.is_empty() {
        return None;
    }
    let dt = ctx.spec.dt as f64;
    let deepest = rows
        .iter()
        .enumerate()
        .flat_map(|(k, r)| {
            let b = character_box(pos(r), ctx.spec.size);
            ctx.level
                .platforms
                .iter()
                .filter(|p| !p.one_way)
                .map(move |p| {
                    let pb = p.aabb(k as f64 * dt);
                    let o = b.maxs.min(pb.maxs) - b.mins.max(pb.mins);
                    o.x.min(o.y).max(0.0)
                })
        })
        .fold(0.0f32, f32::max);
    Some(Measure {
        metric: "push_penetration",
        value: deepest as f64,
        unit: "tiles",
        reference: 0.0,
    })
}

/// Overlap with a moving platform beyond which the character counts as crushed (or run
/// through), in tiles: far beyond any contact tolerance.
pub const CRUSH_DEPTH: f32 = 0.25;

/// `crush_count`: on a level with moving platforms, how many times the character ended up inside
/// a (not one-way) platform by more than [`CRUSH_DEPTH`]: crushed against the level, or run
/// through by a platform that did not push it. Read from the geometry, so a backend without a
/// crush event (Rapier) is counted the same way as the sweep, whose trace also flags the crush.
pub fn crush_count(ctx: &Context, rows: &[TraceRow]) -> Option<Measure> {
    if ctx.level.platforms.is_empty() {
        return None;
    }
    let dt = ctx.spec.dt as f64;
    let inside = |k: usize| {
        let b = character_box(pos(&rows[k]), ctx.spec.size);
        ctx.level.platforms.iter().filter(|p| !p.one_way).any(|p| {
            let pb = p.aabb(k as f64 * dt);
            let o = b.maxs.min(pb.maxs) - b.mins.max(pb.mins);
            o.x.min(o.y) > CRUSH_DEPTH
        })
    };
    let count = (1..rows.len())
        .filter(|&k| inside(k) && !inside(k - 1))
        .count();
    Some(Measure {
        metric: "crush_count",
        value: count as f64,
        unit: "count",
        reference: 0.0,
    })
}

/// `tunneled`: 1 if between two frames the character passed entirely through a solid tile that
/// overlapped its box's cross-section both before and after the move, else 0.
pub fn tunneled(ctx: &Context, rows: &[TraceRow]) -> Measure {
    let size = ctx.spec.size;
    let passed = rows.windows(2).any(|w| {
        let a = character_box(pos(&w[0]), size);
        let b = character_box(pos(&w[1]), size);
        passed_through(ctx.level, &a, &b, 0) || passed_through(ctx.level, &a, &b, 1)
    });
    Measure {
        metric: "tunneled",
        value: passed as u8 as f64,
        unit: "bool",
        reference: 0.0,
    }
}

/// Whether a solid tile lies wholly between boxes `a` and `b` along `axis` while overlapping
/// both boxes on the other axis.
fn passed_through(level: &Level, a: &Aabb, b: &Aabb, axis: usize) -> bool {
    let o = 1 - axis;
    let (gap_lo, gap_hi) = if b.mins[axis] >= a.maxs[axis] {
        (a.maxs[axis], b.mins[axis])
    } else if a.mins[axis] >= b.maxs[axis] {
        (b.maxs[axis], a.mins[axis])
    } else {
        return false;
    };
    let cross_lo = a.mins[o].max(b.mins[o]);
    let cross_hi = a.maxs[o].min(b.maxs[o]);
    if cross_hi <= cross_lo || gap_hi - gap_lo < 1.0 {
        return false;
    }
    let mut area = Aabb::new(Vec2::ZERO, Vec2::ZERO);
    area.mins[axis] = gap_lo;
    area.maxs[axis] = gap_hi;
    area.mins[o] = cross_lo;
    area.maxs[o] = cross_hi;
    level
        .solids_overlapping(&area)
        .any(|t| t.mins[axis] >= gap_lo && t.maxs[axis] <= gap_hi)
}

/// The `ns_per_character_step` row of a timed scenario (see [`crate::scenario::time_scenario`]).
pub fn timing_row(
    level: &Level,
    spec: &ScenarioSpec,
    run: &crate::scenario::RunConfig,
    ns: f64,
) -> MetricRow {
    MetricRow {
        level: level.name.clone(),
        scenario: spec.name.clone(),
        backend: run.backend.name().to_string(),
        config: run.label.clone(),
        metric: "ns_per_character_step",
        value: ns,
        unit: "ns",
        reference: 0.0,
        error: ns,
    }
}

/// A scenario's trace and its metrics on one configuration.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// The run's trace.
    pub trace: Trace,
    /// The metrics that apply to the scenario.
    pub metrics: Vec<MetricRow>,
}

/// Runs `spec` on `run` and measures it.
pub fn evaluate(
    level: &Level,
    spec: &ScenarioSpec,
    run: &crate::scenario::RunConfig,
) -> Result<Evaluation, crate::backend::BackendError> {
    evaluate_with(&mut crate::scenario::Runner::new(level), spec, run)
}

/// Runs `spec` on `run` with a runner that shares level geometry between runs, and measures it.
pub fn evaluate_with(
    runner: &mut crate::scenario::Runner,
    spec: &ScenarioSpec,
    run: &crate::scenario::RunConfig,
) -> Result<Evaluation, crate::backend::BackendError> {
    let level = runner.level();
    let trace = runner.run(spec, run)?;
    let params = crate::scenario::effective_params(&run.params, spec);
    let metrics = compute(&Context {
        shape: run.shape(),
        level,
        spec,
        params: &params,
        trace: &trace,
    });
    Ok(Evaluation { trace, metrics })
}

#[cfg(test)]
mod tests {
    //! Each metric on hand-made traces of a bad controller, so that a test asserting a bound on
    //! a real run is known to be able to fail.
    use super::*;
    use crate::level::{parse_level, InputEvent};

    const LEVEL: &str = r#"
name = "m"
map = """
..........#.........
..........#.........
..........#.........
####################
"""
"#;

    fn spec(spawn: Vec2, inputs: Vec<InputEvent>, duration: f32) -> ScenarioSpec {
        ScenarioSpec {
            name: "s".into(),
            spawn,
            size: Vec2::new(0.8, 0.9),
            velocity: Vec2::ZERO,
            duration,
            dt: 0.1,
            inputs,
            motion: Default::default(),
            expect_y: None,
            ride: None,
        }
    }

    fn trace(points: &[(f32, f32, bool)]) -> Trace {
        Trace {
            level: "m".into(),
            scenario: "s".into(),
            backend: "fake".into(),
            config: "default".into(),
            rows: points
                .iter()
                .enumerate()
                .map(|(k, &(x, y, g))| TraceRow {
                    frame: k as u32,
                    t: k as f32 * 0.1,
                    character: 0,
                    x,
                    y,
                    vx: 0.0,
                    vy: 0.0,
                    grounded: g as u8,
                    ground_nx: 0.0,
                    ground_ny: 0.0,
                    platform: None,
                    ladder: 0,
                    crushed: 0,
                })
                .collect(),
        }
    }

    fn measure(s: &ScenarioSpec, t: &Trace) -> Vec<MetricRow> {
        let level = parse_level(LEVEL, "m.toml").unwrap();
        let p = MotionParams::default();
        compute(&Context {
            shape: CharacterShape::Cuboid,
            level: &level,
            spec: s,
            params: &p,
            trace: t,
        })
    }

    fn value(rows: &[MetricRow], m: &str) -> Option<f64> {
        rows.iter().find(|r| r.metric == m).map(|r| r.value)
    }

    #[test]
    fn tunneling_through_the_wall_is_detected() {
        let s = spec(Vec2::new(5.5, 1.0), vec![], 0.2);
        let through = trace(&[(5.5, 1.0, true), (15.5, 1.0, true), (15.5, 1.0, true)]);
        assert_eq!(value(&measure(&s, &through), "tunneled"), Some(1.0));
        let stopped = trace(&[(5.5, 1.0, true), (9.6, 1.0, true), (9.6, 1.0, true)]);
        assert_eq!(value(&measure(&s, &stopped), "tunneled"), Some(0.0));
        // Dropping through the floor from above.
        let fell = trace(&[(2.5, 2.0, false), (2.5, -1.5, false), (2.5, -2.0, false)]);
        assert_eq!(value(&measure(&s, &fell), "tunneled"), Some(1.0));
    }

    #[test]
    fn penetration_rest_gap_and_jitter_are_measured() {
        let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
        let mut pts = vec![(2.5, 1.0, true); 11];
        pts[4].1 = 0.97; // sank 0.03 into the floor
        pts[10].1 = 1.02; // ends 0.02 above it
        let rows = measure(&s, &trace(&pts));
        assert!((value(&rows, "max_penetration").unwrap() - 0.03).abs() < 1e-6);
        assert!((value(&rows, "rest_gap").unwrap() - 0.02).abs() < 1e-6);
        assert!((value(&rows, "rest_jitter").unwrap() - 0.05).abs() < 1e-6);
    }

    #[test]
    fn flicker_counts_unexplained_airborne_frames_on_ground() {
        let s = spec(Vec2::new(2.5, 1.0), vec![], 0.5);
        let pts = [
            (2.5, 1.0, true),
            (2.5, 1.0, true),
            (2.5, 1.005, false),
            (2.5, 1.0, true),
            (2.5, 1.005, false),
            (2.5, 1.0, true),
        ];
        assert_eq!(
            value(&measure(&s, &trace(&pts)), "grounded_flicker"),
            Some(2.0)
        );
    }

    #[test]
    fn stuck_frames_count_open_ground_only_and_false_grounded_counts_air() {
        let right = vec![InputEvent {
            t: 0.0,
            right: Some(true),
            ..Default::default()
        }];
        // Commanded 0.6 tiles a step; the character moves on step 1, stalls on steps 2 and 3.
        let walk = spec(Vec2::new(1.5, 1.0), right.clone(), 0.3);
        let pts = [
            (1.5, 1.0, true),
            (2.1, 1.0, true),
            (2.1, 1.0, true),
            (2.1, 1.0, true),
        ];
        assert_eq!(
            value(&measure(&walk, &trace(&pts)), "stuck_frames"),
            Some(2.0)
        );
        // Against the wall at x = 10 (box edge 9.6 + 0.4): blocked, not stuck.
        let wall = spec(Vec2::new(9.6, 1.0), right, 0.2);
        let pts = [(9.6, 1.0, true), (9.6, 1.0, true), (9.6, 1.0, true)];
        assert_eq!(
            value(&measure(&wall, &trace(&pts)), "stuck_frames"),
            Some(0.0)
        );
        // Grounded 2 tiles above the floor: false; grounded 0.05 above or 0.3 sunk: real ground.
        let s = spec(Vec2::new(2.5, 1.0), vec![], 0.3);
        let pts = [
            (2.5, 3.0, true),
            (2.5, 1.05, true),
            (2.5, 0.7, true),
            (2.5, 3.0, false),
        ];
        assert_eq!(
            value(&measure(&s, &trace(&pts)), "false_grounded"),
            Some(1.0)
        );
    }

    #[test]
    fn progress_ratio_and_landing_on_a_stuck_or_late_controller() {
        let walk = spec(
            Vec2::new(1.5, 1.0),
            vec![InputEvent {
                t: 0.0,
                right: Some(true),
                ..Default::default()
            }],
            0.5,
        );
        // Commanded: 0.1 s steps at accel 60 reach 6 t/s in one step: 5 x 0.6 = 3 tiles.
        let stuck = trace(&[(1.5, 1.0, true); 6]);
        assert_eq!(value(&measure(&walk, &stuck), "progress_ratio"), Some(0.0));
        let drop = spec(Vec2::new(2.5, 1.5), vec![], 2.0);
        // From 0.5 tiles at g dt² = 0.3: 0.3 * n(n+1)/2 >= 0.5 at n = 2; landing at frame 4.
        let mut pts = vec![(2.5, 1.5, false); 4];
        pts.extend(vec![(2.5, 1.0, true); 17]);
        assert_eq!(
            value(&measure(&drop, &trace(&pts)), "land_frame_error"),
            Some(2.0)
        );
    }
}
