//! The verdict of `platbench check` per scenario and configuration: the diff's metric and
//! trace changes (see [`super::diff`]) gathered by the run they belong to, each run given one
//! status (pass, worse, better, diverged, missing, new), and written as the lines CI prints,
//! `check.csv` and a Markdown summary for a pull request.

use std::collections::HashMap;
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use super::diff::{Change, FailOn, MetricDiff, RunKey, TraceChange, TraceDiff};
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

/// What a run the new run lacks says: the runs `check` lists no more than
/// [`crate::limits::MAX_LISTED_CHANGES`] of (its new run's are the work it did).
const NOT_IN_NEW: &str = "not in the new run";

/// The metric changes of each run of the new run, gathered as the diff finds them
/// ([`super::diff::diff_runs_each`]): a count of each change and the first of each, so that a
/// baseline of any size costs memory in proportion to the new run, never to its own rows.
pub(crate) struct RunChanges {
    fail_on: FailOn,
    /// By `level.scenario`, then `backend config`, every run of the new run (two levels, so a
    /// diff's labels find their run without being copied).
    runs: HashMap<String, HashMap<String, Changed>>,
}

/// One run's changes: the first [`KEPT_PER_CHANGE`] metrics of each change, and how many.
#[derive(Default)]
struct Changed {
    kept: Vec<MetricDiff>,
    counts: [usize; 5],
}

/// How many metrics of each change a run keeps to name: as many as the metric catalog holds,
/// so that a run's every metric is named, and a file's made-up names stop there.
fn kept_per_change() -> usize {
    crate::metrics::registry::METRICS.len()
}

impl RunChanges {
    /// Ready to gather the changes of the runs `new`, judged under `fail_on` (a timing counts
    /// only with `fail_on.timing`).
    pub(crate) fn of_runs(new: &[RunKey], fail_on: FailOn) -> Self {
        let mut runs: HashMap<String, HashMap<String, Changed>> = HashMap::new();
        for [l, s, b, c] in new {
            runs.entry(format!("{l}.{s}"))
                .or_default()
                .insert(format!("{b} {c}"), Changed::default());
        }
        RunChanges { fail_on, runs }
    }

    /// Counts a metric's change to its run, if the run is the new run's.
    pub(crate) fn add(&mut self, m: &MetricDiff) {
        if !self.fail_on.timing && m.metric == "ns_per_character_step" {
            return;
        }
        // A run the new run lacks is not gathered.
        let Some(c) = self
            .runs
            .get_mut(m.scenario.as_str())
            .and_then(|r| r.get_mut(m.config.as_str()))
        else {
            return;
        };
        c.counts[m.change as usize] += 1;
        if c.counts[m.change as usize] <= kept_per_change() {
            c.kept.push(m.clone());
        }
    }
}

/// Every run of `base` and `new` (the baseline's order, then the new run's), each with its
/// status from the changes gathered in `changes` and the diff's `traces` under `fail_on`: a
/// divergence counts not with `fail_on.allow_divergence`, a missing metric or trace not with
/// `fail_on.allow_missing`. Changes are found per run by hash, so this takes time in
/// proportion to the runs and changes.
pub(crate) fn units(
    base: &[RunKey],
    new: &[RunKey],
    changes: &RunChanges,
    traces: &[TraceDiff],
    fail_on: FailOn,
) -> Vec<Unit> {
    use std::collections::HashSet;
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
    // The diff's traces by file (the first of a name).
    let mut trace_of: HashMap<&str, &TraceDiff> = HashMap::new();
    for t in traces {
        trace_of.entry(t.file.as_str()).or_insert(t);
    }
    let none = Changed::default();
    for u in &mut out {
        let key: RunKey = [
            u.level.clone(),
            u.scenario.clone(),
            u.backend.clone(),
            u.config.clone(),
        ];
        let (s, c) = u.labels();
        let changed = changes
            .runs
            .get(&s)
            .and_then(|r| r.get(&c))
            .unwrap_or(&none);
        let trace = trace_of.get(u.trace.as_str()).copied();
        (u.status, u.detail) = judge(
            in_base.contains(&key),
            in_new.contains(&key),
            changed,
            trace,
            fail_on,
        );
    }
    out
}

