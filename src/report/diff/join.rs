//! Matching the two runs of a diff: `metrics.csv` rows by level, scenario, backend,
//! configuration and metric, traces by file name; each matched pair is judged by the rules of
//! `compare`.
//!
//! Both metrics files are streamed. The new run's rows are kept as compact records (its key
//! as five numbered names, its numbers; about 100 bytes a row), each name held once however
//! many rows repeat it; the baseline's rows are then read one at a time and judged against them
//! as they come, in the baseline's order, each verdict handed on as it is found: a baseline of
//! any length costs memory for the keys of its rows the new run lacks only (24 bytes each, to
//! refuse a repeat), so `check`, whose new run is the work it did, stays in proportion to that
//! work. Traces are compared frame by frame in lockstep ([`super::read::compare_traces`]).

use std::collections::{BTreeMap, HashMap};
use std::path::Path;
use std::rc::Rc;

use super::compare::{
    classify, default_tolerance, Change, MetricDiff, RunDiff, Tolerance, TraceChange, TraceDiff,
};
use super::read::{compare_traces, trace_files, CsvRows, DiffError, MetricRef};
use super::timing::{classify_timing, Spread};

/// Each distinct name of the two files (level, scenario, backend, configuration, metric, unit)
/// numbered, and held once.
#[derive(Default)]
struct Names {
    ids: HashMap<Rc<str>, u32>,
    names: Vec<Rc<str>>,
}

impl Names {
    /// The number of `name`, numbering it if new; `None` past `u32::MAX` names.
    fn id(&mut self, name: &str) -> Option<u32> {
        if let Some(&id) = self.ids.get(name) {
            return Some(id);
        }
        let id = u32::try_from(self.names.len()).ok()?;
        let name: Rc<str> = Rc::from(name);
        self.names.push(Rc::clone(&name));
        self.ids.insert(name, id);
        Some(id)
    }

    /// The number of `name`, if it is numbered.
    fn get(&self, name: &str) -> Option<u32> {
        self.ids.get(name).copied()
    }

    fn name(&self, id: u32) -> &str {
        self.names.get(id as usize).map_or("", |n| n)
    }
}

/// A row's key: its level, scenario, backend, configuration and metric, numbered ([`Names`]).
type Key = [u32; 5];

/// The numbers of a metrics row, without its key.
#[derive(Clone, Copy)]
struct Values {
    value: f64,
    frame: Option<u32>,
    q1: Option<f64>,
    q3: Option<f64>,
}

/// A new run's row as kept for the join.
struct NewRow {
    key: Key,
    values: Values,
    /// Its line in the new run's file.
    line: u64,
    /// The line of the baseline's row with its key, once read (0: none yet).
    base_line: u64,
}

/// A baseline key the new run lacks, as 128 bits of two hashes of its names: what finds a
/// repeated key among them without holding their names.
fn missing_key(names: [&str; 5]) -> u128 {
    use std::hash::{DefaultHasher, Hash, Hasher};
    let half = |salt: u8| {
        let mut h = DefaultHasher::new();
        salt.hash(&mut h);
        names.hash(&mut h);
        h.finish()
    };
    (u128::from(half(0)) << 64) | u128::from(half(1))
}

/// One metrics file's rows, read one at a time: `each(key, unit, values, reference, line)`.
fn stream_metrics(
    csv: &mut CsvRows,
    names: &mut Names,
    mut each: impl FnMut(&mut Names, Key, u32, Values, f64, u64) -> Result<(), DiffError>,
) -> Result<(), DiffError> {
    while csv.advance()? {
        let line = csv.line();
        let r: MetricRef<'_> = csv.get()?;
        let too_many = || DiffError::TooManyNames {
            path: csv.path().to_path_buf(),
            line,
        };
        let mut key = [0u32; 5];
        for (slot, name) in key
            .iter_mut()
            .zip([r.level, r.scenario, r.backend, r.config, r.metric])
        {
            *slot = names.id(name).ok_or_else(too_many)?;
        }
        let unit = names.id(r.unit).ok_or_else(too_many)?;
        let values = Values {
            value: r.value,
            frame: r.frame,
            q1: r.q1,
            q3: r.q3,
        };
        each(names, key, unit, values, r.reference, line)?;
    }
    Ok(())
}

/// `level.scenario backend config metric`, for an error naming a key.
fn key_text(names: &Names, k: &Key) -> String {
    let n = |i: usize| names.name(k[i]);
    format!("{}.{} {} {} {}", n(0), n(1), n(2), n(3), n(4))
}

/// A metric's row of the diff from the names of its key, before its verdict.
fn metric_diff(
    n: [&str; 5],
    base: Option<Values>,
    new: Option<Values>,
    change: Change,
) -> MetricDiff {
    MetricDiff {
        scenario: format!("{}.{}", n[0], n[1]),
        config: format!("{} {}", n[2], n[3]),
        metric: n[4].to_string(),
        base: base.map(|v| v.value),
        new: new.map(|v| v.value),
        base_frame: base.and_then(|v| v.frame),
        new_frame: new.and_then(|v| v.frame),
        base_q1: base.and_then(|v| v.q1),
        base_q3: base.and_then(|v| v.q3),
        new_q1: new.and_then(|v| v.q1),
        new_q3: new.and_then(|v| v.q3),
        change,
    }
}

