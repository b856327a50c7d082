//! `platbench stress`: the invariants at the extremes, per backend's stress configurations.

use std::time::Instant;

use anyhow::Result;

use super::{out, output, Harness};

pub(crate) fn stress(
    h: &Harness,
    out_dir: &std::path::Path,
    force: bool,
    jobs: usize,
) -> Result<()> {
    use crate::report::html::{breaks_list, value_list};
    use crate::stress::{envelope, stress_matrix_on};
    let runs = h.registry.stress_configs();
    output::check_target(out_dir, output::Kind::Stress, force)?;
    let started = Instant::now();
    let rows = stress_matrix_on(&runs, jobs, |what| eprintln!("  {what}"))?;
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
