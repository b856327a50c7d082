//! Speed versus accuracy: the scenario set run over a grid of settings, each setting's cost and
//! error, and the Pareto front of the settings no other beats on both.
//!
//! - **Cost**: microseconds of computation per character per second of game time (so a smaller
//!   dt or more substeps cost what they really cost), timed in process as the minimum of 3
//!   repeats of each scenario, averaged over the scenarios.
//! - **Error**: a [`Score`] of the setting's metric rows (by default the registry's weights,
//!   which charge no controller for its declared design; `platbench sweep --score` changes it):
//!   0 is every scored metric ideal, 1 every one clearly wrong. Timing rows are not part of it.
//!   Each setting has a row for the whole score (`scope = all`) and one per behaviour (the score
//!   of that behaviour's metrics), each with its own Pareto front.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};
use svg::node::element::{Circle, Line, Polyline, Text, Title};
use svg::Document;

pub use crate::config::Setting;
use crate::level::Level;
use crate::metrics::score::Score;
use crate::metrics::{evaluate_with, Behaviour, MetricRow};
use crate::registry::Registry;
use crate::scenario::RunError;
use crate::scenario::{time_scenario, Runner};

/// The grid of [`Registry::builtin`]: each setting varies one thing from the defaults (for the
/// sweep: dt from 1/30 to 1/480 s, substeps, epsilon, jump mode, integer positions; for
/// Rapier: dt, substeps, offset, snap distance, grounded feed, collider building and shape).
pub fn grid() -> Vec<Setting> {
    Registry::builtin().tradeoff_settings()
}

/// Colours of the chart's backends that the built-in registry does not know, in the order they
/// first appear in its rows.
pub const PALETTE: &[&str] = &[
    "#1565c0", "#2e7d32", "#6a1b9a", "#ef6c00", "#c62828", "#00838f",
];

/// The backends of `rows`, in the order they first appear.
fn backends_in_order(rows: &[TradeoffRow]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for r in rows {
        if !out.contains(&r.backend) {
            out.push(r.backend.clone());
        }
    }
    out
}

/// The colour of backend `name` among `backends`: its kind's own colour
/// ([`crate::controller::Controller::colour`], as the report's pictures draw it) for a built-in
/// kind, else the palette's by order.
fn backend_colour(backends: &[String], name: &str) -> String {
    if let Some(c) = Registry::builtin().get(name).and_then(|k| k.colour()) {
        return c.to_string();
    }
    let k = backends.iter().position(|b| b == name).unwrap_or(0);
    PALETTE[k % PALETTE.len()].to_string()
}

/// The aggregate error of a setting's metric rows under the default score (see
/// [`Score::default`]).
pub fn error_score(rows: &[MetricRow]) -> f64 {
    Score::default().error(rows)
}

/// The `scope` of a row that scores every behaviour.
pub const ALL: &str = "all";

fn all_scope() -> String {
    ALL.to_string()
}

/// The behaviours a setting gets a row of its own for (every one but cost).
pub fn scored_behaviours() -> impl Iterator<Item = Behaviour> {
    Behaviour::ALL.into_iter().filter(|b| *b != Behaviour::Cost)
}

/// One row of `tradeoff.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TradeoffRow {
    /// Backend name.
    pub backend: String,
    /// Setting label.
    pub setting: String,
    /// Microseconds per character per second of game time (mean over the scenarios of the
    /// minimum of 3 repeats).
    pub cost_us: f64,
    /// Aggregate error in 0..=1.
    pub error: f64,
    /// Whether no other setting is at least as cheap and as accurate, and better in one.
    pub pareto: bool,
    /// Scenarios measured: fewer than the others when the setting does not model some levels
    /// (the sweep's integer mode skips slopes and moving platforms); such a row is drawn but
    /// left out of the Pareto front, its figures being over another set.
    #[serde(default)]
    pub scenarios: usize,
    /// What `error` scores: [`ALL`], or one behaviour's key (`landing`, `slopes`...): the score
    /// of that behaviour's metrics alone. Fronts are marked within a scope.
    #[serde(default = "all_scope")]
    pub scope: String,
}

/// Runs every setting over the levels' scenarios and scores it with `score`, whole and per
/// behaviour; `progress` gets `(done, total, label)`. Runs on every core
/// ([`run_tradeoff_on`]).
pub fn run_tradeoff(
    levels: &[Level],
    settings: &[Setting],
    score: &Score,
    progress: impl FnMut(usize, usize, &str),
) -> Result<Vec<TradeoffRow>, RunError> {
    run_tradeoff_on(
        levels,
        settings,
        score,
        crate::parallel::default_jobs(),
        progress,
    )
}

