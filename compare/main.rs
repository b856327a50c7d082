//! `platbench`: the command-line harness. It only wires the library together: parse levels,
//! run every scenario on every configuration, write CSV files, print tables.

mod builtin;
mod output;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::{Args, Parser, Subcommand};

use platbench::level::{load_tiled_map, parse_level, Level};
use platbench::metrics::{evaluate_with, MetricRow};
use platbench::report::{detail_table, notes, summary_table};
use platbench::scenario::{BackendConfig, RunConfig, Runner};
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
    /// sweep's epsilon and jump mode, Rapier's offset, snap distance, collider building and
    /// shape) and write each setting's cost and error score to DIR/tradeoff.csv, with the
    /// Pareto front marked, and the chart DIR/tradeoff.svg.
    Sweep {
        /// Output directory for tradeoff.csv and tradeoff.svg.
        #[arg(long, default_value = "platbench-sweep")]
        out: PathBuf,
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
        /// Output directory for stability.csv.
        #[arg(long, default_value = "platbench-stress")]
        out: PathBuf,
    },
    /// Run level files (the built-in set when none is given) and write the "pick a backend"
    /// report: DIR/report.html (self-contained: inline pictures, no scripts, no network) and its
    /// Markdown twin DIR/report.md.
    Report(ReportArgs),
    /// Compare a run directory against a baseline: metrics beyond tolerance, first divergent
    /// trace frames. Exits 1 when a metric got worse (or went missing), 0 otherwise.
    Diff(DiffArgs),
}

#[derive(Args)]
struct ReportArgs {
    /// Level files: TOML, or Tiled maps (.tmx); the built-in set when none is given.
    levels: Vec<PathBuf>,
    /// Directory for report.html and report.md.
    #[arg(long, default_value = "platbench-report")]
    out: PathBuf,
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
}

#[derive(Args)]
#[command(allow_negative_numbers = true)]
struct DiffArgs {
    /// Baseline run directory (e.g. compare/baseline).
    base: PathBuf,
    /// New run directory (written by `platbench run --out`).
    new: PathBuf,
    /// Override a metric's tolerance: METRIC=ABS or METRIC=ABS,REL (REL a fraction of the
    /// baseline's distance from ideal). Repeatable. Defaults: 1e-5 + 1% for lengths and ratios,
    /// exact for counts, frames and booleans.
    #[arg(long = "tol", value_name = "METRIC=ABS[,REL]")]
    tolerances: Vec<String>,
    /// Position difference at which a trace diverges, in tiles.
    #[arg(long, default_value_t = 1e-4, value_name = "TILES")]
    position_tolerance: f32,
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
    /// Level files: TOML, or Tiled maps (.tmx); the built-in set when none is given.
    levels: Vec<PathBuf>,
    /// Output directory.
    #[arg(long, default_value = "platbench-out")]
    out: PathBuf,
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => run(&RunArgs::default(), false),
        Some(Command::Run(args)) => run(&args, true),
        Some(Command::Levels) => list_levels(),
        Some(Command::Stress { out }) => stress(&out),
        Some(Command::Sweep { out, levels, score }) => {
            sweep_settings(&out, &levels, score.as_deref())
        }
        Some(Command::Report(args)) => report(&args),
        Some(Command::Diff(args)) => return diff(&args),
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

fn load_levels(paths: &[PathBuf]) -> Result<Vec<Level>> {
    if paths.is_empty() {
        return builtin_levels();
    }
    let mut levels: Vec<Level> = Vec::new();
    for p in paths {
        let is_tiled = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("tmx"));
        let level = if is_tiled {
            let (level, warnings) = load_tiled_map(p)?;
            for w in warnings {
                eprintln!("warning: {w}");
            }
            level
        } else {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("cannot read level file {}", p.display()))?;
            parse_level(&text, &p.display().to_string())?
        };
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
    Ok(levels)
}

fn configs(args: &RunArgs) -> Result<Vec<RunConfig>> {
    let mut set = RunConfig::builtin_set();
    if !args.backends.is_empty() {
        set.retain(|c| args.backends.iter().any(|b| b == c.backend.name()));
    }
    if !args.shapes.is_empty() {
        set.retain(|c| match &c.backend {
            BackendConfig::Rapier(r) => args.shapes.contains(&r.shape.label()),
            _ => true,
        });
    }
    if let Some(eps) = args.epsilon {
        if !(eps.is_finite() && eps >= 0.0) {
            bail!("--epsilon {eps}: expected a finite number >= 0 (tiles)");
        }
        for c in &mut set {
            if let BackendConfig::Sweep(s) = &mut c.backend {
                s.epsilon = eps;
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
            let note = format!("{} {}: {e}", run.backend.name(), run.label);
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
                run.backend.name(),
                run.label
            )
        }),
    }
}

