//! Reading the files of a run directory for a diff, one row at a time: `metrics.csv` rows
//! (owned, [`read_metrics`], or borrowed from the reader's buffer, for the streamed join of
//! `join`), the trace file names, and two traces compared frame by frame in lockstep, so that
//! a trace's length costs time, never memory.

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::trace::TraceRow;

use super::compare::{Divergence, TraceDiff};

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

/// A row of `metrics.csv` borrowed from the reader's record: the same columns as
/// [`MetricRecord`] (so a file one reads, the other reads), without a string allocated per
/// field.
#[derive(Deserialize)]
pub(super) struct MetricRef<'a> {
    pub(super) level: &'a str,
    pub(super) scenario: &'a str,
    pub(super) backend: &'a str,
    pub(super) config: &'a str,
    pub(super) metric: &'a str,
    pub(super) value: f64,
    pub(super) unit: &'a str,
    pub(super) reference: f64,
    pub(super) error: f64,
    #[serde(default)]
    pub(super) frame: Option<u32>,
    #[serde(default)]
    pub(super) q1: Option<f64>,
    #[serde(default)]
    pub(super) q3: Option<f64>,
}

/// Why a run directory could not be compared.
#[derive(Debug, thiserror::Error)]
pub enum DiffError {
    /// A file could not be read (the cause in the message, not chained, so it is said once).
    #[error("cannot read {path}: {cause}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// A file is not a regular file, or cannot be opened.
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
    /// Two rows of a metrics file share their key.
    #[error("{path}:{second}: the row repeats line {first} ({key}); expected one row per level, scenario, backend, configuration and metric")]
    Duplicate {
        /// The file.
        path: PathBuf,
        /// The line of the first row with the key (the header is line 1).
        first: u64,
        /// The line of the repeat.
        second: u64,
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
    /// A field of a CSV row does not hold what its column does.
    #[error("{path}:{line}: field {field} ({column}): found {found:?}; expected {expected}")]
    Field {
        /// The file.
        path: PathBuf,
        /// The line of the row (the header is line 1).
        line: u64,
        /// The field, counted from 1.
        field: u64,
        /// The column's name in the header.
        column: String,
        /// The field's text.
        found: String,
        /// What the column holds.
        expected: &'static str,
    },
    /// The two metrics files name more distinct levels, scenarios, backends, configurations,
    /// metrics and units together than the join numbers (`u32::MAX`).
    #[error("{path}:{line}: more than {} distinct names in the two metrics files; expected fewer (the diff numbers each name in 32 bits)", u32::MAX)]
    TooManyNames {
        /// The file.
        path: PathBuf,
        /// The line of the row whose name was one too many.
        line: u64,
    },
    /// A metrics file holds more rows than [`crate::limits::MAX_METRIC_ROWS`].
    #[error("{path}:{line}: this is row {} of the metrics file; expected at most {max} rows in either run's metrics file (the diff holds the new run's rows to compare the baseline's against them)", max + 1)]
    TooManyRows {
        /// The file.
        path: PathBuf,
        /// The line of the first row past the limit.
        line: u64,
        /// The most rows a metrics file may hold.
        max: u64,
    },
    /// A metrics file or trace is empty: no header, so no run wrote it whole (a truncated or
    /// damaged file would otherwise read as a run of no rows, and every row of the other side
    /// would pass as added or be reported missing).
    #[error("{path}: the file is empty; expected the header line and rows platbench writes (the file was truncated or damaged)")]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A CSV file is malformed.
    #[error("{path}:{line}: {message}")]
    Csv {
        /// The file.
        path: PathBuf,
        /// The line at fault (the header is line 1).
        line: u64,
        /// What was found and what was expected.
        message: String,
    },
}

/// A reader that refuses a CSV record longer than [`crate::limits::MAX_CSV_RECORD_BYTES`]
/// before the CSV reader buffers it. It follows records as the CSV reader does (a quote opens
/// a quoted field only at a field's start, `""` inside one is a quote, a record ends at `\n`,
/// `\r` or both outside quotes) and counts lines, to say where.
struct RecordCap<R> {
    inner: R,
    /// Bytes of the current record so far.
    bytes: u64,
    /// Where the bytes so far leave the current field.
    field: Field,
    /// The line of the current record's start (the header is line 1).
    record_line: u64,
    /// The line being read (a line ends at `\n`, `\r` or both).
    line: u64,
    /// Whether the last byte was `\r`.
    after_cr: bool,
}

/// Where a [`RecordCap`] is in a CSV field.
#[derive(Clone, Copy, PartialEq)]
enum Field {
    /// At a field's first byte.
    Start,
    /// Inside a field that did not open with a quote.
    Plain,
    /// Inside a quoted field.
    Quoted,
    /// Just after a quote inside a quoted field: its end, or half of `""`.
    QuoteSeen,
}

impl<R: std::io::Read> std::io::Read for RecordCap<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            self.bytes += 1;
            self.line += u64::from(b == b'\r' || (b == b'\n' && !self.after_cr));
            self.after_cr = b == b'\r';
            self.field = match (self.field, b) {
                (Field::Start, b'"') | (Field::QuoteSeen, b'"') => Field::Quoted,
                (Field::Quoted, b'"') => Field::QuoteSeen,
                (Field::Quoted, _) => Field::Quoted,
                (_, b',') => Field::Start,
                (_, b'\n' | b'\r') => {
                    (self.bytes, self.record_line) = (0, self.line);
                    Field::Start
                }
                _ => Field::Plain,
            };
            if self.bytes > crate::limits::MAX_CSV_RECORD_BYTES {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    format!(
                        "line {}: the row passes {} bytes; expected rows of at most that (platbench writes a few hundred bytes a row)",
                        self.record_line,
                        crate::limits::MAX_CSV_RECORD_BYTES
                    ),
                ));
            }
        }
        Ok(n)
    }
}

