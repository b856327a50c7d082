//! Stability at the extremes: the invariants every controller should keep (nothing non-finite,
//! no penetration beyond its tolerance, no tunneling, a stable rest, no grounded flicker), checked
//! no penetration beyond its tolerance, no tunneling, a stable rest, no grounded flicker, carry
//! without drift), checked one dimension at a time away from a base case: far from the origin,
//! tiny and huge time steps, fast movers, tiny and huge characters, and (for the sweep) its epsilon
//! down to where it breaks (the seed: "try 0.001, and lower until unstable").

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::backend::BackendError;
use crate::level::{InputEvent, Level, Platform, PlatformMotion, ScenarioSpec, Tile};
use crate::metrics::{evaluate, MetricRow};
use crate::scenario::RunConfig;

/// One dimension of the stress matrix and the values it takes (the base case is the default
/// everywhere else).
#[derive(Clone, Debug)]
pub struct Dimension {
    /// Name, as in `stability.csv`.
    pub name: &'static str,
    /// Values, in the dimension's unit.
    pub values: Vec<f64>,
}

/// The dimensions of DESIGN.md's stress matrix.
pub fn dimensions() -> Vec<Dimension> {
    vec![
        Dimension {
            name: "offset",
            values: vec![0.0, 1e3, 1e4, 1e5, 1e6, 1e7],
        },
        Dimension {
            name: "dt",
            values: vec![1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.05, 0.2],
        },
        Dimension {
            name: "speed",
            values: vec![10.0, 100.0, 1000.0],
        },
        Dimension {
            name: "width",
            values: vec![0.01, 0.1, 0.8, 3.0, 10.0],
        },
        Dimension {
            name: "epsilon",
            values: vec![1e-1, 1e-3, 1e-5, 1e-7, 1e-9],
        },
    ]
}

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
    /// The invariant.
    pub invariant: String,
    /// Whether it held on every probe.
    pub holds: bool,
    /// The worst measured value over the probes (for `finite`, 0 or 1).
    pub measured: f64,
    /// The tolerance it was held to.
    pub tolerance: f64,
}

/// Period of the probe level's moving platforms, in seconds.
const RIDE_PERIOD: f32 = 4.0;

/// The probe level: a floor 300 tiles long with a one-tile wall at x = 250, 40 tiles high (room
/// for a 10-tile character), and for the rides (a level of their own, so that a configuration
/// without moving platforms still runs the static probes) two 12-tile platforms swaying on
/// sines of period [`RIDE_PERIOD`]: platform 0 across x = 8..28 (amplitude 4 tiles, up to 6.3 tiles/s), platform 1 up and down
/// y = 4..8 (amplitude 2 tiles, up to 3.1 tiles/s, its largest downward acceleration 4.9 tiles/s²,
/// well under gravity, so a rider can stay on). Rides along one axis at a time: on a diagonal or
/// circular path Rapier's controller loses its platform even at the base case (the built-in
/// `platforms` level measures that), which would hide every extreme behind it.
/// Merged, the floor is one 300-tile box: long enough to matter, short of the thousands of tiles
/// on which Rapier's rounded shapes sink (a separate finding).
fn probe_level(offset: f32, with_platforms: bool) -> Level {
    let (w, h) = (300u32, 40u32);
    let mut tiles = vec![Tile::Empty; (w * h) as usize];
    for i in 0..w {
        tiles[i as usize] = Tile::Solid;
    }
    for j in 1..h - 2 {
        tiles[(j * w + 250) as usize] = Tile::Solid;
    }
    let mut l = Level::from_tiles("stress", w, h, tiles);
    l.origin = Vec2::splat(offset);
    if with_platforms {
        for (x, amplitude) in [(12.0, Vec2::new(4.0, 0.0)), (30.0, Vec2::new(0.0, 2.0))] {
            l.platforms.push(Platform {
                start: Vec2::new(x, 6.0),
                size: Vec2::new(12.0, 0.5),
                motion: PlatformMotion::Sine {
                    amplitude,
                    period: RIDE_PERIOD,
                },
                one_way: false,
            });
        }
        l.features.moving_platforms = true;
    }
    l
}

