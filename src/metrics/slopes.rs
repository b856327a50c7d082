//! Slopes: staying grounded walking down, the gap to the surface, the speed along it, and the
//! climb limit.

use super::ground::Ground;
use super::{commanded_distance, pos, Context, Measure, Peak};
use crate::scenario::input_script;
use crate::trace::Frames;

/// Columns holding a slope that rises in direction `dir` (+1 right, -1 left) more steeply than
/// the climb limit somewhere in the tile.
pub(super) fn steep_columns<'a>(ctx: &'a Context, dir: f32) -> impl Iterator<Item = i64> + 'a {
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
/// feet to one tile below) is a slope no steeper than the climb limit: read from the row when
/// asked, so nothing is kept per frame.
pub(super) struct SlopeFrames<'a> {
    ctx: &'a Context<'a>,
    rows: Frames<'a>,
    limit: f32,
}

impl<'a> SlopeFrames<'a> {
    /// The slope frames of `rows`.
    pub(super) fn new(ctx: &'a Context<'a>, rows: Frames<'a>) -> Self {
        SlopeFrames {
            ctx,
            rows,
            limit: ctx.params.max_climb_angle.tan() + 1e-3,
        }
    }

    /// Whether row `k` stands over a walkable slope.
    pub(super) fn get(&self, k: usize) -> bool {
        self.on(&self.rows.at(k))
    }

    fn on(&self, r: &crate::trace::TraceRow) -> bool {
        match self.ctx.level.surface_at(r.x, r.y + 0.5, 1.5) {
            Some((_, Some((i, j)))) => {
                let n = self.ctx.level.slope_normal(i, j, r.x);
                (n.x / n.y).abs() <= self.limit
            }
            _ => false,
        }
    }

    /// Each row with whether it stands over a walkable slope, in order.
    pub(super) fn rows(&self) -> impl Iterator<Item = (crate::trace::TraceRow, bool)> + '_ {
        self.rows.iter().map(|r| (r, self.on(&r)))
    }
}

/// Whether the scenario walks (a direction held at some point) and never jumps.
pub(super) fn walks_without_jumping(script: &crate::scenario::Script) -> bool {
    script.iter().any(|i| i.horizontal() != 0.0) && !script.iter().any(|i| i.jump)
}