/// The units CI lists, in their order: every one but the runs the new run lacks past the
/// first [`crate::limits::MAX_LISTED_CHANGES`] of them; and how many of those are left out
/// (`check.csv` holds every run).
pub(crate) fn listed<'a>(units: impl IntoIterator<Item = &'a Unit>) -> (Vec<&'a Unit>, usize) {
    let (mut shown, mut absent, mut left) = (Vec::new(), 0usize, 0usize);
    for u in units {
        if u.status == Status::Missing && u.detail == NOT_IN_NEW {
            absent += 1;
            if absent > crate::limits::MAX_LISTED_CHANGES {
                left += 1;
                continue;
            }
        }
        shown.push(u);
    }
    (shown, left)
}

/// The line after a list that left out `left` runs the new run lacks.
pub(crate) fn left_out_line(left: usize) -> String {
    format!(
        "and {left} more runs of the baseline not in the new run (the first {} are listed; {} lists every run)",
        crate::limits::MAX_LISTED_CHANGES,
        UNITS_FILE
    )
}

/// The file of `check --out` that lists every run.
pub(crate) const UNITS_FILE: &str = "check.csv";

/// A value as the tables show it.
fn value(v: Option<f64>) -> String {
    v.map_or("-".into(), crate::report::format_value)
}

/// The status of a run and what changed, from its metric changes and its trace's.
fn judge(
    in_base: bool,
    in_new: bool,
    changed: &Changed,
    trace: Option<&TraceDiff>,
    fail_on: FailOn,
) -> (Status, String) {
    if !in_new {
        return (Status::Missing, NOT_IN_NEW.into());
    }
    if !in_base {
        return (Status::New, "not in the baseline".into());
    }
    let of = |c: Change| -> (Vec<&MetricDiff>, usize) {
        let kept = changed.kept.iter().filter(|m| m.change == c).collect();
        (kept, changed.counts[c as usize])
    };
    let list = |(ms, total): &(Vec<&MetricDiff>, usize)| {
        let mut text = ms
            .iter()
            .take(3)
            .map(|m| format!("{} {} -> {}", m.metric, value(m.base), value(m.new)))
            .collect::<Vec<_>>()
            .join(", ");
        if *total > 3 {
            let _ = write!(text, " and {} more", total - 3);
        }
        text
    };
    // The names of a change's metrics, every one kept, and how many more there are.
    let names = |(ms, total): &(Vec<&MetricDiff>, usize)| {
        let mut text = ms
            .iter()
            .map(|m| m.metric.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        if *total > ms.len() {
            let _ = write!(text, " and {} more", total - ms.len());
        }
        text
    };
    let worse = of(Change::Worse);
    if worse.1 > 0 {
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
    if missing.1 > 0 && !fail_on.allow_missing {
        return (
            Status::Missing,
            format!("not measured now: {}", names(&missing)),
        );
    }
    let better = of(Change::Better);
    if better.1 > 0 {
        return (Status::Better, list(&better));
    }
    let added = of(Change::Added);
    if added.1 > 0 || trace.is_some_and(|t| t.change == TraceChange::Added) {
        return (
            Status::New,
            if added.1 == 0 {
                "a trace the baseline lacks".into()
            } else {
                format!("measured now only: {}", names(&added))
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
    let (changed, left) = listed(units.iter().filter(|u| u.status != Status::Pass));
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
        if left > 0 {
            let _ = writeln!(md, "\n{}", left_out_line(left));
        }
        md.push_str("\n<details><summary>Every metric and trace that changed</summary>\n\n");
        md.push_str(diff_md.trim_end());
        md.push_str("\n\n</details>\n");
    }
    md
}
