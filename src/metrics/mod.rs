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
//! `max_penetration`, `grounded_flicker`, `stuck_frames`, `tunneled` and `left_level` apply to
//! every scenario; the `expect_*` rows to the scenarios that state those expectations.
//! Only the scenario's character is measured (the trace's first character).

pub mod expect;
pub mod faults;
pub mod ground;
pub mod idle;
pub mod jumping;
pub mod ladders;
pub mod landing;
pub mod oneway;
pub mod platforms;
pub(crate) mod pushers;
mod reference;
pub mod registry;
pub mod score;
pub mod seams;
pub mod slopes;
pub(crate) mod timing;
pub mod walls;

pub use reference::{commanded_distance, commanded_steps, predicted_landing_frame};
pub use registry::{Behaviour, MetricDef, METRICS};
pub(crate) use timing::timing_row;

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
    /// The trace frame (the trace CSV's 0-based `frame` column) at which the value was reached
    /// or is best shown: the first frame of a maximum, the frame of an event, the first
    /// offending frame of a count, the last frame of an end state (each metric's function says
    /// which). `None` where no frame applies: a count of zero or an event that never happened
    /// has no offending frame, and a timing row comes from no frame. A column of
    /// `metrics.csv`, empty when `None` (files written before it have no such column).
    pub frame: Option<u32>,
    /// For a timing row (`ns_per_character_step`, whose value is the median of its samples),
    /// the samples' first quartile; `None` for every other metric. A column of `metrics.csv`
    /// after `frame`, empty when `None`.
    pub q1: Option<f64>,
    /// For a timing row, the samples' third quartile (`q3 - q1` is their interquartile range);
    /// `None` for every other metric. The last column of `metrics.csv`, empty when `None`.
    pub q3: Option<f64>,
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
    /// The trace frame the value was reached at or is best shown at (see [`MetricRow::frame`]).
    pub frame: Option<u32>,
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
                frame: m.frame,
                q1: None,
                q3: None,
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
    let pushers = pushers::Pushers::new(ctx, g);
    push(
        rest.clone()
            .map(|r| landing::rest_jitter(&pushers, rows, landing::settled(ctx, r))),
    );
    push(rest.map(|_| landing::bounce_frames(ctx, &pushers, rows)));
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
    push(platforms::push_penetration(ctx, &ground, &pushers, rows));
    push(platforms::crush_count(ctx, &ground, &pushers, rows));
    push(Some(walls::tunneled(ctx, rows)));
    push(idle::idle_drift(ctx, rows));
    push(Some(expect::left_level(ctx, rows)));
    push(expect::expect_reach(ctx, rows));
    push(expect::expect_grounded_at_end(ctx, rows));
    push(expect::expect_min_y(ctx, rows));
    push(expect::expect_stay_in_map(ctx, rows));
    push(expect::expect_land_on(ctx, rows));
    out
}

/// A running maximum of a per-frame value and the first frame that reached it: the value is
/// the fold `start.max(v0).max(v1)...` (bit for bit what `fold(start, f32::max)` gives), the
/// frame that of the first row at which it reached its final value (the first row pushed if no
/// row exceeded `start`). No allocation: a metric's pass over its rows keeps one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Peak {
    /// The maximum so far.
    pub(crate) value: f32,
    /// The frame that first reached it, `None` before the first row.
    pub(crate) frame: Option<u32>,
}

impl Peak {
    /// A maximum starting at `start` (the value when nothing exceeds it).
    pub(crate) fn new(start: f32) -> Self {
        Peak {
            value: start,
            frame: None,
        }
    }

    /// Takes in value `v` of frame `frame`.
    pub(crate) fn push(&mut self, frame: u32, v: f32) {
        if self.frame.is_none() || v > self.value {
            self.frame = Some(frame);
        }
        self.value = self.value.max(v);
    }
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
mod frame_tests;
#[cfg(test)]
mod pusher_tests;
#[cfg(test)]
mod tests;
