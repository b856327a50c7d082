//! `platbench baseline`: run a selection and write it, with its manifest, as a baseline that
//! `platbench check` compares later runs of the same selection against. Also the manifest of
//! `run --bless`, and the selection a manifest records, read back for `check` and `review`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::Args;

use super::run::{RunArgs, Traces};
use super::select::Selection;
use super::{load_levels_with, output, Harness, ImportArgs};
use crate::config::RunConfig;
use crate::level::Level;
use crate::report::manifest::{content_hash, ConfigRecord, LevelRecord, Manifest, SelectionRecord};

/// `platbench baseline`'s options: `run`'s selection, and where the baseline goes.
#[derive(Args)]
#[command(allow_negative_numbers = true)]
pub(crate) struct BaselineArgs {
    /// Level files: TOML, Tiled maps (.tmx, .tmj) or LDtk projects (.ldtk), told by content; the built-in set when
    /// none is given. Recorded as given: `check` reads them from the same paths, relative to the
    /// directory it runs in.
    pub(crate) levels: Vec<PathBuf>,
    /// The baseline directory to write (placeholder; the harness sets the real help).
    #[arg(long = "baseline", value_name = "DIR")]
    pub(crate) baseline: Option<PathBuf>,
    /// Replace the baseline directory when it already holds a baseline. Without it an existing
    /// baseline is refused, so that one is replaced only on purpose; a missing or empty
    /// directory is written either way, and any other directory is never replaced.
    #[arg(long)]
    pub(crate) replace: bool,
    /// Which traces the baseline keeps: `all` (the default), `none` (metrics.csv only: `check`
    /// then compares metrics only), or `failing` (as `run --traces failing`).
    #[arg(long, value_enum, value_name = "WHICH")]
    pub(crate) traces: Option<Traces>,
    /// Also time each scenario (as `run --timing`); `check` reports timing changes but fails on
    /// them only with --fail-on-timing.
    #[arg(long)]
    pub(crate) timing: bool,
    #[command(flatten)]
    pub(crate) select: Selection,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

/// Where the baseline directory of `given` (or the harness's) came from, as an error names it:
/// `--baseline`, the `PLATBENCH_BASELINE` environment variable, or the harness's default.
pub(crate) fn baseline_origin(h: &Harness, given: Option<&Path>) -> &'static str {
    if given.is_some() {
        "--baseline"
    } else if std::env::var_os("PLATBENCH_BASELINE").is_some_and(|v| Path::new(&v) == h.baseline) {
        "PLATBENCH_BASELINE"
    } else {
        "the harness's baseline"
    }
}

/// The baseline directory of `given`, or the harness's.
pub(crate) fn baseline_dir(h: &Harness, given: Option<&Path>) -> PathBuf {
    given.map_or_else(|| h.baseline.clone(), Path::to_path_buf)
}

/// The help of a `--baseline DIR` option, naming the harness's default.
pub(crate) fn baseline_help(h: &Harness, what: &str) -> String {
    let default = match std::env::current_dir() {
        Ok(cwd) if h.baseline.is_relative() => format!(
            "{} (here: {})",
            h.baseline.display(),
            cwd.join(&h.baseline).display()
        ),
        _ => h.baseline.display().to_string(),
    };
    format!(
        "The baseline directory {what}. Default: the harness's baseline, {default}: the `PLATBENCH_BASELINE` environment variable if set, else `platbench-baseline` in the current directory (for platbench itself, its repository's compare/baseline)"
    )
}

pub(crate) fn baseline(h: &Harness, args: &BaselineArgs) -> Result<()> {
    let dir = baseline_dir(h, args.baseline.as_deref());
    refuse_unless_replacing(&dir, args.replace)?;
    let origin = baseline_origin(h, args.baseline.as_deref());
    output::check_target_as(&dir, output::Kind::Baseline, false, origin)?;
    let run = RunArgs {
        levels: args.levels.clone(),
        traces: Some(args.traces.unwrap_or(Traces::All)),
        timing: args.timing,
        select: args.select.clone(),
        import: args.import.clone(),
        ..RunArgs::default()
    };
    let levels = run
        .select
        .levels(load_levels_with(&run.levels, &run.import)?)?;
    let configs = run.select.builtin_configs(h)?;
    let asked = if run.timing { 1 } else { run.select.jobs() };
    let jobs = super::select::jobs_for_levels(asked, &levels);
    let manifest = manifest_of(&run, &levels, &configs)?;
    eprintln!(
        "platbench baseline: {} scenarios on {} configurations into {}",
        levels.iter().map(|l| l.scenarios.len()).sum::<usize>(),
        configs.len(),
        dir.display()
    );
    let started = Instant::now();
    let mut done = (0, 0);
    output::write_output(&dir, output::Kind::Baseline, false, |staging| {
        let traces = run.traces.unwrap_or(Traces::All);
        let e = super::run::execute(
            &h.registry,
            &levels,
            &configs,
            &run,
            jobs,
            Some((staging, traces)),
        )?;
        done = (e.4, e.5);
        // A baseline holds every run of its selection: one that failed leaves none written.
        super::run::failed_runs(&e.7)?;
        manifest.write(staging)?;
        Ok(())
    })?;
    eprintln!("ran in {:.2} s", started.elapsed().as_secs_f64());
    super::out(&format!(
        "wrote the baseline {}: {} metric rows, {} traces, and {} (the selection, {} levels, {} configurations, platbench {})",
        dir.display(),
        done.0,
        done.1,
        crate::report::manifest::FILE,
        manifest.levels.len(),
        manifest.configs.len(),
        manifest.platbench
    ));
    Ok(())
}