/// A CSV file read one record at a time into one reused buffer: memory is that of its
/// longest row, at most [`crate::limits::MAX_CSV_RECORD_BYTES`].
pub(crate) struct CsvRows {
    path: PathBuf,
    reader: csv::Reader<super::Lines<RecordCap<crate::input::Capped>>>,
    /// The line of the current record (the header is line 1), by [`super::Lines`].
    line: u64,
    headers: csv::StringRecord,
    record: csv::StringRecord,
    /// Rows read so far, and the most the file may hold.
    rows: u64,
    max_rows: u64,
}

impl CsvRows {
    /// Opens `path` (a regular file, [`crate::input::open`]) and reads its header; `what`
    /// names the file's kind in an error.
    pub(crate) fn open(path: &Path, what: &'static str) -> Result<Self, DiffError> {
        let file = crate::input::open(path, u64::MAX, what)?;
        let mut reader = csv::Reader::from_reader(super::Lines::new(RecordCap {
            inner: file,
            bytes: 0,
            field: Field::Start,
            record_line: 1,
            line: 1,
            after_cr: false,
        }));
        let headers = reader
            .headers()
            .map_err(|e| Self::csv(path, 1, &e, None))?
            .clone();
        if headers.iter().all(str::is_empty) {
            return Err(DiffError::Empty {
                path: path.to_path_buf(),
            });
        }
        Ok(CsvRows {
            path: path.to_path_buf(),
            reader,
            line: 1,
            headers,
            record: csv::StringRecord::new(),
            rows: 0,
            max_rows: u64::MAX,
        })
    }

    /// Opens a metrics file ([`Self::open`]) of at most [`crate::limits::MAX_METRIC_ROWS`] rows.
    pub(crate) fn open_metrics(path: &Path) -> Result<Self, DiffError> {
        Ok(CsvRows {
            max_rows: crate::limits::MAX_METRIC_ROWS,
            ..Self::open(path, "metrics file")?
        })
    }

    /// `e`, met at `line`, worded ([`super::worded`]).
    fn csv(
        path: &Path,
        line: u64,
        e: &csv::Error,
        row: Option<(&csv::StringRecord, &csv::StringRecord)>,
    ) -> DiffError {
        let (at, message) = super::worded(e, row);
        DiffError::Csv {
            path: path.to_path_buf(),
            line: at.unwrap_or(line),
            message,
        }
    }

    /// The file.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Reads the next record; false at the end of the file.
    pub(crate) fn advance(&mut self) -> Result<bool, DiffError> {
        let more = self.reader.read_record(&mut self.record).map_err(|e| {
            let byte = e.position().map_or(0, csv::Position::byte);
            Self::csv(&self.path, self.reader.get_mut().line_of(byte), &e, None)
        })?;
        self.rows += u64::from(more);
        let byte = self.record.position().map_or(0, csv::Position::byte);
        self.line = self.reader.get_mut().line_of(byte);
        if self.rows > self.max_rows {
            return Err(DiffError::TooManyRows {
                path: self.path.clone(),
                line: self.line(),
                max: self.max_rows,
            });
        }
        Ok(more)
    }