/// The names of a numbered key.
fn key_names<'a>(names: &'a Names, k: &Key) -> [&'a str; 5] {
    k.map(|id| names.name(id))
}

/// A timing row's median and quartiles; a row without quartiles (written before them, when the
/// value was a minimum of repeats) has none: its spread is its value alone.
fn spread(v: &Values) -> Spread {
    Spread {
        median: v.value,
        q1: v.q1.unwrap_or(v.value),
        q3: v.q3.unwrap_or(v.value),
    }
}

/// Compares run `new` against baseline `base`. `tolerances` overrides the per-unit defaults by
/// metric name; `position_tolerance` (tiles) decides where a trace diverges. The verdicts listed
/// are the first [`crate::limits::MAX_LISTED_CHANGES`] of each change, every one counted
/// ([`RunDiff::counts`]); [`diff_runs_each`] hands on every one.
pub fn diff_runs(
    base: &Path,
    new: &Path,
    tolerances: &BTreeMap<String, Tolerance>,
    position_tolerance: f32,
) -> Result<RunDiff, DiffError> {
    diff_runs_each(base, new, tolerances, position_tolerance, &mut |_| {})
}

/// [`diff_runs`], handing every metric verdict that is not `Same` to `each` as it is found:
/// the baseline's rows in its order, then the rows only the new run has, in its order.
pub fn diff_runs_each(
    base: &Path,
    new: &Path,
    tolerances: &BTreeMap<String, Tolerance>,
    position_tolerance: f32,
    each: &mut dyn FnMut(&MetricDiff),
) -> Result<RunDiff, DiffError> {
    let mut names = Names::default();
    let mut rows: Vec<NewRow> = Vec::new();
    let mut index: HashMap<Key, usize> = HashMap::new();
    let new_path = new.join("metrics.csv");
    let mut csv = CsvRows::open_metrics(&new_path)?;
    stream_metrics(&mut csv, &mut names, |names, key, _, values, _, line| {
        // A repeated key would let one of its rows go uncompared.
        if let Some(&first) = index.get(&key) {
            return Err(DiffError::Duplicate {
                path: new_path.clone(),
                first: rows[first].line,
                second: line,
                key: key_text(names, &key),
            });
        }
        index.insert(key, rows.len());
        rows.push(NewRow {
            key,
            values,
            line,
            base_line: 0,
        });
        Ok(())
    })?;
    let mut out = RunDiff::default();
    let mut found = |out: &mut RunDiff, d: MetricDiff| {
        each(&d);
        out.push(d);
    };
    // The baseline's keys the new run lacks, with their line, to refuse a repeat.
    let mut missing_at: HashMap<u128, u64> = HashMap::new();
    let base_path = base.join("metrics.csv");
    let mut csv = CsvRows::open_metrics(&base_path)?;
    while csv.advance()? {
        let line = csv.line();
        let r: MetricRef<'_> = csv.get()?;
        out.compared += 1;
        let n = [r.level, r.scenario, r.backend, r.config, r.metric];
        let bv = Values {
            value: r.value,
            frame: r.frame,
            q1: r.q1,
            q3: r.q3,
        };
        let repeat = |first: u64| DiffError::Duplicate {
            path: base_path.clone(),
            first,
            second: line,
            key: format!("{}.{} {} {} {}", n[0], n[1], n[2], n[3], n[4]),
        };
        let ids = n.map(|name| names.get(name));
        let at = match ids {
            [Some(a), Some(b), Some(c), Some(d), Some(e)] => index.get(&[a, b, c, d, e]).copied(),
            _ => None,
        };
        let Some(i) = at else {
            if let Some(&first) = missing_at.get(&missing_key(n)) {
                return Err(repeat(first));
            }
            missing_at.insert(missing_key(n), line);
            found(&mut out, metric_diff(n, Some(bv), None, Change::Missing));
            continue;
        };
        let nr = &mut rows[i];
        if nr.base_line != 0 {
            return Err(repeat(nr.base_line));
        }
        nr.base_line = line;
        let unit = crate::metrics::registry::get(r.metric).map_or(r.unit, |d| d.unit);
        let tol = tolerances
            .get(r.metric)
            .copied()
            .unwrap_or_else(|| default_tolerance(unit));
        let change = if unit == "ns" {
            out.timings_compared += 1;
            classify_timing(&spread(&bv), &spread(&nr.values), tol)
        } else {
            classify(bv.value, nr.values.value, r.reference, tol)
        };
        if change != Change::Same {
            found(&mut out, metric_diff(n, Some(bv), Some(nr.values), change));
        }
    }
    drop(missing_at);
    // The rows only the new run has, in its order.
    for nr in rows.iter().filter(|nr| nr.base_line == 0) {
        let d = metric_diff(
            key_names(&names, &nr.key),
            None,
            Some(nr.values),
            Change::Added,
        );
        found(&mut out, d);
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
        let (tb, tn) = (
            base.join("traces").join(name),
            new.join("traces").join(name),
        );
        if let Some(d) = compare_traces(&tb, &tn, position_tolerance)? {
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
    use super::super::read::read_metrics;
    use super::*;
    use std::path::PathBuf;

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
