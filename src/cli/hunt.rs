//! `platbench hunt`: generated levels run on the selected configurations, failures of the
//! invariants shrunk and written as level files.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{bail, Result};
use clap::Args;

use super::select::Selection;
use super::{output, Harness};
use crate::config::RunConfig;
use crate::hunt::{hunt as run_hunt, Finding, HuntOptions, INVARIANTS};

/// `platbench hunt`'s options.
#[derive(Args, Clone)]
pub(crate) struct HuntArgs {
    /// Output directory: one level file per finding and findings.csv (replaced as a whole at
    /// the end, like every command's output; see --force).
    #[arg(long, value_name = "DIR", default_value = "platbench-hunt")]
    out: PathBuf,
    /// Replace --out even when it holds something other than an earlier `platbench hunt`
    /// output. A baseline is never replaced here.
    #[arg(long)]
    force: bool,
    /// Stop starting new cases after this many seconds (a shrink still running is cut short,
    /// and its finding says so).
    #[arg(long, value_name = "SECONDS", default_value = "60", value_parser = parse_budget)]
    budget: f64,
    /// The seed the cases are drawn from: the same seed gives the same cases and findings on
    /// any machine and any number of threads (within the budget).
    #[arg(long, value_name = "N", default_value = "0", value_parser = parse_seed, allow_negative_numbers = true)]
    seed: u64,
    /// Run this many generated cases (rounded up to rounds of 8) instead of stopping at the
    /// budget alone: a hunt whose findings are the same wherever it runs.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1_000_000_000))]
    cases: Option<u64>,
    /// Findings to shrink and keep per configuration and invariant (later failures of the
    /// same kind are counted only).
    #[arg(long, value_name = "N", default_value = "3", value_parser = clap::value_parser!(u64).range(1..=1000))]
    per_kind: u64,
    #[command(flatten)]
    select: Selection,
}

fn parse_budget(s: &str) -> std::result::Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 1e7 => Ok(v),
        Ok(v) => Err(format!("{v} is not a number of seconds in (0, 1e7]")),
        Err(_) => Err(format!(
            "found {s:?}; expected a number of seconds in (0, 1e7]"
        )),
    }
}

/// A seed: any whole number a `u64` holds.
fn parse_seed(s: &str) -> std::result::Result<u64, String> {
    s.trim().parse::<u64>().map_err(|_| {
        format!(
            "found {s:?}; expected a whole number from 0 to {}",
            u64::MAX
        )
    })
}

/// The `platbench run` line that shows a finding written to `file` in `dir`.
fn reproduce(dir: &std::path::Path, select: &Selection, file: &str, run: &RunConfig) -> String {
    let mut cmd = format!(
        "platbench run {} --backend {} --detail",
        dir.join(file).display(),
        run.backend.backend()
    );
    for c in &select.controllers {
        cmd.push_str(&format!(" --controller {}", c.display()));
    }
    cmd.push_str(&format!(" (configuration \"{}\")", run.label));
    cmd
}

fn line(f: &Finding) -> String {
    let v = &f.violation;
    let what = if v.metric.is_empty() {
        if v.invariant == "finite" {
            "non-finite state".to_string()
        } else if v.detail.is_empty() {
            format!(
                "{} = {} > {} (read from the trace)",
                v.invariant, v.value, v.bound
            )
        } else {
            v.detail.clone()
        }
    } else {
        format!("{} = {:.4} > {:.4}", v.metric, v.value, v.bound)
    };
    format!(
        "found {:<14} {} {:<22} {} at frame {}; {}x{} tiles, {} event(s) -> {}.toml",
        f.violation.invariant,
        f.backend,
        format!("\"{}\"", f.config),
        what,
        v.frame.map_or("-".into(), |k| k.to_string()),
        f.shrunk[0],
        f.shrunk[1],
        f.shrunk[4],
        f.name
    )
}

