//! `platbench`: the command-line harness. It only wires the library together: parse levels,
//! run every scenario on every configuration, write CSV files, print tables.

mod builtin;
mod output;

use std::io::IsTerminal as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::{Args, Parser, Subcommand};

use platbench::level::{parse_level, Level};
use platbench::metrics::{evaluate_with, MetricRow};
use platbench::registry::Registry;
use platbench::report::{detail_table, summary_table};
use platbench::scenario::{RunConfig, Runner};
use platbench::trace::Trace;

/// Compare 2D platformer character controllers on the same levels, side by side.
///
/// With no subcommand, runs every built-in scenario on every configuration and prints a
/// summary table (the worst case of each metric per configuration).
#[derive(Parser)]
#[command(
    name = "platbench",
    version,
    about,
    long_about,
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run level files (the built-in set when none is given) and write traces and metrics.
    ///
    /// Writes DIR/traces/<level>.<scenario>.<backend>[.<config>].csv (one row per frame)
    /// and DIR/metrics.csv (one row per metric), replacing DIR as a whole once the run is
    /// complete.
    Run(RunArgs),
    /// List the built-in levels and their scenarios.
    Levels,
    /// Speed versus accuracy: run the scenario set over a grid of settings (dt, substeps, the
    /// sweep's epsilon and jump mode, Rapier's offset, snap distance, grounded feed, collider
    /// building and shape) and write each setting's cost and error score to DIR/tradeoff.csv, with the
    /// Pareto front marked, and the chart DIR/tradeoff.svg.
    Sweep {
        /// Output directory for tradeoff.csv and tradeoff.svg (replaced as a whole; see
        /// --force).
        #[arg(long, default_value = "platbench-sweep")]
        out: PathBuf,
        /// Replace --out even when it holds something other than an earlier `platbench sweep`
        /// output (a directory of your own files, another command's output). Without it such a
        /// directory is refused. A baseline is never replaced but by `run --bless`.
        #[arg(long)]
        force: bool,
        /// Level files: TOML, or Tiled maps (.tmx); the built-in set when none is given.
        levels: Vec<PathBuf>,
        /// The error score: METRIC[=WEIGHT],... (weight 1 if omitted; unlisted metrics weigh
        /// 0). Default: the registry's weights, which charge no controller for its declared
        /// design (Rapier's offset, the sweep's box overhanging a slope).
        #[arg(long)]
        score: Option<String>,
    },
    /// Check the invariants (finite, no penetration beyond the controller's own tolerance, no
    /// tunneling, stable rest, no grounded flicker, carry without drift) at the extremes, one
    /// dimension at a time: offsets 0 to 1e7 tiles, dt 1e-4 to 0.2 s, speeds to 1000 tiles/s,
    /// widths 0.01 to 10 tiles, and the sweep's epsilon 1e-1 to 1e-9. Writes DIR/stability.csv
    /// and prints each configuration's envelope, naming each invariant that broke and where.
    Stress {
        /// Output directory for stability.csv (replaced as a whole; see --force).
        #[arg(long, default_value = "platbench-stress")]
        out: PathBuf,
        /// Replace --out even when it holds something other than an earlier `platbench stress`
        /// output (a directory of your own files, another command's output). Without it such a
        /// directory is refused. A baseline is never replaced but by `run --bless`.
        #[arg(long)]
        force: bool,
    },
    /// Run level files (the built-in set when none is given) and write the "pick a backend"
    /// report: DIR/report.html (self-contained: inline pictures, no scripts, no network) and its
    /// Markdown twin DIR/report.md.
    Report(ReportArgs),
    /// Compare a run directory against a baseline: metrics beyond tolerance, first divergent
    /// trace frames.
    ///
    /// Exit status: 0 when nothing fails; 1 when a metric got worse beyond its tolerance, a
    /// metric or trace of the baseline is missing from the new run (unless --allow-missing),
    /// or a trace diverges beyond --position-tolerance or ends early (unless
    /// --allow-divergence); 2 on an error (a bad option, an unreadable or malformed file).
    /// A NaN where the other run has a number is a difference.
    Diff(DiffArgs),
    /// Show what a Tiled (.tmx) or LDtk (.ldtk) map was read as: each layer with the role it
    /// was given and why, the spawns, the moving platforms with their paths, the warnings, and
    /// the collision grid in the level format's characters (`#` solid, `=` one-way, `H`
    /// ladder, `/` `\` slopes, `.` empty).
    Inspect(InspectArgs),
}

