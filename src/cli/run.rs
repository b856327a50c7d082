//! `platbench run` (and `platbench` with no subcommand): run every scenario on every
//! configuration of the registry, print the summary, write the CSV files.

use std::io::IsTerminal as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::profiles::{facts, load_profiles, verdict_text};
use super::select::Selection;
use super::{load_levels_with, out, output, Harness, ImportArgs};
use crate::config::RunConfig;
use crate::metrics::{evaluate_recorded, evaluate_with, MetricRow, RecordError};
use crate::parallel;
use crate::report::cost::CostRows;
use crate::report::summary_rows::SummaryRows;
use crate::report::verdict::{Scorecard, VerdictRows};
use crate::report::{detail_table, summary_table_in, Coverage};
use crate::scenario::Runner;
use crate::trace::RowStore;

#[derive(Args, Default)]
#[command(allow_negative_numbers = true)]
pub(crate) struct RunArgs {
    /// Level files: TOML, Tiled maps (.tmx, .tmj) or LDtk projects (.ldtk), told by content; the built-in set when
    /// none is given.
    pub(crate) levels: Vec<PathBuf>,
    /// Output directory for metrics.csv and the traces; without it nothing is written. Replaced
    /// as a whole once the run is complete. It must be missing, empty, or an earlier
    /// `platbench run` output (it holds a .platbench-output marker file); anything else is
    /// refused unless --force. A baseline (its marker says so) is refused even with --force:
    /// only --bless, `platbench baseline --replace` and `platbench review` replace one.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Replace --out even when it is not an earlier run's output (a directory of your own
    /// files, another command's output): everything in it is deleted.
    #[arg(long, requires = "out")]
    pub(crate) force: bool,
    /// Which traces --out gets: `all` (the default), `none` (metrics.csv only), or `failing`:
    /// the runs of which a metric of the default error score (registry weight above 0) is off
    /// its reference by more than the size that counts as clearly wrong (0.01 tiles, 0.01 for a
    /// ratio or tiles/s, one frame, one count) beyond the pixel a 16-pixel tile cannot show (one
    /// pixel for a length, one pixel per second for a speed), or is NaN. A run that errors stops
    /// the run.
    #[arg(long, value_enum, value_name = "WHICH", requires = "out")]
    pub(crate) traces: Option<Traces>,
    /// After the verdict and the scorecard, print the worst value of every metric per
    /// configuration, the statements they support, and every metric of every scenario (this
    /// holds every metric row in memory until the end; without it only the rows the verdict
    /// needs are kept).
    #[arg(long)]
    pub(crate) detail: bool,
    /// A game profile file (TOML; see compare/profiles/pixel_precise.toml for the format): the
    /// verdict judges these profiles instead of the built-in ones (repeat for several).
    #[arg(long = "profile", value_name = "FILE")]
    pub(crate) profiles: Vec<PathBuf>,
    /// Replace the committed baseline (compare/baseline for platbench itself; the harness's
    /// baseline directory for a crate calling platbench::cli) with this run, and its
    /// manifest.toml. Runs the built-in set with every configuration (`platbench baseline`
    /// writes a baseline of a selection of your choosing).
    #[arg(long, conflicts_with_all = ["levels", "out", "dt", "epsilon", "backends", "shapes", "timing", "traces", "precisions", "scenarios"])]
    pub(crate) bless: bool,
    /// Also time each scenario on each configuration (in process, 11 whole runs after the
    /// measured one) and add an ns_per_character_step row per scenario and configuration to
    /// metrics.csv: the median of the runs' ns per step, their quartiles in its q1 and q3
    /// columns. With several configurations timed, the summary ends with each one's cost
    /// against the cheapest's. Runs on one thread whatever --jobs says, so that nothing runs
    /// beside a timed step.
    #[arg(long)]
    pub(crate) timing: bool,
    #[command(flatten)]
    pub(crate) select: Selection,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

/// Runs one scenario on one configuration; a configuration that does not model something in the
/// level is left out of that level, noted once in `skipped` (never run on part of it), for the
/// caller to say.
pub(crate) fn evaluate_or_skip(
    runner: &mut Runner,
    spec: &crate::level::ScenarioSpec,
    run: &RunConfig,
    skipped: &mut Vec<String>,
) -> Result<Option<crate::metrics::Evaluation>> {
    let level = runner.level();
    match evaluate_with(runner, spec, run) {
        Err(e) if e.is_failure() => {
            // The run ends alone; the others go on, and the note says it failed.
            eprintln!("  error: {e}");
            skipped.push(format!("FAILED: {e}"));
            Ok(None)
        }
        Err(e) if e.is_unsupported() => {
            let note = format!("{} {}: {e}", run.backend.backend(), run.label);
            if !skipped.contains(&note) {
                skipped.push(note);
            }
            Ok(None)
        }
        e => e.map(Some).with_context(|| running(level, spec, run)),
    }
}

/// The context of an error of one run: which scenario on which configuration.
fn running(
    level: &crate::level::Level,
    spec: &crate::level::ScenarioSpec,
    run: &RunConfig,
) -> String {
    format!(
        "running {}.{} on {}/{}",
        level.name,
        spec.name,
        run.backend.backend(),
        run.label
    )
}

pub(crate) fn run(h: &Harness, args: &RunArgs) -> Result<()> {
    // Where the run goes, checked before any work: a directory that is not this command's
    // output (or a baseline, without --bless) is refused now, not after the run. Without --out
    // (or --bless) nothing is written.
    let (target, kind) = if args.bless {
        (Some(h.baseline.clone()), output::Kind::Baseline)
    } else {
        (args.out.clone(), output::Kind::Run)
    };
    if let Some(target) = &target {
        let flag = if args.bless {
            super::baseline::baseline_origin(h, None)
        } else {
            "--out"
        };
        output::check_target_as(target, kind, args.force, flag)?;
    }
    let levels = args
        .select
        .levels(load_levels_with(&args.levels, &args.import)?)?;
    let configs = args.select.builtin_configs(h)?;
    let profiles = load_profiles(&args.profiles)?;
    // The runs that will write a trace: a configuration that does not model a level's
    // features skips that level (said once, below).
    let scenarios: usize = levels.iter().map(|l| l.scenarios.len()).sum();
    let total = modelled_runs(&levels, &configs);
    let skipped_runs = scenarios * configs.len() - total;
    // Timing measures one thread with nothing else running beside it.
    let asked = if args.timing { 1 } else { args.select.jobs() };
    let jobs = super::select::jobs_for_levels(asked, &levels);
    eprintln!(
        "platbench: {scenarios} scenarios on {} configurations ({total} runs{}) on {jobs} thread{}",
        configs.len(),
        if skipped_runs > 0 {
            format!(", {skipped_runs} skipped where a configuration does not model a level")
        } else {
            String::new()
        },
        if jobs == 1 { "" } else { "s" }
    );
    let traces = if args.bless {
        Traces::All
    } else {
        args.traces.unwrap_or(Traces::All)
    };
    let started = Instant::now();
    let (metrics, coverage, notes, verdict, rows, written, cost, failures) = match &target {
        Some(target) => {
            let mut result = None;
            output::write_output(target, kind, args.force, |dir| {
                result = Some(execute(
                    &h.registry,
                    &levels,
                    &configs,
                    args,
                    jobs,
                    Some((dir, traces)),
                )?);
                if args.bless {
                    // What the baseline holds, for `platbench check`.
                    super::baseline::manifest_of(args, &levels, &configs)?.write(dir)?;
                }
                Ok(())
            })?;
            result.unwrap_or_default()
        }
        None => execute(&h.registry, &levels, &configs, args, jobs, None)?,
    };
    eprintln!("ran in {:.2} s", started.elapsed().as_secs_f64());
    out(&verdict_text(&verdict, &profiles, &args.profiles));
    if args.detail {
        let mut text = summary_table_in(&metrics, &coverage);
        for n in notes {
            text.push_str(&format!("\n- {n}"));
        }
        for (c, why) in crate::report::notes::why_lines(&coverage, &configs, &h.registry) {
            text.push_str(&format!("\n- {c}: {why}"));
        }
        out(&format!(
            "\nWorst value of each metric per configuration:\n{text}"
        ));
        out(&format!(
            "\nEvery metric of every scenario:\n{}",
            detail_table(&metrics)
        ));
    } else {
        out("\n(`--detail` prints the worst value of every metric and every scenario's; `--out DIR` writes the CSV files\nand traces; `platbench report` writes the HTML report with replays)");
    }
    let lines = cost.closing_lines();
    if !lines.is_empty() {
        out(&format!(
            "\nCost per character step (median of each scenario's ratio of median times, ± half their interquartile range):\n  {}",
            lines.join("\n  ")
        ));
    }
    if let Some(target) = &target {
        eprintln!(
            "wrote {written} traces ({}) and {rows} metric rows to {}",
            traces.describe(),
            target.display()
        );
    }
    failed_runs(&failures)
}

/// An error when runs failed (each said on stderr as it happened; the others ran).
pub(crate) fn failed_runs(failures: &[String]) -> Result<()> {
    match failures {
        [] => Ok(()),
        [one] => bail!("a run failed (the others completed): {one}"),
        [first, ..] => bail!(
            "{} runs failed (the others completed; each said above), the first: {first}",
            failures.len()
        ),
    }
}

/// Which traces `run --out` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Traces {
    /// No trace: only metrics.csv.
    None,
    /// Only the traces of failing runs (see [`failing`]).
    Failing,
    /// Every run's trace.
    All,
}

