//! Writing a run's files without losing the previous ones: everything goes into a staging
//! directory beside the target, which replaces the target only once it is complete.

use std::fs;
use std::path::Path;

use anyhow::{Context, Result};

use platbench::metrics::MetricRow;
use platbench::trace::Trace;

/// Writes `DIR/traces/*.csv` and `DIR/metrics.csv`, replacing `DIR` as a whole.
pub fn write_run(dir: &Path, traces: &[Trace], metrics: &[MetricRow]) -> Result<()> {
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => ".".into(),
    };
    fs::create_dir_all(&parent).with_context(|| format!("cannot create {}", parent.display()))?;
    let staging = tempfile::Builder::new()
        .prefix(".platbench-staging-")
        .tempdir_in(&parent)
        .with_context(|| format!("cannot create a staging directory in {}", parent.display()))?;
    let traces_dir = staging.path().join("traces");
    fs::create_dir(&traces_dir)?;
    for t in traces {
        let path = traces_dir.join(t.file_name());
        let file =
            fs::File::create(&path).with_context(|| format!("cannot create {}", path.display()))?;
        t.write_csv(std::io::BufWriter::new(file))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    let mpath = staging.path().join("metrics.csv");
    let mut w = csv::Writer::from_path(&mpath)
        .with_context(|| format!("cannot create {}", mpath.display()))?;
    for m in metrics {
        w.serialize(m)?;
    }
    w.flush()?;
    drop(w);

    // Swap: move the old directory aside, move the new one in, then delete the old one.
    let staged = staging.keep();
    let old = if dir.exists() {
        let aside = parent.join(format!(
            ".platbench-old-{}-{}",
            std::process::id(),
            dir.file_name().and_then(|n| n.to_str()).unwrap_or("out")
        ));
        fs::rename(dir, &aside)
            .with_context(|| format!("cannot move the previous {} aside", dir.display()))?;
        Some(aside)
    } else {
        None
    };
    if let Err(e) = fs::rename(&staged, dir) {
        if let Some(aside) = &old {
            let _ = fs::rename(aside, dir);
        }
        let _ = fs::remove_dir_all(&staged);
        return Err(e).with_context(|| format!("cannot move the new run into {}", dir.display()));
    }
    if let Some(aside) = old {
        fs::remove_dir_all(&aside)
            .with_context(|| format!("cannot remove the previous run at {}", aside.display()))?;
    }
    Ok(())
}
