//! `platbench check`: the CI command. Reads a baseline's manifest, runs the same selection,
//! compares the run with the baseline (`platbench diff`'s rules), prints one line per scenario
//! and configuration and a closing count, and writes the run (metrics, the traces of what
//! changed, `check.csv`, `summary.md`) to `--out`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::baseline::{baseline_dir, run_args_of, selection_of};
use super::{out, output, Harness};
use crate::report::check::{
    closing_line, left_out_line, line, listed, summary_markdown, units, RunChanges, Unit,
};
use crate::report::diff::{diff_runs_each, read_runs, render, DiffFormat, FailOn, Tolerance};
use crate::report::manifest::{content_hash, Manifest};

/// The file of `check --out` that lists every run with its status.
pub(crate) use crate::report::check::UNITS_FILE as UNITS;
/// The Markdown summary of `check --out`.
pub(crate) const SUMMARY: &str = "summary.md";
/// The file of `check --out` naming the baseline the check ran against.
pub(crate) const RECORD: &str = "check.toml";

/// What `check.toml` records: the baseline a check ran against, so that `review` accepts its
/// changes into that baseline only.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct CheckRecord {
    /// The baseline directory, canonical.
    pub(crate) baseline: String,
    /// [`content_hash`] of the baseline's `manifest.toml` when the check ran.
    pub(crate) manifest: String,
}

impl CheckRecord {
    /// The record of the baseline `base` as it is now.
    pub(crate) fn of(base: &Path) -> Result<CheckRecord> {
        let m = base.join(crate::report::manifest::FILE);
        let bytes = crate::limits::read_capped(&m)
            .with_context(|| format!("cannot read {}", m.display()))?;
        Ok(CheckRecord {
            baseline: output::canonical_lenient(base).display().to_string(),
            manifest: content_hash(&bytes),
        })
    }

    /// Reads `CHECK_DIR/check.toml`.
    pub(crate) fn read(check: &Path) -> Result<CheckRecord> {
        let p = check.join(RECORD);
        let text = crate::limits::read_text_capped(&p).with_context(|| {
            format!(
                "cannot read {} (a check by this platbench writes it, naming the baseline it ran against): run `platbench check` again",
                p.display()
            )
        })?;
        toml::from_str(&text).with_context(|| format!("{} is malformed", p.display()))
    }

    /// Writes `DIR/check.toml`.
    pub(crate) fn write(&self, dir: &Path) -> Result<()> {
        let text = toml::to_string(self).context("cannot serialise check.toml")?;
        output::write_file(
            &dir.join(RECORD),
            format!("# The baseline this check ran against: `platbench review` accepts into it only.\n{text}")
                .as_bytes(),
        )
    }
}

/// `platbench check`'s options.
#[derive(Args)]
#[command(allow_negative_numbers = true)]
pub(crate) struct CheckArgs {
    /// The baseline directory (placeholder; the harness sets the real help).
    #[arg(long = "baseline", value_name = "DIR")]
    pub(crate) baseline: Option<PathBuf>,
    /// Where the new run goes: DIR/metrics.csv (every metric), DIR/traces/ (the traces of the
    /// runs that did not pass), DIR/check.csv (every run's status) and DIR/summary.md (for a
    /// pull-request comment). Replaced as a whole, as `run --out` is (see --force); relative to
    /// the current directory.
    #[arg(long, value_name = "DIR", default_value = "platbench-check")]
    pub(crate) out: PathBuf,
    /// Replace --out even when it is not an earlier check's output (everything in it is
    /// deleted). A baseline is never replaced: not the baseline checked against (nor a
    /// directory inside it or holding it), nor any directory holding a manifest.toml that is not
    /// a check's.
    #[arg(long)]
    pub(crate) force: bool,
    /// Override a metric's tolerance, as `diff --tol`: METRIC=ABS or METRIC=ABS,REL (finite,
    /// >= 0). Repeatable.
    #[arg(long = "tol", value_name = "METRIC=ABS[,REL]")]
    pub(crate) tolerances: Vec<String>,
    /// Position difference at which a trace diverges, in tiles (finite and >= 0).
    #[arg(long, default_value_t = 1e-4, value_name = "TILES")]
    pub(crate) position_tolerance: f32,
    /// Fail when a timing got worse beyond its tolerance too (a baseline written with
    /// --timing); by default timings never fail.
    #[arg(long)]
    pub(crate) fail_on_timing: bool,
    /// Do not fail (exit 1) when a metric or trace of the baseline is missing from the new run,
    /// as `diff --allow-missing`; it is still listed.
    #[arg(long)]
    pub(crate) allow_missing: bool,
    /// Do not fail (exit 1) when a trace diverges beyond --position-tolerance or ends before
    /// (or runs past) the baseline's, as `diff --allow-divergence`; it is still listed.
    #[arg(long)]
    pub(crate) allow_divergence: bool,
    /// Threads to run on (default: the cores available); the output is the same whatever the
    /// number.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub(crate) jobs: Option<u32>,
    /// An external controller the baseline ran (a controller file, as `run --controller`;
    /// repeatable): give the same files the baseline was written with.
    #[arg(long = "controller", value_name = "FILE")]
    pub(crate) controllers: Vec<PathBuf>,
}

