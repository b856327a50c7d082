//! The `platbench` command-line harness, as a library: [`main_with`] gives a crate the whole
//! CLI (`run`, `diff`, `report`, `stress`, `sweep`, `levels`, `inspect`, `baseline`, `check`,
//! `review`) over the backend kinds
//! of a [`Registry`], so a user's controller runs beside ours from one call in their `main`:
//!
//! ```no_run
//! use platbench::registry::Registry;
//!
//! fn main() -> std::process::ExitCode {
//!     // Registry::builtin().with::<MyController>() adds a controller of your own.
//!     platbench::cli::main_with(Registry::builtin())
//! }
//! ```
//!
//! It only wires the library together: parse levels, run every scenario on every configuration,
//! write CSV files, print tables. One file per subcommand.

mod baseline;
mod check;
mod controllers;
mod diff;
mod hunt;
mod inspect;
mod levels;
mod load;
mod output;
mod profiles;
mod report;
mod review;
mod review_apply;
mod run;
mod select;
mod stress;
mod tradeoff;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::builder::PossibleValuesParser;
use clap::{CommandFactory as _, FromArgMatches as _, Parser, Subcommand};

use crate::registry::Registry;

#[allow(unused_imports)]
pub(crate) use load::missing_feature;
pub(crate) use load::{load_levels, load_levels_with, ImportArgs};
pub use output::MARKER;

/// What a CLI built by [`main_with_harness`] runs on: the backend kinds, and where its committed
/// baseline lives.
#[derive(Clone, Debug)]
pub struct Harness {
    /// The backend kinds every command runs, in order.
    pub registry: Registry,
    /// The baseline directory: what `run --bless` writes, and the default `--baseline` of
    /// `baseline`, `check` and `review` (every other command refuses to replace a baseline).
    pub baseline: PathBuf,
}

impl Harness {
    /// A harness over `registry` whose baseline is `PLATBENCH_BASELINE` if set, else
    /// `platbench-baseline` in the current directory.
    pub fn new(registry: Registry) -> Self {
        Harness {
            registry,
            baseline: std::env::var_os("PLATBENCH_BASELINE")
                .map_or_else(|| PathBuf::from("platbench-baseline"), PathBuf::from),
        }
    }
}

/// Runs the `platbench` command line (from the process's arguments) over `registry`'s backend
/// kinds, and returns the exit status: 0 on success, 1 when `diff` finds a regression, 2 on an
/// error. The baseline is as [`Harness::new`] says.
///
/// ```no_run
/// use platbench::registry::Registry;
/// use platbench::sweep::SweepConfig;
///
/// fn main() -> std::process::ExitCode {
///     // The sweep alone; `.with::<YourController>()` puts yours beside it.
///     platbench::cli::main_with(Registry::new().with::<SweepConfig>())
/// }
/// ```
pub fn main_with(registry: Registry) -> ExitCode {
    main_with_harness(Harness::new(registry))
}

/// [`main_with`] with the baseline directory of `harness`.
pub fn main_with_harness(harness: Harness) -> ExitCode {
    run_cli(&harness, std::env::args_os())
}

