//! Stability at the extremes: the invariants every controller should keep (nothing non-finite,
//! no penetration beyond its tolerance, no tunneling, a stable rest, no grounded flicker, carry
//! without drift, progress on flat seamed ground with no stuck step, a jump to its height),
//! checked one dimension at a time away from a base case (far from the origin, tiny and huge
//! time steps, fast movers, tiny and huge characters, and the sweep's epsilon down to where it
//! breaks: the seed's "try 0.001, and lower until unstable"), then on small grids of the pairs
//! of dimensions whose failures interact ([`pairs`]).
//!
//! The matrix is a list of independent [`Point`]s ([`points`]), each run alone ([`run_point`])
//! and collected in order, so that running them on several threads changes no row.

use glam::Vec2;
use serde::{Deserialize, Serialize};

use crate::backend::{BackendError, Precision};
use crate::level::{InputEvent, Level, Platform, PlatformMotion, ScenarioSpec, Tile};
use crate::metrics::seams::STUCK_FRACTION;
use crate::metrics::{commanded_steps, evaluate_with, MetricRow};
use crate::scenario::{effective_params, input_script, RunConfig, Runner};

/// One dimension of the stress matrix and the values it takes (the base case is the default
/// everywhere else).
#[derive(Clone, Debug)]
pub struct Dimension {
    /// Name, as in `stability.csv`.
    pub name: &'static str,
    /// Values, in the dimension's unit, in increasing order.
    pub values: Vec<f64>,
    /// The base case's value (one of `values`): where every other dimension stays while this
    /// one is varied.
    pub base: f64,
}

/// The base case: origin at 0, dt 1/60 s, fast mover at 100 tiles/s, a 0.8-tile-wide
/// character, the seed's epsilon 1e-3.
pub const BASE: Case = Case {
    offset: 0.0,
    dt: 1.0 / 60.0,
    speed: 100.0,
    width: 0.8,
    epsilon: 1e-3,
};

/// The base case's value of dimension `name` exactly as the dimensions list it (the f64 of
/// [`BASE`]'s f32 would not compare equal to `1.0 / 60.0`).
fn base_value(name: &str) -> f64 {
    match name {
        "dt" => 1.0 / 60.0,
        "speed" => 100.0,
        "width" => 0.8,
        "epsilon" => 1e-3,
        _ => 0.0,
    }
}

/// The largest offset (tiles) at which f32 configurations are run. Past it an f32 position's
/// spacing is over a tile (8 tiles at 1e8): no probe's step can move a character, every f32
/// configuration measured has broken at or before 1e7 (or refuses the level: integer
/// positions past 2^24 tiles, Box2D), and Rapier's f32 casts there take seconds a point. The
/// offsets past it ([`F64_OFFSETS`]) are run on f64 configurations only.
pub const F32_OFFSET_LIMIT: f64 = crate::limits::MAX_F32_ORIGIN;

/// The offsets past [`F32_OFFSET_LIMIT`] that f64 configurations are run at, up to 1e15 tiles
/// (f64 spacing 1/8 tile there, where an f32 position is at 1e6: the f64 edge, if it is the
/// same spacing as the f32 one, falls inside the range). The probe level's origin is f64
/// ([`Level::origin`]), so each offset is placed exactly (1e12 at 1,000,000,000,000, where an
/// f32 origin would be 999,999,995,904); [`crate::limits::MAX_ORIGIN`] is the last of them.
pub const F64_OFFSETS: [f64; 8] = [1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15];

/// The dimensions of DESIGN.md's stress matrix (the offset's values past [`F32_OFFSET_LIMIT`]
/// are run on f64 configurations only, [`points`]).
pub fn dimensions() -> Vec<Dimension> {
    let dim = |name, values: Vec<f64>| Dimension {
        name,
        base: base_value(name),
        values,
    };
    vec![
        dim(
            "offset",
            [0.0, 1e3, 1e4, 1e5, 1e6, 1e7]
                .into_iter()
                .chain(F64_OFFSETS)
                .collect(),
        ),
        dim("dt", vec![1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.05, 0.2]),
        dim("speed", vec![10.0, 100.0, 1000.0]),
        dim("width", vec![0.01, 0.1, 0.8, 3.0, 10.0]),
        dim("epsilon", vec![1e-9, 1e-7, 1e-5, 1e-3, 1e-1]),
    ]
}

