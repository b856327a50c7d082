//! The invariants hunt checks on every run: each holds for any controller, judged against the
//! contact its configuration declares, and each is read from the metrics `platbench run`
//! reports (so `run` on a found level shows the failing metric) or from the trace itself.

use crate::config::RunConfig;
use crate::level::{Level, ScenarioSpec};
use crate::metrics::{registry, Evaluation, MetricRow};
use crate::trace::Frames;

/// One pixel at the default 16 pixels per tile: the error a game cannot show, and the
/// allowance the error score takes off a length ([`registry::DEFAULT_PIXELS_PER_TILE`]).
/// Lengths within it are not failures.
pub(crate) const PIXEL: f64 = 1.0 / registry::DEFAULT_PIXELS_PER_TILE;

/// Below this fraction of the full-speed step a commanded step is the velocity passing
/// through zero while the character turns, not a command to move: `stuck` counts only steps
/// commanded at least a quarter of the full-speed step.
const MEANINGFUL_STEP: f64 = 0.25;

/// The invariants: name, the metric `platbench run` shows it by, and what it says.
pub const INVARIANTS: [(&str, &str, &str); 11] = [
    (
        "runs",
        "",
        "the run ends without an error from the controller",
    ),
    (
        "finite",
        "",
        "every position and velocity in the trace is a finite number",
    ),
    (
        "penetration",
        "penetration_beyond_declared",
        "no overlap with the level beyond what the configuration declares, by more than a pixel (a character a moving platform squeezes is left to the platform metrics)",
    ),
    (
        "tunnelling",
        "tunneled",
        "never through a solid tile between two frames",
    ),
    (
        "stuck",
        "stuck_frames",
        "no grounded step commanded at a quarter of full speed or more that moved under 1% of it with nothing in the way",
    ),
    (
        "rest",
        "rest_jitter",
        "comes to rest when input stops: the feet move less than a pixel over the last 0.5 s of idle (checked on levels with no ramp steeper than the climb limit, where sliding is the promise)",
    ),
    (
        "climb",
        "",
        "no climb up a slope steeper than the configuration's climb limit: never three grounded steps in a row rising over such a ramp without a jump (not asked of a configuration that declares no limit)",
    ),
    (
        "carry",
        "carry_drift",
        "a rider of a platform whose path nothing blocks stays on it once it first stands on it: not airborne, and drifting no more than the lag of two platform steps plus a pixel",
    ),
    (
        "idle_drift",
        "idle_drift",
        "a settled character with no input moves less than a pixel (same levels as rest)",
    ),
    (
        "false_grounded",
        "false_grounded",
        "never reports grounded with no ground within 0.1 tiles below it",
    ),
    (
        "expect",
        "expect_*",
        "the level's own stated expectations: the feet never below a floor with no pit (min_y), never outside a walled map (stay_in_map), grounded at the end of an idle span on plain ground (grounded_at_end)",
    ),
];

/// A broken invariant.
#[derive(Clone, Debug, PartialEq)]
pub struct Violation {
    /// The invariant's name (an [`INVARIANTS`] entry).
    pub invariant: &'static str,
    /// The metric that shows it (`""` when the trace or the run itself does).
    pub metric: String,
    /// What was measured.
    pub value: f64,
    /// The bound it broke (the value must be at most this).
    pub bound: f64,
    /// The first trace frame that shows it, where one does.
    pub frame: Option<u32>,
    /// The run's error, for `runs`.
    pub detail: String,
}

fn violation(invariant: &'static str, row: &MetricRow, bound: f64) -> Violation {
    Violation {
        invariant,
        metric: row.metric.to_string(),
        value: row.value,
        bound,
        frame: row.frame,
        detail: String::new(),
    }
}

