//! Accepting reviewed runs into a baseline: each accepted run's rows of `metrics.csv` and its
//! trace file become the check's, and every other byte of the baseline stays as it was. The
//! new baseline is written beside the old one and swapped in as a whole (`output::write_output`).

use std::collections::{BTreeSet, HashMap};
use std::fs;
use std::io::{Read as _, Write};
use std::path::Path;

use anyhow::{anyhow, bail, Context as _, Result};

use super::output;
use crate::report::check::Unit;
use crate::report::manifest::{Manifest, FILE};

/// A run's key in `metrics.csv`: level, scenario, backend, configuration.
type Key = (String, String, String, String);

/// A part of a `metrics.csv` as [`scan`] reads it, with its bytes as they are in the file.
enum Part<'a> {
    /// The header (everything before the first record).
    Header(&'a [u8]),
    /// A record, with its run.
    Row(Key, &'a [u8]),
}

/// Reads `path` a record at a time, calling `each` with its header and then every record, in
/// order, each with its bytes as they are in the file: memory is that of the longest record,
/// whatever the file's length. The records must tile the file (each starts where the one before
/// ends, the last ends at the end of the file), or a splice would lose or repeat bytes.
fn scan(path: &Path, mut each: impl FnMut(Part) -> Result<()>) -> Result<()> {
    let open = || crate::input::open(path, u64::MAX, "metrics file");
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(open()?);
    // The same bytes again, read in step with the parser: each record's bytes, verbatim.
    let mut raw = std::io::BufReader::new(open()?);
    let mut take = |n: u64, buf: &mut Vec<u8>| -> Result<()> {
        buf.clear();
        (&mut raw)
            .take(n)
            .read_to_end(buf)
            .with_context(|| format!("cannot read {}", path.display()))?;
        if buf.len() as u64 != n {
            bail!("{}: changed while it was read", path.display());
        }
        Ok(())
    };
    let head = r
        .byte_headers()
        .with_context(|| format!("{}: no header", path.display()))?
        .clone();
    let col = |name: &str| {
        head.iter()
            .position(|h| h == name.as_bytes())
            .with_context(|| format!("{}: no {name} column", path.display()))
    };
    let cols = [
        col("level")?,
        col("scenario")?,
        col("backend")?,
        col("config")?,
    ];
    let untiled = || {
        anyhow!(
            "{}: cannot tell its rows apart byte for byte; refusing to edit it",
            path.display()
        )
    };
    let mut rec = csv::ByteRecord::new();
    let mut bytes = Vec::new();
    // Bytes passed so far; `None` until the header is.
    let mut at: Option<u64> = None;
    loop {
        let more = r
            .read_byte_record(&mut rec)
            .with_context(|| format!("{}: malformed CSV", path.display()))?;
        if !more {
            break;
        }
        let from = rec.position().map_or(0, |p| p.byte());
        let to = r.position().byte();
        let start = match at {
            Some(a) => a,
            None => {
                take(from, &mut bytes)?;
                each(Part::Header(&bytes))?;
                from
            }
        };
        if from != start || to < from {
            return Err(untiled());
        }
        take(to - from, &mut bytes)?;
        at = Some(to);
        let field = |i: usize| String::from_utf8_lossy(rec.get(i).unwrap_or_default()).into_owned();
        let key = (
            field(cols[0]),
            field(cols[1]),
            field(cols[2]),
            field(cols[3]),
        );
        each(Part::Row(key, &bytes))?;
    }
    if at.is_none() {
        // No record: the whole file is the header.
        bytes.clear();
        raw.read_to_end(&mut bytes)
            .with_context(|| format!("cannot read {}", path.display()))?;
        return each(Part::Header(&bytes));
    }
    // Nothing may follow the last record.
    if raw
        .read(&mut [0u8])
        .with_context(|| format!("cannot read {}", path.display()))?
        != 0
    {
        return Err(untiled());
    }
    Ok(())
}

/// The check's `metrics.csv` header and the rows of the `accepted` runs, by run, in file
/// order: all that is kept of it.
struct Taken {
    header: Vec<u8>,
    rows: HashMap<Key, Vec<Vec<u8>>>,
}

/// Reads the check's `metrics.csv` at `path`, keeping the rows of the `accepted` runs.
fn taken(path: &Path, accepted: &BTreeSet<Key>) -> Result<Taken> {
    let mut t = Taken {
        header: Vec::new(),
        rows: HashMap::new(),
    };
    scan(path, |part| {
        match part {
            Part::Header(h) => t.header = h.to_vec(),
            Part::Row(k, bytes) if accepted.contains(&k) => {
                t.rows.entry(k).or_default().push(bytes.to_vec());
            }
            Part::Row(..) => {}
        }
        Ok(())
    })?;
    Ok(t)
}

/// Writes to `out` the baseline's `metrics.csv` at `base` with the rows of the `accepted` runs
/// taken from the check's (`new`: in the place of the baseline's first row of that run; a run
/// new to the baseline at the end; a run gone from the check removed). Every other byte is the
/// baseline's, copied as it is read.
fn splice(base: &Path, new: &Taken, accepted: &BTreeSet<Key>, out: &mut impl Write) -> Result<()> {
    let mut done: BTreeSet<Key> = BTreeSet::new();
    // The last byte written (`None`: nothing yet): a row after one without its line end gets
    // one.
    let mut last: Option<u8> = None;
    fn push(out: &mut dyn Write, last: &mut Option<u8>, bytes: &[u8]) -> std::io::Result<()> {
        if last.is_some_and(|b| b != b'\n') {
            out.write_all(b"\n")?;
            *last = Some(b'\n');
        }
        out.write_all(bytes)?;
        if let Some(&b) = bytes.last() {
            *last = Some(b);
        }
        Ok(())
    }
    let none = Vec::new();
    let rows_of = |k: &Key| new.rows.get(k).unwrap_or(&none);
    let write_err = |e: std::io::Error| anyhow!("cannot write the baseline's metrics.csv: {e}");
    scan(base, |part| {
        match part {
            Part::Header(h) => {
                if h != new.header.as_slice() {
                    bail!("the baseline's metrics.csv and the check's have different columns (a baseline written by another platbench): write the baseline again with `platbench baseline --replace` instead of accepting part of it");
                }
                out.write_all(h).map_err(write_err)?;
                last = h.last().copied();
            }
            Part::Row(k, bytes) => {
                if !accepted.contains(&k) {
                    push(out, &mut last, bytes).map_err(write_err)?;
                } else if !done.contains(&k) {
                    for row in rows_of(&k) {
                        push(out, &mut last, row).map_err(write_err)?;
                    }
                    done.insert(k);
                }
            }
        }
        Ok(())
    })?;
    for k in accepted.iter().filter(|k| !done.contains(*k)) {
        for row in rows_of(k) {
            push(out, &mut last, row).map_err(write_err)?;
        }
    }
    out.flush().map_err(write_err)
}

/// Puts `from` at `to`: a hard link where the filesystem allows (the old baseline is deleted
/// after the swap, so nothing stays shared), else a copy.
fn link_or_copy(from: &Path, to: &Path) -> Result<()> {
    if fs::hard_link(from, to).is_err() {
        fs::copy(from, to)
            .with_context(|| format!("cannot copy {} to {}", from.display(), to.display()))?;
    }
    Ok(())
}

/// The lock file a review holds in the baseline directory while it reads and rewrites it.
pub(crate) const LOCK: &str = ".platbench-lock";

/// A lock older than this is taken to be left by a review that died.
const STALE: std::time::Duration = std::time::Duration::from_secs(3600);

/// An exclusive lock on a baseline directory: `DIR/.platbench-lock`, made with `create_new`,
/// holding the process id and a token; removed on drop if it is still this lock's.
pub(crate) struct Lock {
    path: std::path::PathBuf,
    token: String,
}

impl Lock {
    /// Takes the lock of `dir`; fails when another review holds it, and takes over (with a
    /// warning) a lock older than an hour. `None` when `dir` does not exist (nothing to lock:
    /// reading it fails next, with its own message).
    pub(crate) fn take(dir: &Path) -> Result<Option<Lock>> {
        if !dir.is_dir() {
            return Ok(None);
        }
        let path = dir.join(LOCK);
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos());
        let token = format!(
            "platbench review, process {}, {nanos}\n",
            std::process::id()
        );
        for _ in 0..2 {
            match fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut f) => {
                    use std::io::Write as _;
                    f.write_all(token.as_bytes())
                        .with_context(|| format!("cannot write {}", path.display()))?;
                    return Ok(Some(Lock { path, token }));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let age = fs::metadata(&path)
                        .and_then(|m| m.modified())
                        .ok()
                        .and_then(|t| t.elapsed().ok());
                    if age.is_some_and(|a| a > STALE) {
                        eprintln!(
                            "warning: taking over {}, older than an hour: left by a review that did not finish ({})",
                            path.display(),
                            lock_text(&path)
                        );
                        fs::remove_file(&path).with_context(|| {
                            format!("cannot remove the stale {}", path.display())
                        })?;
                        continue;
                    }
                    bail!(
                        "{} is locked by another review ({}: {}); wait for it to finish (a lock older than an hour is taken over; remove the file if no review is running)",
                        dir.display(),
                        path.display(),
                        lock_text(&path)
                    );
                }
                Err(e) => {
                    return Err(e).with_context(|| format!("cannot create {}", path.display()))
                }
            }
        }
        bail!(
            "cannot take {}: another review took it over first",
            path.display()
        )
    }
}