/// Parses `--tol` values as `diff` does.
fn tolerances(given: &[String]) -> Result<BTreeMap<String, Tolerance>> {
    let mut tols = BTreeMap::new();
    for t in given {
        let Some((m, v)) = t.split_once('=') else {
            bail!("--tol {t}: expected METRIC=ABS or METRIC=ABS,REL");
        };
        if crate::metrics::registry::get(m).is_none() {
            let names: Vec<&str> = crate::metrics::registry::METRICS
                .iter()
                .map(|d| d.name)
                .collect();
            bail!(
                "--tol {t}: no metric is named {m:?}; expected one of {}",
                names.join(", ")
            );
        }
        let mut parts = v.split(',').map(|x| x.trim().parse::<f64>());
        let abs = parts.next().and_then(|r| r.ok());
        let rel = parts.next().map_or(Some(0.0), |r| r.ok());
        match (abs, rel) {
            (Some(abs), Some(rel))
                if abs.is_finite() && abs >= 0.0 && rel.is_finite() && rel >= 0.0 =>
            {
                tols.insert(m.to_string(), Tolerance { abs, rel });
            }
            _ => bail!("--tol {t}: expected METRIC=ABS or METRIC=ABS,REL with finite numbers >= 0"),
        }
    }
    Ok(tols)
}

/// Refuses an --out that is the baseline `base`, lies inside it or holds it, or holds a
/// `manifest.toml` without being a check's output: whatever --force says, a baseline is never
/// replaced (even one whose marker file is gone).
fn refuse_baseline_as_out(base: &Path, out: &Path) -> Result<()> {
    let (b, o) = (
        output::canonical_lenient(base),
        output::canonical_lenient(out),
    );
    if o.starts_with(&b) || b.starts_with(&o) {
        bail!(
            "--out {} is the baseline {} checked against, or lies inside it or holds it; a baseline is never replaced: choose another --out",
            out.display(),
            base.display()
        );
    }
    let marker = output::read_marker(out);
    if out.join(crate::report::manifest::FILE).exists()
        && marker.lines().next() != Some("platbench check")
    {
        bail!(
            "--out {} holds a {} and is not a check's output: it looks like a baseline, and a baseline is never replaced (not even with --force): choose another --out",
            out.display(),
            crate::report::manifest::FILE
        );
    }
    Ok(())
}

