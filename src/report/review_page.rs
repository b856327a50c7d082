//! The page `platbench review` writes for one changed run: its metrics in the baseline and now,
//! and the two traces replayed side by side in one picture (the report's replay: the level, both
//! paths, both characters, the controls). Self-contained: inline styles and script, nothing
//! fetched.

use std::fmt::Write as _;

use crate::config::RunConfig;
use crate::level::{Level, ScenarioSpec};
use crate::registry::Registry;
use crate::trace::Trace;

use super::replay::{escape, scenario_replay, styles, ReplayRun, ScenarioTraces};

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
    /// The baseline's trace.
    pub(crate) base: Option<Trace>,
    /// The new run's trace.
    pub(crate) new: Option<Trace>,
}

/// The page of `r`.
pub(crate) fn review_page(registry: &Registry, r: &ReviewRun) -> String {
    let mut traces: Vec<Trace> = Vec::new();
    let mut faults: Vec<Vec<u8>> = Vec::new();
    for (t, side) in [(&r.base, "baseline"), (&r.new, "new")] {
        let Some(t) = t else { continue };
        faults.push(crate::metrics::with_context(
            r.level,
            r.spec,
            r.run,
            t,
            crate::metrics::faults::frame_faults,
        ));
        let mut t = t.clone();
        t.config = format!("{} ({side})", t.config);
        traces.push(t);
    }
    let configs: Vec<(String, String)> = traces
        .iter()
        .map(|t| (t.backend.clone(), t.config.clone()))
        .collect();
    let styles = styles(registry, &configs);
    let scenario = ScenarioTraces {
        level: r.level,
        spec: r.spec,
        runs: traces
            .iter()
            .zip(faults)
            .map(|(trace, faults)| ReplayRun {
                trace,
                shape: r.run.shape(),
                size: r.run.backend.moved_size(r.spec.size),
                faults,
            })
            .collect(),
    };
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
    if scenario.runs.is_empty() {
        html.push_str("<p>No trace to replay: the baseline keeps none of this run (see its --traces) and the new run wrote none.</p>");
    } else {
        html.push_str("<p>The baseline's run and the new one, replayed together: <b>play</b>, drag the scrubber, or step with the arrow keys after clicking the picture; <b>configurations</b> picks the one shown.</p>");
        html.push_str(&super::html_nav::legend(&styles));
        let shown = configs.clone();
        let (replay, _) = scenario_replay(&r.id, &scenario, &styles, &shown);
        html.push_str(&replay);
        let _ = write!(html, "<script>{}</script>", super::replay::SCRIPT);
    }
    html.push_str("\n</body></html>\n");
    html
}