    /// The line of the current record (the header is line 1).
    pub(crate) fn line(&self) -> u64 {
        self.line
    }

    /// The current record as a `T` (which may borrow from it); a field that does not parse is
    /// named by line, field, column, text found and what was expected.
    pub(crate) fn get<'r, T: Deserialize<'r>>(&'r self) -> Result<T, DiffError> {
        self.record
            .deserialize(Some(&self.headers))
            .map_err(|e| self.field_error(e))
    }

    fn field_error(&self, e: csv::Error) -> DiffError {
        if let csv::ErrorKind::Deserialize { err, .. } = e.kind() {
            let expected = super::expected_of(err.kind());
            let at = err.field().and_then(|f| usize::try_from(f).ok());
            if let (Some(expected), Some(at)) = (expected, at) {
                return DiffError::Field {
                    path: self.path.clone(),
                    line: self.line(),
                    field: at as u64 + 1,
                    column: self.headers.get(at).unwrap_or("?").to_string(),
                    found: self.record.get(at).unwrap_or_default().to_string(),
                    expected,
                };
            }
        }
        let row = Some((&self.headers, &self.record));
        Self::csv(&self.path, self.line(), &e, row)
    }

    /// The next record as an owned `T`, or `None` at the end of the file.
    pub(crate) fn next_row<T: serde::de::DeserializeOwned>(
        &mut self,
    ) -> Result<Option<T>, DiffError> {
        if !self.advance()? {
            return Ok(None);
        }
        self.get().map(Some)
    }

    /// Reads the rest of the file as `T` rows, keeping none: every row is checked, as when the
    /// file was read whole.
    pub(crate) fn check_rest<T: serde::de::DeserializeOwned>(&mut self) -> Result<(), DiffError> {
        while self.next_row::<T>()?.is_some() {}
        Ok(())
    }
}

/// Reads `DIR/metrics.csv` whole, refusing a repeated key. Holds every row (its six strings
/// and numbers); `diff` streams the file instead ([`super::diff_runs`]), `check` keeps its
/// runs only ([`read_runs`]) and `review` the rows of the runs it shows
/// ([`read_metrics_where`]).
pub fn read_metrics(dir: &Path) -> Result<Vec<MetricRecord>, DiffError> {
    read_metrics_where(dir, |_| true)
}

/// The rows of `DIR/metrics.csv` of the runs `keep([level, scenario, backend, config])`
/// selects, read a row at a time: every row is read and checked, only those kept are held (a
/// repeated key among them is refused), so memory is that of the rows kept.
pub fn read_metrics_where(
    dir: &Path,
    mut keep: impl FnMut([&str; 4]) -> bool,
) -> Result<Vec<MetricRecord>, DiffError> {
    let mut csv = CsvRows::open_metrics(&dir.join("metrics.csv"))?;
    let mut rows: Vec<MetricRecord> = Vec::new();
    // A repeated key would let one of its rows go uncompared (the last one read wins).
    let mut seen: BTreeMap<_, u64> = BTreeMap::new();
    while csv.advance()? {
        let r: MetricRef = csv.get()?;
        if !keep([r.level, r.scenario, r.backend, r.config]) {
            continue;
        }
        let r = MetricRecord {
            level: r.level.into(),
            scenario: r.scenario.into(),
            backend: r.backend.into(),
            config: r.config.into(),
            metric: r.metric.into(),
            value: r.value,
            unit: r.unit.into(),
            reference: r.reference,
            error: r.error,
            frame: r.frame,
            q1: r.q1,
            q3: r.q3,
        };
        let key = (
            r.level.clone(),
            r.scenario.clone(),
            r.backend.clone(),
            r.config.clone(),
            r.metric.clone(),
        );
        if let Some(first) = seen.insert(key, csv.line()) {
            return Err(DiffError::Duplicate {
                path: csv.path().to_path_buf(),
                first,
                second: csv.line(),
                key: format!(
                    "{}.{} {} {} {}",
                    r.level, r.scenario, r.backend, r.config, r.metric
                ),
            });
        }
        rows.push(r);
    }
    Ok(rows)
}

/// A run: its level, scenario, backend and configuration.
pub type RunKey = [String; 4];