/// Whether the scenario's walk, as commanded, crosses a column holding a slope no steeper than
/// the climb limit: the slope metrics then apply, whatever the controller does.
pub(super) fn walks_over_slopes(ctx: &Context) -> bool {
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
/// Frame: the first such frame (`None` if there is none).
pub(super) fn slope_airborne_frames(
    ctx: &Context,
    rows: Frames,
    on: &SlopeFrames,
) -> Option<Measure> {
    if !walks_over_slopes(ctx) {
        return None;
    }
    let script = input_script(ctx.spec);
    let (count, first) = super::landing::first_and_count(
        (1..rows.len())
            .filter(|&k| {
                on.get(k) && script[k - 1].horizontal() != 0.0 && !rows.at(k).is_grounded()
            })
            .map(|k| rows.at(k).frame),
    );
    Some(Measure {
        metric: "slope_airborne_frames",
        value: count as f64,
        reference: 0.0,
        frame: first,
    })
}

/// `slope_gap_max`: over the frames reported grounded over a walkable slope, the signed gap
/// between the character's shape and the level's surface that is farthest from touching, in
/// tiles: positive a gap above the surface, negative the depth inside it (the seed's box
/// overhanging a ramp reads as inside it). 0 if it never stood on one.
///
/// Frame: the first of those frames at that gap (`None` if it never stood on one).
pub(super) fn slope_gap_max(ctx: &Context, g: &Ground, on: &SlopeFrames) -> Option<Measure> {
    if !(walks_over_slopes(ctx) || rest_on_slope(ctx)) {
        return None;
    }
    let (mut worst, mut frame) = (0.0f32, None);
    for (r, _) in on.rows().filter(|(r, o)| *o && r.is_grounded()) {
        let b = g.gap(pos(&r));
        if frame.is_none() || b.abs() > worst.abs() {
            frame = Some(r.frame);
        }
        if b.abs() > worst.abs() {
            worst = b;
        }
    }
    Some(Measure {
        metric: "slope_gap_max",
        value: worst as f64,
        reference: 0.0,
        frame,
    })
}

/// How long after the last airborne frame a landing's grounded frames are left out of
/// `slope_gap_declared`, in seconds: three frames at 60 Hz, the snap a controller that lands
/// within its ground prediction takes to close the gap.
pub(crate) const LANDING_SETTLE: f32 = 0.05;

/// `slope_gap_declared`: over the frames reported grounded over a walkable slope, the signed
/// gap less the gap of the stance the configuration declares there (as `rest_gap_declared`
/// judges a rest, vertically), the one farthest from the promise, in tiles: 0 where it stands as
/// it declares, positive hovering above that, negative sunk below it. Every frame counts: a
/// hover of one frame is seen (Rapier's snap-to-ground acts only on a step that does not move
/// up, so the step that carries it over a convex corner of the ground can leave it above the
/// surface until the next step; that is not its declared `offset`). A landing's first frames
/// ([`LANDING_SETTLE`]) are left out (land_frame_error's business). `slope_gap_max` measures
/// against touching; this is the promise, and it is scored (a controller hovering over a ramp
/// while it walks would otherwise be seen only at rest).
///
/// Frame: the first of the frames judged at that value (`None` if no frame was judged).
pub(super) fn slope_gap_declared(ctx: &Context, g: &Ground, on: &SlopeFrames) -> Option<Measure> {
    if !(walks_over_slopes(ctx) || rest_on_slope(ctx)) {
        return None;
    }
    // Frames within LANDING_SETTLE of the last airborne frame are left out.
    let settle = (LANDING_SETTLE / ctx.spec.dt).ceil() as usize;
    let mut since_air = usize::MAX;
    let (mut worst, mut frame) = (0.0f64, None);
    for (r, o) in on.rows() {
        since_air = if r.is_grounded() {
            since_air.saturating_add(1)
        } else {
            0
        };
        if !o || !r.is_grounded() || since_air <= settle {
            continue;
        }
        let b = super::landing::gap_beyond_declared(ctx, g, pos(&r), g.gap(pos(&r)) as f64);
        if frame.is_none() || b.abs() > worst.abs() {
            frame = Some(r.frame);
        }
        if b.abs() > worst.abs() {
            worst = b;
        }
    }
    Some(Measure {
        metric: "slope_gap_declared",
        value: worst,
        reference: 0.0,
        frame,
    })
}

/// `slope_overlap`: on a level with slopes, the deepest overlap of the character's shape with a
/// slope tile's solid part over the run, in tiles (parry's penetration depth). The seed's
/// centre-column rule stands the sweep's box on a slope by the surface under its centre, so its
/// box overhangs the ramp by up to half its width times the gradient (0.4 tiles vertically on a
/// 45-degree ramp for a 0.8-wide box, 0.28 along the ramp's normal): this is that overlap, by
/// design, reported as what it is.
///
/// Frame: the first frame at the deepest overlap.
pub fn slope_overlap(ctx: &Context, g: &Ground, rows: Frames) -> Option<Measure> {
    if !ctx.level.features.slopes {
        return None;
    }
    let mut worst = Peak::new(0.0);
    for r in rows.iter() {
        worst.push(r.frame, g.slope_penetration(pos(&r)));
    }
    Some(Measure {
        metric: "slope_overlap",
        value: worst.value as f64,
        reference: 0.0,
        frame: worst.frame,
    })
}

/// Whether the scenario drops the character onto a slope and leaves it there (no input).
pub(super) fn rest_on_slope(ctx: &Context) -> bool {
    input_script(ctx.spec)
        .iter()
        .all(|i| *i == crate::motion::Input::default())
        && matches!(
            ctx.level
                .surface_at(ctx.spec.spawn.x, ctx.spec.spawn.y, ctx.spec.spawn.y),
            Some((_, Some(_)))
        )
}

/// The speed over a walkable slope against two models, each over the run speed (the speed the
/// same input gives on flat ground), as the mean over the steps walked over a slope at full
/// commanded speed:
///
/// - `slope_speed_ratio`: the horizontal speed, against constant horizontal speed (the seed:
///   the box moves along x at run speed and its height follows the surface);
/// - `slope_surface_speed_ratio`: the speed along the path (x and y), against constant speed
///   along the surface (Godot's `floor_constant_speed`).
///
/// A controller is not wrong for following either model: the report shows both. 0 if it never
/// walked the slope at full speed.
///
/// Frame: for each, the frame ending the measured step whose speed is farthest from the run
/// speed (the first such; `None` if no step was measured): where the mean is best shown off.
pub(super) fn slope_speed_ratios(
    ctx: &Context,
    rows: Frames,
    on: &SlopeFrames,
) -> [Option<Measure>; 2] {
    // A walk into a too-steep rise is steep_blocked's business, not a speed.
    if !walks_over_slopes(ctx) || steep_ahead(ctx) {
        return [None, None];
    }
    let script = input_script(ctx.spec);
    // Steps at full commanded speed: the same direction held since the ramp-up ended.
    let ramp = (ctx.params.run_speed / (ctx.params.run_accel * ctx.spec.dt)).ceil() as usize + 1;
    // Read twice (a count, then each sum), not collected: a soak run has millions of them.
    let steps = || {
        (1..rows.len()).filter(|&k| {
            let dir = script[k - 1].horizontal();
            dir != 0.0
                && on.get(k)
                && on.get(k - 1)
                && k > ramp
                && script.range(k - 1 - ramp..k).all(|i| i.horizontal() == dir)
        })
    };
    let count = steps().count();
    let dt = ctx.spec.dt as f64;
    let mean = |speed: &dyn Fn(usize) -> f64| {
        if count == 0 {
            0.0
        } else {
            steps().map(speed).sum::<f64>() / count as f64
        }
    };
    let horizontal_at = |k: usize| ((rows.at(k).x - rows.at(k - 1).x) as f64 / dt).abs();
    let along_at = |k: usize| (pos(&rows.at(k)) - pos(&rows.at(k - 1))).length() as f64 / dt;
    let horizontal = mean(&horizontal_at);
    let along = mean(&along_at);
    let run = ctx.params.run_speed as f64;
    // The step farthest from the run speed in each model, a third pass over the steps.
    let (mut h_worst, mut a_worst) = ((-1.0f64, None), (-1.0f64, None));
    for k in steps() {
        let frame = Some(rows.at(k).frame);
        let (h, a) = ((horizontal_at(k) - run).abs(), (along_at(k) - run).abs());
        if h > h_worst.0 {
            h_worst = (h, frame);
        }
        if a > a_worst.0 {
            a_worst = (a, frame);
        }
    }
    [
        Some(Measure {
            metric: "slope_speed_ratio",
            value: horizontal / run,
            reference: 1.0,
            frame: h_worst.1,
        }),
        Some(Measure {
            metric: "slope_surface_speed_ratio",
            value: along / run,
            reference: 1.0,
            frame: a_worst.1,
        }),
    ]
}

/// Whether the commanded walk reaches a slope rising more steeply than the climb limit.
pub(super) fn steep_ahead(ctx: &Context) -> bool {
    let script = input_script(ctx.spec);
    let d = commanded_distance(ctx.params, &script, ctx.spec.velocity.x, ctx.spec.dt) as f32;
    let (a, b) = (ctx.spec.spawn.x, ctx.spec.spawn.x + d);
    let (x0, x1) = (a.min(b), a.max(b));
    steep_columns(ctx, d.signum()).any(|i| (i as f32) < x1 && (i as f32 + 1.0) > x0)
}

/// `steep_blocked`: for a walk toward a slope that rises more steeply than the climb limit, 1 if
/// the character never got half a tile above where it started, else 0.
///
/// Frame: the first frame at the highest the feet got (where the climb stopped, or got over).
pub fn steep_blocked(ctx: &Context, rows: Frames) -> Option<Measure> {
    let script = input_script(ctx.spec);
    if !walks_without_jumping(&script) {
        return None;
    }
    if !steep_ahead(ctx) {
        return None;
    }
    let mut top = Peak::new(f32::NEG_INFINITY);
    for r in rows.iter() {
        top.push(r.frame, r.y);
    }
    Some(Measure {
        metric: "steep_blocked",
        value: (top.value < ctx.spec.spawn.y + 0.5) as u8 as f64,
        reference: 1.0,
        frame: top.frame,
    })
}
