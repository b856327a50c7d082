//! Behaviour metrics, computed from a trace, the level geometry and the scenario's script, each
//! against an analytic or geometric reference (DESIGN.md, "metric catalog"). No metric reads
//! backend internals. The definitions (name, unit, behaviour, where each applies, its reference
//! model, its default weight) are in one registry, [`registry::METRICS`]; the computations are
//! in one file per behaviour.
//!
//! A metric is reported only for scenarios where it means something: `land_frame_error` for a
//! character dropped with no input until it should land, `apex_error` for a jump with room
//! above, `progress_ratio` for a walk over flat open ground, `rest_gap` and `rest_jitter` for
//! scenarios that end with at least [`landing::REST_WINDOW`] seconds of idle input.
//! `max_penetration`, `grounded_flicker`, `stuck_frames` and `tunneled` apply to every scenario.
//! Only the scenario's character is measured (the trace's first character).

pub mod faults;
pub mod ground;
pub mod idle;
pub mod jumping;
pub mod ladders;
pub mod landing;
pub mod oneway;
pub mod platforms;
mod reference;
pub mod registry;
pub mod score;
pub mod seams;
pub mod slopes;
pub mod walls;

pub use reference::{commanded_distance, commanded_steps, predicted_landing_frame};
pub use registry::{Behaviour, MetricDef, METRICS};

use serde::Serialize;

use crate::level::{Level, ScenarioSpec};
use crate::motion::MotionParams;
pub use crate::scenario::DeclaredContact;
use crate::shape::CharacterShape;
use crate::trace::{write_rows_csv, Frames, RowStore, Rows, Trace, TraceRow};
use glam::Vec2;
use ground::Ground;

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

/// A measured metric before it is labelled with its run (its unit is the registry's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measure {
    /// Metric name (a [`registry::METRICS`] entry).
    pub metric: &'static str,
    /// Measured value.
    pub value: f64,
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
    /// The contact the configuration declares it keeps (Rapier's offset, the sweep's slope
    /// overhang), for the metrics that score a controller against its own promise.
    pub declared: DeclaredContact,
}

/// Computes every metric that applies to the scenario, from the rows of the trace's first
/// character (the one the scenario spawns: the runner adds one, whatever id its backend gives it).
pub fn compute(ctx: &Context) -> Vec<MetricRow> {
    // The first character's rows: the trace itself when it holds no other (every scenario the
    // harness runs), so a long trace is not copied.
    let id = ctx.trace.rows.first().map_or(0, |r| r.character);
    let rows: std::borrow::Cow<[TraceRow]> = if ctx.trace.rows.iter().all(|r| r.character == id) {
        std::borrow::Cow::Borrowed(&ctx.trace.rows)
    } else {
        ctx.trace.character(id).copied().collect()
    };
    compute_frames(ctx, Frames::new(&rows))
}