#[derive(Args)]
struct InspectArgs {
    /// The map file (.tmx or .ldtk).
    map: PathBuf,
    #[command(flatten)]
    import: ImportArgs,
}

/// Overrides of the map importers' defaults (README, "Tiled maps" and "LDtk maps").
#[derive(Args, Default, Clone)]
#[command(allow_negative_numbers = true)]
struct ImportArgs {
    /// Read a map layer as ROLE: collision, solid, one_way, ladder, objects or decoration
    /// (NAME in any case; repeatable). Overrides the layer's name and properties.
    #[arg(long = "layer", value_name = "NAME=ROLE")]
    layers: Vec<String>,
    /// Read the tile layers no name or property marks as ROLE (collision or decoration).
    #[arg(long, value_name = "ROLE")]
    tile_layers: Option<String>,
    /// Start the probes here instead of the map's spawns: feet position in tiles, y up
    /// (repeatable).
    #[arg(long = "spawn", value_name = "X,Y")]
    spawns: Vec<String>,
    /// LDtk: make an IntGrid value (its number or name) solid, one_way, ladder or empty
    /// (repeatable).
    #[arg(long = "intgrid", value_name = "VALUE=KIND")]
    intgrid: Vec<String>,
    /// LDtk: import this one level of the world (its identifier) instead of the whole world.
    #[arg(long, value_name = "NAME")]
    level: Option<String>,
}

impl ImportArgs {
    fn options(&self) -> Result<platbench::level::ImportOptions> {
        use platbench::level::import::parse_tile_kind;
        use platbench::level::{ImportOptions, LayerRole};
        let mut o = ImportOptions::default();
        for l in &self.layers {
            let Some((name, role)) = l.rsplit_once('=') else {
                bail!("--layer {l}: expected NAME=ROLE");
            };
            let Some(r) = LayerRole::parse(role) else {
                bail!("--layer {l}: {role:?} is no role; expected collision, solid, one_way, ladder, objects or decoration");
            };
            o.layer_roles.push((name.to_string(), r));
        }
        if let Some(t) = &self.tile_layers {
            o.tile_layers = Some(LayerRole::parse(t).with_context(|| {
                format!(
                    "--tile-layers {t}: expected collision, solid, one_way, ladder or decoration"
                )
            })?);
        }
        for sp in &self.spawns {
            let v: Vec<f32> = sp
                .split(',')
                .map(|x| x.trim().parse::<f32>())
                .collect::<Result<_, _>>()
                .map_err(|_| anyhow::anyhow!("--spawn {sp}: expected X,Y in tiles"))?;
            match v[..] {
                [x, y] if x.is_finite() && y.is_finite() => o.spawns.push(glam::Vec2::new(x, y)),
                _ => bail!("--spawn {sp}: expected X,Y, two finite numbers of tiles"),
            }
        }
        for g in &self.intgrid {
            let Some((v, kind)) = g.rsplit_once('=') else {
                bail!("--intgrid {g}: expected VALUE=KIND");
            };
            let Some(t) = parse_tile_kind(kind) else {
                bail!(
                    "--intgrid {g}: {kind:?} is no kind; expected solid, one_way, ladder or empty"
                );
            };
            o.intgrid.push((v.to_string(), t));
        }
        o.level = self.level.clone();
        Ok(o)
    }
}