/// Runs the command line `args` (the program name first) on `harness`; what [`main_with`] does
/// with the process's arguments.
pub fn run_cli<I, T>(harness: &Harness, args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let args: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
    // External controllers join the registry before the options are parsed: their names are
    // --backend values.
    let with_external;
    let harness = match controllers::with_controllers(harness, &args) {
        Ok(None) => harness,
        Ok(Some(h)) => {
            with_external = h;
            &with_external
        }
        Err(e) => {
            eprintln!("error: {e:#}");
            return ExitCode::from(2);
        }
    };
    let names = harness.registry.names();
    if let Some(bad) = names.iter().find(|n| {
        n.is_empty()
            || !n
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' || c == '-')
    }) {
        eprintln!(
            "error: a registered controller is named {bad:?}; expected lower-case ASCII letters, digits, `_` and `-` (Controller::NAME names CSV rows, trace files and --backend values)"
        );
        return ExitCode::from(2);
    }
    let backends = |a: clap::Arg| a.value_parser(PossibleValuesParser::new(names.clone()));
    let command = Cli::command()
        .mut_subcommand("run", |c| c.mut_arg("backends", backends))
        .mut_subcommand("report", |c| c.mut_arg("backends", backends))
        .mut_subcommand("stress", |c| c.mut_arg("backends", backends))
        .mut_subcommand("sweep", |c| c.mut_arg("backends", backends))
        .mut_subcommand("hunt", |c| c.mut_arg("backends", backends))
        .mut_subcommand("baseline", |c| {
            c.mut_arg("backends", backends).mut_arg("baseline", |a| {
                a.help(baseline::baseline_help(harness, "to write"))
            })
        })
        .mut_subcommand("check", |c| {
            c.mut_arg("baseline", |a| {
                a.help(baseline::baseline_help(harness, "to compare with"))
            })
        })
        .mut_subcommand("review", |c| {
            c.mut_arg("baseline", |a| {
                a.help(baseline::baseline_help(harness, "to update"))
            })
        });
    let cli = match command
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m))
    {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { 2 } else { 0 });
        }
    };
    let h = harness;
    let result = match cli.command {
        None => run::run(
            controllers::with_builtin_godot3(h).as_ref().unwrap_or(h),
            &run::RunArgs {
                out: cli.out,
                force: cli.force,
                ..run::RunArgs::default()
            },
        ),
        Some(Command::Run(args)) => run::run(h, &args),
        Some(Command::Levels) => levels::list_levels(),
        Some(Command::Stress {
            out,
            force,
            world_size,
            select,
        }) => stress::stress(h, &out, force, world_size, &select),
        Some(Command::Tradeoff {
            out,
            force,
            levels,
            score,
            pixels_per_tile,
            select,
        }) => tradeoff::tradeoff(
            h,
            &out,
            force,
            &levels,
            (score.as_deref(), &pixels_per_tile),
            &select,
        ),
        Some(Command::Report(args)) => report::report(h, &args),
        Some(Command::Diff(args)) => return diff::diff(&args),
        Some(Command::Baseline(args)) => baseline::baseline(h, &args),
        Some(Command::Check(args)) => return check::check(h, &args),
        Some(Command::Review(args)) => review::review(h, &args),
        Some(Command::Inspect(args)) => inspect::inspect(&args),
        Some(Command::Hunt(args)) => hunt::hunt(h, &args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// The threads `--jobs` asks for, or the cores available.
pub(crate) fn jobs_or_cores(jobs: Option<u32>) -> usize {
    jobs.map_or_else(crate::parallel::default_jobs, |j| j as usize)
}

/// Compare 2D platformer character controllers on the same levels, side by side.
///
/// With no subcommand, runs every built-in scenario on every configuration (Godot 3's too, when
/// godot3-server is installed) and prints the verdict and the scorecard; with --out, writes the
/// traces and metrics too, as `run --out` does.
#[derive(Parser)]
#[command(
    name = "platbench",
    version,
    about,
    long_about,
    args_conflicts_with_subcommands = true,
    term_width = 100
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Also write the run's traces and metrics to DIR (as `run --out DIR`).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// With --out: replace DIR even when it is not an earlier run's output (see `run --force`).
    #[arg(long, requires = "out")]
    force: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Run levels and print the comparison; with --out write traces and metrics.
    ///
    /// Runs level files (the built-in set when none is given). With --out DIR, writes DIR/traces/<level>.<scenario>.<backend>[.<config>].csv (one row
    /// per frame; --traces chooses which) and DIR/metrics.csv (one row per metric), replacing
    /// DIR as a whole once the run is complete. Without --out nothing is written.
    Run(run::RunArgs),
    /// List the built-in levels and their scenarios.
    Levels,
    /// Speed against accuracy: each controller's cost and error over a grid of settings.
    ///
    /// Runs the scenario set over a grid of settings (dt, substeps, the sweep's epsilon and jump mode, Rapier's offset, snap distance, grounded feed, collider
    /// building and shape) and write each setting's cost and error score to DIR/tradeoff.csv, with the
    /// Pareto front marked, and the chart DIR/tradeoff.svg.
    #[command(name = "sweep")]
    Tradeoff {
        /// Output directory for tradeoff.csv and tradeoff.svg (replaced as a whole; see
        /// --force).
        #[arg(long, default_value = "platbench-sweep")]
        out: PathBuf,
        /// Replace --out even when it holds something other than an earlier `platbench sweep`
        /// output (a directory of your own files, another command's output). Without it such a
        /// directory is refused. A baseline is never replaced here.
        #[arg(long)]
        force: bool,
        /// Level files: TOML, Tiled maps (.tmx, .tmj) or LDtk projects (.ldtk), told by content; the built-in set when none is given.
        levels: Vec<PathBuf>,
        /// The error score: METRIC[=WEIGHT],... (weight 1 if omitted; unlisted metrics weigh
        /// 0). Default: the registry's weights, which charge no controller for its declared
        /// design (Rapier's offset, the sweep's box overhanging a slope).
        #[arg(long)]
        score: Option<String>,
        /// The game's pixels per tile: the error score does not charge what the game cannot
        /// show, an error under one pixel for a length or one pixel per second for a speed
        /// (docs/metrics.md, "The error score"). `run`'s verdict and `--traces failing` use the
        /// default.
        #[arg(long, value_name = "N", default_value = "16")]
        pixels_per_tile: String,
        #[command(flatten)]
        select: select::Selection,
    },
    /// Stability at the extremes: offsets, time steps, speeds, widths and their pairs.
    ///
    /// Checks the invariants (finite, no penetration beyond the controller's own tolerance, no
    /// tunneling, stable rest, no grounded flicker, carry without drift, progress over seamed
    /// ground with no stuck step, a jump to its height) at the extremes, one dimension at a
    /// time (offsets 0 to 1e7 tiles, and to 1e15 for f64 configurations; dt 1e-4 to 0.2 s,
    /// speeds to 1000 tiles/s, widths 0.01 to 10 tiles, the sweep's epsilon 1e-1 to 1e-9),
    /// then on small grids of pairs (offset x epsilon, offset x dt, speed x dt, width x speed,
    /// offset x speed; offsets 1e4 to 1e6 in f32, 1e11 to 1e13 in f64). Writes
    /// DIR/stability.csv and prints each configuration's verdict per dimension and each pair's
    /// cells.
    Stress {
        /// Output directory for stability.csv (replaced as a whole; see --force).
        #[arg(long, default_value = "platbench-stress")]
        out: PathBuf,
        /// Replace --out even when it holds something other than an earlier `platbench stress`
        /// output (a directory of your own files, another command's output). Without it such a
        /// directory is refused. A baseline is never replaced here.
        #[arg(long)]
        force: bool,
        /// Also say which configurations hold in a world this many tiles across (positions up
        /// to this far from the origin), from the offsets measured and the combination cells
        /// within it.
        #[arg(long, value_name = "TILES", value_parser = parse_world_size, allow_negative_numbers = true)]
        world_size: Option<f64>,
        #[command(flatten)]
        select: select::Selection,
    },
    /// Run levels and write the report (HTML and Markdown) for picking a controller.
    ///
    /// Runs level files (the built-in set when none is given) and writes the "pick a backend"
    /// report: DIR/report.html (self-contained: inline pictures and one inline script, nothing fetched) and its
    /// Markdown twin DIR/report.md.
    Report(report::ReportArgs),
    /// Compare a run directory against a baseline: worse metrics, first divergent trace frames.
    ///
    /// Exit status: 0 when nothing fails; 1 when a metric got worse beyond its tolerance, a
    /// metric or trace of the baseline is missing from the new run (unless --allow-missing),
    /// or a trace diverges beyond --position-tolerance or ends early (unless
    /// --allow-divergence); 2 on an error (a bad option, an unreadable or malformed file).
    /// A NaN where the other run has a number is a difference.
    Diff(diff::DiffArgs),
    /// Write a baseline of the selection you choose, with a manifest, for `check`.
    ///
    /// Runs the selection (`run`'s options: level files, --backend, --shape, --scenario,
    /// --traces, ...) and writes DIR/metrics.csv, DIR/traces/ and DIR/manifest.toml (the
    /// selection, the levels with a hash of each file, the configurations, the platbench and
    /// key dependency versions), replacing DIR as a whole once the run is complete. An existing
    /// baseline is replaced only with --replace.
    Baseline(baseline::BaselineArgs),
    /// For CI: run a baseline's selection again and compare (one line per run, then counts).
    ///
    /// Reads DIR/manifest.toml of the baseline, runs the same selection, compares it with the
    /// baseline by `diff`'s rules, and prints one line per scenario and configuration (pass,
    /// worse, better, diverged, missing, new) and a closing `N passed, N failed` line; says so
    /// when the platbench or dependency versions differ from the baseline's. Writes the run to
    /// --out. Exit status: 0 when every run passes, 1 on a regression (worse, diverged,
    /// missing), 2 on an error.
    Check(check::CheckArgs),
    /// Review the changes a check found, and accept them into the baseline one by one.
    ///
    /// For each run `check` found changed: its metrics in the baseline and now, and
    /// CHECK_DIR/review/<trace>.html replaying both traces side by side. Asks whether to accept
    /// each (stdin must be a terminal), or decides by --accept-all, --accept PATTERN or
    /// --reject-all. Accepting replaces only that run's metric rows and trace file in the
    /// baseline (and its level's entry in manifest.toml); every other byte stays, and the
    /// baseline is swapped in as a whole. Only the baseline the check ran against is accepted
    /// into. A review holds DIR/.platbench-lock while it runs: a second review of the same
    /// baseline is refused until it ends (a lock older than an hour is taken over, with a
    /// warning).
    Review(review::ReviewArgs),
    /// Show what a Tiled or LDtk map was read as, layer by layer.
    ///
    /// Shows what a Tiled (.tmx, .tmj) or LDtk (.ldtk) map was read as: each layer with the role it
    /// was given and why, the spawns, the moving platforms with their paths, the warnings, and
    /// the collision grid in the level format's characters (`#` solid, `=` one-way, `H`
    /// ladder, `/` `\` slopes, `.` empty).
    Inspect(inspect::InspectArgs),
    /// Search for the level nobody wrote: generated cases, invariants, shrunk failures.
    ///
    /// Generates small levels and input scripts from --seed, runs the selected configurations
    /// on them and checks invariants any controller must keep against its own declared contact
    /// (docs/hunt.md lists them). Each failure is shrunk to a small level that fails the same
    /// way, written to DIR with a comment giving the invariant, the configuration, the frame
    /// and the command that reproduces it; DIR/findings.csv lists them.
    Hunt(hunt::HuntArgs),
}

pub(crate) use crate::suite::builtin_levels;

/// Prints a block of text and a newline; a closed pipe (`platbench | head`) ends the output
/// quietly instead of panicking.
pub(crate) fn out(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let _ = writeln!(stdout, "{text}");
}

/// Reads every row of a CSV file platbench wrote (`sweep`, `stress`, `check`), refusing the
/// file at its row past `max` (before reading further).
pub(crate) fn read_rows_capped<T: serde::de::DeserializeOwned>(
    path: &std::path::Path,
    max: usize,
) -> Result<Vec<T>> {
    read_rows_checked(path, max, |_: &T, _| Ok(()))
}

/// [`read_rows_capped`], calling `check(row, line)` on each row as it is read (line 1 is the
/// header), so a row that makes the file too costly is refused at its line before the rest is
/// read.
pub(crate) fn read_rows_checked<T: serde::de::DeserializeOwned>(
    path: &std::path::Path,
    max: usize,
    mut check: impl FnMut(&T, u64) -> Result<()>,
) -> Result<Vec<T>> {
    let file = crate::input::open(path, crate::limits::MAX_INPUT_BYTES, "input file")?;
    let mut r = csv::Reader::from_reader(crate::report::diff::Lines::new(file));
    let headers = r
        .headers()
        .map_err(|e| csv_error(path, 1, &e, None))?
        .clone();
    let mut record = csv::StringRecord::new();
    let mut rows = Vec::new();
    loop {
        let read = r.read_record(&mut record);
        let byte = match &read {
            Ok(_) => record.position(),
            Err(e) => e.position(),
        }
        .map_or(0, csv::Position::byte);
        let line = r.get_mut().line_of(byte);
        if !read.map_err(|e| csv_error(path, line, &e, None))? {
            break;
        }
        if rows.len() == max {
            anyhow::bail!(
                "{}:{line}: more than {max} rows; expected at most {max}",
                path.display()
            );
        }
        let row: T = record
            .deserialize(Some(&headers))
            .map_err(|e| csv_error(path, line, &e, Some((&headers, &record))))?;
        check(&row, line)?;
        rows.push(row);
    }
    if rows.is_empty() {
        anyhow::bail!(
            "{}: no rows; expected a header line and at least one row",
            path.display()
        );
    }
    Ok(rows)
}

/// A CSV error of the file `path` at its `line`: what was found and what was expected (`row`,
/// the header and the record, names a field that did not parse).
fn csv_error(
    path: &std::path::Path,
    line: u64,
    e: &csv::Error,
    row: Option<(&csv::StringRecord, &csv::StringRecord)>,
) -> anyhow::Error {
    let (at, message) = crate::report::diff::worded(e, row);
    anyhow::anyhow!("{}:{}: {message}", path.display(), at.unwrap_or(line))
}

/// Why a `--world-size` value was refused.
#[derive(Debug, thiserror::Error)]
enum WorldSizeError {
    #[error("{0} is not a world size: give a finite number of tiles, 0 or more")]
    OutOfRange(f64),
    #[error("{0:?} is not a number of tiles: {1}")]
    NotANumber(String, std::num::ParseFloatError),
}

/// A world size for `stress --world-size`: a finite number of tiles, 0 or more.
fn parse_world_size(s: &str) -> Result<f64, WorldSizeError> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        Ok(v) => Err(WorldSizeError::OutOfRange(v)),
        Err(e) => Err(WorldSizeError::NotANumber(s.to_string(), e)),
    }
}