pub(crate) fn hunt(h: &Harness, args: &HuntArgs) -> Result<()> {
    if !args.select.scenarios.is_empty() {
        bail!(
            "--scenario {}: hunt generates its own levels and scenarios; drop --scenario",
            args.select.scenarios.join(",")
        );
    }
    if args.select.dt.is_some() {
        bail!("--dt: hunt's generated scenarios run at the default 1/60 s; drop --dt");
    }
    let runs = args.select.builtin_configs(h)?;
    output::check_target(&args.out, output::Kind::Hunt, args.force)?;
    let options = HuntOptions {
        seed: args.seed,
        budget: Duration::from_secs_f64(args.budget),
        cases: args.cases,
        jobs: super::select::jobs_within_memory_noted(args.select.jobs(), crate::hunt::LEVEL_TILES),
        per_kind: args.per_kind as usize,
    };
    eprintln!(
        "hunting on {} configuration(s), seed {}, budget {} s{}, {} thread(s); findings go to {}",
        runs.len(),
        args.seed,
        args.budget,
        args.cases
            .map_or(String::new(), |n| format!(", at most {n} cases")),
        options.jobs,
        args.out.display()
    );
    let mut last = std::time::Instant::now();
    let dir = args.out.clone();
    let select = args.select.clone();
    let outcome = run_hunt(
        &runs,
        &options,
        &move |file, run| reproduce(&dir, &select, file, run),
        |p| {
            if last.elapsed() >= Duration::from_secs(5) {
                last = std::time::Instant::now();
                eprintln!(
                    "  {:.0} s: {} cases, {} runs, {} failing, {} finding(s)",
                    p.elapsed.as_secs_f64(),
                    p.cases,
                    p.runs,
                    p.failures,
                    p.findings
                );
            }
        },
        |f| println!("{}", line(f)),
    );
    let p = &outcome.progress;
    println!(
        "\n{} cases, {} runs{} in {:.1} s: {} failing run(s), {} finding(s) (seed {}).",
        p.cases,
        p.runs,
        if p.skipped > 0 {
            format!(
                " ({} not run: levels with features the configuration does not model)",
                p.skipped
            )
        } else {
            String::new()
        },
        p.elapsed.as_secs_f64(),
        p.failures,
        outcome.findings.len(),
        args.seed
    );
    if !outcome.failures.is_empty() {
        let mut t = comfy_table::Table::new();
        t.load_style(comfy_table::presets::ASCII_MARKDOWN);
        t.set_header([
            "backend",
            "configuration",
            "invariant",
            "failing runs",
            "findings",
        ]);
        for ((backend, config, invariant), n) in &outcome.failures {
            let kept = outcome
                .findings
                .iter()
                .filter(|f| {
                    &f.backend == backend
                        && &f.config == config
                        && f.violation.invariant == *invariant
                })
                .count();
            t.add_row([
                backend.clone(),
                config.clone(),
                invariant.to_string(),
                n.to_string(),
                kept.to_string(),
            ]);
        }
        println!("{t}");
    }
    let rows: Vec<CsvRow> = outcome.findings.iter().map(CsvRow::of).collect();
    output::write_output(&args.out, output::Kind::Hunt, args.force, |staging| {
        for f in &outcome.findings {
            output::write_file(&staging.join(format!("{}.toml", f.name)), f.toml.as_bytes())?;
        }
        output::write_csv(&staging.join("findings.csv"), &rows)
    })?;
    println!(
        "wrote {} level file(s) and findings.csv to {} (invariants: {})",
        outcome.findings.len(),
        args.out.display(),
        INVARIANTS.map(|i| i.0).join(", ")
    );
    Ok(())
}

/// One row of findings.csv.
#[derive(serde::Serialize)]
struct CsvRow {
    file: String,
    backend: String,
    config: String,
    invariant: &'static str,
    metric: String,
    value: f64,
    bound: f64,
    frame: Option<u32>,
    seed: u64,
    case: u64,
    width: usize,
    height: usize,
    tiles: usize,
    platforms: usize,
    events: usize,
    duration: f32,
    generated_width: usize,
    generated_height: usize,
    generated_tiles: usize,
    tries: usize,
    cut_short: bool,
}

impl CsvRow {
    fn of(f: &Finding) -> CsvRow {
        CsvRow {
            file: format!("{}.toml", f.name),
            backend: f.backend.clone(),
            config: f.config.clone(),
            invariant: f.violation.invariant,
            metric: f.violation.metric.clone(),
            value: f.violation.value,
            bound: f.violation.bound,
            frame: f.violation.frame,
            seed: f.seed,
            case: f.case,
            width: f.shrunk[0],
            height: f.shrunk[1],
            tiles: f.shrunk[2],
            platforms: f.shrunk[3],
            events: f.shrunk[4],
            duration: f.duration,
            generated_width: f.generated[0],
            generated_height: f.generated[1],
            generated_tiles: f.generated[2],
            tries: f.tries,
            cut_short: f.cut_short,
        }
    }
}