#[derive(Args)]
struct ReportArgs {
    /// Level files: TOML, Tiled maps (.tmx) or LDtk projects (.ldtk); the built-in set when
    /// none is given.
    levels: Vec<PathBuf>,
    /// Directory for report.html and report.md (replaced as a whole; see --force).
    #[arg(long, default_value = "platbench-report")]
    out: PathBuf,
    /// Replace --out even when it holds something other than an earlier `platbench report`
    /// output (a directory of your own files, another command's output). Without it such a
    /// directory is refused. A baseline is never replaced but by `run --bless`.
    #[arg(long)]
    force: bool,
    /// Backends to run (repeat or comma-separate); both by default.
    #[arg(long = "backend", value_name = "BACKEND", value_delimiter = ',', value_parser = ["sweep", "rapier"])]
    backends: Vec<String>,
    /// Rapier character shapes to run (repeat or comma-separate); all of them by default.
    #[arg(long = "shape", value_name = "SHAPE", value_delimiter = ',', value_parser = ["capsule", "cuboid", "ball", "round-cuboid"])]
    shapes: Vec<String>,
    /// Include the speed-against-accuracy chart from this tradeoff.csv (written by
    /// `platbench sweep`).
    #[arg(long, value_name = "FILE")]
    tradeoff: Option<PathBuf>,
    /// Include the stability table from this stability.csv (written by `platbench stress`).
    #[arg(long, value_name = "FILE")]
    stability: Option<PathBuf>,
    #[command(flatten)]
    import: ImportArgs,
}

#[derive(Args)]
#[command(allow_negative_numbers = true)]
struct DiffArgs {
    /// Baseline run directory (e.g. compare/baseline).
    base: PathBuf,
    /// New run directory (written by `platbench run --out`).
    new: PathBuf,
    /// Override a metric's tolerance: METRIC=ABS or METRIC=ABS,REL (REL a fraction of the
    /// baseline's distance from ideal; both finite and >= 0; METRIC a name of the metric
    /// catalog). Repeatable. Defaults: 1e-5 + 1% for lengths and ratios, exact for counts,
    /// frames and booleans.
    #[arg(long = "tol", value_name = "METRIC=ABS[,REL]")]
    tolerances: Vec<String>,
    /// Position difference at which a trace diverges, in tiles (finite and >= 0).
    #[arg(long, default_value_t = 1e-4, value_name = "TILES")]
    position_tolerance: f32,
    /// Do not fail (exit 1) when a metric or trace of the baseline is missing from the new run;
    /// it is still listed.
    #[arg(long)]
    allow_missing: bool,
    /// Do not fail (exit 1) when a trace diverges beyond --position-tolerance or ends before
    /// (or runs past) the baseline's; it is still listed.
    #[arg(long)]
    allow_divergence: bool,
    /// Output format.
    #[arg(long, default_value = "text", value_parser = ["text", "md", "csv"])]
    format: String,
    /// Fail (exit 1) when a timing got worse beyond its tolerance too; by default timings are
    /// reported but never fail.
    #[arg(long)]
    fail_on_timing: bool,
}