/// A lock file's text, trimmed (empty when it cannot be read or is not a regular file).
fn lock_text(path: &Path) -> String {
    crate::limits::read_text_capped(path)
        .unwrap_or_default()
        .trim()
        .to_string()
}

impl Drop for Lock {
    fn drop(&mut self) {
        // Only this lock's file: the baseline swapped in has none, and another review may
        // have taken a new one since.
        if crate::limits::read_text_capped(&self.path).is_ok_and(|t| t == self.token) {
            let _ = fs::remove_file(&self.path);
        }
    }
}

/// Copies the tree `from` into `to` (made already), leaving out the marker file at its top.
fn copy_tree(from: &Path, to: &Path, top: bool) -> Result<()> {
    for e in fs::read_dir(from).with_context(|| format!("cannot read {}", from.display()))? {
        let e = e.with_context(|| format!("cannot read {}", from.display()))?;
        let (src, dst) = (e.path(), to.join(e.file_name()));
        if top && (e.file_name() == output::MARKER || e.file_name() == LOCK) {
            continue;
        }
        let kind = e
            .file_type()
            .with_context(|| format!("cannot inspect {}", src.display()))?;
        if kind.is_dir() {
            fs::create_dir(&dst).with_context(|| format!("cannot create {}", dst.display()))?;
            copy_tree(&src, &dst, false)?;
        } else if kind.is_file() {
            link_or_copy(&src, &dst)?;
        } else {
            bail!(
                "{}: not a file or directory; a baseline holds only files",
                src.display()
            );
        }
    }
    Ok(())
}

