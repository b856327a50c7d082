//! Stability at the extremes: the invariants every controller should keep (nothing non-finite,
//! no penetration beyond its tolerance, no tunneling, a stable rest, no grounded flicker), checked
//! one dimension at a time away from a base case: far from the origin, tiny and huge time steps,
//! fast movers, tiny and huge characters, and (for the sweep) its epsilon down to where it breaks
//! (the seed: "try 0.001, and lower until unstable").

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::backend::BackendError;
use crate::level::{InputEvent, Level, ScenarioSpec, Tile};
use crate::metrics::{evaluate, MetricRow};
use crate::scenario::{BackendConfig, RunConfig};

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

/// The probe level: a floor 300 tiles long with a one-tile wall at x = 250, 40 tiles high (room
/// for a 10-tile character). Merged, the floor is one 300-tile box: long enough to matter, short
/// of the thousands of tiles on which Rapier's rounded shapes sink (a separate finding).
fn probe_level(offset: f32) -> Level {
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
    l
}

/// The probes: a drop onto the floor then rest, a walk along the floor, and a fast mover aimed
/// at the wall.
fn probes(size: Vec2, dt: f32, speed: f32) -> Vec<ScenarioSpec> {
    let spec = |name: &str, spawn: Vec2, velocity: Vec2, duration: f32, inputs: Vec<InputEvent>| {
        ScenarioSpec {
            name: name.into(),
            spawn,
            size,
            velocity,
            duration,
            dt,
            inputs,
            motion: Default::default(),
            expect_y: None,
            ride: None,
        }
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
        spec("drop", Vec2::new(50.5, 3.0), Vec2::ZERO, 2.0, vec![]),
        spec(
            "walk",
            Vec2::new(100.5, 1.0),
            Vec2::ZERO,
            2.0,
            vec![right, stop],
        ),
        spec(
            "fast",
            Vec2::new(150.5 - size.x, 1.5),
            Vec2::new(speed, 0.0),
            2.0,
            vec![],
        ),
    ]
}

/// The penetration a backend is held to: the sweep's epsilon, Rapier's offset (1% of the
/// character's height) - each controller's own contact tolerance.
fn penetration_tolerance(run: &RunConfig, size: Vec2) -> f64 {
    match &run.backend {
        BackendConfig::Sweep(c) => c.epsilon as f64,
        BackendConfig::Rapier(_) => 0.01 * size.y as f64,
    }
}

/// Runs the matrix for `runs` (the epsilon dimension only on sweep configurations).
pub fn stress_matrix(
    runs: &[RunConfig],
    mut progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, BackendError> {
    let mut out = Vec::new();
    for d in dimensions() {
        for &v in &d.values {
            progress(&format!("{} = {v}", d.name));
            for base in runs {
                let mut run = base.clone();
                let (mut offset, mut dt, mut speed, mut width) =
                    (0.0f32, 1.0 / 60.0, 100.0f32, 0.8f32);
                match d.name {
                    "offset" => offset = v as f32,
                    "dt" => dt = v as f32,
                    "speed" => speed = v as f32,
                    "width" => width = v as f32,
                    _ => match &mut run.backend {
                        BackendConfig::Sweep(c) => c.epsilon = v as f32,
                        BackendConfig::Rapier(_) => continue,
                    },
                }
                let size = Vec2::new(width, width * 1.125);
                let level = probe_level(offset);
                let tol_pen = penetration_tolerance(&run, size);
                let tol_rest = 1e-3 * size.y as f64;
                let (mut finite, mut pen, mut tunnel, mut jitter, mut flicker) =
                    (true, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
                for spec in probes(size, dt, speed) {
                    let e = evaluate(&level, &spec, &run)?;
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
                    backend: run.backend.name().to_string(),
                    config: run.label.clone(),
                    dimension: d.name.to_string(),
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
            }
        }
    }
    Ok(out)
}

/// For each configuration and dimension, the values at which every invariant held.
pub fn envelope(rows: &[StressRow]) -> Vec<(String, String, Vec<f64>, Vec<f64>)> {
    let mut out: Vec<(String, String, Vec<f64>, Vec<f64>)> = Vec::new();
    for r in rows {
        let key = format!("{} {}", r.backend, r.config);
        let entry = match out.iter_mut().find(|e| e.0 == key && e.1 == r.dimension) {
            Some(e) => e,
            None => {
                out.push((key, r.dimension.clone(), Vec::new(), Vec::new()));
                out.last_mut().expect("just pushed")
            }
        };
        let (ok, bad) = (&mut entry.2, &mut entry.3);
        if !r.holds {
            if !bad.contains(&r.value) {
                bad.push(r.value);
            }
            ok.retain(|v| *v != r.value);
        } else if !bad.contains(&r.value) && !ok.contains(&r.value) {
            ok.push(r.value);
        }
    }
    out
}
