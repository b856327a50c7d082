//! The controller's process: started with piped stdin, stdout and stderr, written one JSON line
//! at a time and read with a deadline. A thread per pipe reads the child's lines (stdout into a
//! bounded channel read with `recv_timeout`, stderr's last lines kept for the error message), so
//! a child that hangs costs its timeout and nothing more. The child is killed and waited for
//! when the [`Process`] drops, whatever ended the run.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde::Serialize;

use super::config::ControllerFile;

/// The longest line a controller may print, in bytes: a line longer is garbage.
const MAX_LINE: u64 = 16 << 20;
/// How many of the child's last stderr lines an error quotes.
const STDERR_LINES: usize = 5;

/// A running controller process.
pub(crate) struct Process {
    child: Child,
    stdin: Option<std::io::BufWriter<ChildStdin>>,
    lines: Receiver<std::io::Result<String>>,
    stderr: Arc<Mutex<VecDeque<String>>>,
}

/// Why talking to the process failed, in words for the error message.
pub(crate) type Failure = String;

impl Process {
    /// Starts the controller of `file`.
    pub(crate) fn start(file: &ControllerFile) -> Result<Process, Failure> {
        let mut child = Command::new(&file.command)
            .args(&file.args)
            .current_dir(&file.working_directory)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| {
                format!(
                    "cannot start `{}` in {}: {e}",
                    file.command.display(),
                    file.working_directory.display()
                )
            })?;
        let (stdin, stdout, stderr) =
            match (child.stdin.take(), child.stdout.take(), child.stderr.take()) {
                (Some(i), Some(o), Some(e)) => (i, o, e),
                _ => {
                    let _ = child.kill();
                    let _ = child.wait();
                    return Err("its pipes could not be opened".into());
                }
            };
        let (tx, lines) = mpsc::sync_channel(4);
        std::thread::spawn(move || {
            let mut out = BufReader::new(stdout);
            loop {
                let mut line = String::new();
                let read = (&mut out).take(MAX_LINE).read_line(&mut line);
                let end = match &read {
                    Ok(0) => true,
                    Ok(_) if !line.ends_with('\n') && line.len() as u64 >= MAX_LINE => {
                        let _ = tx.send(Err(std::io::Error::other(format!(
                            "a line longer than {MAX_LINE} bytes"
                        ))));
                        true
                    }
                    Ok(_) => false,
                    Err(_) => true,
                };
                if end {
                    if let Err(e) = read {
                        let _ = tx.send(Err(e));
                    }
                    return;
                }
                if tx.send(Ok(line)).is_err() {
                    return;
                }
            }
        });
        let kept = Arc::new(Mutex::new(VecDeque::new()));
        let keep = kept.clone();
        std::thread::spawn(move || {
            let mut err = BufReader::new(stderr);
            let mut line = String::new();
            loop {
                line.clear();
                match (&mut err).take(64 << 10).read_line(&mut line) {
                    Ok(0) | Err(_) => return,
                    Ok(_) => {
                        if let Ok(mut q) = keep.lock() {
                            if q.len() == STDERR_LINES {
                                q.pop_front();
                            }
                            q.push_back(line.trim_end().to_string());
                        }
                    }
                }
            }
        });
        Ok(Process {
            child,
            stdin: Some(std::io::BufWriter::new(stdin)),
            lines,
            stderr: kept,
        })
    }

    /// Writes `message` as one line and flushes it.
    pub(crate) fn send(&mut self, message: &impl Serialize) -> Result<(), Failure> {
        let Some(stdin) = self.stdin.as_mut() else {
            return Err("its stdin is closed".into());
        };
        let written = serde_json::to_writer(&mut *stdin, message)
            .map_err(std::io::Error::from)
            .and_then(|()| stdin.write_all(b"\n"))
            .and_then(|()| stdin.flush());
        written.map_err(|e| self.gone(&format!("cannot write to it ({e})")))
    }

    /// The next line it prints, waiting at most `timeout`.
    pub(crate) fn receive(&mut self, timeout: Duration) -> Result<String, Failure> {
        let start = Instant::now();
        match self.lines.recv_timeout(timeout) {
            Ok(Ok(line)) => Ok(line),
            Ok(Err(e)) => Err(self.gone(&format!("its output could not be read ({e})"))),
            Err(RecvTimeoutError::Timeout) => {
                self.kill();
                Err(format!(
                    "no reply within its timeout of {} ms (waited {} ms; killed){}",
                    timeout.as_millis(),
                    start.elapsed().as_millis(),
                    self.stderr_tail()
                ))
            }
            Err(RecvTimeoutError::Disconnected) => Err(self.gone("its stdout closed")),
        }
    }

    /// Closes its stdin and gives it `grace` to exit before it is killed.
    pub(crate) fn finish(&mut self, grace: Duration) {
        self.stdin = None;
        let deadline = Instant::now() + grace;
        while Instant::now() < deadline {
            match self.child.try_wait() {
                Ok(Some(_)) | Err(_) => return,
                Ok(None) => std::thread::sleep(Duration::from_millis(1)),
            }
        }
        self.kill();
    }

    fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    /// The message for a process that stopped answering: its exit status if it exited (given a
    /// moment to), and its last stderr lines.
    fn gone(&mut self, what: &str) -> Failure {
        let deadline = Instant::now() + Duration::from_millis(200);
        let status = loop {
            match self.child.try_wait() {
                Ok(Some(s)) => break Some(s),
                Ok(None) if Instant::now() < deadline => {
                    std::thread::sleep(Duration::from_millis(2))
                }
                _ => break None,
            }
        };
        self.kill();
        // Its stderr thread reads until the pipe closes: give it a moment to keep the last lines.
        std::thread::sleep(Duration::from_millis(20));
        let status = status.map_or_else(
            || "still running; killed".to_string(),
            |s| format!("it exited with {s}"),
        );
        format!("{what}: {status}{}", self.stderr_tail())
    }

    /// `; its stderr ended: ...` with its last lines, or nothing.
    fn stderr_tail(&self) -> String {
        let lines: Vec<String> = self
            .stderr
            .lock()
            .map(|q| q.iter().cloned().collect())
            .unwrap_or_default();
        if lines.is_empty() {
            String::new()
        } else {
            format!("; its stderr ended: {}", lines.join(" | "))
        }
    }
}

impl Drop for Process {
    fn drop(&mut self) {
        self.stdin = None;
        self.kill();
    }
}
