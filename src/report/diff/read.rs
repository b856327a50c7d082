//! Reading the two runs of a diff and matching them: `metrics.csv` rows by level, scenario,
//! configuration and metric, traces by file name; each matched pair is judged by the rules of
//! `compare`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::trace::{Trace, TraceRow};

use super::compare::{
    classify, default_tolerance, first_divergence, Change, MetricDiff, RunDiff, Tolerance,
    TraceChange, TraceDiff,
};
use super::timing::{classify_timing, Spread};

/// Whether `r` is a timing (its unit is ns): judged against its samples' spread.
fn is_timing(r: &MetricRecord) -> bool {
    crate::metrics::registry::get(&r.metric).map_or(r.unit.as_str(), |d| d.unit) == "ns"
}

/// A timing row's median and quartiles; a row without quartiles (written before them, when the
/// value was a minimum of repeats) has none: its spread is its value alone.
fn spread(r: &MetricRecord) -> Spread {
    Spread {
        median: r.value,
        q1: r.q1.unwrap_or(r.value),
        q3: r.q3.unwrap_or(r.value),
    }
}

/// A row of `metrics.csv` as read back (owned strings).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
pub struct MetricRecord {
    /// Level name.
    pub level: String,
    /// Scenario name.
    pub scenario: String,
    /// Backend name.
    pub backend: String,
    /// Configuration label.
    pub config: String,
    /// Metric name.
    pub metric: String,
    /// Measured value.
    pub value: f64,
    /// Unit.
    pub unit: String,
    /// Ideal value.
    pub reference: f64,
    /// `value - reference`.
    pub error: f64,
    /// The trace frame the value was reached at or is best shown at, if the file has a `frame`
    /// column and the row a frame there (files written before the column have none: they read
    /// as `None`). Never compared: a frame moving is not a regression.
    #[serde(default)]
    pub frame: Option<u32>,
    /// A timing row's first quartile of its samples (its value is their median); `None` for
    /// other metrics and for files written before the column (a timing then has no spread).
    #[serde(default)]
    pub q1: Option<f64>,
    /// A timing row's third quartile of its samples; `None` as for `q1`.
    #[serde(default)]
    pub q3: Option<f64>,
}

impl MetricRecord {
    fn key(&self) -> (String, String, String, String, String) {
        (
            self.level.clone(),
            self.scenario.clone(),
            self.backend.clone(),
            self.config.clone(),
            self.metric.clone(),
        )
    }
}

/// Why a run directory could not be compared.
#[derive(Debug, thiserror::Error)]
pub enum DiffError {
    /// A file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A file is not a regular file, or cannot be opened.
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
    /// Two rows of a metrics file share their key.
    #[error("{path}: line {second} repeats line {first} ({key}); expected one row per level, scenario, backend, configuration and metric")]
    Duplicate {
        /// The file.
        path: PathBuf,
        /// The line of the first row with the key (the header is line 1).
        first: usize,
        /// The line of the repeat.
        second: usize,
        /// The key, as `level.scenario backend config metric`.
        key: String,
    },
    /// A trace's file name is not UTF-8: platbench names traces in ASCII, so it is no trace
    /// of a run, and skipping it would leave it uncompared.
    #[error("{path}: the trace's file name is not UTF-8; expected the ASCII names platbench writes (level.scenario.backend.config.csv)")]
    TraceName {
        /// The file.
        path: PathBuf,
    },
    /// A CSV file is malformed.
    #[error("{path}: {source}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// The cause, with its line.
        source: csv::Error,
    },
}

