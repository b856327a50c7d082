//! `platbench report`: the "pick a backend" report, HTML and Markdown.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use super::run::{configs, evaluate_or_skip, RunArgs};
use super::{load_levels_with, output, read_rows, Harness, ImportArgs};
use crate::metrics::MetricRow;
use crate::scenario::Runner;
use crate::trace::Trace;

#[derive(Args)]
pub(crate) struct ReportArgs {
    /// Level files: TOML, Tiled maps (.tmx) or LDtk projects (.ldtk); the built-in set when
    /// none is given.
    pub(crate) levels: Vec<PathBuf>,
    /// Directory for report.html and report.md (replaced as a whole; see --force).
    #[arg(long, default_value = "platbench-report")]
    pub(crate) out: PathBuf,
    /// Replace --out even when it holds something other than an earlier `platbench report`
    /// output (a directory of your own files, another command's output). Without it such a
    /// directory is refused. A baseline is never replaced but by `run --bless`.
    #[arg(long)]
    pub(crate) force: bool,
    /// Backends to run (repeat or comma-separate); every registered backend by default.
    #[arg(long = "backend", value_name = "BACKEND", value_delimiter = ',', value_parser = clap::builder::NonEmptyStringValueParser::new())]
    pub(crate) backends: Vec<String>,
    /// Character shapes to run, of the backends that offer several (Rapier's; repeat or
    /// comma-separate); all of them by default.
    #[arg(long = "shape", value_name = "SHAPE", value_delimiter = ',', value_parser = ["capsule", "cuboid", "ball", "round-cuboid"])]
    pub(crate) shapes: Vec<String>,
    /// Include the speed-against-accuracy chart from this tradeoff.csv (written by
    /// `platbench sweep`).
    #[arg(long, value_name = "FILE")]
    pub(crate) tradeoff: Option<PathBuf>,
    /// Include the stability table from this stability.csv (written by `platbench stress`).
    #[arg(long, value_name = "FILE")]
    pub(crate) stability: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

/// Reads a tradeoff.csv and checks what the chart draws: each cost and error score finite and
/// >= 0 (a damaged file drew NaN and -1e308 costs), and at least one setting per row.
fn read_tradeoff(path: &std::path::Path) -> Result<Vec<crate::tradeoff::TradeoffRow>> {
    let rows: Vec<crate::tradeoff::TradeoffRow> = read_rows(path)?;
    for (k, r) in rows.iter().enumerate() {
        // Line 1 is the header.
        let line = k + 2;
        for (what, v) in [("cost_us", r.cost_us), ("error", r.error)] {
            if !(v.is_finite() && v >= 0.0) {
                bail!(
                    "{}:{line}: {what} is {v}; expected a finite number >= 0 (a tradeoff.csv written by `platbench sweep`; rerun it if the file was damaged)",
                    path.display()
                );
            }
        }
    }
    Ok(rows)
}

pub(crate) fn report(h: &Harness, args: &ReportArgs) -> Result<()> {
    use crate::report::html::{render_report, Extras, ReplayRun, ScenarioTraces};
    // The extra files first: a bad one fails before the long run.
    output::check_target(&args.out, output::Kind::Report, args.force)?;
    let extras = Extras {
        tradeoff: args.tradeoff.as_deref().map(read_tradeoff).transpose()?,
        stability: args.stability.as_deref().map(read_rows).transpose()?,
    };
    let levels = load_levels_with(&args.levels, &args.import)?;
    let configs = configs(
        h,
        &RunArgs {
            backends: args.backends.clone(),
            shapes: args.shapes.clone(),
            ..RunArgs::default()
        },
    )?;
    let mut metrics: Vec<MetricRow> = Vec::new();
    // Per scenario: each run's trace, shape, moved size and per-frame faults.
    type Run = (Trace, crate::shape::CharacterShape, glam::Vec2, Vec<u8>);
    let mut per_scenario: Vec<(usize, usize, Vec<Run>)> = Vec::new();
    let mut skipped: Vec<String> = Vec::new();
    for (li, level) in levels.iter().enumerate() {
        let mut runner = Runner::new(level);
        for (si, spec) in level.scenarios.iter().enumerate() {
            let mut runs = Vec::new();
            for run in &configs {
                let Some(e) = evaluate_or_skip(&mut runner, spec, run, &mut skipped)? else {
                    continue;
                };
                metrics.extend(e.metrics);
                let faults = crate::metrics::with_context(
                    level,
                    spec,
                    run,
                    &e.trace,
                    crate::metrics::faults::frame_faults,
                );
                runs.push((
                    e.trace,
                    run.shape(),
                    run.backend.moved_size(spec.size),
                    faults,
                ));
            }
            per_scenario.push((li, si, runs));
        }
        eprintln!("  {}", level.name);
    }
    let scenarios: Vec<ScenarioTraces> = per_scenario
        .iter()
        .map(|(li, si, runs)| ScenarioTraces {
            level: &levels[*li],
            spec: &levels[*li].scenarios[*si],
            runs: runs
                .iter()
                .map(|(trace, shape, size, faults)| ReplayRun {
                    trace,
                    shape: *shape,
                    size: *size,
                    faults: faults.clone(),
                })
                .collect(),
        })
        .collect();
    let (html, md) = render_report(&h.registry, &metrics, &scenarios, &extras);
    output::write_output(&args.out, output::Kind::Report, args.force, |dir| {
        for (name, text) in [("report.html", &html), ("report.md", &md)] {
            output::write_file(&dir.join(name), text.as_bytes())?;
        }
        Ok(())
    })?;
    for (name, text) in [("report.html", &html), ("report.md", &md)] {
        eprintln!(
            "wrote {} ({} KB)",
            args.out.join(name).display(),
            text.len() / 1024
        );
    }
    Ok(())
}
