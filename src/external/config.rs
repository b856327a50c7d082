//! The controller file: a small TOML naming an external controller's program and how platbench
//! runs it ([`ControllerFile`]). Every error names the file, line and column.

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::Deserialize;
use toml::Spanned;

use super::ExternalError;

/// How platbench drives an external controller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The controller resolves the displacement platbench's shared motion asks for (as
    /// Rapier's character controller does): differences come from collision handling only.
    Collision,
    /// The controller runs its own game rules from the raw inputs.
    Whole,
}

impl Mode {
    /// `collision` or `whole`, as in the file and the protocol.
    pub fn label(self) -> &'static str {
        match self {
            Mode::Collision => "collision",
            Mode::Whole => "whole",
        }
    }
}

/// How platbench and the controller exchange their lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transport {
    /// Over the controller's stdin and stdout (the default).
    Stdio,
    /// Over a TCP connection the controller opens to `127.0.0.1` at the port in the environment
    /// variable `PLATBENCH_PORT`, for a program that cannot read its stdin (Godot 3's headless
    /// server). Its stdout is then free for logs, as its stderr is.
    Tcp,
}

/// A controller file, read and checked.
#[derive(Clone, Debug, PartialEq)]
pub struct ControllerFile {
    /// Where it was read from, for messages.
    pub source: String,
    /// The backend name its rows, traces and `--backend` use (lower-case ASCII letters,
    /// digits, `_` and `-`).
    pub name: String,
    /// The program to run (a path relative to the file's directory when it contains a `/`,
    /// else looked up on the PATH).
    pub command: PathBuf,
    /// Its arguments.
    pub args: Vec<String>,
    /// The directory it runs in (relative to the file's directory; default: that directory).
    pub working_directory: PathBuf,
    /// How platbench drives it.
    pub mode: Mode,
    /// How the lines travel.
    pub transport: Transport,
    /// How long platbench waits for each step's reply before it ends the run.
    pub step_timeout: Duration,
    /// How long platbench waits for the program to start and answer the handshake or a `run`.
    pub start_timeout: Duration,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    name: Spanned<String>,
    command: Spanned<String>,
    #[serde(default)]
    args: Vec<String>,
    working_directory: Option<Spanned<String>>,
    mode: Spanned<String>,
    transport: Option<Spanned<String>>,
    step_timeout_ms: Option<Spanned<u64>>,
    start_timeout_ms: Option<Spanned<u64>>,
}

/// Default per-step timeout, ms.
const STEP_TIMEOUT_MS: u64 = 1000;
/// Default start-up timeout, ms.
const START_TIMEOUT_MS: u64 = 10_000;
/// The longest timeout a file may ask for, ms (ten minutes).
const MAX_TIMEOUT_MS: u64 = 600_000;

