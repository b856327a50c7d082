//! Every file platbench reads from the user is opened here: checked to be a regular file before
//! a byte is read (a named pipe would block the open until a writer came, a device such as
//! `/dev/zero` never ends), and read no further than the cap of its format, when it has one.
//! The errors name the file.

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

/// An input file that was not read, naming it.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The file could not be opened or read. The cause is in the message, not chained as a
    /// source, so that a report of the chain says it once.
    #[error("{}: cannot read it: {cause}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// The path is a directory, a named pipe, a device or a socket.
    #[error("{}: it is {kind}; expected a regular file", path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// What it is instead (`a directory`, `a named pipe (FIFO)`, ...).
        kind: &'static str,
    },
    /// The file is larger than its format allows.
    #[error("{}: it holds more than {} MiB, the most platbench reads from one {what}; expected a smaller file", path.display(), cap / (1024 * 1024))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The most bytes read from it.
        cap: u64,
        /// What the file was read as (`input file`, `trade-off CSV`, ...).
        what: &'static str,
    },
    /// The file is not UTF-8 text.
    #[error("{}:{line}:{column}: {}", path.display(), not_text(.found))]
    NotText {
        /// The file.
        path: PathBuf,
        /// The 1-based line of the first byte that is not UTF-8.
        line: usize,
        /// Its 1-based column, in characters.
        column: usize,
        /// The bytes found there, in hex (`0xFF`).
        found: String,
    },
}

impl InputError {
    /// The file.
    pub fn path(&self) -> &Path {
        match self {
            InputError::Io { path, .. }
            | InputError::NotAFile { path, .. }
            | InputError::TooLarge { path, .. }
            | InputError::NotText { path, .. } => path,
        }
    }

    /// The error for a caller that reads the file as `what` (`level file`): text that is not
    /// UTF-8 at its `FILE:LINE:COLUMN`, as every located error; any other fault as `cannot read
    /// WHAT FILE: why`, the cause said once.
    pub fn reading(&self, what: &str) -> String {
        match self {
            InputError::NotText { .. } => self.to_string(),
            _ => format!(
                "cannot read {what} {}: {}",
                self.path().display(),
                self.reason()
            ),
        }
    }

    /// What is wrong without the file's name, for a caller whose own error names it (and says
    /// it could not read it).
    pub fn reason(&self) -> String {
        match self {
            InputError::Io { cause, .. } => return cause.to_string(),
            InputError::NotText {
                line,
                column,
                found,
                ..
            } => return format!("line {line}, column {column}: {}", not_text(found)),
            _ => {}
        }
        let full = self.to_string();
        let path = self.path().display().to_string();
        full.strip_prefix(&format!("{path}: "))
            .map_or_else(|| full.clone(), str::to_string)
    }
}

impl From<InputError> for std::io::Error {
    /// The reason alone (callers of the `std::io` readers name the file themselves).
    fn from(e: InputError) -> Self {
        let kind = match &e {
            InputError::Io { cause, .. } => cause.kind(),
            InputError::NotAFile { .. } => std::io::ErrorKind::InvalidInput,
            InputError::TooLarge { .. } | InputError::NotText { .. } => {
                std::io::ErrorKind::InvalidData
            }
        };
        std::io::Error::new(kind, e.reason())
    }
}

/// What a path that is not a regular file is, for [`InputError::NotAFile`].
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "a named pipe (FIFO)";
        }
        if t.is_char_device() {
            return "a character device";
        }
        if t.is_block_device() {
            return "a block device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

/// A file opened for reading that yields an error, not a short read, past its cap.
pub struct Capped {
    file: File,
    path: PathBuf,
    left: u64,
    cap: u64,
    what: &'static str,
}

impl Read for Capped {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        // One byte past the cap is asked for, so a file that grew is caught, not cut.
        let room = usize::try_from(self.left.saturating_add(1)).unwrap_or(usize::MAX);
        let n = buf.len().min(room);
        let got = self.file.read(&mut buf[..n])?;
        if got as u64 > self.left {
            return Err(InputError::TooLarge {
                path: self.path.clone(),
                cap: self.cap,
                what: self.what,
            }
            .into());
        }
        self.left -= got as u64;
        Ok(got)
    }
}

