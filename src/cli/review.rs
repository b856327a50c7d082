//! `platbench review CHECK_DIR`: each run a check found changed, its metrics in the baseline
//! and now and a page replaying the two traces side by side; accepted or rejected one by one
//! at a terminal, or all at once by flags. Accepted runs replace their part of the baseline
//! (`review_apply`).

use std::collections::{HashMap, HashSet};
use std::io::{BufRead as _, IsTerminal as _, Write as _};
use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::baseline::{baseline_dir, run_args_of, selection_of};
use super::check::{CheckRecord, UNITS};
use super::{out, output, Harness};
use crate::report::check::{line, Status, Unit};
use crate::report::diff::{read_metrics_where, MetricRecord};
use crate::report::manifest::Manifest;
use crate::report::review_page::{review_page, MetricLine, ReviewRun};

/// `platbench review`'s options.
#[derive(Args)]
pub(crate) struct ReviewArgs {
    /// The output of `platbench check --out` to review.
    #[arg(value_name = "CHECK_DIR", default_value = "platbench-check")]
    pub(crate) check: PathBuf,
    /// The baseline directory (placeholder; the harness sets the real help). It must be the
    /// baseline the check ran against (its check.toml names it); any other is refused.
    #[arg(long = "baseline", value_name = "DIR")]
    pub(crate) baseline: Option<PathBuf>,
    /// Accept every change without asking.
    #[arg(long, conflicts_with_all = ["accept", "reject_all"])]
    pub(crate) accept_all: bool,
    /// Accept the changes whose `LEVEL.SCENARIO/BACKEND CONFIG` matches PATTERN (a glob with
    /// `*` and `?` when it has one, else a substring), reject the others, without asking.
    /// Repeatable. An empty PATTERN is refused; one that matches no change is a warning on
    /// stderr (the review still succeeds, accepting what the others matched).
    #[arg(long = "accept", value_name = "PATTERN", conflicts_with = "reject_all")]
    pub(crate) accept: Vec<String>,
    /// Reject every change without asking: only list them and write their pages.
    #[arg(long)]
    pub(crate) reject_all: bool,
}

/// Whether `text` matches `pattern`: a glob (`*` any run of characters, `?` one) when the
/// pattern has either, else a substring.
pub(crate) fn matches(pattern: &str, text: &str) -> bool {
    if !pattern.contains(['*', '?']) {
        return text.contains(pattern);
    }
    fn glob(p: &[char], t: &[char]) -> bool {
        match p.split_first() {
            None => t.is_empty(),
            Some(('*', rest)) => (0..=t.len()).any(|i| glob(rest, &t[i..])),
            Some(('?', rest)) => !t.is_empty() && glob(rest, &t[1..]),
            Some((c, rest)) => t.first() == Some(c) && glob(rest, &t[1..]),
        }
    }
    let (p, t): (Vec<char>, Vec<char>) = (pattern.chars().collect(), text.chars().collect());
    glob(&p, &t)
}

/// What to do with the changes still to see.
#[derive(Clone, Copy, PartialEq)]
enum Answer {
    Accept,
    Reject,
    AcceptRest,
    RejectRest,
    Quit,
}

fn ask(id: &str) -> Result<Answer> {
    let stdin = std::io::stdin();
    loop {
        print!("accept {id} into the baseline? [y]es [n]o [a]ccept the rest [r]eject the rest [q]uit, changing nothing: ");
        let _ = std::io::stdout().flush();
        let mut answer = String::new();
        if stdin
            .lock()
            .read_line(&mut answer)
            .context("cannot read stdin")?
            == 0
        {
            return Ok(Answer::RejectRest);
        }
        match answer.trim() {
            "y" | "yes" => return Ok(Answer::Accept),
            "n" | "no" => return Ok(Answer::Reject),
            "a" => return Ok(Answer::AcceptRest),
            "r" => return Ok(Answer::RejectRest),
            "q" => return Ok(Answer::Quit),
            _ => println!("answer y, n, a, r or q"),
        }
    }
}

/// The run of `u`: level, scenario, backend, configuration.
fn run_of(u: &Unit) -> [&str; 4] {
    [&u.level, &u.scenario, &u.backend, &u.config]
}

/// `rows` by their run, each run's in file order.
fn by_run(rows: &[MetricRecord]) -> HashMap<[&str; 4], Vec<&MetricRecord>> {
    let mut out: HashMap<[&str; 4], Vec<&MetricRecord>> = HashMap::new();
    for r in rows {
        out.entry([&r.level, &r.scenario, &r.backend, &r.config])
            .or_default()
            .push(r);
    }
    out
}