/// The offsets of the combination grids for configurations in `precision`: the three decades
/// before the precision's one-dimension edge (where the sweep's positions still snap and rest),
/// so that the grid shows what a finer step, a faster mover or a smaller epsilon adds there. In
/// f32 1e4, 1e5 and 1e6 tiles (spacing 1/1024, 1/128 and 1/16 tile; 1e7 breaks every
/// configuration alone; the walk's progress alone already leaves its band at 1e5 and 1e6, by
/// the rounding of its 0.1-tile step). In f64 1e11, 1e12 and 1e13 (spacing 2^-16, 2^-13 and
/// 2^-9 tile, about 1.5e-5, 1.2e-4 and 2.0e-3; each holds alone, 1e14 breaks): an f64 world's
/// positions there are as coarse as an f32 world's at 1e3 to 1e5, so the same interactions (a
/// step of a few spacings or under one, an epsilon under one spacing) reach it there, where an
/// f32 grid would show an f64 configuration nothing (its spacing at 1e6 is 1.2e-10 tile).
pub fn pair_offsets(precision: Precision) -> Vec<f64> {
    match precision {
        Precision::F32 => vec![1e4, 1e5, 1e6],
        Precision::F64 => vec![1e11, 1e12, 1e13],
    }
}

/// The pairs of dimensions whose failures interact, each on a small grid (the base case
/// elsewhere), for configurations in `precision`: an epsilon below the spacing far out, a step
/// too small to move a position far out, a time step too coarse for a fast mover, a tiny
/// character at speed, and a fast mover far out. The grids straddle the one-dimension edges
/// measured alone; the offsets are the precision's own ([`pair_offsets`]).
pub fn pairs(precision: Precision) -> Vec<(Dimension, Dimension)> {
    let dim = |name, values: Vec<f64>| Dimension {
        name,
        base: base_value(name),
        values,
    };
    let offsets = || dim("offset", pair_offsets(precision));
    let dts = match precision {
        // 1e-3 s rather than the one-dimension 1e-4: its walking step (6e-3 tiles) is
        // already under the f32 spacing at 1e5 tiles (1/128), at a tenth of the cost.
        Precision::F32 => vec![1e-3, 1.0 / 240.0, 0.05],
        // 1e-4 s as well: its walking step (6e-4 tiles) is 5 f64 spacings at 1e12 and under
        // one at 1e13, where 1e-3 s (6e-3 tiles, 3.07 spacings) rounds to 3: the steps that
        // f32 meets at 1e4 to 1e5. 0.05 s stays for the coarse side (a jump's steps).
        Precision::F64 => vec![1e-4, 1e-3, 0.05],
    };
    vec![
        (offsets(), dim("epsilon", vec![1e-7, 1e-5, 1e-3])),
        (offsets(), dim("dt", dts)),
        (
            dim("speed", vec![100.0, 1000.0]),
            dim("dt", vec![1.0 / 240.0, 0.05, 0.2]),
        ),
        (
            dim("width", vec![0.01, 0.1, 10.0]),
            dim("speed", vec![100.0, 1000.0]),
        ),
        (offsets(), dim("speed", vec![10.0, 1000.0])),
    ]
}

/// One point of the matrix: the value of every dimension.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Offset of the probe level's origin from the world origin, in tiles (both axes), in f64 so
    /// that the far offsets are exact ([`F64_OFFSETS`]).
    pub offset: f64,
    /// Time step, in seconds.
    pub dt: f32,
    /// The fast mover's speed towards the wall, in tiles/s.
    pub speed: f32,
    /// The character's width, in tiles (its height is 1.125 times that).
    pub width: f32,
    /// The overlap tolerance, in tiles, for a configuration that has one (others ignore it).
    pub epsilon: f32,
}

impl Case {
    /// The value of dimension `name` (0 for an unknown name).
    pub fn get(&self, name: &str) -> f64 {
        match name {
            "offset" => self.offset,
            "dt" => self.dt as f64,
            "speed" => self.speed as f64,
            "width" => self.width as f64,
            "epsilon" => self.epsilon as f64,
            _ => 0.0,
        }
    }