/// Computes every metric that applies to the scenario from `rows`, the measured character's
/// rows, wherever they are held (in memory or spilled, [`crate::trace::RowStore`]); `ctx.trace`
/// gives only the labels. Memory: the level's and a few values per metric, whatever the run's
/// length (nothing is kept per frame).
pub(crate) fn compute_frames(ctx: &Context, rows: Frames) -> Vec<MetricRow> {
    let ground = Ground::new(ctx.level, ctx.shape, ctx.spec.size);
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
                unit: registry::unit(m.metric),
                reference: m.reference,
                error: m.value - m.reference,
            });
        }
    };
    push(landing::land_frame_error(ctx, rows));
    let rest = landing::rest_frames(ctx, g, rows);
    push(
        rest.clone()
            .map(|r| landing::rest_gap(ctx, g, rows.slice(r))),
    );
    push(
        rest.clone()
            .map(|r| landing::rest_gap_declared(ctx, g, rows.slice(r))),
    );
    push(Some(landing::max_penetration(g, rows)));
    push(Some(landing::penetration_beyond_declared(ctx, g, rows)));
    push(
        rest.clone()
            .map(|r| landing::rest_jitter(rows.slice(landing::settled(ctx, r)))),
    );
    push(rest.map(|_| landing::bounce_frames(ctx, rows)));
    push(Some(landing::grounded_flicker(ctx, g, rows)));
    push(Some(landing::false_grounded(ctx, g, rows)));
    push(jumping::apex_error(ctx, rows));
    push(seams::progress_ratio(ctx, rows));
    push(Some(seams::stuck_frames(ctx, rows)));
    let on_slope = slopes::SlopeFrames::new(ctx, rows);
    push(slopes::slope_airborne_frames(ctx, rows, &on_slope));
    push(slopes::slope_gap_max(ctx, g, &on_slope));
    push(slopes::slope_gap_declared(ctx, g, &on_slope));
    push(slopes::slope_overlap(ctx, g, rows));
    let [horizontal, along] = slopes::slope_speed_ratios(ctx, rows, &on_slope);
    push(horizontal);
    push(along);
    push(slopes::steep_blocked(ctx, rows));
    push(oneway::oneway_result(ctx, rows));
    push(ladders::ladder_speed_error(ctx, rows));
    push(ladders::ladder_result(ctx, rows));
    let ride = platforms::ride_frames(ctx, rows);
    push(ride.as_ref().map(|r| platforms::carry_drift(ctx, rows, r)));
    push(
        ride.as_ref()
            .map(|r| platforms::carry_airborne_frames(rows, r)),
    );
    push(platforms::push_penetration(ctx, &ground, rows));
    push(platforms::crush_count(ctx, &ground, rows));
    push(Some(walls::tunneled(ctx, rows)));
    push(idle::idle_drift(ctx, rows));
    out
}

/// A trace row's feet.
fn pos(r: &TraceRow) -> Vec2 {
    Vec2::new(r.x, r.y)
}

/// Whether the row stands on ground: grounded and not in the ladder state (a climber passing
/// through a ladder top is inside it by right, whatever its grounded flag says).
fn standing(r: &TraceRow) -> bool {
    r.is_grounded() && r.ladder == 0
}

/// The `ns_per_character_step` row of a timed scenario (see [`crate::scenario::time_scenario`]).
pub(crate) fn timing_row(
    level: &Level,
    spec: &ScenarioSpec,
    run: &crate::config::RunConfig,
    ns: f64,
) -> MetricRow {
    MetricRow {
        level: level.name.clone(),
        scenario: spec.name.clone(),
        backend: run.backend.backend().to_string(),
        config: run.label.clone(),
        metric: "ns_per_character_step",
        value: ns,
        unit: registry::unit("ns_per_character_step"),
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
    run: &crate::config::RunConfig,
) -> Result<Evaluation, crate::scenario::RunError> {
    evaluate_with(&mut crate::scenario::Runner::new(level), spec, run)
}

/// Runs `spec` on `run` with a runner that shares level geometry between runs, and measures it.
pub fn evaluate_with(
    runner: &mut crate::scenario::Runner,
    spec: &ScenarioSpec,
    run: &crate::config::RunConfig,
) -> Result<Evaluation, crate::scenario::RunError> {
    let trace = runner.run(spec, run)?;
    let metrics = with_context(runner.level(), spec, run, &trace, compute);
    Ok(Evaluation { trace, metrics })
}

/// A run recorded with its rows streamed into a [`RowStore`] (spilled to a temporary file past
/// its limit) and measured from there: what `platbench run` does, so that its memory does not
/// grow with the length of a scenario.
pub struct Recorded {
    /// The run's labels (its `rows` are empty: the rows are in `rows`).
    pub trace: Trace,
    /// The run's rows (one character's: the runner adds one).
    pub rows: Rows,
    /// The metrics that apply to the scenario.
    pub metrics: Vec<MetricRow>,
}

impl Recorded {
    /// Writes the rows as the trace's CSV (see [`Trace::write_csv`]).
    pub fn write_csv<W: std::io::Write>(&self, w: W) -> Result<(), csv::Error> {
        write_rows_csv(self.rows.frames().iter(), w)?;
        match self.rows.take_error() {
            Some(e) => Err(e.into()),
            None => Ok(()),
        }
    }
}

/// Why a recorded run failed.
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The controller refused or failed the run, or the harness refused its input.
    #[error(transparent)]
    Run(#[from] crate::scenario::RunError),
    /// The temporary file holding a long run's rows could not be written or read back.
    #[error(
        "cannot hold the run's rows in a temporary file in {} (set TMPDIR to a writable folder with room for 44 bytes a frame)",
        std::env::temp_dir().display()
    )]
    Spill(#[from] std::io::Error),
}