/// The probes: a drop onto the floor then rest, a walk along the floor, a fast mover aimed at the
/// wall, and a rider standing on each moving platform for two of its periods and a half.
fn probes(size: Vec2, dt: f32, speed: f32) -> Vec<ScenarioSpec> {
    let spec = |name: &str, spawn: Vec2, duration: f32, inputs: Vec<InputEvent>| ScenarioSpec {
        size,
        dt,
        ..ScenarioSpec::new(name.into(), spawn, duration, inputs)
    };
    let ride = |name: &str, x: f32, platform: u32| ScenarioSpec {
        ride: Some(platform),
        ..spec(name, Vec2::new(x, 6.5), 2.5 * RIDE_PERIOD, vec![])
    };
    let right = InputEvent {
        t: 0.0,
        right: Some(true),
        ..Default::default()
    };
    let stop = InputEvent {
        t: 1.0,
        right: Some(false),
        ..Default::default()
    };
    vec![
        spec("drop", Vec2::new(50.5, 3.0), 2.0, vec![]),
        spec("walk", Vec2::new(100.5, 1.0), 2.0, vec![right, stop]),
        ScenarioSpec {
            velocity: Vec2::new(speed, 0.0),
            ..spec("fast", Vec2::new(150.5 - size.x, 1.5), 2.0, vec![])
        },
        ride("ride_across", 18.0, 0),
        ride("ride_up_down", 36.0, 1),
    ]
}

