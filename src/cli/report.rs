//! `platbench report`: the "pick a backend" report, HTML and Markdown.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;

use super::run::evaluate_or_skip;
use super::select::Selection;
use super::{load_levels_with, output, read_rows_checked, Harness, ImportArgs};
use crate::metrics::MetricRow;
use crate::scenario::Runner;
use crate::trace::Trace;

#[derive(Args)]
pub(crate) struct ReportArgs {
    /// Level files: TOML, Tiled maps (.tmx, .tmj) or LDtk projects (.ldtk), told by content; the built-in set when
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
    /// Include the speed-against-accuracy chart from this tradeoff.csv (written by
    /// `platbench sweep`).
    #[arg(long, value_name = "FILE")]
    pub(crate) tradeoff: Option<PathBuf>,
    /// Include the stability table from this stability.csv (written by `platbench stress`).
    #[arg(long, value_name = "FILE")]
    pub(crate) stability: Option<PathBuf>,
    /// A game profile file (TOML; see compare/profiles/pixel_precise.toml for the format): the
    /// verdict judges these profiles instead of the built-in ones (repeat for several).
    #[arg(long = "profile", value_name = "FILE")]
    pub(crate) profiles: Vec<PathBuf>,
    #[command(flatten)]
    pub(crate) select: Selection,
    #[command(flatten)]
    pub(crate) import: ImportArgs,
}

/// Reads a tradeoff.csv and checks what the chart draws: each cost and error score finite and
/// >= 0 (a damaged file drew NaN and -1e308 costs), and at least one setting per row.
fn read_tradeoff(path: &std::path::Path) -> Result<Vec<crate::tradeoff::TradeoffRow>> {
    // `platbench sweep` writes a few hundred rows; the chart draws an element per row.
    let rows: Vec<crate::tradeoff::TradeoffRow> =
        super::read_rows_capped(path, crate::limits::MAX_TRADEOFF_ROWS)?;
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

/// Reads a stability.csv, refusing it at its row past [`crate::limits::MAX_STABILITY_ROWS`]
/// or at the row that would make the report's combination grids hold more than
/// [`crate::limits::MAX_STABILITY_GRID_CELLS`] cells together: a grid has a cell for every row
/// and column, measured or not, so a few thousand rows of distinct values could ask for
/// millions.
fn read_stability(path: &std::path::Path) -> Result<Vec<crate::stress::StressRow>> {
    use crate::limits::MAX_STABILITY_GRID_CELLS as MAX;
    use crate::report::GridShape;
    let mut grids: std::collections::HashMap<String, GridShape> = Default::default();
    let mut total = 0u64;
    let most = crate::limits::MAX_STABILITY_ROWS;
    read_rows_checked(path, most, |r: &crate::stress::StressRow, line| {
        if r.dimension2.is_empty() {
            return Ok(());
        }
        let pair = format!("{} x {}", r.dimension, r.dimension2);
        let g = grids.entry(pair.clone()).or_default();
        let before = g.cells();
        let config = format!("{} {}", r.backend, r.config);
        g.add(&config, r.value, r.value2.unwrap_or(f64::NAN));
        total += g.cells() - before;
        if total > MAX {
            bail!(
                "{}:{line}: the combination grids would hold {total} cells ({pair}: {} rows of configuration and value x {} values); expected at most {MAX} (a stability.csv written by `platbench stress` draws about 250)",
                path.display(),
                g.rows.len(),
                g.columns.len()
            );
        }
        Ok(())
    })
}

/// The runner of level `li` from `cache`, made anew when the cache holds another level's.
fn runner_for<'c, 'a>(
    cache: &'c mut Option<(usize, Runner<'a>)>,
    levels: &'a [crate::level::Level],
    li: usize,
) -> &'c mut Runner<'a> {
    if cache.as_ref().is_none_or(|(l, _)| *l != li) {
        *cache = None;
    }
    &mut cache
        .get_or_insert_with(|| (li, Runner::new(&levels[li])))
        .1
}

