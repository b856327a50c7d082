//! Running the stress matrix: its independent points, their fan-out over threads, each point's
//! probes run and measured, and the rows they become.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::backend::Precision;
use crate::config::RunConfig;
use crate::level::{Platform, ScenarioSpec};
use crate::metrics::seams::STUCK_FRACTION;
use crate::metrics::{commanded_steps, evaluate_with, MetricRow};
use crate::scenario::RunError;
use crate::scenario::{effective_params, input_script, Runner};

use super::definition::{
    dimensions, pairs, Case, BASE, F32_OFFSET_LIMIT, JUMP_TOLERANCE, PROGRESS_BAND,
};
use super::probes::{probe_level, probes};

/// One checked invariant.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StressRow {
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// Dimension name.
    pub dimension: String,
    /// Its value.
    pub value: f64,
    /// The second dimension of a combination cell (empty on a one-dimension row).
    #[serde(default)]
    pub dimension2: String,
    /// Its value (empty on a one-dimension row).
    #[serde(default)]
    pub value2: Option<f64>,
    /// The invariant.
    pub invariant: String,
    /// Whether it held on every probe.
    pub holds: bool,
    /// The worst measured value over the probes (for `finite`, 0 or 1).
    pub measured: f64,
    /// The tolerance it was held to: an upper bound on `measured`, except for `progress`,
    /// where it is how far the fraction of the commanded distance covered may be from 1, either
    /// way ([`PROGRESS_BAND`]).
    pub tolerance: f64,
}

/// How far a rider moved on its platform, and the lag a carry may show without drifting, in tiles.
///
/// The drift is the largest change of the rider's position relative to the platform from row
/// `from` on (stress: the first step, since the spawn row has no contact yet). A controller that carries its rider with the
/// platform's velocity of the step before (Rapier's controller does) trails by the difference of
/// two steps' displacements, which sums to at most twice the platform's largest displacement in
/// one step, however long the ride: that is the allowance returned, computed from the platform's
/// motion over the run (as the backends place it, so far from the origin a step is a multiple of
/// the spacing of the configuration's `precision`). More than the allowance (plus a rest's
/// tolerance) is a rider that slips, bounces or falls off. A configuration on a subpixel grid of
/// `grid` subpixels per tile (0 for none) moves the platform along its path rounded to that
/// grid, in level coordinates whatever the offset; the drift is measured against that platform,
/// the one it moves.
pub(crate) fn carry_drift(
    p: &Platform,
    origin: glam::DVec2,
    (grid, precision): (u32, Precision),
    trace: &crate::trace::Trace,
    dt: f32,
    from: usize,
) -> (f64, f64) {
    // The platform where the backends put it: placed in the world in the configuration's
    // precision (in f32 at 1e6 tiles from the origin, on a grid of 1/16 tile) and brought back
    // to level coordinates, as the trace is; or on the subpixel grid.
    let at = |k: usize| {
        let t = k as f64 * dt as f64;
        if grid > 0 {
            p.placed_aabb(t, grid).mins.as_dvec2()
        } else {
            precision.placed(p.position(t).as_dvec2(), origin)
        }
    };
    let rel = |k: usize| {
        let r = &trace.rows[k];
        glam::DVec2::new(r.x as f64, r.y as f64) - at(k)
    };
    let n = trace.rows.len();
    if n < 2 || from >= n {
        return (0.0, 0.0);
    }
    let first = rel(from);
    let drift = (from..n)
        .map(|k| (rel(k) - first).length())
        .fold(
            0.0,
            |a: f64, d| if d.is_nan() { f64::INFINITY } else { a.max(d) },
        );
    let step = (1..n)
        .map(|k| (at(k) - at(k - 1)).length())
        .fold(0.0, f64::max);
    (drift, 2.0 * step)
}

/// The penetration a backend is held to: the sweep's epsilon, none on integer positions (they
/// snap exactly and have no epsilon), Rapier's offset (1% of the character's height) - each
/// controller's own contact tolerance.
fn penetration_tolerance(run: &RunConfig, size: Vec2) -> f64 {
    run.backend.contact_tolerance(size)
}

