//! Rendering a diff: the counts line and the tables of changed metrics and traces (Markdown-style
//! ASCII for a terminal, a CI log or a pull request), or the metric changes as CSV.

use super::compare::{Change, MetricDiff, RunDiff, TraceChange};

/// Output format of a diff.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffFormat {
    /// Tables for a terminal or a CI log.
    Text,
    /// Markdown, for a pull request (the same tables, which are Markdown already).
    Markdown,
    /// CSV of the metric changes, for machines.
    Csv,
}

/// A value, with the trace frame it was reached at when the run's `metrics.csv` gives one; a
/// timing (unit ns) to three significant figures with its samples' interquartile range when
/// the file gives its quartiles.
fn fmt_opt(
    metric: &str,
    v: Option<f64>,
    frame: Option<u32>,
    quartiles: (Option<f64>, Option<f64>),
) -> String {
    let unit = crate::metrics::registry::get(metric).map_or("", |d| d.unit);
    let value = |v: f64| crate::report::format_metric(v, unit);
    match (v, frame, quartiles) {
        (None, _, _) => "-".into(),
        (Some(v), _, (Some(q1), Some(q3))) if unit == "ns" => {
            format!("{} (IQR {}-{})", value(v), value(q1), value(q3))
        }
        (Some(v), None, _) => value(v),
        (Some(v), Some(f), _) => format!("{} (frame {f})", value(v)),
    }
}

fn fmt_pos(p: Option<(f32, f32)>) -> String {
    p.map_or("-".into(), |(x, y)| format!("({x}, {y})"))
}

/// Renders a diff: the metrics it lists ([`RunDiff::push`]) and the counts of every one; as
/// CSV the metrics it lists (`platbench diff --format csv` writes every one as found, with
/// [`super::diff_runs_each`]).
pub fn render(d: &RunDiff, format: DiffFormat) -> String {
    if format == DiffFormat::Csv {
        let mut w = csv::Writer::from_writer(Vec::new());
        for m in &d.metrics {
            let _ = w.serialize(m);
        }
        return w
            .into_inner()
            .ok()
            .and_then(|b| String::from_utf8(b).ok())
            .unwrap_or_default();
    }
    let mut out = String::new();
    let [worse, better, missing, added] = [
        Change::Worse,
        Change::Better,
        Change::Missing,
        Change::Added,
    ]
    .map(|c| d.counts.of(c));
    out.push_str(&format!(
        "{} metrics compared: {worse} worse, {better} better, {missing} missing, {added} added; {} traces compared, {} diverge or differ in presence\n",
        d.compared,
        d.traces_compared,
        d.traces.len()
    ));
    if d.timings_compared > 0 {
        out.push_str(&format!(
            "{} timings compared: worse or better only beyond both runs' noise (interquartile ranges apart, and the median moved by more than the timing tolerance)\n",
            d.timings_compared
        ));
    }
    if !d.metrics.is_empty() {
        let mut t = comfy_table::Table::new();
        // Markdown-style ASCII reads the same in a terminal, a CI log and a pull request.
        t.load_style(comfy_table::presets::ASCII_MARKDOWN);
        t.set_header(vec![
            "change",
            "scenario",
            "configuration",
            "metric",
            "base",
            "new",
        ]);
        let mut rows: Vec<&MetricDiff> = d.metrics.iter().collect();
        rows.sort_by_key(|m| {
            (
                m.change != Change::Worse && m.change != Change::Missing,
                m.scenario.clone(),
            )
        });
        for m in rows {
            let change = format!("{:?}", m.change).to_lowercase();
            t.add_row(vec![
                change,
                m.scenario.clone(),
                m.config.clone(),
                m.metric.clone(),
                fmt_opt(&m.metric, m.base, m.base_frame, (m.base_q1, m.base_q3)),
                fmt_opt(&m.metric, m.new, m.new_frame, (m.new_q1, m.new_q3)),
            ]);
        }
        out.push('\n');
        out.push_str(&t.to_string());
        out.push('\n');
        if d.unlisted() > 0 {
            out.push_str(&format!(
                "and {} more changed metrics not listed (the first {} of each change are); `platbench diff --format csv` lists every one\n",
                d.unlisted(),
                crate::limits::MAX_LISTED_CHANGES
            ));
        }
    }
    if !d.traces.is_empty() {
        let mut t = comfy_table::Table::new();
        t.load_style(comfy_table::presets::ASCII_MARKDOWN);
        t.set_header(vec![
            "trace",
            "first divergent frame",
            "base (x, y)",
            "new (x, y)",
        ]);
        for tr in &d.traces {
            t.add_row(vec![
                tr.file.clone(),
                match tr.change {
                    TraceChange::Missing => "missing from the new run".into(),
                    TraceChange::Added => "only in the new run".into(),
                    _ => tr.frame.map_or("-".into(), |f| f.to_string()),
                },
                fmt_pos(tr.base),
                fmt_pos(tr.new),
            ]);
        }
        out.push('\n');
        out.push_str(&t.to_string());
        out.push('\n');
    }
    out
}
