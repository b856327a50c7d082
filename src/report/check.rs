//! The verdict of `platbench check` per scenario and configuration: the diff's metric and
//! trace changes (see [`super::diff`]) gathered by the run they belong to, each run given one
//! status (pass, worse, better, diverged, missing, new), and written as the lines CI prints,
//! `check.csv` and a Markdown summary for a pull request.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::diff::{Change, FailOn, MetricDiff, RunDiff, RunKey, TraceChange, TraceDiff};
use crate::trace::Trace;

/// What happened to one scenario on one configuration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum Status {
    /// Every metric within its tolerance, the trace the same.
    Pass,
    /// A metric got worse beyond its tolerance.
    Worse,
    /// Metrics got better beyond their tolerance, none worse, the trace the same.
    Better,
    /// The trace diverges beyond the position tolerance or ends early; no metric worse.
    Diverged,
    /// In the baseline, not in the new run (or some of its metrics or its trace are not).
    Missing,
    /// In the new run only (or with metrics or a trace the baseline lacks).
    New,
}

impl Status {
    /// The word CI prints.
    pub(crate) fn word(self) -> &'static str {
        match self {
            Status::Pass => "pass",
            Status::Worse => "worse",
            Status::Better => "better",
            Status::Diverged => "diverged",
            Status::Missing => "missing",
            Status::New => "new",
        }
    }

    /// Whether it fails the check.
    pub(crate) fn fails(self) -> bool {
        matches!(self, Status::Worse | Status::Diverged | Status::Missing)
    }
}

/// One scenario on one configuration: a row of `check.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub(crate) struct Unit {
    /// Level name.
    pub(crate) level: String,
    /// Scenario name.
    pub(crate) scenario: String,
    /// Backend name.
    pub(crate) backend: String,
    /// Configuration label.
    pub(crate) config: String,
    /// Its status.
    pub(crate) status: Status,
    /// Its trace file name inside `traces/`.
    pub(crate) trace: String,
    /// What changed, in a few words (empty on a pass).
    pub(crate) detail: String,
}

impl Unit {
    /// `level.scenario/backend config`: what `review --accept` matches.
    pub(crate) fn id(&self) -> String {
        format!(
            "{}.{}/{} {}",
            self.level, self.scenario, self.backend, self.config
        )
    }

    /// `level.scenario` and `backend config`, as the diff labels its rows.
    fn labels(&self) -> (String, String) {
        (
            format!("{}.{}", self.level, self.scenario),
            format!("{} {}", self.backend, self.config),
        )
    }
}

/// The trace file name of a run.
pub(crate) fn trace_name(level: &str, scenario: &str, backend: &str, config: &str) -> String {
    Trace {
        level: level.into(),
        scenario: scenario.into(),
        backend: backend.into(),
        config: config.into(),
        rows: Vec::new(),
    }
    .file_name()
}

/// Every run of `base` and `new` (the baseline's order, then the new run's), each with its
/// status from the diff `d` of the two under `fail_on`: a timing counts only with
/// `fail_on.timing`, a divergence not with `fail_on.allow_divergence`, a missing metric or
/// trace not with `fail_on.allow_missing`. The diff's changes are found per run by hash, so
/// this takes time in proportion to the runs and changes.
pub(crate) fn units(base: &[RunKey], new: &[RunKey], d: &RunDiff, fail_on: FailOn) -> Vec<Unit> {
    use std::collections::{HashMap, HashSet};
    let mut out: Vec<Unit> = Vec::new();
    let in_base: HashSet<&RunKey> = base.iter().collect();
    let in_new: HashSet<&RunKey> = new.iter().collect();
    let mut seen = HashSet::new();
    for key in base.iter().chain(new) {
        if seen.insert(key) {
            let [level, scenario, backend, config] = key;
            out.push(Unit {
                level: level.clone(),
                scenario: scenario.clone(),
                backend: backend.clone(),
                config: config.clone(),
                status: Status::Pass,
                trace: trace_name(level, scenario, backend, config),
                detail: String::new(),
            });
        }
    }
    // The diff's metric changes by the labels of their run, in the diff's order; its traces'
    // by file (the first of a name).
    let mut metrics_of: HashMap<(&str, &str), Vec<&MetricDiff>> = HashMap::new();
    for m in &d.metrics {
        metrics_of
            .entry((m.scenario.as_str(), m.config.as_str()))
            .or_default()
            .push(m);
    }
    let mut trace_of: HashMap<&str, &TraceDiff> = HashMap::new();
    for t in &d.traces {
        trace_of.entry(t.file.as_str()).or_insert(t);
    }
    for u in &mut out {
        let key: RunKey = [
            u.level.clone(),
            u.scenario.clone(),
            u.backend.clone(),
            u.config.clone(),
        ];
        let (s, c) = u.labels();
        let metrics: Vec<&MetricDiff> = metrics_of
            .get(&(s.as_str(), c.as_str()))
            .into_iter()
            .flatten()
            .copied()
            .filter(|m| fail_on.timing || m.metric != "ns_per_character_step")
            .collect();
        let trace = trace_of.get(u.trace.as_str()).copied();
        (u.status, u.detail) = judge(
            in_base.contains(&key),
            in_new.contains(&key),
            &metrics,
            trace,
            fail_on,
        );
    }
    out
}

