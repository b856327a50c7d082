//! `platbench diff BASE NEW`: the regression compare of two run directories.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use super::out;

#[derive(Args)]
#[command(allow_negative_numbers = true)]
pub(crate) struct DiffArgs {
    /// Baseline run directory (e.g. compare/baseline).
    pub(crate) base: PathBuf,
    /// New run directory (written by `platbench run --out`).
    pub(crate) new: PathBuf,
    /// Override a metric's tolerance: METRIC=ABS or METRIC=ABS,REL (REL a fraction of the
    /// baseline's distance from ideal; both finite and >= 0; METRIC a name of the metric
    /// catalog). Repeatable. Defaults: 1e-5 + 1% for lengths and ratios, exact for counts,
    /// frames and booleans.
    #[arg(long = "tol", value_name = "METRIC=ABS[,REL]")]
    pub(crate) tolerances: Vec<String>,
    /// Position difference at which a trace diverges, in tiles (finite and >= 0).
    #[arg(long, default_value_t = 1e-4, value_name = "TILES")]
    pub(crate) position_tolerance: f32,
    /// Do not fail (exit 1) when a metric or trace of the baseline is missing from the new run;
    /// it is still listed.
    #[arg(long)]
    pub(crate) allow_missing: bool,
    /// Do not fail (exit 1) when a trace diverges beyond --position-tolerance or ends before
    /// (or runs past) the baseline's; it is still listed.
    #[arg(long)]
    pub(crate) allow_divergence: bool,
    /// Output format.
    #[arg(long, default_value = "text", value_parser = ["text", "md", "csv"])]
    pub(crate) format: String,
    /// Fail (exit 1) when a timing got worse beyond its tolerance too; by default timings are
    /// reported but never fail.
    #[arg(long)]
    pub(crate) fail_on_timing: bool,
}

pub(crate) fn diff(args: &DiffArgs) -> ExitCode {
    use crate::report::diff::{diff_runs_each, render, DiffFormat, FailOn, MetricDiff, Tolerance};
    let p = args.position_tolerance;
    if !(p.is_finite() && p >= 0.0) {
        eprintln!("error: --position-tolerance {p}: expected a finite number of tiles >= 0 (a NaN or infinite tolerance would pass every trace)");
        return ExitCode::from(2);
    }
    let mut tols = std::collections::BTreeMap::new();
    for t in &args.tolerances {
        if let Some((m, _)) = t.split_once('=') {
            if crate::metrics::registry::get(m).is_none() {
                let names: Vec<&str> = crate::metrics::registry::METRICS
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
            // A third number was ignored: refused, as any other malformed value.
            if parts.next().is_some() {
                return None;
            }
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
    // A file given for a run is named as such, not as its `metrics.csv` that is not there.
    for (which, dir) in [("BASE", &args.base), ("NEW", &args.new)] {
        if dir.exists() && !dir.is_dir() {
            eprintln!(
                "error: {which} {} is a file, not a directory; expected the --out directory of `platbench run` (it holds metrics.csv and traces/)",
                dir.display()
            );
            return ExitCode::from(2);
        }
    }
    let format = match args.format.as_str() {
        "md" => DiffFormat::Markdown,
        "csv" => DiffFormat::Csv,
        _ => DiffFormat::Text,
    };
    // CSV lists every changed metric, written as found; the tables list the first
    // MAX_LISTED_CHANGES of each change and count the rest.
    let stdout = std::io::stdout();
    let mut csv_out = (format == DiffFormat::Csv)
        .then(|| csv::Writer::from_writer(std::io::BufWriter::new(stdout.lock())));
    let mut rows = 0usize;
    let mut each = |m: &MetricDiff| {
        if let Some(w) = csv_out.as_mut() {
            rows += 1;
            let _ = w.serialize(m);
        }
    };
    let result = diff_runs_each(&args.base, &args.new, &tols, p, &mut each);
    if let Some(mut w) = csv_out.take() {
        let _ = w.flush();
        drop(w);
        if rows == 0 && result.is_ok() {
            out("");
        }
    }
    match result {
        Ok(d) => {
            if format != DiffFormat::Csv {
                out(render(&d, format).trim_end());
            }
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