/// The invariants `evaluation` of `spec` on `run` breaks, in [`INVARIANTS`]' order.
pub(crate) fn check(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    evaluation: &Evaluation,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let trace = &evaluation.trace;
    if let Some(r) = trace
        .rows
        .iter()
        .find(|r| ![r.x, r.y, r.vx, r.vy].iter().all(|v| v.is_finite()))
    {
        out.push(Violation {
            invariant: "finite",
            metric: String::new(),
            value: 1.0,
            bound: 0.0,
            frame: Some(r.frame),
            detail: String::new(),
        });
        // Nothing measured from a non-finite trace means more.
        return out;
    }
    let get = |m: &str| evaluation.metrics.iter().find(|r| r.metric == m);
    // A character a moving platform presses into the level is squeezed, which the platform
    // metrics judge (push_penetration, crush_count), not this invariant.
    let squeezed = trace.rows.iter().any(|r| r.crushed != 0)
        || get("push_penetration").is_some_and(|r| r.value > PIXEL)
        || get("crush_count").is_some_and(|r| r.value > 0.0);
    if let Some(r) = get("penetration_beyond_declared").filter(|r| r.value > PIXEL && !squeezed) {
        out.push(violation("penetration", r, PIXEL));
    }
    if let Some(r) = get("tunneled").filter(|r| r.value > 0.0) {
        out.push(violation("tunnelling", r, 0.0));
    }
    // A character that fell out of the level (through a pit, off an open side) has nothing
    // left to stand, rest or ride on: only the invariants above judge its run.
    if get("left_level").is_some_and(|r| r.value > 0.0) {
        return out;
    }
    // Rest and idle drift are judged on static ground the character had time to settle on:
    // no moving platform (a character standing on one moves with it), no ramp steeper than
    // the climb limit (sliding down it is the promise), and an idle end of at least
    // SETTLE_TIME.
    let settles =
        level.platforms.is_empty() && !level_has_steep(level, run) && idle_end(spec) >= SETTLE_TIME;
    if let Some(v) = stuck(level, spec, run, evaluation) {
        out.push(v);
    }
    if settles {
        if let Some(r) = get("rest_jitter").filter(|r| r.value > PIXEL) {
            out.push(violation("rest", r, PIXEL));
        }
    }
    if let Some(v) = climb(level, spec, run, evaluation) {
        out.push(v);
    }
    if let Some(v) = carry(level, spec, run, evaluation) {
        out.push(v);
    }
    if settles {
        if let Some(r) = get("idle_drift").filter(|r| r.value > PIXEL) {
            out.push(violation("idle_drift", r, PIXEL));
        }
    }
    // With moving platforms, one frame is allowed: the trace places a platform at the row's
    // time, and a controller reports the contact of its step, which may have moved the
    // platform before or after its character.
    let allowed = if level.platforms.is_empty() { 0.0 } else { 1.0 };
    if let Some(r) = get("false_grounded").filter(|r| r.value > allowed) {
        out.push(violation("false_grounded", r, allowed));
    }
    // Grounded at the end is asked of an idle end long enough to land (a shrunk script may
    // have cut it short).
    let settled_end = idle_end(spec) >= SETTLE_TIME;
    if let Some(r) = evaluation.metrics.iter().find(|r| {
        r.metric.starts_with("expect_")
            && r.value > 0.0
            && (settled_end || r.metric != "expect_grounded_at_end")
    }) {
        out.push(violation("expect", r, 0.0));
    }
    out
}

/// The idle span at the end a rest is judged after, s: the 0.5 s the rest metrics read, after
/// a fall from the top of the generator's tallest map (10 tiles at 30 tiles/s², 0.82 s) or a
/// jump's rise and fall (3 tiles, 0.9 s).
const SETTLE_TIME: f32 = 1.5;

/// How long the scenario ends with no button held, s.
fn idle_end(spec: &ScenarioSpec) -> f32 {
    let script = crate::scenario::input_script(spec);
    let idle = crate::motion::Input::default();
    let last = script.rposition(|i| *i != idle);
    let steps = script.len() - last.map_or(0, |k| k + 1);
    steps as f32 * spec.dt
}

/// Whether the level holds a slope steeper than the configuration's climb limit.
fn level_has_steep(level: &Level, run: &RunConfig) -> bool {
    let limit = run.params.max_climb_angle.tan() + 1e-4;
    (0..level.height as i64).any(|j| {
        (0..level.width as i64).any(|i| match level.tile(i, j) {
            crate::level::Tile::Slope(s) => {
                let (a, b) = (s.height_at(0.0), s.height_at(1.0));
                (a - b).abs() > limit
            }
            _ => false,
        })
    })
}

