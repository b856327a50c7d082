//! Writing a command's output directory without losing anything: the directory is replaced
//! only when it is missing, empty, or holds the output of the same command (recognised by the
//! marker file every output holds); everything goes into a staging directory beside it, which
//! replaces it only once complete. A run killed midway leaves a staging directory that the next
//! write beside it removes, once it has proved the directory is one a dead platbench left.

use std::ffi::{OsStr, OsString};
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};

/// The marker file in every directory platbench writes: one line, `platbench <kind>`.
pub const MARKER: &str = ".platbench-output";
/// Prefix of a staging directory: `.platbench-staging-<pid>-<n>`.
const STAGING: &str = ".platbench-staging-";
/// Prefix of a replaced output moved aside for the swap: `.platbench-old-<pid>-<n>-<name>`.
const OLD: &str = ".platbench-old-";

/// The most bytes a file name holds on the systems platbench runs on (Linux's `NAME_MAX`, the
/// limit of ext4, APFS and NTFS alike).
const NAME_MAX: usize = 255;

/// Which command wrote a directory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// `platbench run --out`.
    Run,
    /// `platbench run --bless`: the committed baseline.
    Baseline,
    /// `platbench report --out`.
    Report,
    /// `platbench stress --out`.
    Stress,
    /// `platbench sweep --out`.
    Sweep,
    /// `platbench check --out`.
    Check,
    /// `platbench hunt --out`.
    Hunt,
}

impl Kind {
    const ALL: [Kind; 7] = [
        Kind::Run,
        Kind::Baseline,
        Kind::Report,
        Kind::Stress,
        Kind::Sweep,
        Kind::Check,
        Kind::Hunt,
    ];

    fn name(self) -> &'static str {
        match self {
            Kind::Run => "run",
            Kind::Baseline => "baseline",
            Kind::Report => "report",
            Kind::Stress => "stress",
            Kind::Sweep => "sweep",
            Kind::Check => "check",
            Kind::Hunt => "hunt",
        }
    }

    fn command(self) -> &'static str {
        match self {
            Kind::Baseline => "platbench run --bless",
            Kind::Run => "platbench run",
            Kind::Report => "platbench report",
            Kind::Stress => "platbench stress",
            Kind::Sweep => "platbench sweep",
            Kind::Check => "platbench check",
            Kind::Hunt => "platbench hunt",
        }
    }

    fn marker_text(self) -> String {
        format!("platbench {}\n", self.name())
    }
}

/// The text of `dir`'s marker file; empty when it has none, or when the marker is not a regular
/// file (a named pipe there would block the read).
pub(crate) fn read_marker(dir: &Path) -> String {
    crate::limits::read_text_capped(&dir.join(MARKER)).unwrap_or_default()
}

/// The kind named by `dir`'s marker file, if it has one that platbench wrote.
fn marker_of(dir: &Path) -> Option<Kind> {
    let text = read_marker(dir);
    let line = text.lines().next()?.trim();
    Kind::ALL
        .into_iter()
        .find(|k| line == format!("platbench {}", k.name()))
}

/// Checks that `dir` may be replaced by an output of `kind`, before any work is done:
///
/// - a missing or empty directory is written;
/// - a directory holding the same command's output (its marker) is replaced;
/// - a baseline (marker `platbench baseline`) is replaced only by `run --bless`, `baseline`
///   and `review` (their callers ask `Kind::Baseline`), whatever else is asked;
/// - a file is never replaced;
/// - anything else (a user's directory, another command's output) only with `force`; the
///   filesystem root, the current directory and its ancestors never.
pub(crate) fn check_target(dir: &Path, kind: Kind, force: bool) -> Result<()> {
    check_target_as(dir, kind, force, "--out")
}