/// The runs of `DIR/metrics.csv`, each once, in the order of its first row, read a row at a
/// time (every row read and checked, none kept): memory is that of the runs, not the rows.
pub fn read_runs(dir: &Path) -> Result<Vec<RunKey>, DiffError> {
    let mut csv = CsvRows::open_metrics(&dir.join("metrics.csv"))?;
    let mut seen: HashSet<RunKey> = HashSet::new();
    let mut runs: Vec<RunKey> = Vec::new();
    while csv.advance()? {
        let r: MetricRef = csv.get()?;
        let key = [r.level, r.scenario, r.backend, r.config];
        // A run's rows come together: most rows are of the run before.
        if runs
            .last()
            .is_some_and(|last| last.iter().zip(key).all(|(a, b)| a == b))
        {
            continue;
        }
        let key = key.map(String::from);
        if seen.insert(key.clone()) {
            runs.push(key);
        }
    }
    Ok(runs)
}

/// The names of the trace files (`*.csv`) of `DIR/traces`, sorted.
pub(super) fn trace_files(dir: &Path) -> Result<Vec<String>, DiffError> {
    let tdir = dir.join("traces");
    let entries = std::fs::read_dir(&tdir).map_err(|cause| DiffError::Io {
        path: tdir.clone(),
        cause,
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

/// Compares two traces row by row, reading both in lockstep: the first frame where they
/// diverge or one ends ([`Divergence`]). Both files are read to their end even past a
/// divergence, so that a malformed row anywhere is an error, as when they were read whole;
/// an error in the baseline's file is the one reported when both have one.
pub(super) fn compare_traces(
    base: &Path,
    new: &Path,
    tol: f32,
) -> Result<Option<TraceDiff>, DiffError> {
    let mut b = CsvRows::open(base, "trace")?;
    let mut n = CsvRows::open(new, "trace")?;
    let mut d = Divergence::new(tol);
    loop {
        let rb = b.next_row::<TraceRow>()?;
        let rn = match n.next_row::<TraceRow>() {
            Ok(rn) => rn,
            Err(e) => {
                b.check_rest::<TraceRow>()?;
                return Err(e);
            }
        };
        match (rb, rn) {
            (Some(rb), Some(rn)) => d.pair(&rb, &rn),
            (rb, rn) => {
                d.end(rb.as_ref(), rn.as_ref());
                b.check_rest::<TraceRow>()?;
                n.check_rest::<TraceRow>()?;
                return Ok(d.finish());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads `bytes` through a [`RecordCap`] whole: its error's text, if any.
    fn capped(bytes: Vec<u8>) -> Result<(), String> {
        use std::io::Read as _;
        let mut r = RecordCap {
            inner: bytes.as_slice(),
            bytes: 0,
            field: Field::Start,
            record_line: 1,
            line: 1,
            after_cr: false,
        };
        r.read_to_end(&mut Vec::new())
            .map(|_| ())
            .map_err(|e| e.to_string())
    }

    #[test]
    fn records_end_where_the_csv_reader_ends_them() {
        // 2 MiB of short rows (twice MAX_CSV_RECORD_BYTES) pass whatever ends their lines, and
        // a quote in the middle of a plain field is a plain byte, as the csv crate reads it (an
        // adversary's CR-only file and hand-edited `flat"seams` were read as one long row).
        let rows = |end: &str| "a,flat\"seams,1\"2,\"q\"\"x\"".to_string() + end;
        for end in ["\n", "\r", "\r\n"] {
            assert_eq!(
                capped(rows(end).repeat(100_000).into_bytes()),
                Ok(()),
                "{end:?}"
            );
        }
        // A quoted field's line ends stay in its record; the row's first line is named.
        for end in ["\n", "\r", "\r\n"] {
            let long = format!("h{end}a,\"{}\"{end}", format!("x{end}").repeat(600_000));
            let err = capped(long.into_bytes()).unwrap_err();
            assert!(
                err.starts_with("line 2: the row passes 1048576 bytes"),
                "{end:?}: {err}"
            );
        }
    }

    #[test]
    fn a_metrics_file_past_its_row_limit_is_refused_at_the_first_row_too_many() {
        // The limit is MAX_METRIC_ROWS (2 million, too many for a unit test to write); the
        // count is the same with a limit of 3: three rows read, the fourth refused at line 5.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("metrics.csv");
        std::fs::write(&path, "a,b\n1,2\n3,4\n5,6\n7,8\n").unwrap();
        let mut rows = CsvRows {
            max_rows: 3,
            ..CsvRows::open(&path, "metrics file").unwrap()
        };
        for _ in 0..3 {
            assert!(rows.advance().unwrap());
        }
        let err = rows.advance().unwrap_err().to_string();
        assert!(
            err.contains(":5: this is row 4 of the metrics file; expected at most 3 rows"),
            "{err}"
        );
    }
}