/// The metrics of `u`, the baseline's beside the check's, in the baseline's order.
fn metric_lines(base: &[&MetricRecord], new: &[&MetricRecord]) -> Vec<MetricLine> {
    let show = |r: Option<&&MetricRecord>| {
        r.map_or("-".to_string(), |r| crate::report::format_value(r.value))
    };
    // Each side's first row of each metric, found by hash.
    fn first<'a>(rows: &[&'a MetricRecord]) -> HashMap<&'a str, usize> {
        let mut m: HashMap<&str, usize> = HashMap::new();
        for (i, r) in rows.iter().enumerate() {
            m.entry(r.metric.as_str()).or_insert(i);
        }
        m
    }
    let (in_base, in_new) = (first(base), first(new));
    let mut names: Vec<&str> = base.iter().map(|r| r.metric.as_str()).collect();
    let mut listed: HashSet<&str> = names.iter().copied().collect();
    for r in new {
        if listed.insert(&r.metric) {
            names.push(&r.metric);
        }
    }
    names
        .into_iter()
        .map(|m| {
            let (b, n) = (
                in_base.get(m).map(|&i| &base[i]),
                in_new.get(m).map(|&i| &new[i]),
            );
            MetricLine {
                metric: m.to_string(),
                base: show(b),
                new: show(n),
                changed: b.map(|r| r.value.to_bits()) != n.map(|r| r.value.to_bits()),
            }
        })
        .collect()
}