fn run(args: &RunArgs, write: bool) -> Result<()> {
    if !args.bless {
        let same = |a: &std::path::Path, b: &std::path::Path| {
            a.canonicalize()
                .ok()
                .zip(b.canonicalize().ok())
                .is_some_and(|(a, b)| a == b)
        };
        if write && same(&args.out, &baseline_dir()) {
            bail!(
                "--out {} is the committed baseline; it is replaced only on purpose, with `platbench run --bless`",
                args.out.display()
            );
        }
    }
    let mut levels = load_levels(&args.levels)?;
    if let Some(dt) = args.dt {
        if !(dt.is_finite() && dt > 0.0 && dt <= 1.0) {
            bail!("--dt {dt}: expected a time step in seconds, 0 < dt <= 1");
        }
        for l in &mut levels {
            for s in &mut l.scenarios {
                s.dt = dt;
            }
        }
    }
    let configs = configs(args)?;
    let total: usize = levels.iter().map(|l| l.scenarios.len()).sum::<usize>() * configs.len();
    eprintln!(
        "platbench: {} scenarios on {} configurations ({} runs)",
        total / configs.len().max(1),
        configs.len(),
        total
    );
    let started = Instant::now();
    let mut traces: Vec<Trace> = Vec::new();
    let mut metrics: Vec<MetricRow> = Vec::new();
    let mut done = 0;
    let mut skipped: Vec<String> = Vec::new();
    for level in &levels {
        let level_start = Instant::now();
        let mut runner = Runner::new(level);
        for spec in &level.scenarios {
            for run in &configs {
                let Some(e) = evaluate_or_skip(&mut runner, spec, run, &mut skipped)? else {
                    done += 1;
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
        eprintln!(
            "  [{done}/{total}] {} ({}) {:.2} s",
            level.name,
            level.source,
            level_start.elapsed().as_secs_f64()
        );
    }
    eprintln!("ran in {:.2} s", started.elapsed().as_secs_f64());
    let mut text = summary_table(&metrics);
    for n in notes(&metrics) {
        text.push_str(&format!("\n- {n}"));
    }
    out(&text);
    if args.detail {
        out(&format!("\n{}", detail_table(&metrics)));
    }
    if write {
        let out = if args.bless {
            baseline_dir()
        } else {
            args.out.clone()
        };
        output::write_run(&out, &traces, &metrics)?;
        eprintln!(
            "wrote {} traces and {} metric rows to {}",
            traces.len(),
            metrics.len(),
            out.display()
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
    use platbench::report::diff::{diff_runs, render, DiffFormat, Tolerance};
    let mut tols = std::collections::BTreeMap::new();
    for t in &args.tolerances {
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
                eprintln!("error: --tol {t}: expected METRIC=ABS or METRIC=ABS,REL with non-negative numbers");
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
            if d.regressed(args.fail_on_timing) {
                eprintln!("regression: a metric got worse beyond its tolerance (or went missing)");
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
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

fn report(args: &ReportArgs) -> Result<()> {
    use platbench::report::html::{render_report, Extras, ScenarioTraces};
    // The extra files first: a bad one fails before the long run.
    let extras = Extras {
        tradeoff: args.tradeoff.as_deref().map(read_rows).transpose()?,
        stability: args.stability.as_deref().map(read_rows).transpose()?,
    };
    let levels = load_levels(&args.levels)?;
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
    let (html, md) = render_report(&metrics, &scenarios, &extras);
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    for (name, text) in [("report.html", &html), ("report.md", &md)] {
        let path = args.out.join(name);
        let mut tmp = tempfile::NamedTempFile::new_in(&args.out)
            .with_context(|| format!("cannot write in {}", args.out.display()))?;
        std::io::Write::write_all(&mut tmp, text.as_bytes())?;
        tmp.persist(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        eprintln!("wrote {} ({} KB)", path.display(), text.len() / 1024);
    }
    Ok(())
}

fn sweep_settings(
    out_dir: &std::path::Path,
    level_files: &[PathBuf],
    score: Option<&str>,
) -> Result<()> {
    use platbench::metrics::score::Score;
    use platbench::tradeoff::{chart_svg_scope, grid, run_tradeoff, scored_behaviours, ALL};
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
    std::fs::create_dir_all(out_dir)
        .with_context(|| format!("cannot create {}", out_dir.display()))?;
    let csv_tmp = tempfile::NamedTempFile::new_in(out_dir)?;
    let mut w = csv::Writer::from_writer(csv_tmp.as_file());
    for r in &rows {
        w.serialize(r)?;
    }
    w.flush()?;
    drop(w);
    csv_tmp.persist(out_dir.join("tradeoff.csv"))?;
    let mut svg_tmp = tempfile::NamedTempFile::new_in(out_dir)?;
    std::io::Write::write_all(&mut svg_tmp, chart_svg_scope(&rows, ALL).as_bytes())?;
    svg_tmp.persist(out_dir.join("tradeoff.svg"))?;
    // The front per behaviour: tradeoff.<behaviour>.svg.
    for b in scored_behaviours() {
        let mut tmp = tempfile::NamedTempFile::new_in(out_dir)?;
        std::io::Write::write_all(&mut tmp, chart_svg_scope(&rows, b.key()).as_bytes())?;
        tmp.persist(out_dir.join(format!("tradeoff.{}.svg", b.key())))?;
    }
    eprintln!(
        "wrote tradeoff.csv, tradeoff.svg and tradeoff.<behaviour>.svg to {}",
        out_dir.display()
    );
    Ok(())
}

fn stress(out_dir: &std::path::Path) -> Result<()> {
    use platbench::rapier::{CharacterShape, ColliderBuilding};
    use platbench::report::html::{breaks_list, value_list};
    use platbench::stress::{envelope, stress_matrix};
    let runs = [
        RunConfig::sweep_default(),
        RunConfig::sweep_integer(32),
        RunConfig::rapier(ColliderBuilding::PerTile, CharacterShape::Capsule),
        RunConfig::rapier(ColliderBuilding::Merged, CharacterShape::Capsule),
    ];
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
    std::fs::create_dir_all(out_dir)
        .with_context(|| format!("cannot create {}", out_dir.display()))?;
    let path = out_dir.join("stability.csv");
    let tmp = tempfile::NamedTempFile::new_in(out_dir)?;
    let mut w = csv::Writer::from_writer(tmp.as_file());
    for r in &rows {
        w.serialize(r)?;
    }
    w.flush()?;
    drop(w);
    tmp.persist(&path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    eprintln!("wrote {}", path.display());
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