/// Reads controller file `text` from `path`.
pub(crate) fn parse(text: &str, path: &Path) -> Result<ControllerFile, ExternalError> {
    let source = path.display().to_string();
    let at = |offset: usize, message: String| {
        let (line, column) = crate::input::line_column(text, offset);
        ExternalError::File {
            file: source.clone(),
            line,
            column,
            message,
        }
    };
    let raw: Raw = toml::from_str(text).map_err(|e| {
        let (offset, message) = crate::level::explain_toml_error(text, &e);
        at(offset, message)
    })?;
    let name = raw.name.get_ref();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' || c == '-')
    {
        return Err(at(
            raw.name.span().start,
            format!("name {name:?}: expected lower-case ASCII letters, digits, `_` and `-` (it names CSV rows, trace files and --backend values)"),
        ));
    }
    if raw.command.get_ref().trim().is_empty() {
        return Err(at(
            raw.command.span().start,
            "command is empty: expected the program to run".into(),
        ));
    }
    let mode = match raw.mode.get_ref().as_str() {
        "collision" => Mode::Collision,
        "whole" => Mode::Whole,
        other => {
            return Err(at(
                raw.mode.span().start,
                format!("mode {other:?}: expected \"collision\" (the controller resolves the shared motion's displacement) or \"whole\" (it runs its own game rules)"),
            ))
        }
    };
    let transport = match raw.transport.as_ref().map(|t| (t, t.get_ref().as_str())) {
        None | Some((_, "stdio")) => Transport::Stdio,
        Some((_, "tcp")) => Transport::Tcp,
        Some((t, other)) => {
            return Err(at(
                t.span().start,
                format!("transport {other:?}: expected \"stdio\" (JSON lines over its stdin and stdout, the default) or \"tcp\" (it connects to 127.0.0.1 at the port in $PLATBENCH_PORT)"),
            ))
        }
    };
    let timeout = |v: &Option<Spanned<u64>>, default: u64, what: &str| match v {
        None => Ok(Duration::from_millis(default)),
        Some(v) if (1..=MAX_TIMEOUT_MS).contains(v.get_ref()) => {
            Ok(Duration::from_millis(*v.get_ref()))
        }
        Some(v) => Err(at(
            v.span().start,
            format!(
                "{what} {}: expected 1 to {MAX_TIMEOUT_MS} milliseconds",
                v.get_ref()
            ),
        )),
    };
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let command = raw.command.get_ref();
    let command = if command.contains('/') {
        dir.join(command)
    } else {
        PathBuf::from(command)
    };
    Ok(ControllerFile {
        source: source.clone(),
        name: name.clone(),
        command,
        args: raw.args,
        working_directory: raw
            .working_directory
            .as_ref()
            .map_or_else(|| dir.to_path_buf(), |w| dir.join(w.get_ref())),
        mode,
        transport,
        step_timeout: timeout(&raw.step_timeout_ms, STEP_TIMEOUT_MS, "step_timeout_ms")?,
        start_timeout: timeout(&raw.start_timeout_ms, START_TIMEOUT_MS, "start_timeout_ms")?,
    })
}

/// Reads the controller file at `path`.
pub(crate) fn read(path: &Path) -> Result<ControllerFile, ExternalError> {
    let text = crate::limits::read_text_capped(path).map_err(|e| ExternalError::Read {
        file: path.display().to_string(),
        message: e.to_string(),
    })?;
    parse(&text, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<ControllerFile, ExternalError> {
        parse(text, Path::new("dir/c.toml"))
    }

    #[test]
    fn a_file_reads_with_its_defaults() {
        let c = parse_str(
            "name = \"py\"\ncommand = \"python3\"\nargs = [\"client.py\"]\nmode = \"collision\"\n",
        )
        .unwrap();
        assert_eq!(c.name, "py");
        assert_eq!(c.command, PathBuf::from("python3"));
        assert_eq!(c.working_directory, PathBuf::from("dir"));
        assert_eq!(c.mode, Mode::Collision);
        assert_eq!(c.transport, Transport::Stdio);
        assert_eq!(c.step_timeout, Duration::from_millis(STEP_TIMEOUT_MS));
        let c = parse_str(
            "name = \"py\"\ncommand = \"./run.sh\"\nmode = \"whole\"\nstep_timeout_ms = 50\n",
        )
        .unwrap();
        assert_eq!(c.command, PathBuf::from("dir/./run.sh"));
        assert_eq!(c.step_timeout, Duration::from_millis(50));
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let e = parse_str("name = \"py\"\ncommand = \"python3\"\nmode = \"fast\"\n").unwrap_err();
        assert!(
            e.to_string().starts_with("dir/c.toml:3:8: mode \"fast\""),
            "{e}"
        );
        let e = parse_str("name = \"Py Client\"\ncommand = \"x\"\nmode = \"whole\"\n").unwrap_err();
        assert!(e.to_string().starts_with("dir/c.toml:1:8: name"), "{e}");
        let e =
            parse_str("name = \"py\"\ncommand = \"x\"\nmode = \"whole\"\nstep_timeout_ms = 0\n")
                .unwrap_err();
        assert!(e.to_string().starts_with("dir/c.toml:4:19:"), "{e}");
        let e = parse_str("name = \"py\"\ncommand = \"x\"\nmode = \"whole\"\ncolour = 1\n")
            .unwrap_err();
        assert!(e.to_string().starts_with("dir/c.toml:4:1:"), "{e}");
        let e = parse_str("name = \"g\"\ncommand = \"x\"\nmode = \"whole\"\ntransport = \"udp\"\n")
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with("dir/c.toml:4:13: transport \"udp\""),
            "{e}"
        );
        let e = parse_str("name = \"py\"\nmode = \"whole\"\n").unwrap_err();
        assert!(e.to_string().contains("command"), "{e}");
    }
}