/// [`run_tradeoff`] on `jobs` threads: the runs that give the metrics fan out over them (the
/// rows are the same whatever the number); the timing then runs on one thread, nothing beside
/// it.
pub fn run_tradeoff_on(
    levels: &[Level],
    settings: &[Setting],
    score: &Score,
    jobs: usize,
    progress: impl FnMut(usize, usize, &str),
) -> Result<Vec<TradeoffRow>, RunError> {
    let mut first = None;
    let rows = run_tradeoff_reporting(levels, settings, score, jobs, progress, |e| {
        first.get_or_insert_with(|| e.clone());
    })?;
    first.map_or(Ok(rows), Err)
}

/// [`run_tradeoff_on`] that goes on past a run that failed ([`RunError::is_failure`]: an
/// external controller that crashed, hung or answered out of protocol): `on_failure` hears each,
/// the setting it belongs to gets no row (a row over fewer scenarios would compare unlike
/// sets), and the other settings complete. Other errors end the sweep.
pub fn run_tradeoff_reporting(
    levels: &[Level],
    settings: &[Setting],
    score: &Score,
    jobs: usize,
    mut progress: impl FnMut(usize, usize, &str),
    mut on_failure: impl FnMut(&RunError),
) -> Result<Vec<TradeoffRow>, RunError> {
    // Each setting's scenarios, with the setting's time step: (setting, level, scenario).
    let spec_of = |s: &Setting, level: &Level, si: usize| {
        let mut spec = level.scenarios[si].clone();
        if let Some(dt) = s.dt {
            spec.dt = dt;
        }
        spec
    };
    let mut items: Vec<(usize, usize, usize)> = Vec::new();
    for k in 0..settings.len() {
        for (li, level) in levels.iter().enumerate() {
            for si in 0..level.scenarios.len() {
                items.push((k, li, si));
            }
        }
    }
    // The metrics, fanned out: None for a level the setting does not model (left out of its
    // row).
    let mut measured: Vec<Option<Vec<MetricRow>>> = Vec::with_capacity(items.len());
    let mut failed = vec![false; settings.len()];
    crate::parallel::for_each_ordered(
        jobs,
        items.len(),
        || None::<(usize, Runner)>,
        |cache, i| {
            let (k, li, si) = items[i];
            if cache.as_ref().is_none_or(|(l, _)| *l != li) {
                *cache = Some((li, Runner::new(&levels[li])));
            }
            let Some((_, runner)) = cache.as_mut() else {
                unreachable!("set just above")
            };
            let spec = spec_of(&settings[k], &levels[li], si);
            match evaluate_with(runner, &spec, &settings[k].run) {
                Err(e) if e.is_unsupported() => Ok(None),
                e => e.map(|e| Some(e.metrics)),
            }
        },
        |i, r| {
            match r {
                Ok(m) => measured.push(m),
                Err(e) if e.is_failure() => {
                    on_failure(&e);
                    failed[items[i].0] = true;
                    measured.push(None);
                }
                Err(e) => return Err(e),
            }
            Ok::<(), RunError>(())
        },
    )?;
    let mut out = Vec::new();
    let mut measured = measured.into_iter();
    for (k, s) in settings.iter().enumerate() {
        progress(k, settings.len(), &s.label);
        let mut rows = Vec::new();
        let (mut cost, mut n) = (0.0, 0usize);
        for level in levels {
            let mut runner = Runner::new(level);
            for si in 0..level.scenarios.len() {
                let Some(metrics) = measured.next().flatten() else {
                    continue;
                };
                if failed[k] {
                    continue;
                }
                rows.extend(metrics);
                let spec = spec_of(s, level, si);
                // ns per frame (its substeps included) over seconds per frame, in microseconds.
                match time_scenario(&mut runner, &spec, &s.run, 3) {
                    Ok(ns) => cost += ns / spec.dt as f64 / 1000.0,
                    Err(e) if e.is_failure() => {
                        on_failure(&e);
                        failed[k] = true;
                    }
                    Err(e) => return Err(e),
                }
                n += 1;
            }
        }
        if failed[k] {
            continue;
        }
        let row = |scope: &str, error: f64| TradeoffRow {
            backend: s.run.backend.backend().to_string(),
            setting: s.label.clone(),
            cost_us: cost / n.max(1) as f64,
            error,
            pareto: false,
            scenarios: n,
            scope: scope.to_string(),
        };
        out.push(row(ALL, score.error(&rows)));
        for b in scored_behaviours() {
            out.push(row(b.key(), score.error_of(&rows, b)));
        }
    }
    progress(settings.len(), settings.len(), "done");
    mark_pareto(&mut out);
    Ok(out)
}

