//! `platbench sweep`, the trade-off command: cost against error over each controller's grid of
//! settings (the command keeps the name users know; the code calls it what it is).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;

use super::select::Selection;
use super::{load_levels, out, output, Harness};
use crate::tradeoff::Setting;

pub(crate) fn tradeoff(
    h: &Harness,
    out_dir: &std::path::Path,
    force: bool,
    level_files: &[PathBuf],
    (score, pixels_per_tile): (Option<&str>, &str),
    select: &Selection,
) -> Result<()> {
    use crate::metrics::score::Score;
    use crate::tradeoff::{chart_svg_scope, run_tradeoff_reporting, scored_behaviours, ALL};
    output::check_target(out_dir, output::Kind::Sweep, force)?;
    let score = match score {
        Some(s) => Score::parse(s)?,
        None => Score::default(),
    }
    .at_pixels_per_tile(pixels_per_tile)?;
    let levels = select.levels(load_levels(level_files)?)?;
    let settings = selected_settings(h, select)?;
    let jobs = super::select::jobs_for_levels(select.jobs(), &levels);
    eprintln!("error score: {}", score.describe());
    let started = Instant::now();
    let mut failures = Vec::new();
    let rows = run_tradeoff_reporting(
        &levels,
        &settings,
        &score,
        jobs,
        |done, total, label| {
            let width = 30;
            let filled = done * width / total.max(1);
            eprintln!(
                "  [{}{}] {done}/{total} {label} ({:.0} s)",
                "#".repeat(filled),
                ".".repeat(width - filled),
                started.elapsed().as_secs_f64()
            );
        },
        |e| {
            eprintln!("  error: {e} (its setting gets no row; the others go on)");
            failures.push(e.to_string());
        },
    )?;
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
    if most == 0 && !failures.is_empty() {
        return super::run::failed_runs(&failures);
    }
    if most == 0 {
        anyhow::bail!(
            "nothing was measured: no selected setting models a selected scenario (each skipped the levels whose features it does not model; see above); nothing written"
        );
    }
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
    super::run::failed_runs(&failures)
}

/// The registry's grid of settings cut and set by the selection options: `--dt` replaces the
/// time step of every setting but those that set their own (labelled `dt=`), `--epsilon` the
/// overlap tolerance of every setting but those that set their own (labelled `epsilon=`).
fn selected_settings(h: &Harness, select: &Selection) -> Result<Vec<Setting>> {
    let sets_own = |label: &str, what: &str| label.contains(&format!("{what}="));
    let base = h
        .registry
        .tradeoff_settings()
        .into_iter()
        .map(|s| {
            let own = (s.label, s.run.label.clone(), s.dt);
            (s.run, own)
        })
        .collect();
    let dt = select.dt()?;
    let selected = select.configs(h, base, |run| sets_own(&run.label, "epsilon"))?;
    Ok(selected
        .into_iter()
        .map(|(run, (label, run_label, own_dt))| {
            // A build in another precision is labelled as its run is; an override is said.
            let mut label = run.label.replacen(&run_label, &label, 1);
            if let (Some(eps), Some(_), false) = (
                select.epsilon,
                run.backend.epsilon(),
                sets_own(&run.label, "epsilon"),
            ) {
                label = format!("{label} epsilon={eps}");
            }
            let dt = match dt {
                Some(dt) if !sets_own(&run.label, "dt") => {
                    label = format!("{label} dt={dt}");
                    Some(dt)
                }
                _ => own_dt,
            };
            Setting { label, dt, run }
        })
        .collect())
}