/// Opens `path` for reading: a regular file (symbolic links followed) of at most `cap` bytes
/// (`u64::MAX` for a format with no cap); `what` names the format in the error.
pub fn open(path: &Path, cap: u64, what: &'static str) -> Result<Capped, InputError> {
    let io = |cause| InputError::Io {
        path: path.to_path_buf(),
        cause,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    let check = |meta: &std::fs::Metadata| {
        if !meta.is_file() {
            return Err(InputError::NotAFile {
                path: path.to_path_buf(),
                kind: kind_of(meta),
            });
        }
        if meta.len() > cap {
            return Err(InputError::TooLarge {
                path: path.to_path_buf(),
                cap,
                what,
            });
        }
        Ok(())
    };
    check(&meta)?;
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    // Should the path become a named pipe after the check, the open does not wait for a writer;
    // the check below then refuses it. A regular file reads the same either way.
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let file = options.open(path).map_err(io)?;
    check(&file.metadata().map_err(io)?)?;
    Ok(Capped {
        file,
        path: path.to_path_buf(),
        left: cap,
        cap,
        what,
    })
}

/// Reads a whole regular file of at most `cap` bytes ([`open`]).
pub fn read(path: &Path, cap: u64, what: &'static str) -> Result<Vec<u8>, InputError> {
    let mut bytes = Vec::new();
    open(path, cap, what)?
        .read_to_end(&mut bytes)
        .map_err(|cause| match cause.kind() {
            std::io::ErrorKind::InvalidData => InputError::TooLarge {
                path: path.to_path_buf(),
                cap,
                what,
            },
            _ => InputError::Io {
                path: path.to_path_buf(),
                cause,
            },
        })?;
    Ok(bytes)
}

/// [`read`] as UTF-8 text.
pub fn read_text(path: &Path, cap: u64, what: &'static str) -> Result<String, InputError> {
    String::from_utf8(read(path, cap, what)?).map_err(|e| {
        let (line, column, found) = not_utf8_at(e.as_bytes(), e.utf8_error());
        InputError::NotText {
            path: path.to_path_buf(),
            line,
            column,
            found,
        }
    })
}

/// Where the first byte of `bytes` that is not UTF-8 is (`e` says which): its line and column
/// (1-based, the column in characters) and the bytes found there, in hex.
pub(crate) fn not_utf8_at(bytes: &[u8], e: std::str::Utf8Error) -> (usize, usize, String) {
    let valid = e.valid_up_to();
    let text = std::str::from_utf8(bytes.get(..valid).unwrap_or_default()).unwrap_or_default();
    let (line, column) = line_column(text, valid);
    let bad = bytes.get(valid..).unwrap_or_default();
    let found = bad
        .iter()
        .take(e.error_len().unwrap_or(bad.len()).min(4))
        .map(|b| format!("0x{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ");
    (line, column, found)
}

/// What a file that is not UTF-8 holds where it stops being UTF-8, and what was expected.
pub(crate) fn not_text(found: &str) -> String {
    format!("found byte(s) {found}, not UTF-8; expected UTF-8 text (save the file as UTF-8)")
}

/// `s` quoted as an error shows what it found: whole up to 100 characters (a long layer name
/// of a real map is 40 to 60), else its first 40, `…` and its length, so a 100 MB name is not
/// echoed whole.
pub(crate) fn quoted(s: &str) -> String {
    const WHOLE: usize = 100;
    const SHOWN: usize = 40;
    match s.char_indices().nth(WHOLE) {
        None => format!("{s:?}"),
        Some(_) => {
            let at = s.char_indices().nth(SHOWN).map_or(s.len(), |(at, _)| at);
            format!("{:?}… ({} bytes)", &s[..at], s.len())
        }
    }
}

/// Line and column (both 1-based, the column in characters) of byte `offset` in `text`, for an
/// error that points into a file. An offset past the end or inside a character names the place
/// just before it, never panics.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |p| p + 1);
    (
        before.matches('\n').count() + 1,
        before[line_start..].chars().count() + 1,
    )
}

/// FNV-1a, 64 bits, of `bytes`: a cheap hash for telling a changed file (a baseline's levels, the
/// built-in Godot client's copy), not for security.
pub(crate) fn fnv1a64(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    #[test]
    fn line_column_counts_characters_and_never_lands_inside_one() {
        assert_eq!(super::line_column("ab\ncd", 4), (2, 2));
        // Byte 1 is inside the two-byte 'é': the place before it, column 1.
        assert_eq!(super::line_column("é", 1), (1, 1));
        // Past the end: the end.
        assert_eq!(super::line_column("x\n", 99), (2, 1));
    }

    #[test]
    fn the_first_byte_that_is_not_utf8_is_placed_by_line_and_column() {
        let at = |b: &[u8]| {
            let e = std::str::from_utf8(b).err().unwrap();
            super::not_utf8_at(b, e)
        };
        // After 'é' (two bytes, one column) on line 2: column 3.
        assert_eq!(at(b"a\n\xc3\xa9x\xffy"), (2, 3, "0xFF".into()));
        // A character cut short at the end.
        assert_eq!(at(b"ab\xe2\x82"), (1, 3, "0xE2 0x82".into()));
    }

    #[test]
    fn fnv1a64_is_the_published_function() {
        // The FNV-1a offset basis for no input, and the published value for "a".
        assert_eq!(super::fnv1a64([]), 0xcbf2_9ce4_8422_2325);
        assert_eq!(super::fnv1a64(*b"a"), 0xaf63_dc4c_8601_ec8c);
    }

    use super::*;

    #[test]
    fn only_regular_files_within_their_cap_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("f.csv");
        std::fs::write(&f, "abcd").unwrap();
        assert_eq!(read(&f, 4, "test file").unwrap(), b"abcd");
        let e = read(&f, 3, "test file").unwrap_err();
        assert!(matches!(e, InputError::TooLarge { cap: 3, .. }), "{e}");
        assert!(
            e.to_string().starts_with(&format!("{}: ", f.display())),
            "{e}"
        );
        let e = read(dir.path(), 4, "test file").unwrap_err();
        assert!(e.to_string().contains("it is a directory"), "{e}");
        assert_eq!(e.reason(), "it is a directory; expected a regular file");
        let e = read(&dir.path().join("none"), 4, "test file").unwrap_err();
        assert!(e.to_string().contains("none: cannot read it: "), "{e}");
        assert!(!e.reason().contains("cannot read"), "{e}");
        #[cfg(unix)]
        {
            // A device that never ends, and a named pipe no one writes to (the open would block).
            let e = read(Path::new("/dev/zero"), 4, "test file").unwrap_err();
            assert!(e.to_string().contains("a character device"), "{e}");
            let fifo = dir.path().join("p");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            assert!(made.is_ok_and(|s| s.success()), "mkfifo");
            let e = read(&fifo, 4, "test file").unwrap_err();
            assert!(e.to_string().contains("a named pipe (FIFO)"), "{e}");
        }
    }
}