/// Marks the rows no other row dominates (as cheap or cheaper and as accurate or more, and
/// strictly better in one).
/// Rows are compared only with rows of the same `scope`.
pub(crate) fn mark_pareto(rows: &mut [TradeoffRow]) {
    // Only rows measured over the whole scenario set are compared.
    let full = rows.iter().map(|r| r.scenarios).max().unwrap_or(0);
    let points: Vec<Option<(f64, f64)>> = rows
        .iter()
        .map(|r| (r.scenarios == full).then_some((r.cost_us, r.error)))
        .collect();
    let scopes: Vec<String> = rows.iter().map(|r| r.scope.clone()).collect();
    for (i, r) in rows.iter_mut().enumerate() {
        r.pareto = points[i].is_some_and(|(c, e)| {
            !points.iter().enumerate().any(|(j, p)| {
                scopes[j] == scopes[i]
                    && p.is_some_and(|(cj, ej)| j != i && cj <= c && ej <= e && (cj < c || ej < e))
            })
        });
    }
}

/// Cost (log scale) against the whole error score ([`ALL`]), one dot per setting, the Pareto
/// front joined.
pub fn chart_svg(rows: &[TradeoffRow]) -> String {
    chart_svg_scope(rows, ALL)
}

/// Cost (log scale) against the error of one `scope` ([`ALL`] or a behaviour's key), one dot
/// per setting, that scope's Pareto front joined.
pub(crate) fn chart_svg_scope(rows: &[TradeoffRow], scope: &str) -> String {
    let rows: Vec<TradeoffRow> = rows.iter().filter(|r| r.scope == scope).cloned().collect();
    let rows = &rows[..];
    let (w, h, m) = (720.0f64, 420.0f64, 60.0f64);
    let costs: Vec<f64> = rows.iter().map(|r| r.cost_us.max(1e-3).log10()).collect();
    let (c0, c1) = costs.iter().fold((f64::MAX, f64::MIN), |(a, b), &c| {
        (a.min(c.floor()), b.max(c.ceil()))
    });
    let e1 = rows
        .iter()
        .map(|r| r.error)
        .fold(0.0f64, f64::max)
        .max(1e-3)
        * 1.1;
    let x = |c: f64| m + (c - c0) / (c1 - c0).max(1e-9) * (w - 2.0 * m);
    let y = |e: f64| h - m - e / e1 * (h - 2.0 * m);
    let mut doc = Document::new()
        .set("width", w)
        .set("height", h)
        .set("viewBox", (0, 0, w, h))
        .set("class", "tradeoff");
    doc = doc
        .add(
            Line::new()
                .set("x1", m)
                .set("y1", h - m)
                .set("x2", w - m)
                .set("y2", h - m)
                .set("stroke", "#444"),
        )
        .add(
            Line::new()
                .set("x1", m)
                .set("y1", m)
                .set("x2", m)
                .set("y2", h - m)
                .set("stroke", "#444"),
        )
        .add(
            Text::new("microseconds per character per game second (log)")
                .set("x", w / 2.0 - 80.0)
                .set("y", h - 15.0)
                .set("font-size", 12),
        )
        .add(
            Text::new(if scope == ALL {
                "error score".to_string()
            } else {
                format!("error score: {scope}")
            })
            .set("x", 8)
            .set("y", m - 20.0)
            .set("font-size", 12),
        );
    for k in 0..=4 {
        let e = e1 * k as f64 / 4.0;
        doc = doc.add(
            Text::new(format!("{e:.3}"))
                .set("x", 18)
                .set("y", y(e) + 4.0)
                .set("font-size", 10),
        );
    }
    let backends = backends_in_order(rows);
    for (i, name) in backends.iter().enumerate() {
        let colour = backend_colour(&backends, name);
        let ly = 20.0 + 16.0 * i as f64;
        doc = doc
            .add(
                Circle::new()
                    .set("cx", w - 150.0)
                    .set("cy", ly)
                    .set("r", 4.0)
                    .set("fill", colour.as_str()),
            )
            .add(
                Text::new(name.as_str())
                    .set("x", w - 140.0)
                    .set("y", ly + 4.0)
                    .set("font-size", 11),
            );
    }
    doc = doc.add(
        Text::new("filled: Pareto front (dashed)")
            .set("x", w - 150.0)
            .set("y", 24.0 + 16.0 * backends.len() as f64)
            .set("font-size", 10),
    );
    let mut decade = c0;
    while decade <= c1 + 1e-9 {
        doc = doc.add(
            Text::new(format!("{}", 10f64.powf(decade)))
                .set("x", x(decade) - 10.0)
                .set("y", h - m + 16.0)
                .set("font-size", 10),
        );
        decade += 1.0;
    }
    let mut front: Vec<(f64, f64)> = rows
        .iter()
        .zip(&costs)
        .filter(|(r, _)| r.pareto)
        .map(|(r, c)| (x(*c), y(r.error)))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    doc = doc.add(
        Polyline::new()
            .set("points", front)
            .set("fill", "none")
            .set("stroke", "#888")
            .set("stroke-dasharray", "4,3"),
    );
    for (r, c) in rows.iter().zip(&costs) {
        let colour = backend_colour(&backends, &r.backend);
        let mut label = String::new();
        let _ = write!(
            label,
            "{} {}: {:.1} us/s, error {:.4}",
            r.backend, r.setting, r.cost_us, r.error
        );
        doc = doc.add(
            Circle::new()
                .set("cx", x(*c))
                .set("cy", y(r.error))
                .set("r", if r.pareto { 5.0 } else { 3.5 })
                .set("fill", if r.pareto { colour.as_str() } else { "white" })
                .set("stroke", colour)
                .add(Title::new(label)),
        );
        if r.pareto {
            doc = doc.add(
                Text::new(format!("{} {}", r.backend, r.setting))
                    .set("x", x(*c) + 7.0)
                    .set("y", y(r.error) - 6.0)
                    .set("font-size", 10),
            );
        }
    }
    doc.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(cost: f64, error: f64) -> TradeoffRow {
        TradeoffRow {
            backend: "sweep".into(),
            setting: format!("{cost}/{error}"),
            cost_us: cost,
            error,
            pareto: false,
            scenarios: 1,
            scope: ALL.into(),
        }
    }

    /// Each built-in backend is drawn in its kind's own colour, the one the report's pictures
    /// use (before, the chart gave Box2D the palette's third colour, #6a1b9a, not its #00838f).
    #[test]
    #[cfg(all(feature = "rapier", feature = "box2d"))]
    fn the_chart_draws_each_builtin_backend_in_its_own_colour() {
        let registry = Registry::builtin();
        let names: Vec<String> = registry
            .kinds()
            .iter()
            .map(|k| k.name().to_string())
            .collect();
        assert!(names.len() >= 3, "{names:?}");
        let rows: Vec<TradeoffRow> = names
            .iter()
            .map(|n| TradeoffRow {
                backend: n.clone(),
                ..row(1.0, 0.1)
            })
            .collect();
        let svg = chart_svg(&rows);
        for n in &names {
            let own = registry.colour(n);
            assert_eq!(backend_colour(&names, n), own, "{n}");
            assert!(svg.contains(own), "{n}: {own} not in the chart");
        }
    }

    #[test]
    fn a_row_over_fewer_scenarios_is_drawn_but_not_on_the_front() {
        let mut rows = vec![row(10.0, 0.5), row(20.0, 0.1), row(1.0, 0.01)];
        rows[2].scenarios = 0;
        mark_pareto(&mut rows);
        // The cheapest and most accurate row covers fewer scenarios: it dominates nothing.
        assert_eq!(
            rows.iter().map(|r| r.pareto).collect::<Vec<_>>(),
            vec![true, true, false]
        );
    }

    #[test]
    fn pareto_front_keeps_the_undominated() {
        let mut rows = vec![
            row(100.0, 0.1),
            row(200.0, 0.05),
            row(300.0, 0.2),
            row(100.0, 0.2),
        ];
        mark_pareto(&mut rows);
        let front: Vec<bool> = rows.iter().map(|r| r.pareto).collect();
        assert_eq!(front, vec![true, true, false, false]);
    }
}