/// The baseline's manifest with the entry of each level of an `accepted` run (its hash and
/// scenarios) taken from the manifest of the check's run, so that the baseline records the
/// level its accepted runs ran on; `None` when that changes nothing.
fn updated_manifest(base: &Path, check: &Path, accepted: &[&Unit]) -> Result<Option<Manifest>> {
    let mut m = Manifest::read(base)?;
    let ran = Manifest::read(check)?;
    let before = m.clone();
    let levels: BTreeSet<&str> = accepted.iter().map(|u| u.level.as_str()).collect();
    for name in levels {
        let Some(new) = ran.levels.iter().find(|l| l.name == name) else {
            continue;
        };
        match m.levels.iter_mut().find(|l| l.name == name) {
            Some(old) => *old = new.clone(),
            None => m.levels.push(new.clone()),
        }
    }
    Ok((m != before).then_some(m))
}

/// Accepts the runs `accepted` of the check output `check` into the baseline `base`: their
/// metric rows and trace files become the check's; the rest of the baseline is byte-identical.
/// Written as a whole: a failure leaves the baseline as it was.
pub(crate) fn accept(base: &Path, check: &Path, accepted: &[&Unit]) -> Result<()> {
    if accepted.is_empty() {
        return Ok(());
    }
    let keys: BTreeSet<Key> = accepted
        .iter()
        .map(|u| {
            (
                u.level.clone(),
                u.scenario.clone(),
                u.backend.clone(),
                u.config.clone(),
            )
        })
        .collect();
    // The check's rows of the accepted runs; the baseline's file is copied row by row into
    // the staging directory below.
    let new_rows = taken(&check.join("metrics.csv"), &keys)?;
    let manifest = updated_manifest(base, check, accepted)?;
    let marker = crate::limits::read_capped(&base.join(output::MARKER))
        .with_context(|| format!("cannot read {}", base.join(output::MARKER).display()))?;
    output::write_output(base, output::Kind::Baseline, false, |staging| {
        copy_tree(base, staging, true)?;
        output::write_file(&staging.join(output::MARKER), &marker)?;
        let m = staging.join("metrics.csv");
        fs::remove_file(&m).with_context(|| format!("cannot replace {}", m.display()))?;
        let file =
            fs::File::create(&m).with_context(|| format!("cannot create {}", m.display()))?;
        let mut w = std::io::BufWriter::new(file);
        splice(&base.join("metrics.csv"), &new_rows, &keys, &mut w)?;
        if let Some(manifest) = &manifest {
            // A hard link to the old baseline's file: unlinked first, not written through.
            let f = staging.join(FILE);
            fs::remove_file(&f).with_context(|| format!("cannot replace {}", f.display()))?;
            manifest.write(staging)?;
        }
        let traces = staging.join("traces");
        fs::create_dir_all(&traces)
            .with_context(|| format!("cannot create {}", traces.display()))?;
        for u in accepted {
            let (new, old) = (check.join("traces").join(&u.trace), traces.join(&u.trace));
            if old.exists() {
                fs::remove_file(&old)
                    .with_context(|| format!("cannot replace {}", old.display()))?;
            }
            if new.exists() {
                fs::copy(&new, &old).with_context(|| {
                    format!("cannot copy {} to {}", new.display(), old.display())
                })?;
            }
        }
        Ok(())
    })
}