    /// This case with dimension `name` set to `v` (an unknown name changes nothing).
    pub fn with(mut self, name: &str, v: f64) -> Self {
        match name {
            "offset" => self.offset = v,
            "dt" => self.dt = v as f32,
            "speed" => self.speed = v as f32,
            "width" => self.width = v as f32,
            "epsilon" => self.epsilon = v as f32,
            _ => {}
        }
        self
    }
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

/// The invariants, in the order they are checked and named (the first that breaks colours a
/// combination cell).
pub const INVARIANTS: [&str; 9] = [
    "finite",
    "penetration",
    "no_tunneling",
    "stable_rest",
    "no_flicker",
    "carry_no_drift",
    "progress",
    "no_stuck",
    "jump_height",
];

/// The least fraction of the commanded distance a walk over flat seamed ground must cover.
/// The commanded distance already includes the acceleration ramp, so an exact controller
/// covers 1.0 up to rounding; 1% is what rounding a walking step (0.1 tiles at 1/60 s) onto
/// the f32 grid can cost where the spacing is a few thousandths of a tile, and the loss the
/// report already calls progress lost (`progress_ratio < 0.99`). The Rapier walks at
/// 1e5 tiles (91% to 96% per tile) are broken by it. The most is [`PROGRESS_MAX`].
pub const PROGRESS_MIN: f64 = 0.99;

/// How far the fraction of the commanded distance a walk covers may be from 1, either way:
/// `1 - PROGRESS_MIN`, 1%. Rounding a step to the nearest representable position lengthens it
/// as readily as it shortens it (a 0.1-tile step is 1.6 spacings of 1/16 tile at 1e6 tiles and
/// rounds up to 2: 125%), so the band is symmetric about 1 with the tolerance the short side
/// already had: a walk that overshoots by more than 1% has not held either (it carries the
/// character past where the game put it, a ledge or a door), and every configuration is held
/// to the same band.
pub const PROGRESS_BAND: f64 = 1.0 - PROGRESS_MIN;

/// The largest fraction of the commanded distance a walk may cover: `1 + PROGRESS_BAND`, 101%.
pub const PROGRESS_MAX: f64 = 1.0 + PROGRESS_BAND;

/// How far a jump's apex may miss the requested height, in tiles: one pixel of a 16-pixel tile
/// (the seed's slope tiles are drawn in 16ths), below which a player sees no difference and the
/// seed's "jump exactly 3 tiles" still holds.
pub const JUMP_TOLERANCE: f64 = 1.0 / 16.0;

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
fn probe_level(offset: f64, with_platforms: bool) -> Level {
    let (w, h) = (300u32, 40u32);
    let mut tiles = vec![Tile::Empty; (w * h) as usize];
    for i in 0..w {
        tiles[i as usize] = Tile::Solid;
    }
    for j in 1..h - 2 {
        tiles[(j * w + 250) as usize] = Tile::Solid;
    }
    let mut l = Level::from_tiles("stress", w, h, tiles);
    l.origin = glam::DVec2::splat(offset);
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

/// How long the walk probe holds "right", in seconds: 60 tiles at the run speed of 6 tiles/s,
/// the walk in which the issue found Rapier stuck at 1e5 tiles (per tile its floor has a seam
/// every tile, 60 of them).
const WALK_TIME: f32 = 10.0;

/// The probes: a drop onto the floor then rest, a walk along the floor, a standing jump, a fast
/// mover aimed at the wall, and a rider standing on each moving platform for two of its periods
/// and a half.
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
        t: WALK_TIME,
        right: Some(false),
        ..Default::default()
    };
    let jump = |t: f32, on: bool| InputEvent {
        t,
        jump: Some(on),
        ..Default::default()
    };
    vec![
        spec("drop", Vec2::new(50.5, 3.0), 2.0, vec![]),
        spec(
            "walk",
            Vec2::new(100.5, 1.0),
            WALK_TIME + 0.5,
            vec![right, stop],
        ),
        spec(
            "jump",
            Vec2::new(200.5, 1.0),
            1.5,
            vec![jump(0.25, true), jump(0.5, false)],
        ),
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
/// the spacing of the configuration's `precision`). More than the allowance (plus a rest's
/// tolerance) is a rider that slips, bounces or falls off. A configuration on a subpixel grid of
/// `grid` subpixels per tile (0 for none) moves the platform along its path rounded to that
/// grid, in level coordinates whatever the offset; the drift is measured against that platform,
/// the one it moves.
fn carry_drift(
    p: &Platform,
    origin: glam::DVec2,
    (grid, precision): (u32, Precision),
    trace: &crate::trace::Trace,
    dt: f32,
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

/// Checks that every probe can run at the base time step `dt` (seconds): each probe's duration
/// over `dt` is within the frame caps of [`crate::limits::check_timing`].
pub fn check_base_dt(dt: f32) -> Result<(), BackendError> {
    let size = Vec2::new(BASE.width, BASE.width * 1.125);
    for spec in probes(size, dt, BASE.speed) {
        crate::limits::check_timing(spec.duration as f64, dt as f64).map_err(|m| {
            crate::backend::invalid(
                "dt",
                format!("the {} probe ({} s): {m}", spec.name, spec.duration),
                "a base time step at which every stress probe runs within the frame caps",
            )
        })?;
    }
    Ok(())
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
) -> Result<Vec<StressRow>, BackendError> {
    stress_matrix_on(runs, crate::parallel::default_jobs(), progress)
}

/// Runs the matrix for `runs` on `jobs` threads: builds [`points`], runs each with
/// [`run_point`] (the points are independent and fan out) and collects their rows in matrix
/// order whatever the threads. `progress` hears each new dimension value or combination cell.
pub fn stress_matrix_on(
    runs: &[RunConfig],
    jobs: usize,
    progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, BackendError> {
    stress_matrix_with(runs, None, jobs, progress)
}

/// [`stress_matrix_on`] with the base time step `dt` (seconds; [`BASE`]'s 1/60 s when `None`)
/// for every probe outside the dt dimension ([`points_with`]).
pub fn stress_matrix_with(
    runs: &[RunConfig],
    dt: Option<f32>,
    jobs: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<StressRow>, BackendError> {
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
            out.extend(rows?);
            Ok::<(), BackendError>(())
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
pub fn run_point(point: &Point) -> Result<Vec<StressRow>, BackendError> {
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
                Err(BackendError::Unsupported { .. }) => {
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
                Err(BackendError::Unsupported { .. }) => return Ok(Vec::new()),
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
            let (d, lag) = carry_drift(p, ride_level.origin, placing, &e.trace, case.dt);
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

/// The rows of one point from its probes' outcomes, in [`INVARIANTS`] order.
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
    for r in rows.iter().filter(|r| r.dimension2.is_empty()) {
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

/// Where a configuration stops holding, on one side of a dimension's base value.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// The farthest value from the base, on this side, up to which every invariant held at
    /// every value (`None` when one broke at the base).
    pub last_holding: Option<f64>,
    /// The first value past it where an invariant broke, with those that broke there, in
    /// [`INVARIANTS`] order (`None`: every value on this side held).
    pub first_break: Option<(f64, Vec<String>)>,
}

/// One configuration's verdict along one dimension: from the base value down and up, the last
/// value where every invariant holds and the first where one breaks, and which.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Backend and configuration label.
    pub config: String,
    /// Dimension name.
    pub dimension: String,
    /// The base value.
    pub base: f64,
    /// Going from the base to smaller values.
    pub down: Edge,
    /// Going from the base to larger values.
    pub up: Edge,
}

/// The invariants that broke among `rows` (one value's rows of one configuration), in
/// [`INVARIANTS`] order.
fn broken<'a>(rows: impl Iterator<Item = &'a StressRow> + Clone) -> Vec<String> {
    let mut out: Vec<String> = INVARIANTS
        .iter()
        .filter(|i| rows.clone().any(|r| !r.holds && r.invariant == **i))
        .map(|i| i.to_string())
        .collect();
    // An invariant another backend's rows name (none yet) after the known ones.
    for r in rows.filter(|r| !r.holds) {
        if !out.contains(&r.invariant) {
            out.push(r.invariant.clone());
        }
    }
    out
}

/// Walks `values` (ordered away from the base, the base first) and finds the edge.
fn edge(values: &[f64], broken_at: impl Fn(f64) -> Vec<String>) -> Edge {
    let mut last = None;
    for &v in values {
        let b = broken_at(v);
        if !b.is_empty() {
            return Edge {
                last_holding: last,
                first_break: Some((v, b)),
            };
        }
        last = Some(v);
    }
    Edge {
        last_holding: last,
        first_break: None,
    }
}

/// Each configuration's verdict along each dimension of [`dimensions`], from the one-dimension
/// rows of `rows` (in the order the configurations and dimensions first appear).
pub fn verdicts(rows: &[StressRow]) -> Vec<Verdict> {
    let dims = dimensions();
    let mut out = Vec::new();
    for e in envelope(rows) {
        let Some(d) = dims.iter().find(|d| d.name == e.dimension) else {
            continue;
        };
        let mine = |r: &&StressRow| {
            r.dimension2.is_empty()
                && r.dimension == e.dimension
                && format!("{} {}", r.backend, r.config) == e.config
        };
        let mut values: Vec<f64> = rows.iter().filter(mine).map(|r| r.value).collect();
        values.sort_by(f64::total_cmp);
        values.dedup();
        let broken_at = |v: f64| broken(rows.iter().filter(mine).filter(move |r| r.value == v));
        let base = if values.contains(&d.base) {
            d.base
        } else {
            values.first().copied().unwrap_or(d.base)
        };
        let mut down: Vec<f64> = values.iter().copied().filter(|&v| v <= base).collect();
        down.reverse();
        let up: Vec<f64> = values.iter().copied().filter(|&v| v >= base).collect();
        out.push(Verdict {
            config: e.config.clone(),
            dimension: e.dimension.clone(),
            base,
            down: edge(&down, broken_at),
            up: edge(&up, broken_at),
        });
    }
    out
}

impl Verdict {
    /// The verdict in words: `holds to 1e6; breaks at 1e7 (stable_rest, progress)`, `holds
    /// from 1e-4 to 0.05; breaks at 0.2 (penetration)`, or `breaks at the base case 0.0167
    /// (carry_no_drift)`.
    pub fn text(&self) -> String {
        let f = crate::report::format_setting;
        let names = |b: &[String]| b.join(", ");
        match (self.down.last_holding, self.up.last_holding) {
            (None, _) | (_, None) => {
                let b = self
                    .up
                    .first_break
                    .as_ref()
                    .or(self.down.first_break.as_ref())
                    .map_or(String::new(), |(_, b)| names(b));
                format!("breaks at the base case {} ({b})", f(self.base))
            }
            (Some(lo), Some(hi)) => {
                let mut t = if lo == hi {
                    format!("holds at {}", f(lo))
                } else if lo == self.base {
                    format!("holds to {}", f(hi))
                } else {
                    format!("holds from {} to {}", f(lo), f(hi))
                };
                for (v, b) in [&self.down.first_break, &self.up.first_break]
                    .into_iter()
                    .flatten()
                {
                    t.push_str(&format!("; breaks at {} ({})", f(*v), names(b)));
                }
                t
            }
        }
    }
}

/// How far from the world's origin a configuration holds: its `offset` rows walked out from 0
/// as a [`Verdict`] walks them, with the invariants that already broke at offset 0 set aside
/// (they break for a reason other than the distance, such as Rapier's carry), so that an f32
/// and an f64 build of one set-up compare on what the distance alone breaks.
#[derive(Clone, Debug, PartialEq)]
pub struct Reach {
    /// Backend and configuration label.
    pub config: String,
    /// The invariants broken at offset 0, set aside, in [`INVARIANTS`] order.
    pub at_origin: Vec<String>,
    /// From offset 0 outwards: the last offset where every other invariant held, and the first
    /// where one broke.
    pub edge: Edge,
}

impl Reach {
    /// `holds to 1e13; breaks at 1e14 (progress); set aside, broken at 0: carry_no_drift`.
    pub fn text(&self) -> String {
        let f = crate::report::format_setting;
        let mut t = match (self.edge.last_holding, &self.edge.first_break) {
            (Some(v), _) => format!("holds to {}", f(v)),
            (None, _) => "breaks at 0".to_string(),
        };
        if let Some((v, b)) = &self.edge.first_break {
            if self.edge.last_holding.is_some() {
                t.push_str(&format!("; breaks at {} ({})", f(*v), b.join(", ")));
            } else {
                t.push_str(&format!(" ({})", b.join(", ")));
            }
        }
        if !self.at_origin.is_empty() {
            t.push_str(&format!(
                "; set aside, broken at 0: {}",
                self.at_origin.join(", ")
            ));
        }
        t
    }
}

/// Each configuration's [`Reach`], from the one-dimension `offset` rows of `rows`.
pub fn reach(rows: &[StressRow]) -> Vec<Reach> {
    let mut configs: Vec<String> = Vec::new();
    let offset_rows: Vec<&StressRow> = rows
        .iter()
        .filter(|r| r.dimension2.is_empty() && r.dimension == "offset")
        .collect();
    for r in &offset_rows {
        let c = format!("{} {}", r.backend, r.config);
        if !configs.contains(&c) {
            configs.push(c);
        }
    }
    configs
        .into_iter()
        .map(|config| {
            let mine: Vec<&StressRow> = offset_rows
                .iter()
                .copied()
                .filter(|r| format!("{} {}", r.backend, r.config) == config)
                .collect();
            let at = |v: f64| mine.iter().copied().filter(move |r| r.value == v);
            let at_origin = broken(at(0.0));
            let mut values: Vec<f64> = mine.iter().map(|r| r.value).filter(|&v| v >= 0.0).collect();
            values.sort_by(f64::total_cmp);
            values.dedup();
            let edge = edge(&values, |v| {
                broken(at(v))
                    .into_iter()
                    .filter(|i| !at_origin.contains(i))
                    .collect()
            });
            Reach {
                config,
                at_origin,
                edge,
            }
        })
        .collect()
}

/// Whether a configuration holds in a world `size` tiles across (positions up to `size` tiles
/// from the origin), read from its `offset` rows.
#[derive(Clone, Debug, PartialEq)]
pub struct WorldVerdict {
    /// Backend and configuration label.
    pub config: String,
    /// `Some(true)`: every invariant held at every measured offset up to the first one at or
    /// past `size`, and in every combination cell with an offset within `size`; `Some(false)`:
    /// one broke at a measured offset within `size`, or in such a combination cell; `None`:
    /// held at every measured offset and cell within `size`, broke at the next offset past it,
    /// so the offsets between were not measured.
    pub holds: Option<bool>,
    /// The verdict in words, naming the offsets and invariants (for one broken at offset 0, how
    /// far those that held there hold, [`reach`]).
    pub text: String,
    /// The combination cells with an offset within `size` where an invariant broke, as
    /// `offset x dt at (1e5, 1e-4): progress`.
    pub combinations: Vec<String>,
}

/// Which configurations hold in a world `size` tiles across: each configuration's `offset` rows
/// (the base case elsewhere), and the combination cells within that offset that broke (any one
/// of them is a break in that world).
pub fn world_verdicts(rows: &[StressRow], size: f64) -> Vec<WorldVerdict> {
    let f = crate::report::format_setting;
    let reaches = reach(rows);
    let mut out = Vec::new();
    for v in verdicts(rows)
        .into_iter()
        .filter(|v| v.dimension == "offset")
    {
        let ofs = |r: &&StressRow| format!("{} {}", r.backend, r.config) == v.config;
        let mut values: Vec<f64> = rows
            .iter()
            .filter(ofs)
            .filter(|r| r.dimension2.is_empty() && r.dimension == "offset")
            .map(|r| r.value)
            .collect();
        values.sort_by(f64::total_cmp);
        values.dedup();
        let cover = values.iter().copied().find(|&x| x >= size);
        let first_break = v.up.first_break.clone();
        let (holds, text) = match (&first_break, cover) {
            (Some((b, inv)), _) if *b <= size => {
                let mut t = format!("breaks at offset {} ({})", f(*b), inv.join(", "));
                // Broken at the origin already: how far the others hold ([`reach`]), so that
                // an f32 and an f64 build still read apart.
                if *b == 0.0 {
                    if let Some(r) = reaches.iter().find(|r| r.config == v.config) {
                        let aside = |e: &Edge| match (e.last_holding, &e.first_break) {
                            (Some(l), Some((x, i))) => format!(
                                "; those that held at 0 hold to {}, break at {} ({})",
                                f(l),
                                f(*x),
                                i.join(", ")
                            ),
                            (Some(l), None) => format!("; those that held at 0 hold to {}", f(l)),
                            (None, _) => String::new(),
                        };
                        t.push_str(&aside(&r.edge));
                    }
                }
                (Some(false), t)
            }
            (Some((b, inv)), Some(c)) if *b == c => (
                None,
                format!(
                    "holds to offset {}, breaks at {} ({}); {} itself not measured",
                    v.up.last_holding.map_or("-".into(), f),
                    f(*b),
                    inv.join(", "),
                    f(size)
                ),
            ),
            (_, Some(c)) => (
                Some(true),
                format!("holds at every offset measured up to {}", f(c)),
            ),
            (_, None) => (
                None,
                format!(
                    "holds to offset {}, the largest measured; {} not measured",
                    v.up.last_holding.map_or("-".into(), f),
                    f(size)
                ),
            ),
        };
        let mut combinations = Vec::new();
        for r in rows.iter().filter(ofs).filter(|r| {
            !r.holds && !r.dimension2.is_empty() && r.dimension == "offset" && r.value <= size
        }) {
            let cell = format!(
                "{} x {} at ({}, {})",
                r.dimension,
                r.dimension2,
                f(r.value),
                r.value2.map_or("-".into(), f)
            );
            match combinations
                .iter_mut()
                .find(|(c, _): &&mut (String, Vec<String>)| *c == cell)
            {
                Some((_, inv)) => inv.push(r.invariant.clone()),
                None => combinations.push((cell, vec![r.invariant.clone()])),
            }
        }
        // A cell within the world that breaks is a break within it: the world's positions
        // reach that offset, and the cell's other value (a dt, a speed, an epsilon) is one the
        // matrix holds alone at the base case.
        // Broken already (at the origin, say): the cells that break an invariant that held
        // there are still said, so a configuration broken at 0 does not read sturdier than one
        // that is not.
        let at_origin: Vec<String> = reaches
            .iter()
            .find(|r| r.config == v.config)
            .map_or_else(Vec::new, |r| r.at_origin.clone());
        let more = combinations
            .iter()
            .filter(|(_, inv)| inv.iter().any(|i| !at_origin.contains(i)))
            .count();
        let cells = |n: usize| {
            let (noun, verb) = if n == 1 { ("", "s") } else { ("s", "") };
            format!("{n} combination cell{noun} within it break{verb}")
        };
        let (holds, text) = match (holds, combinations.len()) {
            (Some(false), _) if more > 0 => (holds, format!("{text}; and {} more", cells(more))),
            (Some(false), _) | (_, 0) => (holds, text),
            (_, n) => (Some(false), format!("{text}; but {}", cells(n))),
        };
        out.push(WorldVerdict {
            config: v.config.clone(),
            holds,
            text,
            combinations: combinations
                .into_iter()
                .map(|(c, inv)| format!("{c}: {}", inv.join(", ")))
                .collect(),
        });
    }
    out
}

/// One combination cell of one configuration: the first invariant (in [`INVARIANTS`] order)
/// that broke there, or `None` where every invariant held.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Backend and configuration label.
    pub config: String,
    /// The pair, as `offset x epsilon`.
    pub pair: String,
    /// The first dimension's value.
    pub a: f64,
    /// The second dimension's value.
    pub b: f64,
    /// The invariants that broke, in [`INVARIANTS`] order (empty: every one held).
    pub broken: Vec<String>,
}

/// The combination cells of `rows`, in the order they first appear.
pub fn cells(rows: &[StressRow]) -> Vec<Cell> {
    let mut out: Vec<Cell> = Vec::new();
    for r in rows.iter().filter(|r| !r.dimension2.is_empty()) {
        let config = format!("{} {}", r.backend, r.config);
        let pair = format!("{} x {}", r.dimension, r.dimension2);
        let b = r.value2.unwrap_or(f64::NAN);
        let i = match out
            .iter()
            .position(|c| c.config == config && c.pair == pair && c.a == r.value && c.b == b)
        {
            Some(i) => i,
            None => {
                out.push(Cell {
                    config,
                    pair,
                    a: r.value,
                    b,
                    broken: Vec::new(),
                });
                out.len() - 1
            }
        };
        if !r.holds {
            out[i].broken.push(r.invariant.clone());
        }
    }
    for c in &mut out {
        let order = |i: &String| INVARIANTS.iter().position(|k| k == i).unwrap_or(usize::MAX);
        c.broken.sort_by_key(order);
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
            dimension2: String::new(),
            value2: None,
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

    fn at(dimension: &str, value: f64, invariant: &str, holds: bool) -> StressRow {
        StressRow {
            dimension: dimension.into(),
            ..row(value, invariant, holds)
        }
    }

    #[test]
    fn verdict_walks_out_from_the_base_value_on_each_side() {
        // dt: base 1/60; 1e-4 breaks progress, 0.2 breaks penetration; 1/240 and 0.05 hold.
        let mut rows = Vec::new();
        for v in [1e-4, 1.0 / 240.0, 1.0 / 60.0, 0.05, 0.2] {
            rows.push(at("dt", v, "penetration", v != 0.2));
            rows.push(at("dt", v, "progress", v != 1e-4));
        }
        let v = &verdicts(&rows)[0];
        assert_eq!(v.base, 1.0 / 60.0);
        assert_eq!(v.down.last_holding, Some(1.0 / 240.0));
        assert_eq!(
            v.down.first_break,
            Some((1e-4, vec!["progress".to_string()]))
        );
        assert_eq!(v.up.last_holding, Some(0.05));
        assert_eq!(
            v.text(),
            "holds from 0.0042 to 0.05; breaks at 1e-4 (progress); breaks at 0.2 (penetration)"
        );
        // Broken at the base: named as such, whatever holds farther out.
        let rows = [
            at("offset", 0.0, "carry_no_drift", false),
            at("offset", 1e3, "carry_no_drift", true),
        ];
        assert_eq!(
            verdicts(&rows)[0].text(),
            "breaks at the base case 0 (carry_no_drift)"
        );
    }

    #[test]
    fn world_verdict_needs_the_first_offset_past_the_world_to_hold() {
        let rows: Vec<StressRow> = [0.0, 1e5, 1e6, 1e7]
            .iter()
            .map(|&v| at("offset", v, "progress", v < 1e7))
            .chain([StressRow {
                dimension2: "dt".into(),
                value2: Some(1e-3),
                ..at("offset", 1e5, "jump_height", false)
            }])
            .collect();
        let w = |size| world_verdicts(&rows, size).remove(0);
        // Without the combination cell: the offsets alone decide.
        let alone: Vec<StressRow> = rows[..4].to_vec();
        let a = |size| world_verdicts(&alone, size).remove(0).holds;
        assert_eq!(a(1e6), Some(true));
        assert_eq!(a(5e5), Some(true));
        // 5e6: 1e6 held, 1e7 broke; between them nothing was measured.
        assert_eq!(a(5e6), None);
        assert_eq!(a(1e7), Some(false));
        // The cell at offset 1e5 broke: every world that reaches 1e5 breaks, whatever its
        // offsets alone say; a world within 1e4 does not reach it.
        for size in [1e5, 5e5, 1e6, 5e6, 1e7] {
            assert_eq!(w(size).holds, Some(false), "{size}");
        }
        assert_eq!(
            w(1e6).text,
            "holds at every offset measured up to 1e6; but 1 combination cell within it breaks"
        );
        assert_eq!(
            w(1e6).combinations,
            vec!["offset x dt at (1e5, 0.001): jump_height"]
        );
        assert_eq!(w(1e4).holds, Some(true));
        assert!(w(1e4).combinations.is_empty());
        // Broken at the origin (the carry): the invariants that held there are followed out.
        let rows: Vec<StressRow> = [0.0, 1e5, 1e14]
            .iter()
            .flat_map(|&v| {
                [
                    at("offset", v, "carry_no_drift", false),
                    at("offset", v, "progress", v < 1e14),
                ]
            })
            .collect();
        assert_eq!(
            world_verdicts(&rows, 1e5)[0].text,
            "breaks at offset 0 (carry_no_drift); those that held at 0 hold to 1e5, break at 1e14 (progress)"
        );
        // A cell within the world that breaks another invariant is said too (issue 22 second
        // review: Rapier f64 read sturdier than the f64 sweep); one that breaks only the carry
        // again is not news.
        let mut more = rows.clone();
        more.push(StressRow {
            dimension2: "dt".into(),
            value2: Some(1e-4),
            ..at("offset", 1e5, "progress", false)
        });
        more.push(StressRow {
            dimension2: "dt".into(),
            value2: Some(1e-3),
            ..at("offset", 1e5, "carry_no_drift", false)
        });
        assert_eq!(
            world_verdicts(&more, 1e5)[0].text,
            "breaks at offset 0 (carry_no_drift); those that held at 0 hold to 1e5, break at 1e14 (progress); and 1 combination cell within it breaks more"
        );
    }

    #[test]
    fn reach_sets_aside_what_broke_at_the_origin() {
        // carry breaks everywhere; progress from 1e14 on; penetration only at 1e15.
        let mut rows = Vec::new();
        for v in [0.0, 1e7, 1e13, 1e14, 1e15] {
            rows.push(at("offset", v, "carry_no_drift", false));
            rows.push(at("offset", v, "progress", v < 1e14));
            rows.push(at("offset", v, "penetration", v < 1e15));
        }
        let r = &reach(&rows)[0];
        assert_eq!(r.at_origin, vec!["carry_no_drift".to_string()]);
        assert_eq!(r.edge.last_holding, Some(1e13));
        assert_eq!(
            r.text(),
            "holds to 1e13; breaks at 1e14 (progress); set aside, broken at 0: carry_no_drift"
        );
        // The verdict itself still reads the break at the base case.
        assert!(verdicts(&rows)[0]
            .text()
            .starts_with("breaks at the base case"));
    }

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