impl Traces {
    fn describe(self) -> &'static str {
        match self {
            Traces::None => "--traces none",
            Traces::Failing => "--traces failing: the failing runs'",
            Traces::All => "every run's",
        }
    }
}

/// Whether a run fails: a metric of the default error score (a registry weight above 0) is off
/// its reference by more than the size that counts as clearly wrong (0.01 tiles, 0.01 for a
/// ratio or tiles/s, one frame, one count; [`crate::metrics::MetricDef::scale`]) beyond the
/// error a 16-pixel tile cannot show (one pixel, one pixel per second;
/// [`crate::metrics::MetricDef::charged`] above 1, as the verdict grades a row not kept), or is
/// not a number.
pub(crate) fn failing(metrics: &[MetricRow]) -> bool {
    use crate::metrics::registry::{get, DEFAULT_PIXELS_PER_TILE};
    metrics.iter().any(|m| {
        get(m.metric)
            .is_some_and(|d| d.weight > 0.0 && d.charged(m.error, DEFAULT_PIXELS_PER_TILE) > 1.0)
    })
}

/// What one (scenario, configuration) run gave.
enum Outcome {
    /// The configuration does not model the level: the note to print once.
    Skipped(String),
    /// Its metric rows (the timing row first, with --timing), and whether its trace was written.
    Ran(Vec<MetricRow>, bool),
    /// The controller failed during the run (an external controller's process): the message.
    Failed(String),
}