/// Runs `platbench check`: 0 when every run passes, 1 on a regression, 2 on an error.
pub(crate) fn check(h: &Harness, args: &CheckArgs) -> ExitCode {
    match check_inner(h, args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn check_inner(h: &Harness, args: &CheckArgs) -> Result<ExitCode> {
    let p = args.position_tolerance;
    if !(p.is_finite() && p >= 0.0) {
        bail!("--position-tolerance {p}: expected a finite number of tiles >= 0");
    }
    let tols = tolerances(&args.tolerances)?;
    let base = baseline_dir(h, args.baseline.as_deref());
    let manifest = Manifest::read(&base)?;
    let record = CheckRecord::of(&base)?;
    refuse_baseline_as_out(&base, &args.out)?;
    output::check_target(&args.out, output::Kind::Check, args.force)?;
    // The external controllers the baseline was written with, loaded again.
    let recorded = super::controllers::with_recorded(h, &manifest.selection.controllers)?;
    let h = recorded.as_ref().unwrap_or(h);
    let run = run_args_of(&manifest, args.jobs);
    let (levels, configs, mut notes) = selection_of(h, &manifest, &run)?;
    let ran = super::baseline::manifest_of(&run, &levels, &configs)?;
    for v in manifest.version_changes() {
        notes.insert(
            0,
            format!(
                "versions differ: {v}; a difference below may come from that, not from your change"
            ),
        );
    }
    for n in &notes {
        out(&format!("note: {n}"));
    }
    let asked = if run.timing { 1 } else { run.select.jobs() };
    let jobs = super::select::jobs_for_levels(asked, &levels);
    let fail_on = FailOn {
        timing: args.fail_on_timing,
        allow_missing: args.allow_missing,
        allow_divergence: args.allow_divergence,
    };
    eprintln!(
        "platbench check: {} scenarios on {} configurations against {}",
        levels.iter().map(|l| l.scenarios.len()).sum::<usize>(),
        configs.len(),
        base.display()
    );
    let started = Instant::now();
    let mut result: Option<(Vec<Unit>, Vec<String>)> = None;
    output::write_output(&args.out, output::Kind::Check, args.force, |dir| {
        let traces = run.traces.unwrap_or(super::run::Traces::All);
        super::run::execute(
            &h.registry,
            &levels,
            &configs,
            &run,
            jobs,
            Some((dir, traces)),
        )?;
        // The runs of the new run, whose changes are gathered as the diff finds them; the
        // diff itself keeps the first of each change and counts the rest.
        let n = read_runs(dir)?;
        let mut changes = RunChanges::of_runs(&n, fail_on);
        let d = diff_runs_each(&base, dir, &tols, p, &mut |m| changes.add(m))
            .with_context(|| format!("comparing with the baseline {}", base.display()))?;
        // The runs of the baseline, not their rows: what the lines list.
        let b = read_runs(&base)?;
        let all = units(&b, &n, &changes, &d.traces, fail_on);
        // Only the traces of what changed stay: what `review` replays and CI uploads.
        for u in all
            .iter()
            .filter(|u| u.status == crate::report::check::Status::Pass)
        {
            let t = dir.join("traces").join(&u.trace);
            if t.exists() {
                std::fs::remove_file(&t)
                    .with_context(|| format!("cannot remove {}", t.display()))?;
            }
        }
        super::output::write_csv(&dir.join(UNITS), &all)?;
        record.write(dir)?;
        ran.write(dir)?;
        let md = summary_markdown(&all, &notes, &render(&d, DiffFormat::Markdown));
        output::write_file(&dir.join(SUMMARY), md.as_bytes())?;
        result = Some((all, d.failures(fail_on)));
        Ok(())
    })?;
    let Some((all, failures)) = result else {
        bail!("the check wrote nothing");
    };
    eprintln!("ran in {:.2} s", started.elapsed().as_secs_f64());
    let mut text = String::new();
    let (shown, left) = listed(&all);
    for u in shown {
        text.push_str(&line(u));
        text.push('\n');
    }
    if left > 0 {
        text.push_str(&left_out_line(left));
        text.push('\n');
    }
    out(text.trim_end());
    for f in &failures {
        eprintln!("regression: {f}");
    }
    eprintln!(
        "wrote {} ({}, {}, the changed traces); `platbench review {} --baseline {}` shows and accepts the changes",
        args.out.display(),
        UNITS,
        SUMMARY,
        args.out.display(),
        record.baseline
    );
    out(&closing_line(&all));
    let failed = all.iter().any(|u| u.status.fails());
    Ok(if failed || !failures.is_empty() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
