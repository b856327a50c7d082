//! `platbench stress`: the invariants at the extremes, per backend's stress configurations.

use std::time::Instant;

use anyhow::{bail, Result};

use super::select::Selection;
use super::{out, output, Harness};

pub(crate) fn stress(
    h: &Harness,
    out_dir: &std::path::Path,
    force: bool,
    world_size: Option<f64>,
    select: &Selection,
) -> Result<()> {
    use crate::report::html::breaks_list;
    use crate::stress::{stress_matrix_reporting, verdicts, world_verdicts};
    if !select.scenarios.is_empty() {
        bail!(
            "--scenario {}: stress runs its own probe levels (a fast mover, a seam, a platform, a jump), not level files; drop --scenario",
            select.scenarios.join(",")
        );
    }
    let base = h.registry.stress_configs().into_iter().map(|c| (c, ()));
    let runs: Vec<_> = select
        .configs(h, base.collect(), |_| false)?
        .into_iter()
        .map(|(c, ())| c)
        .collect();
    output::check_target(out_dir, output::Kind::Stress, force)?;
    let mut runs = runs;
    if let Some(dt) = select.dt()? {
        crate::stress::check_base_dt(dt).map_err(|e| anyhow::anyhow!("--dt {dt}: {e}"))?;
    }
    // stability.csv's rows say when their base is not the default's.
    for r in &mut runs {
        if let Some(dt) = select.dt {
            r.label = format!("{} dt={dt}", r.label);
        }
        if let (Some(eps), Some(_)) = (select.epsilon, r.backend.epsilon()) {
            r.label = format!("{} epsilon={eps}", r.label);
        }
    }
    let started = Instant::now();
    let mut failures = Vec::new();
    let rows = stress_matrix_reporting(
        &runs,
        select.dt()?,
        // Each thread builds a probe level's world at a time.
        super::select::jobs_within_memory_noted(select.jobs(), crate::stress::PROBE_TILES),
        |what| eprintln!("  {what}"),
        |e| {
            eprintln!("  error: {e} (the other probes go on)");
            failures.push(e.to_string());
        },
    )?;
    eprintln!("ran in {:.1} s", started.elapsed().as_secs_f64());
    let table = |header: Vec<String>| {
        let mut t = comfy_table::Table::new();
        t.load_style(comfy_table::presets::ASCII_MARKDOWN);
        t.set_header(header);
        t
    };
    let mut t = table(
        [
            "configuration",
            "dimension",
            "verdict",
            "each invariant that broke, where",
        ]
        .map(String::from)
        .to_vec(),
    );
    let envelopes = crate::stress::envelopes_by_key(&rows);
    for v in verdicts(&rows) {
        let breaks = envelopes
            .get(&(v.config.clone(), v.dimension.clone()))
            .map_or("-".into(), breaks_list);
        t.add_row(vec![
            v.config.clone(),
            v.dimension.clone(),
            v.text(),
            breaks,
        ]);
    }
    out(&t.to_string());
    out("");
    let mut t = table(
        [
            "configuration",
            "how far from the origin it holds (offset, tiles; what broke at 0 set aside)",
        ]
        .map(String::from)
        .to_vec(),
    );
    for r in crate::stress::reach(&rows) {
        t.add_row(vec![r.config.clone(), r.text()]);
    }
    out(&t.to_string());
    for t in crate::report::html::pair_tables(&rows) {
        out("");
        out(&t);
    }
    if let Some(size) = world_size {
        out("");
        let mut t = table(
            [
                format!(
                    "in a world of {} tiles",
                    crate::report::format_setting(size)
                ),
                "holds".into(),
                "verdict".into(),
                "combination cells within it that break".into(),
            ]
            .to_vec(),
        );
        for w in world_verdicts(&rows, size) {
            let holds = match w.holds {
                Some(true) => "yes",
                Some(false) => "no",
                None => "not measured",
            };
            let combos = if w.combinations.is_empty() {
                "-".to_string()
            } else {
                w.combinations.join("; ")
            };
            t.add_row(vec![w.config, holds.into(), w.text, combos]);
        }
        out(&t.to_string());
    }
    output::write_output(out_dir, output::Kind::Stress, force, |dir| {
        output::write_csv(&dir.join("stability.csv"), &rows)
    })?;
    eprintln!("wrote {}", out_dir.join("stability.csv").display());
    super::run::failed_runs(&failures)
}