/// How far a rider moved on its platform, and the lag a carry may show without drifting, in tiles.
///
/// The drift is the largest change of the rider's position relative to the platform from the
/// first step on (the spawn row has no contact yet). A controller that carries its rider with the
/// platform's velocity of the step before (Rapier's controller does) trails by the difference of
/// two steps' displacements, which sums to at most twice the platform's largest displacement in
/// one step, however long the ride: that is the allowance returned, computed from the platform's
/// motion over the run (as the backends place it, so far from the origin a step is a multiple of
/// the f32 spacing). More than the allowance (plus a rest's tolerance) is a rider that slips,
/// bounces or falls off. A configuration on a subpixel grid of `grid` subpixels per tile (0 for
/// none) moves the platform along its path rounded to that grid, in level coordinates whatever
/// the offset; the drift is measured against that platform, the one it moves.
fn carry_drift(
    p: &Platform,
    origin: Vec2,
    grid: u32,
    trace: &crate::trace::Trace,
    dt: f32,
) -> (f64, f64) {
    // The platform where the backends put it: placed in the world in f32 (at 1e6 tiles from the
    // origin, on a grid of 1/16 tile) and brought back to level coordinates, as the trace is;
    // or on the subpixel grid.
    let at = |k: usize| {
        let t = k as f64 * dt as f64;
        if grid > 0 {
            p.placed_aabb(t, grid).mins.as_dvec2()
        } else {
            ((p.position(t) + origin) - origin).as_dvec2()
        }
    };
    let rel = |k: usize| {
        let r = &trace.rows[k];
        glam::DVec2::new(r.x as f64, r.y as f64) - at(k)
    };
    let n = trace.rows.len();
    if n < 2 {
        return (0.0, 0.0);
    }
    let first = rel(1);
    let drift = (1..n)
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

/// Runs the matrix for `runs` (the epsilon dimension only on sweep configurations), on every
/// core ([`stress_matrix_on`]).
pub fn stress_matrix(
    runs: &[RunConfig],
    progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, BackendError> {
    stress_matrix_on(runs, crate::parallel::default_jobs(), progress)
}

/// [`stress_matrix`] on `jobs` threads: each (dimension, value, configuration) cell is
/// independent and they fan out; the rows come back in matrix order whatever the threads.
pub fn stress_matrix_on(
    runs: &[RunConfig],
    jobs: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, BackendError> {
    let dims = dimensions();
    let mut cells = Vec::new();
    for (di, d) in dims.iter().enumerate() {
        for (vi, &v) in d.values.iter().enumerate() {
            for base in runs {
                cells.push((di, vi, v, base));
            }
        }
    }
    let mut out = Vec::new();
    crate::parallel::for_each_ordered(
        jobs,
        cells.len(),
        || (),
        |_, i| {
            let (di, _, v, base) = cells[i];
            stress_cell(dims[di].name, v, base)
        },
        |i, rows| {
            let (di, vi, v, _) = cells[i];
            if i == 0 || cells[i - 1].0 != di || cells[i - 1].1 != vi {
                progress(&format!("{} = {v}", dims[di].name));
            }
            out.extend(rows?);
            Ok(())
        },
    )?;
    Ok(out)
}

/// The rows of one cell of the matrix: configuration `base` with `dimension` at `v` (none for
/// the epsilon of a configuration without one).
fn stress_cell(dimension: &str, v: f64, base: &RunConfig) -> Result<Vec<StressRow>, BackendError> {
    let mut out = Vec::new();
    let mut run = base.clone();
    let (mut offset, mut dt, mut speed, mut width) = (0.0f32, 1.0 / 60.0, 100.0f32, 0.8f32);
    match dimension {
        "offset" => offset = v as f32,
        "dt" => dt = v as f32,
        "speed" => speed = v as f32,
        "width" => width = v as f32,
        // The epsilon exists only in the sweep's float mode.
        _ => match run
            .backend
            .epsilon()
            .and(run.backend.with_epsilon(v as f32))
        {
            Some(b) => run.backend = b,
            None => return Ok(Vec::new()),
        },
    }
    let size = Vec2::new(width, width * 1.125);
    let level = probe_level(offset, false);
    let ride_level = probe_level(offset, true);
    let tol_pen = penetration_tolerance(&run, size);
    let tol_rest = 1e-3 * size.y as f64;
    let grid = run
        .backend
        .declared_contact(size, run.params.max_climb_angle)
        .surface_grid;
    let (mut finite, mut pen, mut tunnel, mut jitter, mut flicker) =
        (true, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    // The carry's worst excess over its allowance, and that ride's figures.
    let (mut drift, mut drift_tol) = (0.0f64, 0.0f64);
    let mut carry_modelled = true;
    for spec in probes(size, dt, speed) {
        let on = if spec.ride.is_some() {
            &ride_level
        } else {
            &level
        };
        let e = match evaluate(on, &spec, &run) {
            Err(BackendError::Unsupported { .. }) if spec.ride.is_some() => {
                // No moving platforms in this configuration: no carry row.
                carry_modelled = false;
                continue;
            }
            e => e?,
        };
        let get = |m: &str| -> Option<f64> {
            e.metrics
                .iter()
                .find(|r: &&MetricRow| r.metric == m)
                .map(|r| r.value)
        };
        finite &= e
            .trace
            .rows
            .iter()
            .all(|r| [r.x, r.y, r.vx, r.vy].iter().all(|v| v.is_finite()));
        if let Some(p) = spec.ride.and_then(|i| ride_level.platforms.get(i as usize)) {
            // A ride feeds only its own invariant (and `finite`): the others keep
            // the meaning they have on the static floor.
            let (d, lag) = carry_drift(p, ride_level.origin, grid, &e.trace, dt);
            let tol = lag + tol_rest;
            if drift_tol == 0.0 || d - tol > drift - drift_tol {
                (drift, drift_tol) = (d, tol);
            }
            continue;
        }
        pen = pen.max(get("max_penetration").unwrap_or(0.0));
        tunnel = tunnel.max(get("tunneled").unwrap_or(0.0));
        if spec.name == "drop" {
            // At rest: the height range over the last half second (the landing and
            // its settling are land_frame_error's business).
            let last = (0.5 / dt).ceil() as usize;
            let tail = &e.trace.rows[e.trace.rows.len().saturating_sub(last)..];
            let (lo, hi) = tail.iter().fold((f32::MAX, f32::MIN), |(lo, hi), r| {
                (lo.min(r.y), hi.max(r.y))
            });
            jitter = jitter.max((hi - lo) as f64);
        }
        flicker = flicker.max(get("grounded_flicker").unwrap_or(0.0));
    }
    let pen = if pen.is_nan() { f64::INFINITY } else { pen };
    let row = |invariant: &str, holds, measured, tolerance| StressRow {
        backend: run.backend.backend().to_string(),
        config: run.label.clone(),
        dimension: dimension.to_string(),
        value: v,
        invariant: invariant.to_string(),
        holds,
        measured,
        tolerance,
    };
    out.push(row("finite", finite, (!finite) as u8 as f64, 0.0));
    out.push(row("penetration", finite && pen <= tol_pen, pen, tol_pen));
    out.push(row("no_tunneling", finite && tunnel == 0.0, tunnel, 0.0));
    out.push(row(
        "stable_rest",
        finite && jitter <= tol_rest,
        jitter,
        tol_rest,
    ));
    out.push(row("no_flicker", finite && flicker == 0.0, flicker, 0.0));
    // A rider is at rest on its platform: held to the stable rest's bound plus the lag
    // a carry may show (see `carry_drift`).
    if carry_modelled {
        out.push(row(
            "carry_no_drift",
            finite && drift <= drift_tol,
            drift,
            drift_tol,
        ));
    }
    Ok(out)
}

/// One configuration's results along one dimension of the matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct Envelope {
    /// Backend and configuration label.
    pub config: String,
    /// Dimension name.
    pub dimension: String,
    /// The values at which every invariant held, in matrix order.
    pub holds: Vec<f64>,
    /// Each invariant that broke somewhere, with the values at which it broke, in matrix order.
    pub breaks: Vec<(String, Vec<f64>)>,
}

impl Envelope {
    /// The values at which some invariant broke, in matrix order.
    pub fn broken_values(&self) -> Vec<f64> {
        let mut v: Vec<f64> = Vec::new();
        for (_, vs) in &self.breaks {
            for x in vs {
                if !v.contains(x) {
                    v.push(*x);
                }
            }
        }
        v.sort_by(f64::total_cmp);
        v
    }
}

/// For each configuration and dimension, the values at which every invariant held and, per
/// invariant, those at which it broke (so an invariant that breaks everywhere, such as a
/// controller that cannot carry a rider at the base case, does not hide where the others hold).
pub fn envelope(rows: &[StressRow]) -> Vec<Envelope> {
    let mut out: Vec<Envelope> = Vec::new();
    for r in rows {
        let config = format!("{} {}", r.backend, r.config);
        let i = match out
            .iter()
            .position(|e| e.config == config && e.dimension == r.dimension)
        {
            Some(i) => i,
            None => {
                out.push(Envelope {
                    config,
                    dimension: r.dimension.clone(),
                    holds: Vec::new(),
                    breaks: Vec::new(),
                });
                out.len() - 1
            }
        };
        let e = &mut out[i];
        if r.holds {
            if !e.holds.contains(&r.value) {
                e.holds.push(r.value);
            }
        } else {
            match e.breaks.iter_mut().find(|(inv, _)| *inv == r.invariant) {
                Some((_, vs)) => vs.push(r.value),
                None => e.breaks.push((r.invariant.clone(), vec![r.value])),
            }
        }
    }
    for e in &mut out {
        let bad = e.broken_values();
        e.holds.retain(|v| !bad.contains(v));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(value: f64, invariant: &str, holds: bool) -> StressRow {
        StressRow {
            backend: "b".into(),
            config: "c".into(),
            dimension: "offset".into(),
            value,
            invariant: invariant.into(),
            holds,
            measured: 0.0,
            tolerance: 0.0,
        }
    }

    #[test]
    fn envelope_names_each_broken_invariant_and_keeps_only_values_where_all_held() {
        let rows = [
            row(0.0, "finite", true),
            row(0.0, "carry_no_drift", false),
            row(1.0, "finite", true),
            row(1.0, "carry_no_drift", true),
            row(2.0, "finite", false),
            row(2.0, "carry_no_drift", false),
        ];
        let e = envelope(&rows);
        assert_eq!(e.len(), 1);
        assert_eq!(e[0].holds, vec![1.0]);
        assert_eq!(
            e[0].breaks,
            vec![
                ("carry_no_drift".to_string(), vec![0.0, 2.0]),
                ("finite".to_string(), vec![2.0])
            ]
        );
        assert_eq!(e[0].broken_values(), vec![0.0, 2.0]);
    }
}
