//! The page `platbench review` writes for one changed run: its metrics in the baseline and now,
//! and the two traces replayed side by side in one picture (the report's replay: the level, both
//! paths, both characters, the controls). Self-contained: inline styles and script, nothing
//! fetched.

use std::fmt::Write as _;

use std::path::Path;

use crate::config::RunConfig;
use crate::level::{Level, ScenarioSpec};
use crate::registry::Registry;
use crate::trace::{Trace, TraceRow};

use super::diff::{CsvRows, DiffError};
use super::replay::{draw_replay, escape, style_of, styles, Drawing, DrawnRun, Style};

/// One metric's row on the page.
pub(crate) struct MetricLine {
    /// Metric name.
    pub(crate) metric: String,
    /// Its value in the baseline, as shown.
    pub(crate) base: String,
    /// Its value now, as shown.
    pub(crate) new: String,
    /// Whether it differs.
    pub(crate) changed: bool,
}

/// What the page shows: the run, what changed, its metrics and its two traces (either may be
/// absent: a run new or gone, or a baseline without traces).
pub(crate) struct ReviewRun<'a> {
    /// The level run.
    pub(crate) level: &'a Level,
    /// The scenario.
    pub(crate) spec: &'a ScenarioSpec,
    /// The configuration (its shape and moved size draw the character).
    pub(crate) run: &'a RunConfig,
    /// `level.scenario/backend config`.
    pub(crate) id: String,
    /// The status and what changed, in a few words.
    pub(crate) headline: String,
    /// Its metrics.
    pub(crate) metrics: Vec<MetricLine>,
    /// The baseline's trace file (left out when it cannot be read as a trace).
    pub(crate) base: &'a Path,
    /// The new run's trace file (the same).
    pub(crate) new: &'a Path,
}

/// What a first pass over a trace file found: the rows of character 0 (the one drawn) and the
/// character of its first row (whose rows the faults are of, [`crate::metrics::faults`]).
struct Counted {
    drawn: usize,
    measured: u32,
}

/// Reads the trace at `path` a row at a time, calling `each` with every row; `None` when it
/// cannot be opened or a row does not read as a trace row. An empty file is a trace of no
/// rows. Memory is one row's, whatever the trace's length.
fn stream_trace(path: &Path, mut each: impl FnMut(TraceRow)) -> Option<()> {
    let mut rows = match CsvRows::open(path, "trace") {
        Ok(rows) => rows,
        Err(DiffError::Empty { .. }) => return Some(()),
        Err(_) => return None,
    };
    while let Some(r) = rows.next_row::<TraceRow>().ok()? {
        each(r);
    }
    Some(())
}

/// The first pass over a trace file ([`Counted`]).
fn count(path: &Path) -> Option<Counted> {
    let mut c = Counted {
        drawn: 0,
        measured: 0,
    };
    let mut first = true;
    stream_trace(path, |r| {
        if first {
            c.measured = r.character;
            first = false;
        }
        c.drawn += usize::from(r.character == 0);
    })?;
    Some(c)
}

/// The page of `r`. Each trace is read twice a row at a time (its length, then its drawn
/// frames, the box around its path and its faults), never held whole: a trace of millions of
/// frames is drawn in the memory of its [`super::replay::MAX_DRAWN_FRAMES`] drawn frames.
pub(crate) fn review_page(registry: &Registry, r: &ReviewRun) -> String {
    let (backend, config) = (r.run.backend.backend(), r.run.label.as_str());
    let read: Vec<(&Path, String, Counted)> = [(r.base, "baseline"), (r.new, "new")]
        .into_iter()
        .filter_map(|(p, side)| Some((p, format!("{config} ({side})"), count(p)?)))
        .collect();
    let configs: Vec<(String, String)> = read
        .iter()
        .map(|(_, c, _)| (backend.to_string(), c.clone()))
        .collect();
    let styles = styles(registry, &configs);
    let runs: Vec<(&Path, &str, &Counted, &Style)> = read
        .iter()
        .filter_map(|(p, c, n)| Some((*p, c.as_str(), n, style_of(&styles, backend, c)?)))
        .collect();
    let drawing = Drawing::of(runs.iter().map(|(_, _, n, _)| n.drawn).max().unwrap_or(0));
    let size = r.run.backend.moved_size(r.spec.size);
    let drawn: Vec<(DrawnRun, &Style)> = runs
        .iter()
        .map(|(path, c, n, style)| {
            let mut b = drawing.run(size);
            // The metrics' context, without the rows: the faults are found a row at a time.
            let labels = Trace {
                level: r.level.name.clone(),
                scenario: r.spec.name.clone(),
                backend: backend.to_string(),
                config: c.to_string(),
                rows: Vec::new(),
            };
            crate::metrics::with_context(r.level, r.spec, r.run, &labels, |ctx| {
                let mut scan = crate::metrics::faults::fault_scan(ctx);
                // A file changed between the two passes is drawn as far as it reads.
                let _ = stream_trace(path, |row| {
                    if row.character == n.measured {
                        b.fault(scan(row));
                    }
                    if row.character == 0 {
                        b.row(row);
                    }
                });
            });
            (b.finish(backend, c, r.run.shape()), *style)
        })
        .collect();
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>platbench review: {}</title><style>{}{}</style></head><body><h1>{}</h1><p class=\"lead\">{}</p>",
        escape(&r.id),
        super::html_nav::PAGE_STYLE,
        super::replay::STYLE,
        escape(&r.id),
        escape(&r.headline)
    );
    html.push_str("<table><thead><tr><th>metric</th><th>baseline</th><th>new</th><th></th></tr></thead><tbody>");
    for m in &r.metrics {
        let _ = write!(
            html,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(&m.metric),
            escape(&m.base),
            escape(&m.new),
            if m.changed { "changed" } else { "" }
        );
    }
    html.push_str("</tbody></table>");
    if read.is_empty() {
        html.push_str("<p>No trace to replay: the baseline keeps none of this run (see its --traces) and the new run wrote none.</p>");
    } else {
        html.push_str("<p>The baseline's run and the new one, replayed together: <b>play</b>, drag the scrubber, or step with the arrow keys after clicking the picture; <b>configurations</b> picks the one shown.</p>");
        html.push_str(&super::html_nav::legend(&styles));
        let (replay, _) = draw_replay(&r.id, r.level, r.spec, &drawn, &drawing, &configs);
        html.push_str(&replay);
        let _ = write!(html, "<script>{}</script>", super::replay::SCRIPT);
    }
    html.push_str("\n</body></html>\n");
    html
}