/// The (scenario, configuration) runs of `levels` that `configs` make: a configuration that
/// does not run a level ([`crate::backend::runs`]: its features, its origin) makes none there.
fn modelled_runs(levels: &[crate::level::Level], configs: &[RunConfig]) -> usize {
    levels
        .iter()
        .flat_map(|l| l.scenarios.iter().map(move |s| (l, s)))
        .map(|(l, s)| {
            configs
                .iter()
                .filter(|c| crate::backend::runs_scenario(&*c.backend, l, s))
                .count()
        })
        .sum()
}

/// What [`execute`] returns: the rows the summary reads, the scenarios each configuration ran,
/// the notes, the scorecard, the number of metric rows, the number of traces written, the
/// timings.
type Executed = (
    Vec<MetricRow>,
    Coverage,
    Vec<String>,
    Scorecard,
    usize,
    usize,
    CostRows,
    Vec<String>,
);

/// Runs every scenario of `levels` on every configuration on `jobs` threads, writing each trace
/// `dir` asks for as soon as its run ends and metrics.csv as the rows come, in run order (level,
/// scenario, configuration) whatever the threads. Returns the metric rows the summary needs
/// (every row with --detail; see [`SummaryRows`]) with the scenarios each configuration ran,
/// the notes on the rows, the number of rows, the number of traces written, and the runs that
/// failed (each said on stderr; the others ran).
pub(crate) fn execute<'a>(
    registry: &crate::registry::Registry,
    levels: &'a [crate::level::Level],
    configs: &[RunConfig],
    args: &RunArgs,
    jobs: usize,
    dir: Option<(&std::path::Path, Traces)>,
) -> Result<Executed> {
    // The runs, in order (level, scenario, configuration), found from their index through each
    // level's first run: memory in the levels, not the runs.
    let mut firsts: Vec<usize> = Vec::with_capacity(levels.len());
    let mut runs = 0usize;
    for level in levels {
        firsts.push(runs);
        runs += level.scenarios.len() * configs.len();
    }
    let item = |i: usize| {
        let li = firsts.partition_point(|&f| f <= i) - 1;
        let k = i - firsts[li];
        (li, k / configs.len(), k % configs.len())
    };
    let traces_dir = dir.map(|(d, _)| d.join("traces"));
    if let Some(t) = &traces_dir {
        std::fs::create_dir(t).with_context(|| format!("cannot create {}", t.display()))?;
    }
    let mut csv = match dir {
        Some((d, _)) => {
            let path = d.join("metrics.csv");
            Some((
                csv::Writer::from_path(&path)
                    .with_context(|| format!("cannot create {}", path.display()))?,
                path,
            ))
        }
        None => None,
    };
    let mode = dir.map_or(Traces::None, |(_, m)| m);
    // The timings first, in rounds over every run (each run's samples spread over the whole
    // timing), on this one thread; the measured runs below take their samples.
    let timed = if args.timing {
        let started = Instant::now();
        let live = std::io::stderr().is_terminal();
        let t = crate::metrics::timing::time_rounds(levels, configs, |round| {
            if live {
                eprint!(
                    "\r\x1b[K  timing round {}/{}",
                    round + 1,
                    crate::metrics::timing::SAMPLES
                );
            }
        });
        if live {
            eprint!("\r\x1b[K");
        }
        eprintln!(
            "  timed every run {} times, in rounds, in {:.2} s",
            crate::metrics::timing::SAMPLES,
            started.elapsed().as_secs_f64()
        );
        t
    } else {
        Vec::new()
    };
    // One runner per thread, kept while its jobs stay on one level and one backend (they come
    // in level order, each scenario's configurations grouped by backend): what a backend built
    // for the level (Rapier's colliders) is dropped before another backend builds its world,
    // so a thread holds one backend's world at a time. On a 1000 x 1000 solid map Rapier's
    // per-tile colliders held beside Box2D's per-tile world took a run on one thread from
    // 0.6 to 1.05 GB; rebuilding Rapier's colliders once per scenario costs far less.
    let init = || None::<(usize, &'static str, Runner<'a>)>;
    let work =
        |cache: &mut Option<(usize, &'static str, Runner<'a>)>, i: usize| -> Result<Outcome> {
            let (li, si, ci) = item(i);
            let (level, spec, run) = (&levels[li], &levels[li].scenarios[si], &configs[ci]);
            let backend = run.backend.backend();
            if cache
                .as_ref()
                .is_none_or(|(l, b, _)| *l != li || *b != backend)
            {
                // The old runner's geometry goes before the new one's is built.
                *cache = None;
                *cache = Some((li, backend, Runner::new(level)));
            }
            let Some((_, _, runner)) = cache.as_mut() else {
                unreachable!("set just above")
            };
            let mut e = match evaluate_recorded(runner, spec, run, RowStore::default()) {
                Err(RecordError::Run(e)) if e.is_failure() => {
                    return Ok(Outcome::Failed(e.to_string()));
                }
                Err(RecordError::Run(e)) if e.is_unsupported() => {
                    return Ok(Outcome::Skipped(format!(
                        "{} {}: {e}",
                        run.backend.backend(),
                        run.label
                    )));
                }
                e => e.with_context(|| running(level, spec, run))?,
            };
            let mut metrics = Vec::with_capacity(e.metrics.len() + 1);
            if args.timing {
                let mut samples = timed.get(i).copied().unwrap_or_default();
                let t = crate::metrics::timing::Timing::of(&mut samples).with_context(|| {
                    format!(
                        "timing {}.{} on {}/{}: a sample is not a finite number of ns",
                        level.name,
                        spec.name,
                        run.backend.backend(),
                        run.label
                    )
                })?;
                metrics.push(crate::metrics::timing_row(level, spec, run, t));
            }
            metrics.extend(std::mem::take(&mut e.metrics));
            let keep = match mode {
                Traces::None => false,
                Traces::Failing => failing(&metrics),
                Traces::All => true,
            };
            if let (true, Some(t)) = (keep, &traces_dir) {
                let path = t.join(e.trace.file_name());
                let file = std::fs::File::create(&path)
                    .with_context(|| format!("cannot create {}", path.display()))?;
                e.write_csv(std::io::BufWriter::new(file))
                    .with_context(|| format!("cannot write {}", path.display()))?;
            }
            Ok(Outcome::Ran(metrics, keep))
        };
    // Progress within a level, only for a person watching: a terminal's stderr.
    let live = std::io::stderr().is_terminal();
    let total = modelled_runs(levels, configs);
    // Every row for --detail; else only those the summary needs (see SummaryRows).
    let mut metrics: Vec<MetricRow> = Vec::new();
    let mut kept = SummaryRows::default();
    let mut notes = crate::report::notes::RunNotes::new();
    let mut verdict = VerdictRows::new(
        configs.iter().map(|c| facts(c, registry)).collect(),
        levels
            .iter()
            .map(|l| (l.name.clone(), l.features))
            .collect(),
    );
    let mut rows_seen = 0usize;
    let mut cost = CostRows::default();
    let mut failures: Vec<String> = Vec::new();
    let (mut done, mut written) = (0usize, 0usize);
    // Refusals on the current level, per configuration: the first is said, the others counted
    // and said as a count when the level ends (nothing grows with the scenarios).
    let mut refused: Vec<usize> = vec![0; configs.len()];
    let mut level_start = Instant::now();
    parallel::for_each_ordered(jobs, runs, init, work, |i, outcome| {
        let (li, si, ci) = item(i);
        let level = &levels[li];
        if si == 0 && ci == 0 {
            level_start = Instant::now();
            refused.iter_mut().for_each(|n| *n = 0);
        }
        match outcome? {
            Outcome::Failed(message) => {
                eprintln!("  error: {message}");
                failures.push(message);
            }
            Outcome::Skipped(note) => {
                refused[ci] += 1;
                if refused[ci] == 1 {
                    eprintln!("  skipped {note}");
                }
            }
            Outcome::Ran(rows, wrote) => {
                if let Some((w, path)) = &mut csv {
                    for m in &rows {
                        w.serialize(m)
                            .with_context(|| format!("cannot write {}", path.display()))?;
                    }
                }
                rows_seen += rows.len();
                verdict.push_run(&rows);
                cost.push_run(&rows);
                if args.detail {
                    metrics.extend(rows);
                } else {
                    notes.push_run(&rows);
                    kept.push_run(rows);
                }
                written += wrote as usize;
                done += 1;
            }
        }
        if live {
            eprint!(
                "\r\x1b[K  [{done}/{total}] {}: scenario {}/{} {}",
                level.name,
                si + 1,
                level.scenarios.len(),
                level.scenarios[si].name,
            );
        }
        if si + 1 == level.scenarios.len() && ci + 1 == configs.len() {
            if live {
                eprint!("\r\x1b[K");
            }
            let m = level.scenarios.len();
            for (c, &n) in configs.iter().zip(&refused) {
                if n > 1 && n < m {
                    eprintln!(
                        "  skipped {} {} on {n} of {m} scenarios of {} (the first said above)",
                        c.backend.backend(),
                        c.label,
                        level.name
                    );
                }
            }
            eprintln!(
                "  [{done}/{total}] {} ({}) {:.2} s",
                level.name,
                level.source,
                level_start.elapsed().as_secs_f64()
            );
        }
        Ok::<(), anyhow::Error>(())
    })?;
    if done == 0 && failures.is_empty() {
        bail!(
            "nothing was measured: every configuration refused every scenario (the skipped lines above say why); choose other configurations (--backend, --shape, --precision) or other levels"
        );
    }
    if let Some((mut w, path)) = csv {
        w.flush()
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    let (coverage, notes) = if args.detail {
        (
            Coverage::of(&metrics),
            crate::report::notes::notes(&metrics),
        )
    } else {
        let (rows, coverage) = kept.into_parts();
        metrics = rows;
        (coverage, notes.notes())
    };
    Ok((
        metrics,
        coverage,
        notes,
        verdict.scorecard(),
        rows_seen,
        written,
        cost,
        failures,
    ))
}