pub(crate) fn report(h: &Harness, args: &ReportArgs) -> Result<()> {
    use crate::report::html::{render_report, Extras, ReplayRun, ScenarioTraces};
    // The extra files first: a bad one fails before the long run.
    output::check_target(&args.out, output::Kind::Report, args.force)?;
    let profiles = super::profiles::load_profiles(&args.profiles)?;
    let mut extras = Extras {
        // Filled once the run is in (below).
        verdict: String::new(),
        verdict_text: String::new(),
        tradeoff: args.tradeoff.as_deref().map(read_tradeoff).transpose()?,
        stability: args.stability.as_deref().map(read_stability).transpose()?,
    };
    let levels = args
        .select
        .levels(load_levels_with(&args.levels, &args.import)?)?;
    let configs = args.select.builtin_configs(h)?;
    let mut metrics: Vec<MetricRow> = Vec::new();
    // Per scenario: each run's trace, shape, moved size and per-frame faults.
    type Run = (Trace, crate::shape::CharacterShape, glam::Vec2, Vec<u8>);
    let mut per_scenario: Vec<(usize, usize, Vec<Run>)> = Vec::new();
    let mut skipped: Vec<String> = Vec::new();
    // Every (level, scenario), fanned out over --jobs threads; each thread keeps the runner of
    // the level it is on (its built geometry), and the results are taken in order.
    let items: Vec<(usize, usize)> = levels
        .iter()
        .enumerate()
        .flat_map(|(li, l)| (0..l.scenarios.len()).map(move |si| (li, si)))
        .collect();
    type Done = (Vec<MetricRow>, Vec<Run>, Vec<String>);
    let work = |cache: &mut Option<_>, i: usize| -> Result<Done> {
        let (li, si) = items[i];
        let level = &levels[li];
        let runner = runner_for(cache, &levels, li);
        let spec = &level.scenarios[si];
        let (mut rows, mut runs, mut notes) = (Vec::new(), Vec::new(), Vec::new());
        for run in &configs {
            let Some(e) = evaluate_or_skip(runner, spec, run, &mut notes)? else {
                continue;
            };
            rows.extend(e.metrics);
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
        Ok((rows, runs, notes))
    };
    crate::parallel::for_each_ordered(
        super::select::jobs_for_levels(args.select.jobs(), &levels),
        items.len(),
        || None,
        work,
        |i, done: Result<Done>| -> Result<()> {
            let (rows, runs, notes) = done?;
            for note in notes {
                if !skipped.contains(&note) {
                    eprintln!("  skipped {note}");
                    skipped.push(note);
                }
            }
            metrics.extend(rows);
            let (li, si) = items[i];
            per_scenario.push((li, si, runs));
            if si + 1 == levels[li].scenarios.len() {
                eprintln!("  {}", levels[li].name);
            }
            Ok(())
        },
    )?;
    if metrics.is_empty() {
        bail!(
            "nothing was measured: no selected configuration models a selected scenario (see the skips above); nothing written"
        );
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
    // The verdict over every row, in run order (scenario by scenario, configuration by
    // configuration), as `run` makes it.
    let facts = configs
        .iter()
        .map(|c| super::profiles::facts(c, &h.registry))
        .collect();
    let level_features = levels
        .iter()
        .map(|l| (l.name.clone(), l.features))
        .collect();
    let card = crate::report::verdict::VerdictRows::of(facts, level_features, &metrics);
    let verdicts: Vec<_> = profiles
        .iter()
        .map(|p| crate::report::verdict::pick(&card, p))
        .collect();
    extras.verdict = crate::report::verdict::render_verdict_html(
        &card,
        &verdicts,
        &super::profiles::profile_source(&args.profiles),
    );
    extras.verdict_text = super::profiles::verdict_text(&card, &profiles, &args.profiles);
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