/// Runs `spec` on `run`, streaming its rows into `store`, and measures it from there (see
/// [`Recorded`]); the metrics are those [`evaluate_with`] gives, bit for bit.
pub fn evaluate_recorded(
    runner: &mut crate::scenario::Runner,
    spec: &ScenarioSpec,
    run: &crate::config::RunConfig,
    mut store: RowStore,
) -> Result<Recorded, RecordError> {
    // Row 0 and one per step; a time step out of range is refused before anything is reserved.
    if crate::limits::check_timing(spec.duration as f64, spec.dt as f64).is_ok() {
        store.reserve(crate::scenario::step_count(spec) + 1);
    }
    let trace = runner.record(spec, run, &mut |r| store.push(r))?;
    let rows = store.finish()?;
    let metrics = with_context(runner.level(), spec, run, &trace, |ctx| {
        compute_frames(ctx, rows.frames())
    });
    if let Some(e) = rows.take_error() {
        return Err(e.into());
    }
    Ok(Recorded {
        trace,
        rows,
        metrics,
    })
}

/// Calls `f` with the context the metrics read for `trace`, a run of `spec` on `run`: the
/// scenario's effective parameters, and the box the configuration really moves (integer
/// positions round it up to whole subpixels) with the contact it declares for it.
pub(crate) fn with_context<R>(
    level: &Level,
    spec: &ScenarioSpec,
    run: &crate::config::RunConfig,
    trace: &Trace,
    f: impl FnOnce(&Context) -> R,
) -> R {
    let params = crate::scenario::effective_params(&run.params, spec);
    let mut moved = spec.clone();
    moved.size = run.backend.moved_size(spec.size);
    f(&Context {
        shape: run.shape(),
        level,
        spec: &moved,
        params: &params,
        trace,
        declared: run.backend.declared_contact_in(
            moved.size,
            &params,
            spec.dt / run.substeps.max(1) as f32,
        ),
    })
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
            declared: DeclaredContact::default(),
        })
    }

    fn value(rows: &[MetricRow], m: &str) -> Option<f64> {
        rows.iter().find(|r| r.metric == m).map(|r| r.value)
    }

    #[test]
    fn every_computed_metric_is_in_the_registry() {
        // A walk and a rest: the metrics every scenario gets and the rest metrics. A metric
        // computed but not registered would print with no unit, in no table.
        let s = spec(Vec2::new(2.5, 1.0), vec![], 1.0);
        let rows = measure(&s, &trace(&[(2.5, 1.0, true); 11]));
        // A rest with no input gets the rest metrics and those of every scenario.
        let names: Vec<&str> = rows.iter().map(|r| r.metric).collect();
        assert_eq!(
            names,
            [
                "rest_gap",
                "rest_gap_declared",
                "max_penetration",
                "penetration_beyond_declared",
                "rest_jitter",
                "bounce_frames",
                "grounded_flicker",
                "false_grounded",
                "stuck_frames",
                "tunneled",
                "idle_drift"
            ]
        );
        for r in &rows {
            assert!(
                registry::get(r.metric).is_some(),
                "{} unregistered",
                r.metric
            );
            assert_eq!(r.unit, registry::unit(r.metric));
        }
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
        pts[4].1 = 0.97; // sank 0.03 into the floor while settling
        pts[8].1 = 0.99; // dips 0.01 in the last half second, at rest
        pts[10].1 = 1.02; // ends 0.02 above it
        let rows = measure(&s, &trace(&pts));
        assert!((value(&rows, "max_penetration").unwrap() - 0.03).abs() < 1e-6);
        assert!((value(&rows, "rest_gap").unwrap() - 0.02).abs() < 1e-6);
        // Jitter counts from the settled rest (the last 0.5 s, rows 6 to 10): 1.02 - 0.99. The
        // settling dip at row 4 is the landing's business, not the rest's.
        assert!((value(&rows, "rest_jitter").unwrap() - 0.03).abs() < 1e-6);
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