/// Refuses an existing baseline at `dir` unless `replace`.
fn refuse_unless_replacing(dir: &Path, replace: bool) -> Result<()> {
    let marker = output::read_marker(dir);
    if !replace && marker.lines().next() == Some("platbench baseline") {
        bail!(
            "{} already holds a baseline; a baseline is replaced only on purpose: pass --replace to write this run over it (or choose another --baseline DIR)",
            dir.display()
        );
    }
    Ok(())
}

/// The manifest of a run of `args` over `levels` and `configs`.
pub(crate) fn manifest_of(
    args: &RunArgs,
    levels: &[Level],
    configs: &[RunConfig],
) -> Result<Manifest> {
    let s = &args.select;
    let selection = SelectionRecord {
        files: args
            .levels
            .iter()
            .map(|p| p.display().to_string())
            .collect(),
        backends: s.backends.clone(),
        shapes: s.shapes.clone(),
        precisions: s.precisions.clone(),
        scenarios: s.scenarios.clone(),
        dt: s.dt,
        epsilon: s.epsilon,
        traces: traces_word(args.traces.unwrap_or(Traces::All)).into(),
        timing: args.timing,
        layers: args.import.layers.clone(),
        tile_layers: args.import.tile_layers.clone(),
        spawns: args.import.spawns.clone(),
        intgrid: args.import.intgrid.clone(),
        ldtk_level: args.import.level.clone(),
        edges: args.import.edges.clone(),
        controllers: s
            .controllers
            .iter()
            .map(|p| p.display().to_string())
            .collect(),
    };
    let mut records = Vec::new();
    for l in levels {
        records.push(LevelRecord {
            name: l.name.clone(),
            source: l.source.clone(),
            hash: level_hash(&args.levels, l)?,
            scenarios: l.scenarios.iter().map(|s| s.name.clone()).collect(),
        });
    }
    let configs = configs
        .iter()
        .map(|c| ConfigRecord {
            backend: c.backend.backend().to_string(),
            label: c.label.clone(),
        })
        .collect();
    Ok(Manifest::new(selection, records, configs))
}

/// The content hash of the file `level` was read from: a built-in level's embedded text, or the
/// file given whose path is its source.
pub(crate) fn level_hash(files: &[PathBuf], level: &Level) -> Result<String> {
    if let Some(file) = level.source.strip_prefix("builtin:") {
        if let Some((_, text)) = crate::builtin::LEVELS.iter().find(|(f, _)| *f == file) {
            return Ok(content_hash(text.as_bytes()));
        }
    }
    let path = files
        .iter()
        .find(|p| p.display().to_string() == level.source)
        .map_or_else(|| PathBuf::from(&level.source), PathBuf::clone);
    let bytes = crate::limits::read_capped(&path)
        .with_context(|| format!("cannot read {} to hash it", path.display()))?;
    Ok(content_hash(&bytes))
}

/// `--traces` as the manifest records it.
fn traces_word(t: Traces) -> &'static str {
    match t {
        Traces::All => "all",
        Traces::Failing => "failing",
        Traces::None => "none",
    }
}

/// The options of a run of the selection `m` records, on `jobs` threads.
pub(crate) fn run_args_of(m: &Manifest, jobs: Option<u32>) -> RunArgs {
    let s = &m.selection;
    RunArgs {
        levels: s.files.iter().map(PathBuf::from).collect(),
        traces: Some(match s.traces.as_str() {
            "none" => Traces::None,
            "failing" => Traces::Failing,
            _ => Traces::All,
        }),
        timing: s.timing,
        select: Selection {
            backends: s.backends.clone(),
            shapes: s.shapes.clone(),
            precisions: s.precisions.clone(),
            dt: s.dt,
            epsilon: s.epsilon,
            scenarios: s.scenarios.clone(),
            jobs,
            controllers: s.controllers.iter().map(PathBuf::from).collect(),
        },
        import: ImportArgs {
            layers: s.layers.clone(),
            tile_layers: s.tile_layers.clone(),
            spawns: s.spawns.clone(),
            intgrid: s.intgrid.clone(),
            level: s.ldtk_level.clone(),
            edges: s.edges.clone(),
        },
        ..RunArgs::default()
    }
}

/// The levels and configurations of the selection `args` (read back from a manifest), with a
/// note for each level file whose content changed since the manifest was written.
pub(crate) fn selection_of(
    h: &Harness,
    m: &Manifest,
    args: &RunArgs,
) -> Result<(Vec<Level>, Vec<RunConfig>, Vec<String>)> {
    for f in &args.levels {
        if !f.exists() {
            bail!(
                "the baseline's level file {} is not there (the manifest records it relative to the directory `platbench baseline` ran in; run check from that directory)",
                f.display()
            );
        }
    }
    let levels = args
        .select
        .levels(load_levels_with(&args.levels, &args.import)?)?;
    let configs = args.select.builtin_configs(h)?;
    let mut notes = Vec::new();
    for l in &levels {
        match m.levels.iter().find(|r| r.name == l.name) {
            Some(r) => {
                let now = level_hash(&args.levels, l)?;
                if now != r.hash {
                    notes.push(format!(
                        "level {} ({}) changed since the baseline ({} then, {now} now): its scenarios may differ because of that",
                        l.name, l.source, r.hash
                    ));
                }
            }
            None => notes.push(format!(
                "level {} ({}) is not in the baseline's manifest",
                l.name, l.source
            )),
        }
    }
    Ok((levels, configs, notes))
}