/// One independent run of the matrix: a configuration at one case, labelled by the dimension
/// (or pair of dimensions) varied.
#[derive(Clone, Debug)]
pub struct Point {
    /// The configuration, its epsilon set to the case's where it has one.
    pub run: RunConfig,
    /// The case.
    pub case: Case,
    /// The dimension varied and its value.
    pub dimension: (&'static str, f64),
    /// The second dimension of a combination cell and its value.
    pub dimension2: Option<(&'static str, f64)>,
}

/// The configuration at `case`: with the case's epsilon if it has an overlap tolerance and
/// `epsilon_varied`; `None` when the epsilon is varied on a configuration without one.
fn configured(run: &RunConfig, case: &Case, epsilon_varied: bool) -> Option<RunConfig> {
    if !epsilon_varied {
        return Some(run.clone());
    }
    let b = run
        .backend
        .epsilon()
        .and(run.backend.with_epsilon(case.epsilon))?;
    Some(RunConfig {
        backend: b,
        ..run.clone()
    })
}

/// Every point of the matrix for `runs`, in the order their rows are written: each dimension
/// alone, value by value, then each pair of [`pairs`] cell by cell, the f32 configurations on
/// their grid and then the f64 ones on theirs; within a value or cell, `runs` in order. The
/// epsilon is varied only on configurations that have one, and offsets past
/// [`F32_OFFSET_LIMIT`] only on f64 configurations.
pub fn points(runs: &[RunConfig]) -> Vec<Point> {
    points_with(runs, None)
}

/// [`points`] with every probe outside the dt dimension (and its pairs) stepped by `dt`
/// seconds instead of [`BASE`]'s 1/60 s, when given.
pub fn points_with(runs: &[RunConfig], dt: Option<f32>) -> Vec<Point> {
    let base = Case {
        dt: dt.unwrap_or(BASE.dt),
        ..BASE
    };
    let mut out = Vec::new();
    for d in dimensions() {
        for &v in &d.values {
            let case = base.with(d.name, v);
            let far = d.name == "offset" && v > F32_OFFSET_LIMIT;
            for base in runs {
                if far && base.backend.precision() == Precision::F32 {
                    continue;
                }
                if let Some(run) = configured(base, &case, d.name == "epsilon") {
                    out.push(Point {
                        run,
                        case,
                        dimension: (d.name, v),
                        dimension2: None,
                    });
                }
            }
        }
    }
    // Pair by pair, each precision's grid in turn (f32 first), so that a pair's cells stay
    // together whatever the precision.
    let by_precision = [Precision::F32, Precision::F64].map(|p| (p, pairs(p)));
    for k in 0..by_precision[0].1.len() {
        for (precision, grids) in &by_precision {
            let (a, b) = &grids[k];
            for &va in &a.values {
                for &vb in &b.values {
                    let case = base.with(a.name, va).with(b.name, vb);
                    let eps = a.name == "epsilon" || b.name == "epsilon";
                    for base in runs.iter().filter(|r| r.backend.precision() == *precision) {
                        if let Some(run) = configured(base, &case, eps) {
                            out.push(Point {
                                run,
                                case,
                                dimension: (a.name, va),
                                dimension2: Some((b.name, vb)),
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// Runs the matrix for `runs` on every core ([`stress_matrix_on`]).
pub fn stress_matrix(
    runs: &[RunConfig],
    progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, RunError> {
    stress_matrix_on(runs, crate::parallel::default_jobs(), progress)
}

/// Runs the matrix for `runs` on `jobs` threads: builds [`points`], runs each with
/// [`run_point`] (the points are independent and fan out) and collects their rows in matrix
/// order whatever the threads. `progress` hears each new dimension value or combination cell.
pub fn stress_matrix_on(
    runs: &[RunConfig],
    jobs: usize,
    progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, RunError> {
    stress_matrix_with(runs, None, jobs, progress)
}

/// [`stress_matrix_on`] with the base time step `dt` (seconds; [`BASE`]'s 1/60 s when `None`)
/// for every probe outside the dt dimension ([`points_with`]).
pub fn stress_matrix_with(
    runs: &[RunConfig],
    dt: Option<f32>,
    jobs: usize,
    progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, RunError> {
    let mut first = None;
    let rows = stress_matrix_reporting(runs, dt, jobs, progress, |e| {
        first.get_or_insert_with(|| e.clone());
    })?;
    first.map_or(Ok(rows), Err)
}

/// [`stress_matrix_with`] that goes on past a run that failed ([`RunError::is_failure`]: an
/// external controller that crashed, hung or answered out of protocol): `on_failure` hears each,
/// its point gives no rows, and the other points complete. Other errors end the matrix.
pub fn stress_matrix_reporting(
    runs: &[RunConfig],
    dt: Option<f32>,
    jobs: usize,
    mut progress: impl FnMut(&str),
    mut on_failure: impl FnMut(&RunError),
) -> Result<Vec<StressRow>, RunError> {
    let points = points_with(runs, dt);
    let mut out = Vec::new();
    let mut last = String::new();
    crate::parallel::for_each_ordered(
        jobs,
        points.len(),
        || (),
        |_, i| run_point(&points[i]),
        |i, rows| {
            let what = points[i].label();
            if what != last {
                progress(&what);
                last = what;
            }
            match rows {
                Ok(rows) => out.extend(rows),
                Err(e) if e.is_failure() => on_failure(&e),
                Err(e) => return Err(e),
            }
            Ok::<(), RunError>(())
        },
    )?;
    Ok(out)
}

impl Point {
    /// `offset = 1e5`, or `offset = 1e5, dt = 0.0001` for a combination cell.
    pub fn label(&self) -> String {
        let (d, v) = self.dimension;
        match self.dimension2 {
            None => format!("{d} = {v}"),
            Some((d2, v2)) => format!("{d} = {v}, {d2} = {v2}"),
        }
    }
}

/// The outcomes of one point's probes, before they become rows.
#[derive(Default)]
struct Outcome {
    finite: bool,
    pen: f64,
    tunnel: f64,
    jitter: f64,
    flicker: f64,
    /// The carry's worst drift and its allowance (`None`: no moving platforms modelled).
    carry: Option<(f64, f64)>,
    progress: f64,
    stuck: f64,
    jump: f64,
}

/// Runs one point's probes and returns its rows, one per invariant (no `carry_no_drift` row
/// for a configuration that does not model moving platforms).
pub fn run_point(point: &Point) -> Result<Vec<StressRow>, RunError> {
    let run = &point.run;
    let case = point.case;
    let size = Vec2::new(case.width, case.width * 1.125);
    let level = probe_level(case.offset, false);
    let ride_level = probe_level(case.offset, true);
    let mut runner = Runner::new(&level);
    let mut ride_runner = Runner::new(&ride_level);
    let tol_pen = penetration_tolerance(run, size);
    let tol_rest = 1e-3 * size.y as f64;
    let grid = run
        .backend
        .declared_contact(size, run.params.max_climb_angle)
        .surface_grid;
    let mut o = Outcome {
        finite: true,
        progress: f64::NAN,
        jump: f64::NAN,
        ..Default::default()
    };
    let mut carry_modelled = true;
    let (mut drift, mut drift_tol) = (0.0f64, 0.0f64);
    for spec in probes(size, case.dt, case.speed) {
        let e = if spec.ride.is_some() {
            match evaluate_with(&mut ride_runner, &spec, run) {
                Err(e) if e.is_unsupported() => {
                    // No moving platforms in this configuration: no carry row.
                    carry_modelled = false;
                    continue;
                }
                e => e?,
            }
        } else {
            match evaluate_with(&mut runner, &spec, run) {
                // The backend refuses the probe level itself (Box2D's f32 geometry far from
                // the origin): the point is not measured, so it has no rows.
                Err(e) if e.is_unsupported() => return Ok(Vec::new()),
                e => e?,
            }
        };
        let get = |m: &str| -> Option<f64> {
            e.metrics
                .iter()
                .find(|r: &&MetricRow| r.metric == m)
                .map(|r| r.value)
        };
        o.finite &= e
            .trace
            .rows
            .iter()
            .all(|r| [r.x, r.y, r.vx, r.vy].iter().all(|v| v.is_finite()));
        if let Some(p) = spec.ride.and_then(|i| ride_level.platforms.get(i as usize)) {
            // A ride feeds only its own invariant (and `finite`): the others keep the meaning
            // they have on the static floor.
            let placing = (grid, run.backend.precision());
            let (d, lag) = carry_drift(p, ride_level.origin, placing, &e.trace, case.dt, 1);
            let tol = lag + tol_rest;
            if drift_tol == 0.0 || d - tol > drift - drift_tol {
                (drift, drift_tol) = (d, tol);
            }
            continue;
        }
        if spec.name == "jump" {
            // The jump feeds only its height: its landing is the drop's business. A jump the
            // metric cannot measure (no take-off found) counts as missed.
            o.jump = get("apex_error").map_or(f64::INFINITY, f64::abs);
            continue;
        }
        o.pen = o.pen.max(get("max_penetration").unwrap_or(0.0));
        o.tunnel = o.tunnel.max(get("tunneled").unwrap_or(0.0));
        if spec.name == "drop" {
            // At rest: the height range over the last half second (the landing and its
            // settling are land_frame_error's business).
            let last = (0.5 / case.dt).ceil() as usize;
            let tail = &e.trace.rows[e.trace.rows.len().saturating_sub(last)..];
            let (lo, hi) = tail.iter().fold((f32::MAX, f32::MIN), |(lo, hi), r| {
                (lo.min(r.y), hi.max(r.y))
            });
            o.jitter = o.jitter.max((hi - lo) as f64);
        }
        if spec.name == "walk" {
            // The walk's floor is flat and open, so progress_ratio applies; a walk it does not
            // measure counts as no progress.
            o.progress = get("progress_ratio").unwrap_or(0.0);
            o.stuck = stuck_steps(run, &spec, &e.trace, case.offset);
        }
        o.flicker = o.flicker.max(get("grounded_flicker").unwrap_or(0.0));
    }
    if carry_modelled {
        o.carry = Some((drift, drift_tol));
    }
    Ok(rows_of(point, &o, tol_pen, tol_rest))
}

/// The smallest move a stored position can make at world coordinate `x` (tiles): the spacing
/// of the configuration's `precision` there, or one subpixel where the configuration keeps
/// positions on a grid.
fn storage_unit(x: f64, per_tile: u32, precision: Precision) -> f64 {
    let spacing = precision.spacing(x);
    match per_tile {
        0 => spacing,
        n => spacing.max(1.0 / n as f64),
    }
}

/// Stuck steps of the walk over its flat, open floor: grounded steps commanded to move at least
/// one storage unit ([`storage_unit`] at the character's world position, and at least the f32
/// spacing of the trace's level coordinates, the finest move a trace can show) that moved less than
/// [`crate::metrics::seams::STUCK_FRACTION`] of the commanded step. A commanded step under one
/// unit cannot move a stored position by itself (an integer mode carries the fraction to the
/// next step; a float loses it): that is quantization, and what it costs shows in `progress`.
fn stuck_steps(
    run: &RunConfig,
    spec: &ScenarioSpec,
    trace: &crate::trace::Trace,
    offset: f64,
) -> f64 {
    let script = input_script(spec);
    let params = effective_params(&run.params, spec);
    let commanded = commanded_steps(&params, &script, spec.velocity.x, spec.dt);
    let per_tile = run
        .backend
        .declared_contact(spec.size, params.max_climb_angle)
        .surface_grid;
    let mut count = 0u32;
    for (k, step) in commanded.enumerate() {
        let (Some(before), Some(after)) = (trace.rows.get(k), trace.rows.get(k + 1)) else {
            break;
        };
        if script[k].horizontal() == 0.0 || !after.is_grounded() {
            continue;
        }
        // The trace holds level coordinates in f32: a step under their spacing cannot be seen
        // moving, whatever the configuration stores (it only matters in f64, where the world
        // spacing is finer than the trace's).
        let x = offset + before.x as f64;
        let seen = Precision::F32.spacing(before.x as f64);
        if step.abs() < storage_unit(x, per_tile, run.backend.precision()).max(seen) {
            continue;
        }
        if (((after.x - before.x) as f64).abs()) < STUCK_FRACTION * step.abs() {
            count += 1;
        }
    }
    count as f64
}

/// The rows of one point from its probes' outcomes, in [`INVARIANTS`](super::INVARIANTS) order.
fn rows_of(point: &Point, o: &Outcome, tol_pen: f64, tol_rest: f64) -> Vec<StressRow> {
    let finite = o.finite;
    let nan_inf = |v: f64| if v.is_nan() { f64::INFINITY } else { v };
    let row = |invariant: &str, holds: bool, measured: f64, tolerance: f64| StressRow {
        backend: point.run.backend.backend().to_string(),
        config: point.run.label.clone(),
        dimension: point.dimension.0.to_string(),
        value: point.dimension.1,
        dimension2: point.dimension2.map_or(String::new(), |d| d.0.to_string()),
        value2: point.dimension2.map(|d| d.1),
        invariant: invariant.to_string(),
        holds,
        measured,
        tolerance,
    };
    let pen = nan_inf(o.pen);
    let mut out = vec![
        row("finite", finite, (!finite) as u8 as f64, 0.0),
        row("penetration", finite && pen <= tol_pen, pen, tol_pen),
        row("no_tunneling", finite && o.tunnel == 0.0, o.tunnel, 0.0),
        row(
            "stable_rest",
            finite && o.jitter <= tol_rest,
            o.jitter,
            tol_rest,
        ),
        row("no_flicker", finite && o.flicker == 0.0, o.flicker, 0.0),
    ];
    // A rider is at rest on its platform: held to the stable rest's bound plus the lag a carry
    // may show (see `carry_drift`).
    if let Some((drift, tol)) = o.carry {
        out.push(row("carry_no_drift", finite && drift <= tol, drift, tol));
    }
    // Within the band either way: short (stuck, or steps rounded down) and long (steps rounded
    // up) alike. 1 +/- PROGRESS_BAND rather than PROGRESS_MIN..PROGRESS_MAX so that the row's
    // tolerance is the one bound both sides are held to.
    let progress = if o.progress.is_nan() { 0.0 } else { o.progress };
    out.push(row(
        "progress",
        finite && (progress - 1.0).abs() <= PROGRESS_BAND,
        progress,
        PROGRESS_BAND,
    ));
    out.push(row("no_stuck", finite && o.stuck == 0.0, o.stuck, 0.0));
    let jump = nan_inf(o.jump);
    out.push(row(
        "jump_height",
        finite && jump <= JUMP_TOLERANCE,
        jump,
        JUMP_TOLERANCE,
    ));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stress::{PROGRESS_MAX, PROGRESS_MIN};

    #[test]
    fn progress_breaks_on_both_sides_of_its_band() {
        let point = Point {
            run: crate::sweep::kind::run_default(),
            case: BASE,
            dimension: ("offset", 0.0),
            dimension2: None,
        };
        let progress = |p: f64| {
            let o = Outcome {
                finite: true,
                progress: p,
                ..Default::default()
            };
            let rows = rows_of(&point, &o, 0.0, 0.0);
            rows.into_iter()
                .find(|r| r.invariant == "progress")
                .unwrap()
        };
        // 1 +/- 1%: the f32 sweep's walk 1e6 tiles out (1.248, its 0.1-tile steps rounded up to
        // 2/16) breaks as a stuck one does; a walk within 1% either way holds.
        for (p, holds) in [
            (1.0, true),
            (PROGRESS_MIN, true),
            (PROGRESS_MAX, true),
            (0.98, false),
            (1.0156, false),
            (1.248, false),
            (f64::NAN, false),
        ] {
            assert_eq!(progress(p).holds, holds, "{p}");
        }
        assert_eq!(progress(1.0).tolerance, PROGRESS_BAND);
    }

    #[test]
    fn storage_unit_is_the_f32_spacing_or_a_subpixel() {
        // 2^17 = 131072 > 1e5 >= 2^16: spacing 2^(16-23) = 1/128.
        assert_eq!(storage_unit(1e5, 0, Precision::F32), 1.0 / 128.0);
        assert_eq!(storage_unit(1e5, 32, Precision::F32), 1.0 / 32.0);
        assert_eq!(storage_unit(1e7, 32, Precision::F32), 1.0);
        // f64: 2^16 <= 1e5 < 2^17, spacing 2^(16-52).
        assert_eq!(storage_unit(1e5, 0, Precision::F64), 2f64.powi(-36));
        assert_eq!(storage_unit(1e10, 0, Precision::F64), 2f64.powi(33 - 52));
    }
}