/// [`check_target`], naming the option that gave `dir` as `flag` in its messages.
pub(crate) fn check_target_as(dir: &Path, kind: Kind, force: bool, flag: &str) -> Result<()> {
    // A `..` after a name: `ghost/../victim` is checked while `ghost` is missing (so nothing is
    // there), then names `victim` once the missing folders are created for the output.
    let mut named = false;
    for c in dir.components() {
        match c {
            std::path::Component::ParentDir if named => bail!(
                "{flag} {}: a `..` after a folder name; give the path without it (the folders on the way are created, so the path would name another directory once written)",
                dir.display()
            ),
            std::path::Component::Normal(_) => named = true,
            _ => {}
        }
    }
    // The previous output is moved aside as `.platbench-old-<pid>-<n>-NAME` for the swap, and a
    // file name holds at most 255 bytes: a longer NAME was found too long only after the work.
    let longest = NAME_MAX - format!("{OLD}{}-{}-", u32::MAX, u32::MAX).len();
    if let Some(name) = dir.file_name().filter(|n| n.len() > longest) {
        bail!(
            "{flag} {}: the folder's name is {} bytes; expected at most {longest} (platbench moves a previous output aside under `{OLD}<pid>-<n>-` and its name, and a file name holds at most {NAME_MAX} bytes)",
            dir.display(),
            name.len()
        );
    }
    let meta = match fs::symlink_metadata(dir) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(e).with_context(|| format!("cannot inspect {}", dir.display())),
    };
    if !meta.is_dir() {
        bail!(
            "{flag} {} exists and is not a directory; platbench writes a directory there and never replaces a file: remove it or choose another {flag}",
            dir.display()
        );
    }
    if let (Ok(canon), Ok(cwd)) = (dir.canonicalize(), std::env::current_dir()) {
        if cwd.starts_with(&canon) {
            bail!(
                "{flag} {} is the current directory or one of its parents; platbench replaces its output directory as a whole, so it must be a directory of its own",
                dir.display()
            );
        }
    }
    let found = marker_of(dir);
    if found == Some(Kind::Baseline) && kind != Kind::Baseline {
        bail!(
            "{flag} {} is a platbench baseline (its {MARKER} file says so); a baseline is replaced only on purpose, with `platbench run --bless`, `platbench baseline --replace` or `platbench review`",
            dir.display()
        );
    }
    if found == Some(kind) || force {
        return Ok(());
    }
    if let Some(other) = found {
        bail!(
            "{flag} {} holds the output of `{}`, not of `{}`; refusing to replace it. Choose another {flag}, or pass --force to replace it",
            dir.display(),
            other.command(),
            kind.command()
        );
    }
    let entries = fs::read_dir(dir)
        .with_context(|| format!("cannot read {}", dir.display()))?
        .count();
    if entries > 0 {
        bail!(
            "{flag} {} already exists, holds {entries} entries and is not a platbench output (it has no {MARKER} file); refusing to replace it. Choose another {flag}, or pass --force to replace it and everything in it",
            dir.display()
        );
    }
    Ok(())
}

/// `p` made absolute with its symbolic links resolved, as far as it exists: the deepest
/// existing ancestor canonicalized, the rest appended as given.
pub(crate) fn canonical_lenient(p: &Path) -> PathBuf {
    let abs = if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir().map_or_else(|_| p.to_path_buf(), |c| c.join(p))
    };
    let mut rest = Vec::new();
    let mut at = abs.as_path();
    loop {
        if let Ok(c) = at.canonicalize() {
            return rest
                .iter()
                .rev()
                .fold(c, |acc: PathBuf, part| acc.join(part));
        }
        match (at.parent(), at.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name.to_os_string());
                at = parent;
            }
            _ => return abs,
        }
    }
}

/// The directory `dir` sits in (`.` for a bare name).
fn parent_of(dir: &Path) -> PathBuf {
    match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => ".".into(),
    }
}

/// Whether process `pid` is known to have ended: only where `/proc` lists the live processes
/// (Linux); elsewhere nothing is known, and nothing is cleaned.
fn process_ended(pid: u32) -> bool {
    Path::new("/proc/self").exists() && !Path::new("/proc").join(pid.to_string()).exists()
}

/// The process and the output's own name (any bytes the system accepts) of a directory moved
/// aside for the swap, `.platbench-old-<pid>-<n>-<name>`; `None` for any other name.
fn moved_aside(name: &OsStr) -> Option<(u32, OsString)> {
    #[cfg(unix)]
    let bytes = std::os::unix::ffi::OsStrExt::as_bytes(name);
    #[cfg(not(unix))]
    let bytes = name.to_str()?.as_bytes();
    let rest = bytes.strip_prefix(OLD.as_bytes())?;
    let mut parts = rest.splitn(3, |&b| b == b'-');
    let pid = std::str::from_utf8(parts.next()?)
        .ok()?
        .parse::<u32>()
        .ok()?;
    parts.next()?;
    let target = parts.next()?;
    if target.is_empty() {
        return None;
    }
    #[cfg(unix)]
    let target = OsString::from(<OsStr as std::os::unix::ffi::OsStrExt>::from_bytes(target));
    #[cfg(not(unix))]
    let target = OsString::from(std::str::from_utf8(target).ok()?);
    Some((pid, target))
}