/// Reads `DIR/metrics.csv`.
pub fn read_metrics(dir: &Path) -> Result<Vec<MetricRecord>, DiffError> {
    let path = dir.join("metrics.csv");
    let file = crate::input::open(&path, u64::MAX, "metrics file")?;
    let rows: Vec<MetricRecord> = csv::Reader::from_reader(file)
        .deserialize()
        .collect::<Result<_, _>>()
        .map_err(|source| DiffError::Csv {
            path: path.clone(),
            source,
        })?;
    // A repeated key would let one of its rows go uncompared (the last one read wins).
    let mut seen: BTreeMap<_, usize> = BTreeMap::new();
    for (k, r) in rows.iter().enumerate() {
        if let Some(first) = seen.insert(r.key(), k) {
            return Err(DiffError::Duplicate {
                path,
                first: first + 2,
                second: k + 2,
                key: format!(
                    "{}.{} {} {} {}",
                    r.level, r.scenario, r.backend, r.config, r.metric
                ),
            });
        }
    }
    Ok(rows)
}

fn read_trace(path: &Path) -> Result<Vec<TraceRow>, DiffError> {
    let file = crate::input::open(path, u64::MAX, "trace")?;
    Trace::read_rows(file).map_err(|source| DiffError::Csv {
        path: path.to_path_buf(),
        source,
    })
}

fn trace_files(dir: &Path) -> Result<Vec<String>, DiffError> {
    let tdir = dir.join("traces");
    let entries = std::fs::read_dir(&tdir).map_err(|source| DiffError::Io {
        path: tdir.clone(),
        source,
    })?;
    let mut names: Vec<String> = Vec::new();
    for e in entries.filter_map(|e| e.ok()) {
        match e.file_name().into_string() {
            Ok(n) if n.ends_with(".csv") => names.push(n),
            Ok(_) => {}
            Err(_) => return Err(DiffError::TraceName { path: e.path() }),
        }
    }
    names.sort();
    Ok(names)
}

