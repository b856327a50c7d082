//! `platbench run` (and `platbench` with no subcommand): run every scenario on every
//! configuration of the registry, print the summary, write the CSV files.

use std::io::IsTerminal as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::{load_levels_with, out, output, Harness, ImportArgs};
use crate::metrics::{evaluate_with, MetricRow};
use crate::report::{detail_table, summary_table};
use crate::scenario::{RunConfig, Runner};
use crate::trace::Trace;

#[derive(Args, Default)]
#[command(allow_negative_numbers = true)]
pub(crate) struct RunArgs {
    /// Level files: TOML, Tiled maps (.tmx) or LDtk projects (.ldtk); the built-in set when
    /// none is given.
    pub(crate) levels: Vec<PathBuf>,
    /// Output directory, replaced as a whole once the run is complete. It must be missing,
    /// empty, or an earlier `platbench run` output (it holds a .platbench-output marker file);
    /// anything else is refused unless --force. A baseline (its marker says so) is refused
    /// even with --force: only --bless replaces it.
    #[arg(long, default_value = "platbench-out")]
    pub(crate) out: PathBuf,
    /// Replace --out even when it is not an earlier run's output (a directory of your own
    /// files, another command's output): everything in it is deleted.
    #[arg(long)]
    pub(crate) force: bool,
    /// Print every metric of every scenario, not only the per-metric summary.
    #[arg(long)]
    pub(crate) detail: bool,
    /// Replace the committed baseline (compare/baseline for platbench itself; the harness's
    /// baseline directory for a crate calling platbench::cli) with this run: the only way it is
    /// written. Runs the built-in set with every configuration.
    #[arg(long, conflicts_with_all = ["levels", "out", "dt", "epsilon", "backends", "shapes", "timing"])]
    pub(crate) bless: bool,
    /// Override every scenario's time step, in seconds.
    #[arg(long, value_name = "SECONDS")]
    pub(crate) dt: Option<f32>,
    /// The overlap tolerance of the configurations that have one (the sweep's epsilon), in
    /// tiles.
    #[arg(long, value_name = "TILES")]
    pub(crate) epsilon: Option<f32>,
    /// Also time each scenario on each configuration (in process, minimum of 5 repeats) and
    /// add an ns_per_character_step row per scenario and configuration to metrics.csv.
    #[arg(long)]
    pub(crate) timing: bool,
    /// Backends to run (repeat or comma-separate); every registered backend by default.
    #[arg(long = "backend", value_name = "BACKEND", value_delimiter = ',', value_parser = clap::builder::NonEmptyStringValueParser::new())]
    pub(crate) backends: Vec<String>,
    /// Character shapes to run, of the backends that offer several (Rapier's; repeat or
    /// comma-separate); all of them by default.
    #[arg(long = "shape", value_name = "SHAPE", value_delimiter = ',', value_parser = ["capsule", "cuboid", "ball", "round-cuboid"])]
    pub(crate) shapes: Vec<String>,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

pub(crate) fn configs(h: &Harness, args: &RunArgs) -> Result<Vec<RunConfig>> {
    let registry = &h.registry;
    let mut set = registry.builtin_configs();
    if !args.backends.is_empty() {
        set.retain(|c| args.backends.iter().any(|b| b == c.backend.backend()));
    }
    // `--shape` picks among the shapes of the backends that offer a choice.
    let has_choice = |c: &RunConfig| {
        registry
            .get(c.backend.backend())
            .is_some_and(|k| k.shapes().len() > 1)
    };
    if !args.shapes.is_empty() {
        if !set.iter().any(has_choice) {
            let offering: Vec<&str> = registry
                .kinds()
                .iter()
                .filter(|k| k.shapes().len() > 1)
                .map(|k| k.name())
                .collect();
            bail!(
                "--shape {} picks the character shapes of a backend that offers several ({}), but none of them runs (--backend {}); drop --shape, or add --backend {}",
                args.shapes.join(","),
                offering.join(", "),
                args.backends.join(","),
                offering.join(",")
            );
        }
        set.retain(|c| !has_choice(c) || args.shapes.contains(&c.shape().label()));
    }
    if let Some(eps) = args.epsilon {
        if !crate::limits::within(eps as f64, (0.0, crate::limits::MAX_EPSILON)) {
            bail!(
                "--epsilon {eps}: expected tiles, 0 <= epsilon <= {}",
                crate::limits::MAX_EPSILON
            );
        }
        for c in &mut set {
            if let Some(b) = c.backend.with_epsilon(eps) {
                c.backend = b;
            }
        }
    }
    Ok(set)
}

/// Runs one scenario on one configuration; a configuration that does not model something in the
/// level is left out of that level, said once on stderr (never run on part of it).
pub(crate) fn evaluate_or_skip(
    runner: &mut Runner,
    spec: &crate::level::ScenarioSpec,
    run: &RunConfig,
    skipped: &mut Vec<String>,
) -> Result<Option<crate::metrics::Evaluation>> {
    let level = runner.level();
    match evaluate_with(runner, spec, run) {
        Err(e @ crate::backend::BackendError::Unsupported { .. }) => {
            let note = format!("{} {}: {e}", run.backend.backend(), run.label);
            if !skipped.contains(&note) {
                eprintln!("  skipped {note}");
                skipped.push(note);
            }
            Ok(None)
        }
        e => e.map(Some).with_context(|| {
            format!(
                "running {}.{} on {}/{}",
                level.name,
                spec.name,
                run.backend.backend(),
                run.label
            )
        }),
    }
}

pub(crate) fn run(h: &Harness, args: &RunArgs, write: bool) -> Result<()> {
    // Where the run goes, checked before any work: a directory that is not this command's
    // output (or a baseline, without --bless) is refused now, not after the run.
    let (target, kind) = if args.bless {
        (h.baseline.clone(), output::Kind::Baseline)
    } else {
        (args.out.clone(), output::Kind::Run)
    };
    if write {
        output::check_target(&target, kind, args.force)?;
    }
    if let Some(dt) = args.dt {
        let (lo, hi) = crate::limits::DT_RANGE;
        if !crate::limits::dt_in_range(dt as f64) {
            bail!("--dt {dt}: expected a time step in seconds, {lo} <= dt <= {hi}");
        }
    }
    let mut levels = load_levels_with(&args.levels, &args.import)?;
    if let Some(dt) = args.dt {
        // The frame caps hold for the step given here as for a step in the file.
        for l in &mut levels {
            let mut level_frames = 0u64;
            for s in &mut l.scenarios {
                s.dt = dt;
                level_frames +=
                    crate::limits::check_timing(s.duration as f64, dt as f64).map_err(|m| {
                        anyhow::anyhow!("--dt {dt} on {} scenario {}: {m}", l.source, s.name)
                    })?;
            }
            if level_frames > crate::limits::MAX_LEVEL_FRAMES {
                bail!(
                    "--dt {dt}: the scenarios of {} would run {level_frames} frames together; expected at most {}",
                    l.source,
                    crate::limits::MAX_LEVEL_FRAMES
                );
            }
        }
    }
    let configs = configs(h, args)?;
    // The runs that will write a trace: a configuration that does not model a level's
    // features skips that level (said once, below).
    let scenarios: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    let total: usize = levels
        .iter()
        .map(|l| l.scenarios.len() * configs.iter().filter(|c| c.backend.supports(l)).count())
        .sum();
    let skipped_runs = scenarios * configs.len() - total;
    eprintln!(
        "platbench: {scenarios} scenarios on {} configurations ({total} runs{})",
        configs.len(),
        if skipped_runs > 0 {
            format!(", {skipped_runs} skipped where a configuration does not model a level")
        } else {
            String::new()
        }
    );
    // Progress within a level, only for a person watching: a terminal's stderr.
    let live = std::io::stderr().is_terminal();
    let started = Instant::now();
    let mut traces: Vec<Trace> = Vec::new();
    let mut metrics: Vec<MetricRow> = Vec::new();
    let mut done = 0;
    let mut skipped: Vec<String> = Vec::new();
    for level in &levels {
        let level_start = Instant::now();
        let mut runner = Runner::new(level);
        for (si, spec) in level.scenarios.iter().enumerate() {
            for run in &configs {
                if live {
                    eprint!(
                        "\r\x1b[K  [{done}/{total}] {}: scenario {}/{} {} on {} {} ({} frames)",
                        level.name,
                        si + 1,
                        level.scenarios.len(),
                        spec.name,
                        run.backend.backend(),
                        run.label,
                        crate::scenario::step_count(spec)
                    );
                }
                let Some(e) = evaluate_or_skip(&mut runner, spec, run, &mut skipped)? else {
                    continue;
                };
                if args.timing {
                    let ns = crate::scenario::time_scenario(&mut runner, spec, run, 5)?;
                    metrics.push(crate::metrics::timing_row(level, spec, run, ns));
                }
                metrics.extend(e.metrics);
                if write {
                    traces.push(e.trace);
                }
                done += 1;
            }
        }
        if live {
            eprint!("\r\x1b[K");
        }
        eprintln!(
            "  [{done}/{total}] {} ({}) {:.2} s",
            level.name,
            level.source,
            level_start.elapsed().as_secs_f64()
        );
    }
    eprintln!("ran in {:.2} s", started.elapsed().as_secs_f64());
    let mut text = summary_table(&metrics);
    for n in h.registry.notes(&metrics) {
        text.push_str(&format!("\n- {n}"));
    }
    out(&text);
    if args.detail {
        out(&format!("\n{}", detail_table(&metrics)));
    }
    if write {
        output::write_run(&target, kind, args.force, &traces, &metrics)?;
        eprintln!(
            "wrote {} traces and {} metric rows to {}",
            traces.len(),
            metrics.len(),
            target.display()
        );
    } else {
        eprintln!("(worst case per metric over all scenarios; `platbench run --detail` lists every scenario, `--out DIR` writes the CSV files)");
    }
    Ok(())
}