/// Removes the staging directories a dead platbench left in `parent`, and puts back an output
/// it had moved aside and not replaced. Only entries whose names platbench gives, of a process
/// that has ended, are touched. Says on stderr what it did.
pub(crate) fn clean_stale(parent: &Path) {
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for e in entries.filter_map(|e| e.ok()) {
        let name = e.file_name().to_string_lossy().into_owned();
        let path = e.path();
        if !e.file_type().is_ok_and(|t| t.is_dir()) {
            continue;
        }
        if let Some(rest) = name.strip_prefix(STAGING) {
            let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<u32>().ok()) else {
                continue;
            };
            // Its own marker (written first) or nothing at all: a directory platbench made.
            let ours = marker_of(&path).is_some()
                || fs::read_dir(&path).is_ok_and(|mut d| d.next().is_none());
            if pid != std::process::id() && process_ended(pid) && ours {
                match fs::remove_dir_all(&path) {
                    Ok(()) => eprintln!(
                        "note: removed {}, left by an interrupted platbench (process {pid})",
                        path.display()
                    ),
                    Err(err) => eprintln!("warning: cannot remove {}: {err}", path.display()),
                }
            }
        } else if let Some((pid, target)) = moved_aside(&e.file_name()) {
            if pid == std::process::id() || !process_ended(pid) {
                continue;
            }
            let target = parent.join(target);
            if target.exists() {
                match fs::remove_dir_all(&path) {
                    Ok(()) => eprintln!(
                        "note: removed {}, the previous output an interrupted platbench (process {pid}) had replaced",
                        path.display()
                    ),
                    Err(err) => eprintln!("warning: cannot remove {}: {err}", path.display()),
                }
            } else if fs::rename(&path, &target).is_ok() {
                eprintln!(
                    "note: put {} back as {}: an interrupted platbench (process {pid}) had moved it aside",
                    path.display(),
                    target.display()
                );
            }
        }
    }
}

/// A staging directory, removed when dropped unless it was moved into place.
struct Staging {
    path: Option<PathBuf>,
}

impl Staging {
    fn create(parent: &Path) -> Result<Staging> {
        for n in 0..1000u32 {
            let path = parent.join(format!("{STAGING}{}-{n}", std::process::id()));
            match fs::create_dir(&path) {
                Ok(()) => return Ok(Staging { path: Some(path) }),
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => {
                    return Err(e).with_context(|| {
                        format!("cannot create a staging directory in {}", parent.display())
                    })
                }
            }
        }
        bail!(
            "cannot create a staging directory in {}: 1000 names taken",
            parent.display()
        )
    }

    fn path(&self) -> &Path {
        self.path.as_deref().unwrap_or(Path::new("."))
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if let Some(p) = self.path.take() {
            let _ = fs::remove_dir_all(p);
        }
    }
}

/// Writes `text` to `path` (mode 0644 under the usual umask, as any file the user creates).
pub(crate) fn write_file(path: &Path, text: &[u8]) -> Result<()> {
    let mut f =
        fs::File::create(path).with_context(|| format!("cannot create {}", path.display()))?;
    f.write_all(text)
        .and_then(|()| f.flush())
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Writes an output of `kind` into `dir` as a whole: checks `dir` again ([`check_target`]),
/// cleans what an interrupted platbench left beside it, lets `fill` write the files into a
/// staging directory (with the marker), then swaps the staging directory in.
pub(crate) fn write_output(
    dir: &Path,
    kind: Kind,
    force: bool,
    fill: impl FnOnce(&Path) -> Result<()>,
) -> Result<()> {
    check_target(dir, kind, force)?;
    let parent = parent_of(dir);
    fs::create_dir_all(&parent).with_context(|| format!("cannot create {}", parent.display()))?;
    clean_stale(&parent);
    let mut staging = Staging::create(&parent)?;
    write_file(&staging.path().join(MARKER), kind.marker_text().as_bytes())?;
    fill(staging.path())?;

    // Swap: move the old directory aside, move the new one in, then delete the old one.
    let old = if fs::symlink_metadata(dir).is_ok() {
        // The output's own name, whatever its bytes, so that a later run puts it back there.
        let name = dir.file_name().unwrap_or(OsStr::new("out"));
        let aside = (0..1000u32)
            .map(|n| {
                let mut aside = OsString::from(format!("{OLD}{}-{n}-", std::process::id()));
                aside.push(name);
                parent.join(aside)
            })
            .find(|p| !p.exists())
            .with_context(|| format!("no free name to move {} aside", dir.display()))?;
        fs::rename(dir, &aside)
            .with_context(|| format!("cannot move the previous {} aside", dir.display()))?;
        Some(aside)
    } else {
        None
    };
    if let Err(e) = fs::rename(staging.path(), dir) {
        if let Some(aside) = &old {
            let _ = fs::rename(aside, dir);
        }
        return Err(e)
            .with_context(|| format!("cannot move the new output into {}", dir.display()));
    }
    staging.path = None;
    if let Some(aside) = old {
        fs::remove_dir_all(&aside)
            .with_context(|| format!("cannot remove the previous output at {}", aside.display()))?;
    }
    Ok(())
}

/// Serialises `rows` as CSV into `path`.
pub fn write_csv<T: serde::Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    let mut w = csv::Writer::from_path(path)
        .with_context(|| format!("cannot create {}", path.display()))?;
    for r in rows {
        w.serialize(r)
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    w.flush()
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}