/// A value as the tables show it.
fn value(v: Option<f64>) -> String {
    v.map_or("-".into(), crate::report::format_value)
}

/// The status of a run and what changed, from its metric changes and its trace's.
fn judge(
    in_base: bool,
    in_new: bool,
    metrics: &[&MetricDiff],
    trace: Option<&TraceDiff>,
    fail_on: FailOn,
) -> (Status, String) {
    if !in_new {
        return (Status::Missing, "not in the new run".into());
    }
    if !in_base {
        return (Status::New, "not in the baseline".into());
    }
    let of =
        |c: Change| -> Vec<&&MetricDiff> { metrics.iter().filter(|m| m.change == c).collect() };
    let list = |ms: &[&&MetricDiff]| {
        let mut text = ms
            .iter()
            .take(3)
            .map(|m| format!("{} {} -> {}", m.metric, value(m.base), value(m.new)))
            .collect::<Vec<_>>()
            .join(", ");
        if ms.len() > 3 {
            let _ = write!(text, " and {} more", ms.len() - 3);
        }
        text
    };
    let worse = of(Change::Worse);
    if !worse.is_empty() {
        return (Status::Worse, list(&worse));
    }
    if let Some(t) = trace {
        let at = |p: Option<(f32, f32)>| p.map_or("-".into(), |(x, y)| format!("({x}, {y})"));
        match t.change {
            TraceChange::Diverged | TraceChange::Truncated if !fail_on.allow_divergence => {
                let what = if t.change == TraceChange::Diverged {
                    "the trace diverges"
                } else {
                    "the trace ends early or runs on"
                };
                return (
                    Status::Diverged,
                    format!(
                        "{what} at frame {}: {} in the baseline, {} now",
                        t.frame.map_or("-".into(), |f| f.to_string()),
                        at(t.base),
                        at(t.new)
                    ),
                );
            }
            TraceChange::Missing if !fail_on.allow_missing => {
                return (Status::Missing, "its trace is not in the new run".into());
            }
            _ => {}
        }
    }
    let missing = of(Change::Missing);
    if !missing.is_empty() && !fail_on.allow_missing {
        let names: Vec<&str> = missing.iter().map(|m| m.metric.as_str()).collect();
        return (
            Status::Missing,
            format!("not measured now: {}", names.join(", ")),
        );
    }
    let better = of(Change::Better);
    if !better.is_empty() {
        return (Status::Better, list(&better));
    }
    let added = of(Change::Added);
    if !added.is_empty() || trace.is_some_and(|t| t.change == TraceChange::Added) {
        let names: Vec<&str> = added.iter().map(|m| m.metric.as_str()).collect();
        return (
            Status::New,
            if names.is_empty() {
                "a trace the baseline lacks".into()
            } else {
                format!("measured now only: {}", names.join(", "))
            },
        );
    }
    (Status::Pass, String::new())
}

/// The line CI prints for a run.
pub(crate) fn line(u: &Unit) -> String {
    let mut s = format!(
        "{:<8} {}.{} [{} {}]",
        u.status.word(),
        u.level,
        u.scenario,
        u.backend,
        u.config
    );
    if !u.detail.is_empty() {
        let _ = write!(s, ": {}", u.detail);
    }
    s
}

/// How many runs passed and failed, by status.
pub(crate) fn counts(units: &[Unit]) -> (usize, usize, String) {
    let n = |s: Status| units.iter().filter(|u| u.status == s).count();
    let failed = units.iter().filter(|u| u.status.fails()).count();
    let detail = format!(
        "{} worse, {} diverged, {} missing; {} better, {} new",
        n(Status::Worse),
        n(Status::Diverged),
        n(Status::Missing),
        n(Status::Better),
        n(Status::New)
    );
    (units.len() - failed, failed, detail)
}

/// The closing line: `N passed, N failed (...)`.
pub(crate) fn closing_line(units: &[Unit]) -> String {
    let (passed, failed, detail) = counts(units);
    format!("{passed} passed, {failed} failed ({detail})")
}

/// The Markdown summary for a pull-request comment: the closing line, the version notes, the
/// table of every run that did not pass, and the diff's own tables (`diff_md`).
pub(crate) fn summary_markdown(units: &[Unit], notes: &[String], diff_md: &str) -> String {
    let (_, failed, _) = counts(units);
    let mut md = format!(
        "## platbench check: {}\n\n**{}**\n",
        if failed == 0 { "pass" } else { "regression" },
        closing_line(units)
    );
    if !notes.is_empty() {
        md.push('\n');
        for n in notes {
            let _ = writeln!(md, "- {n}");
        }
    }
    let changed: Vec<&Unit> = units.iter().filter(|u| u.status != Status::Pass).collect();
    if !changed.is_empty() {
        md.push_str("\n| status | scenario | configuration | what changed |\n|---|---|---|---|\n");
        for u in changed {
            let _ = writeln!(
                md,
                "| {} | {}.{} | {} {} | {} |",
                u.status.word(),
                u.level,
                u.scenario,
                u.backend,
                u.config,
                u.detail.replace('|', "\\|")
            );
        }
        md.push_str("\n<details><summary>Every metric and trace that changed</summary>\n\n");
        md.push_str(diff_md.trim_end());
        md.push_str("\n\n</details>\n");
    }
    md
}