pub(crate) fn review(h: &Harness, args: &ReviewArgs) -> Result<()> {
    let flags = args.accept_all || args.reject_all || !args.accept.is_empty();
    if !flags && !std::io::stdin().is_terminal() {
        bail!("review asks about each change on a terminal, and stdin is not one; pass --accept-all, --accept PATTERN or --reject-all to decide without asking");
    }
    if args.accept.iter().any(String::is_empty) {
        bail!("--accept '': an empty pattern would match every change; pass --accept-all to accept them all");
    }
    if !args.check.is_dir() {
        let found = match std::fs::metadata(&args.check) {
            Ok(_) => "is not a directory",
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => "does not exist",
            Err(_) => "cannot be read",
        };
        bail!(
            "{} {found}; expected the --out directory of `platbench check`",
            args.check.display()
        );
    }
    let marker = output::read_marker(&args.check);
    if marker.lines().next() != Some("platbench check") {
        bail!(
            "{} is not the output of `platbench check --out` (its {} file does not say `platbench check`)",
            args.check.display(),
            output::MARKER
        );
    }
    let units_path = args.check.join(UNITS);
    // A trace is named by its run; a row naming another file (`../x.csv`, an absolute path)
    // would have the review replace a file outside the baseline.
    let units: Vec<Unit> = super::read_rows_checked(&units_path, usize::MAX, |u: &Unit, line| {
        let named = crate::report::check::trace_name(&u.level, &u.scenario, &u.backend, &u.config);
        if u.trace != named {
            bail!(
                "{}:{line}: the run {} names the trace {}; expected {named:?}, the name `platbench check` gives its trace (was the file edited? run the check again)",
                units_path.display(),
                u.id(),
                crate::input::quoted(&u.trace)
            );
        }
        Ok(())
    })?;
    let base = baseline_dir(h, args.baseline.as_deref());
    // Held until the review returns: two reviews at once would each write the baseline they
    // read, and the later would lose the earlier's acceptances.
    let _lock = super::review_apply::Lock::take(&base)?;
    let manifest = Manifest::read(&base)?;
    let (ran, now) = (CheckRecord::read(&args.check)?, CheckRecord::of(&base)?);
    if ran.baseline != now.baseline {
        bail!(
            "{} ran against the baseline {}, not {}; its changes are accepted only into the baseline it ran against: pass --baseline {} (or run the check again against {})",
            args.check.display(),
            ran.baseline,
            now.baseline,
            ran.baseline,
            now.baseline
        );
    }
    if ran.manifest != now.manifest {
        bail!(
            "the baseline {} changed since {} ran against it (its {} is not the one the check saw: the baseline was written again); run the check again",
            now.baseline,
            args.check.display(),
            crate::report::manifest::FILE
        );
    }
    let changed: Vec<&Unit> = units.iter().filter(|u| u.status != Status::Pass).collect();
    if changed.is_empty() {
        out(&format!(
            "nothing to review: every run of {} passed",
            args.check.display()
        ));
        return Ok(());
    }
    // Only the rows of the runs shown are kept, each file read a row at a time.
    let shown: HashSet<[&str; 4]> = changed.iter().map(|u| run_of(u)).collect();
    let (base_rows, new_rows) = (
        read_metrics_where(&base, |k| shown.contains(&k))?,
        read_metrics_where(&args.check, |k| shown.contains(&k))?,
    );
    let (base_rows, new_rows) = (by_run(&base_rows), by_run(&new_rows));
    // The levels and configurations draw the pages; without them the pages are left out.
    let selection = selection_of(h, &manifest, &run_args_of(&manifest, None));
    if let Err(e) = &selection {
        eprintln!("warning: no replay pages: {e:#}");
    }
    let pages = args.check.join("review");
    std::fs::create_dir_all(&pages)
        .with_context(|| format!("cannot create {}", pages.display()))?;
    let mut accepted: Vec<&Unit> = Vec::new();
    let mut rest: Option<bool> = None;
    for u in &changed {
        let (b, n) = (
            base_rows.get(&run_of(u)).cloned().unwrap_or_default(),
            new_rows.get(&run_of(u)).cloned().unwrap_or_default(),
        );
        let metrics = metric_lines(&b, &n);
        let mut table = comfy_table::Table::new();
        table.load_style(comfy_table::presets::ASCII_MARKDOWN);
        table.set_header(vec!["metric", "baseline", "new", ""]);
        for m in &metrics {
            table.add_row(vec![
                m.metric.clone(),
                m.base.clone(),
                m.new.clone(),
                if m.changed {
                    "changed".into()
                } else {
                    String::new()
                },
            ]);
        }
        out(&format!("\n{}\n{table}", line(u)));
        if let Ok((levels, configs, _)) = &selection {
            let level = levels.iter().find(|l| l.name == u.level);
            let spec = level.and_then(|l| l.scenarios.iter().find(|s| s.name == u.scenario));
            let run = configs
                .iter()
                .find(|c| c.backend.backend() == u.backend && c.label == u.config);
            if let (Some(level), Some(spec), Some(run)) = (level, spec, run) {
                let traces = (
                    base.join("traces").join(&u.trace),
                    args.check.join("traces").join(&u.trace),
                );
                let page = review_page(
                    &h.registry,
                    &ReviewRun {
                        level,
                        spec,
                        run,
                        id: u.id(),
                        headline: line(u),
                        metrics,
                        base: &traces.0,
                        new: &traces.1,
                    },
                );
                let path = pages.join(u.trace.replace(".csv", ".html"));
                output::write_file(&path, page.as_bytes())?;
                out(&format!("replay: {}", path.display()));
            }
        }
        let yes = if args.accept_all {
            true
        } else if args.reject_all {
            false
        } else if !args.accept.is_empty() {
            let id = u.id();
            args.accept.iter().any(|p| matches(p, &id))
        } else if let Some(r) = rest {
            r
        } else {
            match ask(&u.id())? {
                Answer::Accept => true,
                Answer::Reject => false,
                Answer::AcceptRest => {
                    rest = Some(true);
                    true
                }
                Answer::RejectRest => {
                    rest = Some(false);
                    false
                }
                Answer::Quit => {
                    out("quit: the baseline is unchanged");
                    return Ok(());
                }
            }
        };
        out(if yes { "accepted" } else { "rejected" });
        if yes {
            accepted.push(u);
        }
    }
    for p in &args.accept {
        if !changed.iter().any(|u| matches(p, &u.id())) {
            eprintln!(
                "warning: --accept {p:?} matches no change of {}",
                args.check.display()
            );
        }
    }
    super::review_apply::accept(&base, &args.check, &accepted)?;
    // The baseline's manifest may have taken the check's levels: the check still ran against
    // this baseline, for a later review of the changes rejected now.
    let after = CheckRecord::of(&base)?;
    if after != now {
        after.write(&args.check)?;
    }
    out(&format!(
        "\n{} of {} changes accepted into {}; {} rejected (the baseline keeps them as they were)",
        accepted.len(),
        changed.len(),
        base.display(),
        changed.len() - accepted.len()
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::matches;

    #[test]
    fn patterns_are_globs_or_substrings() {
        let id = "plain.drop/toy flush";
        assert!(matches("plain.drop", id));
        assert!(matches("plain.*/toy *", id));
        assert!(matches("*flush", id));
        assert!(!matches("*walk*", id));
        assert!(!matches("plain.dro?", id));
        assert!(matches("plain.dro?/*", id));
    }
}