/// `stuck`: the steps `stuck_frames` counts, less those commanded under a quarter of the
/// full-speed step (the velocity passing through zero as the character turns).
fn stuck(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    evaluation: &Evaluation,
) -> Option<Violation> {
    let trace = &evaluation.trace;
    crate::metrics::with_context(level, spec, run, trace, |ctx| {
        let full = ctx.params.run_speed as f64 * spec.dt as f64;
        let script = crate::scenario::input_script(ctx.spec);
        let commanded = crate::metrics::commanded_steps(
            ctx.params,
            script.iter(),
            ctx.spec.velocity.x,
            spec.dt,
        );
        let rows = Frames::new(&trace.rows);
        let mut count = 0u32;
        let mut first = None;
        for (k, (stuck, step)) in crate::metrics::seams::stuck_steps(ctx, rows)
            .zip(commanded)
            .enumerate()
        {
            let before = rows.at(k);
            // Turning: the controller still moving the other way on this step or the one
            // before (its velocity passing through zero), which the reference's friction (applied in the air too) can
            // put a few frames off.
            let prev = rows.at(k.saturating_sub(1));
            let turning = (before.vx as f64) * step < 0.0 || (prev.vx as f64) * step < 0.0;
            // On a moving platform the step is the walk plus the carry (a walk against the
            // platform stands still in the level): `stuck` judges walks on the level's own
            // ground.
            let riding = before.platform.is_some() || rows.at(k + 1).platform.is_some();
            if stuck
                && step.abs() >= MEANINGFUL_STEP * full
                && !turning
                && !riding
                && !blocked_ahead(ctx.level, &before, step, ctx.spec.size)
            {
                count += 1;
                first = first.or(Some(rows.at(k + 1).frame));
            }
        }
        (count > 0).then(|| Violation {
            invariant: "stuck",
            metric: "stuck_frames".into(),
            value: count as f64,
            bound: 0.0,
            frame: first,
            detail: String::new(),
        })
    })
}

/// Whether something `stuck_frames` does not read (it reads solid tiles and too-steep ramps)
/// blocks the box moved by `step` above the floor band: a sloped tile rising there (a
/// height-array step or a ramp's side too high to walk up) or a moving platform's box.
fn blocked_ahead(
    level: &Level,
    before: &crate::trace::TraceRow,
    step: f64,
    size: glam::Vec2,
) -> bool {
    let feet = glam::Vec2::new(before.x + step as f32, before.y);
    let b = crate::level::character_box(feet, size);
    let floor = b.mins.y + 0.05;
    let slope = (b.mins.y.floor() as i64..b.maxs.y.ceil() as i64).any(|j| {
        (b.mins.x.floor() as i64..b.maxs.x.ceil() as i64).any(|i| match level.tile(i, j) {
            crate::level::Tile::Slope(sl) => {
                let u0 = (b.mins.x - i as f32).clamp(0.0, 1.0);
                let u1 = (b.maxs.x - i as f32).clamp(0.0, 1.0);
                let top = (0..=8)
                    .map(|n| sl.height_at(u0 + (u1 - u0) * n as f32 / 8.0))
                    .fold(0.0f32, f32::max);
                j as f32 + top > floor
            }
            _ => false,
        })
    });
    let platform = level.platforms.iter().any(|p| {
        // Where it is over the step (the row's time and the next), grown by a step's travel.
        [0.0, 1.0 / 60.0].iter().any(|dt| {
            let q = p.aabb(before.t as f64 + dt);
            q.mins.x < b.maxs.x + 0.1
                && q.maxs.x > b.mins.x - 0.1
                && q.mins.y < b.maxs.y
                && q.maxs.y > floor
        })
    });
    slope || platform
}

/// Grounded steps in a row rising over a too-steep slope that make a climb past the limit
/// (fewer can be the step onto the ramp's foot or a snap onto its corner).
const CLIMB_STEPS: u32 = 3;