/// Compares run `new` against baseline `base`. `tolerances` overrides the per-unit defaults by
/// metric name; `position_tolerance` (tiles) decides where a trace diverges.
pub fn diff_runs(
    base: &Path,
    new: &Path,
    tolerances: &BTreeMap<String, Tolerance>,
    position_tolerance: f32,
) -> Result<RunDiff, DiffError> {
    let b = read_metrics(base)?;
    let n = read_metrics(new)?;
    let new_by_key: BTreeMap<_, _> = n.iter().map(|r| (r.key(), r)).collect();
    let base_keys: std::collections::BTreeSet<_> = b.iter().map(|r| r.key()).collect();
    let mut out = RunDiff::default();
    for br in &b {
        let tol = tolerances.get(&br.metric).copied().unwrap_or_else(|| {
            default_tolerance(
                crate::metrics::registry::get(&br.metric).map_or(&br.unit, |d| d.unit),
            )
        });
        let label = |r: &MetricRecord| {
            (
                format!("{}.{}", r.level, r.scenario),
                format!("{} {}", r.backend, r.config),
            )
        };
        let (scenario, config) = label(br);
        out.compared += 1;
        let nr = new_by_key.get(&br.key()).copied();
        let change = match nr {
            None => Change::Missing,
            Some(nr) if is_timing(br) => classify_timing(&spread(br), &spread(nr), tol),
            Some(nr) => classify(br.value, nr.value, br.reference, tol),
        };
        if is_timing(br) {
            out.timings_compared += nr.is_some() as usize;
        }
        if change != Change::Same {
            out.metrics.push(MetricDiff {
                scenario,
                config,
                metric: br.metric.clone(),
                base: Some(br.value),
                new: nr.map(|r| r.value),
                base_frame: br.frame,
                new_frame: nr.and_then(|r| r.frame),
                base_q1: br.q1,
                base_q3: br.q3,
                new_q1: nr.and_then(|r| r.q1),
                new_q3: nr.and_then(|r| r.q3),
                change,
            });
        }
    }
    for nr in n.iter().filter(|r| !base_keys.contains(&r.key())) {
        out.metrics.push(MetricDiff {
            scenario: format!("{}.{}", nr.level, nr.scenario),
            config: format!("{} {}", nr.backend, nr.config),
            metric: nr.metric.clone(),
            base: None,
            new: Some(nr.value),
            base_frame: None,
            new_frame: nr.frame,
            base_q1: None,
            base_q3: None,
            new_q1: nr.q1,
            new_q3: nr.q3,
            change: Change::Added,
        });
    }
    let (bt, nt) = (trace_files(base)?, trace_files(new)?);
    for name in bt.iter().chain(nt.iter().filter(|n| !bt.contains(n))) {
        let (in_b, in_n) = (bt.contains(name), nt.contains(name));
        if !(in_b && in_n) {
            out.traces.push(TraceDiff {
                file: name.clone(),
                change: if in_b {
                    TraceChange::Missing
                } else {
                    TraceChange::Added
                },
                frame: None,
                base: None,
                new: None,
            });
            continue;
        }
        out.traces_compared += 1;
        let rb = read_trace(&base.join("traces").join(name))?;
        let rn = read_trace(&new.join("traces").join(name))?;
        if let Some(d) = first_divergence(&rb, &rn, position_tolerance) {
            out.traces.push(TraceDiff {
                file: name.clone(),
                ..d
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "level,scenario,backend,config,metric,value,unit,reference,error";

    /// A run directory holding `metrics` as its metrics.csv and no trace.
    fn run_dir(root: &Path, name: &str, metrics: &str) -> PathBuf {
        let dir = root.join(name);
        std::fs::create_dir_all(dir.join("traces")).unwrap();
        std::fs::write(dir.join("metrics.csv"), metrics).unwrap();
        dir
    }

    #[test]
    fn metrics_are_read_with_or_without_the_frame_column_and_frames_are_not_compared() {
        let root = tempfile::tempdir().unwrap();
        // Written before the frame column (an old baseline, a user's CI baseline).
        let old = run_dir(
            root.path(),
            "old",
            &format!("{HEADER}\nm,s,sweep,default,max_penetration,0.5,tiles,0,0.5\n"),
        );
        // With it: the same value reached on another frame, and a row without a frame.
        let new = run_dir(
            root.path(),
            "new",
            &format!(
                "{HEADER},frame\nm,s,sweep,default,max_penetration,0.5,tiles,0,0.5,7\n\
                 m,s,sweep,default,ns_per_character_step,9,ns,0,9,\n"
            ),
        );
        let o = read_metrics(&old).unwrap();
        assert_eq!(o.len(), 1);
        assert_eq!((o[0].value, o[0].frame), (0.5, None));
        let n = read_metrics(&new).unwrap();
        assert_eq!(n[0].frame, Some(7));
        assert_eq!(n[1].frame, None);
        // Old against new: the value is the same, the frame is not compared (only the added
        // timing row is listed).
        let d = diff_runs(&old, &new, &BTreeMap::new(), 1e-4).unwrap();
        assert_eq!(d.compared, 1);
        assert_eq!(d.metrics.len(), 1, "{:?}", d.metrics);
        assert_eq!(d.metrics[0].change, Change::Added);
        // A frame that moved is no change either; a value that moved shows both frames.
        let moved = run_dir(
            root.path(),
            "moved",
            &format!("{HEADER},frame\nm,s,sweep,default,max_penetration,0.5,tiles,0,0.5,3\n"),
        );
        assert!(diff_runs(&new, &moved, &BTreeMap::new(), 1e-4)
            .unwrap()
            .metrics
            .iter()
            .all(|m| m.metric != "max_penetration"));
        let worse = run_dir(
            root.path(),
            "worse",
            &format!("{HEADER},frame\nm,s,sweep,default,max_penetration,0.9,tiles,0,0.9,12\n"),
        );
        let d = diff_runs(&new, &worse, &BTreeMap::new(), 1e-4).unwrap();
        let m = d
            .metrics
            .iter()
            .find(|m| m.metric == "max_penetration")
            .unwrap();
        assert_eq!(m.change, Change::Worse);
        assert_eq!((m.base_frame, m.new_frame), (Some(7), Some(12)));
    }
}