#[derive(Args, Default)]
#[command(allow_negative_numbers = true)]
struct RunArgs {
    /// Level files: TOML, Tiled maps (.tmx) or LDtk projects (.ldtk); the built-in set when
    /// none is given.
    levels: Vec<PathBuf>,
    /// Output directory, replaced as a whole once the run is complete. It must be missing,
    /// empty, or an earlier `platbench run` output (it holds a .platbench-output marker file);
    /// anything else is refused unless --force. A baseline (its marker says so) is refused
    /// even with --force: only --bless replaces it.
    #[arg(long, default_value = "platbench-out")]
    out: PathBuf,
    /// Replace --out even when it is not an earlier run's output (a directory of your own
    /// files, another command's output): everything in it is deleted.
    #[arg(long)]
    force: bool,
    /// Print every metric of every scenario, not only the per-metric summary.
    #[arg(long)]
    detail: bool,
    /// Replace the committed baseline (compare/baseline) with this run: the only way it is
    /// written. Runs the built-in set with every configuration.
    #[arg(long, conflicts_with_all = ["levels", "out", "dt", "epsilon", "backends", "shapes", "timing"])]
    bless: bool,
    /// Override every scenario's time step, in seconds.
    #[arg(long, value_name = "SECONDS")]
    dt: Option<f32>,
    /// The sweep controller's overlap tolerance, in tiles.
    #[arg(long, value_name = "TILES")]
    epsilon: Option<f32>,
    /// Also time each scenario on each configuration (in process, minimum of 5 repeats) and
    /// add an ns_per_character_step row per scenario and configuration to metrics.csv.
    #[arg(long)]
    timing: bool,
    /// Backends to run (repeat or comma-separate); both by default.
    #[arg(long = "backend", value_name = "BACKEND", value_delimiter = ',', value_parser = ["sweep", "rapier"])]
    backends: Vec<String>,
    /// Rapier character shapes to run (repeat or comma-separate); all of them by default.
    #[arg(long = "shape", value_name = "SHAPE", value_delimiter = ',', value_parser = ["capsule", "cuboid", "ball", "round-cuboid"])]
    shapes: Vec<String>,
    #[command(flatten)]
    import: ImportArgs,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => run(&RunArgs::default(), false),
        Some(Command::Run(args)) => run(&args, true),
        Some(Command::Levels) => list_levels(),
        Some(Command::Stress { out, force }) => stress(&out, force),
        Some(Command::Sweep {
            out,
            force,
            levels,
            score,
        }) => sweep_settings(&out, force, &levels, score.as_deref()),
        Some(Command::Report(args)) => report(&args),
        Some(Command::Diff(args)) => return diff(&args),
        Some(Command::Inspect(args)) => inspect(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// Parses the built-in levels; they are part of the binary, so a failure is a bug.
fn builtin_levels() -> Result<Vec<Level>> {
    builtin::LEVELS
        .iter()
        .map(|(file, text)| {
            parse_level(text, &format!("builtin:{file}"))
                .with_context(|| format!("built-in level {file} is invalid"))
        })
        .collect()
}

/// Whether `p` names a map file of `ext` (any case).
fn has_ext(p: &std::path::Path, ext: &str) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Loads a Tiled or LDtk map with the import overrides, printing its warnings — those gathered
/// before a failure too.
fn load_map(p: &std::path::Path, opts: &platbench::level::ImportOptions) -> Result<Level> {
    let result = if has_ext(p, "ldtk") {
        platbench::level::ldtk::load_ldtk_with(p, opts)
            .map_err(|f| (anyhow::Error::new(f.error), f.warnings))
    } else {
        platbench::level::load_tiled_map_with(p, opts)
            .map_err(|f| (anyhow::Error::new(f.error), f.warnings))
    };
    match result {
        Ok((level, warnings)) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            Ok(level)
        }
        Err((e, warnings)) => {
            for w in warnings {
                eprintln!("warning: {w}");
            }
            Err(e)
        }
    }
}

fn load_levels(paths: &[PathBuf]) -> Result<Vec<Level>> {
    load_levels_with(paths, &ImportArgs::default())
}

fn load_levels_with(paths: &[PathBuf], import: &ImportArgs) -> Result<Vec<Level>> {
    if paths.is_empty() {
        return builtin_levels();
    }
    let opts = import.options()?;
    let mut levels: Vec<Level> = Vec::new();
    for p in paths {
        let level = if has_ext(p, "tmx") || has_ext(p, "ldtk") {
            load_map(p, &opts)?
        } else {
            let text = platbench::limits::read_text_capped(p)
                .with_context(|| format!("cannot read level file {}", p.display()))?;
            parse_level(&text, &p.display().to_string())?
        };
        if level.scenarios.is_empty() {
            // Nothing would run: a level without scenarios would put a run of zero cost and
            // zero error into every table and onto the trade-off's front.
            eprintln!(
                "warning: {}: the level has no [[scenario]] entries, so nothing runs on it; skipped (add a [[scenario]] with a name, spawn and duration)",
                level.source
            );
            continue;
        }
        if let Some(other) = levels.iter().find(|l| l.name == level.name) {
            bail!(
                "{} and {} both name their level {:?}; level names must be unique in a run (they name the trace files)",
                other.source,
                level.source,
                level.name
            );
        }
        levels.push(level);
    }
    if levels.is_empty() {
        bail!("none of the level files has a scenario to run");
    }
    Ok(levels)
}

fn configs(args: &RunArgs) -> Result<Vec<RunConfig>> {
    let registry = Registry::builtin();
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
        if !platbench::limits::within(eps as f64, (0.0, platbench::limits::MAX_EPSILON)) {
            bail!(
                "--epsilon {eps}: expected tiles, 0 <= epsilon <= {}",
                platbench::limits::MAX_EPSILON
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
fn evaluate_or_skip(
    runner: &mut Runner,
    spec: &platbench::level::ScenarioSpec,
    run: &RunConfig,
    skipped: &mut Vec<String>,
) -> Result<Option<platbench::metrics::Evaluation>> {
    let level = runner.level();
    match evaluate_with(runner, spec, run) {
        Err(e @ platbench::backend::BackendError::Unsupported { .. }) => {
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

fn run(args: &RunArgs, write: bool) -> Result<()> {
    // Where the run goes, checked before any work: a directory that is not this command's
    // output (or a baseline, without --bless) is refused now, not after the run.
    let (target, kind) = if args.bless {
        (baseline_dir(), output::Kind::Baseline)
    } else {
        (args.out.clone(), output::Kind::Run)
    };
    if write {
        output::check_target(&target, kind, args.force)?;
    }
    if let Some(dt) = args.dt {
        let (lo, hi) = platbench::limits::DT_RANGE;
        if !platbench::limits::dt_in_range(dt as f64) {
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
                level_frames += platbench::limits::check_timing(s.duration as f64, dt as f64)
                    .map_err(|m| {
                        anyhow::anyhow!("--dt {dt} on {} scenario {}: {m}", l.source, s.name)
                    })?;
            }
            if level_frames > platbench::limits::MAX_LEVEL_FRAMES {
                bail!(
                    "--dt {dt}: the scenarios of {} would run {level_frames} frames together; expected at most {}",
                    l.source,
                    platbench::limits::MAX_LEVEL_FRAMES
                );
            }
        }
    }
    let configs = configs(args)?;
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
                        platbench::scenario::step_count(spec)
                    );
                }
                let Some(e) = evaluate_or_skip(&mut runner, spec, run, &mut skipped)? else {
                    continue;
                };
                if args.timing {
                    let ns = platbench::scenario::time_scenario(&mut runner, spec, run, 5)?;
                    metrics.push(platbench::metrics::timing_row(level, spec, run, ns));
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
    for n in Registry::builtin().notes(&metrics) {
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

/// Prints a block of text and a newline; a closed pipe (`platbench | head`) ends the output
/// quietly instead of panicking.
fn out(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let _ = writeln!(stdout, "{text}");
}

/// The committed baseline directory (`PLATBENCH_BASELINE` overrides it, for tests).
fn baseline_dir() -> PathBuf {
    std::env::var_os("PLATBENCH_BASELINE")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("compare/baseline"))
}

fn diff(args: &DiffArgs) -> ExitCode {
    use platbench::report::diff::{diff_runs, render, DiffFormat, FailOn, Tolerance};
    let p = args.position_tolerance;
    if !(p.is_finite() && p >= 0.0) {
        eprintln!("error: --position-tolerance {p}: expected a finite number of tiles >= 0 (a NaN or infinite tolerance would pass every trace)");
        return ExitCode::from(2);
    }
    let mut tols = std::collections::BTreeMap::new();
    for t in &args.tolerances {
        if let Some((m, _)) = t.split_once('=') {
            if platbench::metrics::registry::get(m).is_none() {
                let names: Vec<&str> = platbench::metrics::registry::METRICS
                    .iter()
                    .map(|d| d.name)
                    .collect();
                eprintln!(
                    "error: --tol {t}: no metric is named {m:?}; expected one of {}",
                    names.join(", ")
                );
                return ExitCode::from(2);
            }
        }
        let parsed = t.split_once('=').and_then(|(m, v)| {
            let mut parts = v.split(',').map(|x| x.trim().parse::<f64>());
            let abs = parts.next()?.ok()?;
            let rel = match parts.next() {
                Some(r) => r.ok()?,
                None => 0.0,
            };
            (abs.is_finite() && abs >= 0.0 && rel.is_finite() && rel >= 0.0)
                .then(|| (m.to_string(), Tolerance { abs, rel }))
        });
        match parsed {
            Some((m, tol)) => {
                tols.insert(m, tol);
            }
            None => {
                eprintln!("error: --tol {t}: expected METRIC=ABS or METRIC=ABS,REL with finite numbers >= 0");
                return ExitCode::from(2);
            }
        }
    }
    let format = match args.format.as_str() {
        "md" => DiffFormat::Markdown,
        "csv" => DiffFormat::Csv,
        _ => DiffFormat::Text,
    };
    match diff_runs(&args.base, &args.new, &tols, args.position_tolerance) {
        Ok(d) => {
            out(render(&d, format).trim_end());
            let failures = d.failures(FailOn {
                timing: args.fail_on_timing,
                allow_missing: args.allow_missing,
                allow_divergence: args.allow_divergence,
            });
            if failures.is_empty() {
                ExitCode::SUCCESS
            } else {
                for f in failures {
                    eprintln!("regression: {f}");
                }
                ExitCode::from(1)
            }
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// Reads every row of a CSV file written by `platbench sweep` or `platbench stress`.
fn read_rows<T: serde::de::DeserializeOwned>(path: &std::path::Path) -> Result<Vec<T>> {
    let mut r =
        csv::Reader::from_path(path).with_context(|| format!("cannot read {}", path.display()))?;
    let rows = r
        .deserialize()
        .collect::<Result<Vec<T>, _>>()
        .with_context(|| format!("{}: not the CSV this option expects", path.display()))?;
    if rows.is_empty() {
        anyhow::bail!("{}: no rows", path.display());
    }
    Ok(rows)
}

/// Reads a tradeoff.csv and checks what the chart draws: each cost and error score finite and
/// >= 0 (a damaged file drew NaN and -1e308 costs), and at least one setting per row.
fn read_tradeoff(path: &std::path::Path) -> Result<Vec<platbench::tradeoff::TradeoffRow>> {
    let rows: Vec<platbench::tradeoff::TradeoffRow> = read_rows(path)?;
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

fn report(args: &ReportArgs) -> Result<()> {
    use platbench::report::html::{render_report, Extras, ScenarioTraces};
    // The extra files first: a bad one fails before the long run.
    output::check_target(&args.out, output::Kind::Report, args.force)?;
    let extras = Extras {
        tradeoff: args.tradeoff.as_deref().map(read_tradeoff).transpose()?,
        stability: args.stability.as_deref().map(read_rows).transpose()?,
    };
    let levels = load_levels_with(&args.levels, &args.import)?;
    let configs = configs(&RunArgs {
        backends: args.backends.clone(),
        shapes: args.shapes.clone(),
        ..RunArgs::default()
    })?;
    let mut metrics: Vec<MetricRow> = Vec::new();
    let mut per_scenario: Vec<(usize, usize, Vec<Trace>)> = Vec::new();
    let mut skipped: Vec<String> = Vec::new();
    for (li, level) in levels.iter().enumerate() {
        let mut runner = Runner::new(level);
        for (si, spec) in level.scenarios.iter().enumerate() {
            let mut traces = Vec::new();
            for run in &configs {
                let Some(e) = evaluate_or_skip(&mut runner, spec, run, &mut skipped)? else {
                    continue;
                };
                metrics.extend(e.metrics);
                traces.push(e.trace);
            }
            per_scenario.push((li, si, traces));
        }
        eprintln!("  {}", level.name);
    }
    let scenarios: Vec<ScenarioTraces> = per_scenario
        .iter()
        .map(|(li, si, traces)| ScenarioTraces {
            level: &levels[*li],
            spec: &levels[*li].scenarios[*si],
            traces: traces.iter().collect(),
        })
        .collect();
    let (html, md) = render_report(&Registry::builtin(), &metrics, &scenarios, &extras);
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

fn sweep_settings(
    out_dir: &std::path::Path,
    force: bool,
    level_files: &[PathBuf],
    score: Option<&str>,
) -> Result<()> {
    use platbench::metrics::score::Score;
    use platbench::tradeoff::{chart_svg_scope, grid, run_tradeoff, scored_behaviours, ALL};
    output::check_target(out_dir, output::Kind::Sweep, force)?;
    let score = match score {
        Some(s) => Score::parse(s)?,
        None => Score::default(),
    };
    eprintln!("error score: {}", score.describe());
    let levels = load_levels(level_files)?;
    let settings = grid();
    let started = Instant::now();
    let rows = run_tradeoff(&levels, &settings, &score, |done, total, label| {
        let width = 30;
        let filled = done * width / total.max(1);
        eprintln!(
            "  [{}{}] {done}/{total} {label} ({:.0} s)",
            "#".repeat(filled),
            ".".repeat(width - filled),
            started.elapsed().as_secs_f64()
        );
    })?;
    let mut t = comfy_table::Table::new();
    t.load_style(comfy_table::presets::ASCII_MARKDOWN);
    t.set_header(vec![
        "backend",
        "setting",
        "us per character per game second",
        "error score",
        "scenarios",
        "Pareto",
    ]);
    // A setting that ran fewer scenarios is measured over another set: said, and never on the
    // front.
    let most = rows.iter().map(|r| r.scenarios).max().unwrap_or(0);
    for r in rows.iter().filter(|r| r.scope == ALL) {
        t.add_row(vec![
            r.backend.clone(),
            r.setting.clone(),
            format!("{:.1}", r.cost_us),
            format!("{:.4}", r.error),
            if r.scenarios < most {
                format!("over {} of {most}", r.scenarios)
            } else {
                r.scenarios.to_string()
            },
            if r.pareto { "*".into() } else { String::new() },
        ]);
    }
    out(&t.to_string());
    output::write_output(out_dir, output::Kind::Sweep, force, |dir| {
        output::write_csv(&dir.join("tradeoff.csv"), &rows)?;
        output::write_file(
            &dir.join("tradeoff.svg"),
            chart_svg_scope(&rows, ALL).as_bytes(),
        )?;
        // The front per behaviour: tradeoff.<behaviour>.svg.
        for b in scored_behaviours() {
            output::write_file(
                &dir.join(format!("tradeoff.{}.svg", b.key())),
                chart_svg_scope(&rows, b.key()).as_bytes(),
            )?;
        }
        Ok(())
    })?;
    eprintln!(
        "wrote tradeoff.csv, tradeoff.svg and tradeoff.<behaviour>.svg to {}",
        out_dir.display()
    );
    Ok(())
}

fn stress(out_dir: &std::path::Path, force: bool) -> Result<()> {
    use platbench::report::html::{breaks_list, value_list};
    use platbench::stress::{envelope, stress_matrix};
    let runs = Registry::builtin().stress_configs();
    output::check_target(out_dir, output::Kind::Stress, force)?;
    let started = Instant::now();
    let rows = stress_matrix(&runs, |what| eprintln!("  {what}"))?;
    eprintln!("ran in {:.1} s", started.elapsed().as_secs_f64());
    let mut t = comfy_table::Table::new();
    t.load_style(comfy_table::presets::ASCII_MARKDOWN);
    t.set_header(vec![
        "configuration",
        "dimension",
        "every invariant holds at",
        "breaks at",
    ]);
    for e in envelope(&rows) {
        t.add_row(vec![
            e.config.clone(),
            e.dimension.clone(),
            value_list(&e.holds),
            breaks_list(&e),
        ]);
    }
    out(&t.to_string());
    output::write_output(out_dir, output::Kind::Stress, force, |dir| {
        output::write_csv(&dir.join("stability.csv"), &rows)
    })?;
    eprintln!("wrote {}", out_dir.join("stability.csv").display());
    Ok(())
}

fn list_levels() -> Result<()> {
    for level in builtin_levels()? {
        out(&format!(
            "{} ({} x {} tiles): {}",
            level.name, level.width, level.height, level.description
        ));
        for s in &level.scenarios {
            out(&format!("    {}  ({} s)", s.name, s.duration));
        }
    }
    Ok(())
}

/// `platbench inspect MAP`: what the import read, for a user to compare with their game.
fn inspect(args: &InspectArgs) -> Result<()> {
    use platbench::level::import::ascii_map;
    let opts = args.import.options()?;
    let p = &args.map;
    let r = if has_ext(p, "ldtk") {
        platbench::level::ldtk::import_ldtk_with(p, &opts).map_err(|f| {
            for w in &f.warnings {
                eprintln!("warning: {w}");
            }
            anyhow::Error::new(f.error)
        })?
    } else {
        let t = platbench::level::import_tiled_map_with(p, &opts).map_err(|f| {
            for w in &f.warnings {
                eprintln!("warning: {w}");
            }
            anyhow::Error::new(f.error)
        })?;
        platbench::level::import::MapImport {
            level: t.level,
            spawns: t.spawns,
            spawn_sources: t.spawn_sources,
            layers: t.layers,
            warnings: t.warnings,
        }
    };
    let l = &r.level;
    let mut text = format!(
        "{}: level {:?}, {} x {} tiles{}\n",
        p.display(),
        l.name,
        l.width,
        l.height,
        if l.features.names().is_empty() {
            String::new()
        } else {
            format!(" ({})", l.features.names().join(", "))
        }
    );
    text.push_str("\nlayers:\n");
    for layer in &r.layers {
        text.push_str(&format!(
            "  {:?} ({}): {} — {}\n",
            layer.name,
            layer.kind,
            layer.role.name(),
            layer.why
        ));
    }
    text.push_str("\nspawns (feet, tiles, y up):\n");
    if r.spawns.is_empty() {
        text.push_str("  none\n");
    }
    for (s, why) in r.spawns.iter().zip(&r.spawn_sources) {
        text.push_str(&format!(
            "  {} at ({}, {}) — {why}\n",
            s.name, s.position.x, s.position.y
        ));
    }
    text.push_str("\nplatforms:\n");
    if l.platforms.is_empty() {
        text.push_str("  none\n");
    }
    for (k, pl) in l.platforms.iter().enumerate() {
        let path = match &pl.motion {
            platbench::level::PlatformMotion::Waypoints { points, speed } => format!(
                "path {} at {speed} tiles/s",
                points
                    .iter()
                    .map(|q| format!("({}, {})", q.x, q.y))
                    .collect::<Vec<_>>()
                    .join(" -> ")
            ),
            other => format!("{other:?}"),
        };
        text.push_str(&format!(
            "  {k}: {} x {} at ({}, {}){}, {path}\n",
            pl.size.x,
            pl.size.y,
            pl.start.x,
            pl.start.y,
            if pl.one_way { ", one-way" } else { "" }
        ));
    }
    text.push_str(&format!("\nwarnings: {}\n", r.warnings.len()));
    for w in &r.warnings {
        text.push_str(&format!("  {}: {}\n", w.subject, w.message));
    }
    let (map, legend) = ascii_map(l);
    text.push_str("\ngrid (top row first; # solid, = one-way, H ladder, / \\ slopes, . empty):\n");
    text.push_str(&map);
    for (c, s) in legend {
        text.push_str(&format!("  {c} = {s:?}\n"));
    }
    out(text.trim_end());
    Ok(())
}