/// `climb`: [`CLIMB_STEPS`] grounded steps in a row, with no jump held, each raising the feet
/// while the surface under the character's centre is a slope tile steeper than the
/// configuration's climb limit (a line ramp; height arrays are stairs).
fn climb(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    evaluation: &Evaluation,
) -> Option<Violation> {
    if run.backend.capabilities().no_climb_limit {
        return None;
    }
    let limit = run.params.max_climb_angle.tan() + 1e-4;
    let script = crate::scenario::input_script(spec);
    let rows = &evaluation.trace.rows;
    let mut run_len = 0u32;
    for k in 1..rows.len() {
        let (a, b) = (&rows[k - 1], &rows[k]);
        let steep = level
            .surface_at(b.x, b.y + 0.5, 1.0)
            .and_then(|(_, tile)| tile)
            .is_some_and(|(i, j)| match level.tile(i, j) {
                // A ramp's line, unclamped (a 63.4-degree ramp spans two tiles); height
                // arrays are stairs the seed walks by design.
                crate::level::Tile::Slope(crate::level::Slope::Line { left, right }) => {
                    (right - left).abs() > limit
                }
                _ => false,
            });
        let jumping = script.get(k - 1).is_some_and(|i| i.jump);
        // Carried up by a platform over the ramp is not climbing it.
        let carried = a.platform.is_some() || b.platform.is_some();
        if steep && !jumping && !carried && a.is_grounded() && b.is_grounded() && b.y > a.y + 1e-3 {
            run_len += 1;
            if run_len >= CLIMB_STEPS {
                return Some(Violation {
                    invariant: "climb",
                    metric: String::new(),
                    value: run_len as f64,
                    bound: (CLIMB_STEPS - 1) as f64,
                    frame: Some(b.frame),
                    detail: String::new(),
                });
            }
        } else {
            run_len = 0;
        }
    }
    None
}

/// `carry`: a rider airborne over its ride, or drifting on it beyond the lag of a controller
/// that carries with the platform's velocity of the step before (twice the platform's largest
/// step; stress's allowance) plus a pixel.
fn carry(
    level: &Level,
    spec: &ScenarioSpec,
    run: &RunConfig,
    evaluation: &Evaluation,
) -> Option<Violation> {
    if run.backend.capabilities().no_rider_carry {
        // Its own design carries no rider: not a promise it breaks.
        return None;
    }
    let ride = spec.ride? as usize;
    let p = level.platforms.get(ride)?;
    if !ride_is_clear(level, spec, ride) {
        return None;
    }
    let rows = &evaluation.trace.rows;
    // Judged from the first row it stands on the platform: a rider spawned on a platform
    // already moving down has no contact yet, and no controller can know of it before.
    let Some(settled) = rows
        .iter()
        .position(|r| r.is_grounded() && r.platform == Some(ride as u32))
    else {
        return Some(Violation {
            invariant: "carry",
            metric: "carry_airborne_frames".into(),
            value: rows.len() as f64,
            bound: 0.0,
            frame: rows.first().map(|r| r.frame),
            detail: String::new(),
        });
    };
    if let Some(r) = rows[settled..].iter().find(|r| !r.is_grounded()) {
        let airborne = rows[settled..].iter().filter(|r| !r.is_grounded()).count();
        return Some(Violation {
            invariant: "carry",
            metric: "carry_airborne_frames".into(),
            value: airborne as f64,
            bound: 0.0,
            frame: Some(r.frame),
            detail: String::new(),
        });
    }
    let grid = run
        .backend
        .declared_contact(spec.size, run.params.max_climb_angle)
        .surface_grid;
    let placing = (grid, run.backend.precision());
    let (drift, lag) = crate::stress::carry_drift(
        p,
        level.origin,
        placing,
        &evaluation.trace,
        spec.dt,
        settled,
    );
    let bound = lag + PIXEL;
    (drift > bound).then(|| Violation {
        invariant: "carry",
        metric: "carry_drift".into(),
        value: drift,
        bound,
        frame: evaluation
            .metrics
            .iter()
            .find(|r| r.metric == "carry_drift")
            .and_then(|r| r.frame),
        detail: String::new(),
    })
}

/// Whether nothing can push a rider off platform `ride`: no tile in the box its platform
/// sweeps, grown upward by the rider's height and half a tile, and no other platform's box
/// reaching into it (what makes a platform one its rider can follow; the generator keeps a
/// ride's path clear, and a shrunk case that is not clear is not judged on `carry`).
fn ride_is_clear(level: &Level, spec: &ScenarioSpec, ride: usize) -> bool {
    let (lo, mut hi) = level.platforms[ride].reach();
    hi.y += spec.size.y as f64 + 0.5;
    let cells_clear = (lo.y.floor() as i64..hi.y.ceil() as i64).all(|j| {
        (lo.x.floor() as i64..hi.x.ceil() as i64)
            .all(|i| level.tile(i, j) == crate::level::Tile::Empty)
    });
    let platforms_clear = level.platforms.iter().enumerate().all(|(k, q)| {
        let (qlo, qhi) = q.reach();
        k == ride || qlo.x >= hi.x || qhi.x <= lo.x || qlo.y >= hi.y || qhi.y <= lo.y
    });
    cells_clear && platforms_clear
}
