//! The controller's process and its connection: JSON lines over the child's stdin and stdout, or
//! over a TCP connection on the loopback interface that the child opens to platbench (for
//! programs that cannot read their stdin, such as Godot 3's headless server; the controller
//! file's `transport`). A thread reads the connection's lines into a bounded channel read with
//! `recv_timeout`, and threads keep the last lines of the child's stderr (and, over TCP, of its
//! stdout) for the error message, so a child that hangs costs its timeout and nothing more. The
//! child is killed and waited for when the [`Process`] drops, whatever ended the run.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde::Serialize;

use super::config::{ControllerFile, Transport};

/// The longest line a controller may print, in bytes: a line longer is garbage.
const MAX_LINE: u64 = 16 << 20;
/// How many of the child's last stderr (or stdout) lines an error quotes.
const TAIL_LINES: usize = 5;
/// The environment variable that gives a TCP controller the port to connect to.
pub(crate) const PORT_VARIABLE: &str = "PLATBENCH_PORT";

/// The child's last lines on a stream it writes freely, kept for error messages.
type Tail = Arc<Mutex<VecDeque<String>>>;

/// A running controller process.
pub(crate) struct Process {
    child: Child,
    writer: Option<std::io::BufWriter<Box<dyn Write + Send>>>,
    /// The TCP connection, to shut down when platbench has nothing more to say.
    socket: Option<TcpStream>,
    lines: Receiver<std::io::Result<String>>,
    stderr: Tail,
    stdout: Option<Tail>,
}

/// Why talking to the process failed, in words for the error message.
pub(crate) type Failure = String;

/// Reads `from` line by line into a channel until it ends, fails or the receiver goes.
fn read_lines(from: impl Read + Send + 'static) -> Receiver<std::io::Result<String>> {
    let (tx, lines) = mpsc::sync_channel(4);
    std::thread::spawn(move || {
        let mut out = BufReader::new(from);
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
    lines
}

/// Keeps the last lines `from` writes, until it ends.
fn keep_tail(from: impl Read + Send + 'static) -> Tail {
    let kept = Arc::new(Mutex::new(VecDeque::new()));
    let keep = kept.clone();
    std::thread::spawn(move || {
        let mut from = BufReader::new(from);
        let mut line = String::new();
        loop {
            line.clear();
            match (&mut from).take(64 << 10).read_line(&mut line) {
                Ok(0) | Err(_) => return,
                Ok(_) => {
                    if let Ok(mut q) = keep.lock() {
                        if q.len() == TAIL_LINES {
                            q.pop_front();
                        }
                        q.push_back(line.trim_end().to_string());
                    }
                }
            }
        }
    });
    kept
}

/// Kills and waits for `child`, returning `failure`.
fn abandon(child: &mut Child, failure: String) -> Failure {
    let _ = child.kill();
    let _ = child.wait();
    failure
}

impl Process {
    /// Starts the controller of `file` and opens its connection (over TCP: waits up to the
    /// file's `start_timeout` for the child to connect).
    pub(crate) fn start(file: &ControllerFile) -> Result<Process, Failure> {
        let listener = match file.transport {
            Transport::Stdio => None,
            Transport::Tcp => Some(
                TcpListener::bind(("127.0.0.1", 0))
                    .and_then(|l| l.set_nonblocking(true).map(|()| l))
                    .map_err(|e| format!("cannot listen on the loopback interface: {e}"))?,
            ),
        };
        let mut command = Command::new(&file.command);
        command
            .args(&file.args)
            .current_dir(&file.working_directory)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        match &listener {
            None => command.stdin(Stdio::piped()),
            Some(l) => {
                let port = l
                    .local_addr()
                    .map_err(|e| format!("cannot read the listening port: {e}"))?
                    .port();
                command
                    .env(PORT_VARIABLE, port.to_string())
                    .stdin(Stdio::null())
            }
        };
        let mut child = command.spawn().map_err(|e| {
            format!(
                "cannot start `{}` in {}: {e}",
                file.command.display(),
                file.working_directory.display()
            )
        })?;
        let (Some(stdout), Some(stderr)) = (child.stdout.take(), child.stderr.take()) else {
            return Err(abandon(&mut child, "its pipes could not be opened".into()));
        };
        let stderr = keep_tail(stderr);
        let Some(listener) = listener else {
            let Some(stdin) = child.stdin.take() else {
                return Err(abandon(&mut child, "its stdin could not be opened".into()));
            };
            return Ok(Process {
                child,
                writer: Some(std::io::BufWriter::new(Box::new(stdin))),
                socket: None,
                lines: read_lines(stdout),
                stderr,
                stdout: None,
            });
        };
        let stdout = keep_tail(stdout);
        let socket = Self::accept(&listener, &mut child, file.start_timeout).map_err(|e| {
            let mut p = String::new();
            append_tail(&mut p, "stdout", &stdout);
            append_tail(&mut p, "stderr", &stderr);
            abandon(&mut child, format!("{e}{p}"))
        })?;
        let connection = socket
            .set_nodelay(true)
            .and_then(|()| socket.try_clone())
            .and_then(|r| socket.try_clone().map(|w| (r, w)));
        let (reader, writer) = match connection {
            Ok(c) => c,
            Err(e) => return Err(abandon(&mut child, format!("its connection failed: {e}"))),
        };
        Ok(Process {
            child,
            writer: Some(std::io::BufWriter::new(Box::new(writer))),
            socket: Some(socket),
            lines: read_lines(reader),
            stderr,
            stdout: Some(stdout),
        })
    }

    /// Waits for `child` to connect to `listener`, at most `timeout`.
    fn accept(
        listener: &TcpListener,
        child: &mut Child,
        timeout: Duration,
    ) -> Result<TcpStream, Failure> {
        let start = Instant::now();
        loop {
            match listener.accept() {
                Ok((socket, _)) => {
                    return socket
                        .set_nonblocking(false)
                        .map(|()| socket)
                        .map_err(|e| format!("its connection failed: {e}"))
                }
                Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {}
                Err(e) => return Err(format!("its connection failed: {e}")),
            }
            if let Ok(Some(status)) = child.try_wait() {
                return Err(format!(
                    "it exited with {status} before connecting to port ${PORT_VARIABLE}"
                ));
            }
            if start.elapsed() >= timeout {
                return Err(format!(
                    "it did not connect to port ${PORT_VARIABLE} within its start timeout of {} ms (killed)",
                    timeout.as_millis()
                ));
            }
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    /// Writes `message` as one line and flushes it.
    pub(crate) fn send(&mut self, message: &impl Serialize) -> Result<(), Failure> {
        let Some(writer) = self.writer.as_mut() else {
            return Err("its input is closed".into());
        };
        let written = serde_json::to_writer(&mut *writer, message)
            .map_err(std::io::Error::from)
            .and_then(|()| writer.write_all(b"\n"))
            .and_then(|()| writer.flush());
        written.map_err(|e| self.gone(&format!("cannot write to it ({e})")))
    }

    /// The next line it replies, waiting at most `timeout`.
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
                    self.tails()
                ))
            }
            Err(RecvTimeoutError::Disconnected) => Err(self.gone(match self.socket {
                None => "its stdout closed",
                Some(_) => "it closed the connection",
            })),
        }
    }

    /// Closes its input (stdin, or the connection's sending half) and gives it `grace` to exit
    /// before it is killed.
    pub(crate) fn finish(&mut self, grace: Duration) {
        self.close_input();
        let deadline = Instant::now() + grace;
        while Instant::now() < deadline {
            match self.child.try_wait() {
                Ok(Some(_)) | Err(_) => return,
                Ok(None) => std::thread::sleep(Duration::from_millis(1)),
            }
        }
        self.kill();
    }

    fn close_input(&mut self) {
        self.writer = None;
        if let Some(socket) = &self.socket {
            let _ = socket.shutdown(Shutdown::Write);
        }
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
        format!("{what}: {status}{}", self.tails())
    }

    /// `; its stderr ended: ...` with its last lines (and its stdout's, over TCP), or nothing.
    fn tails(&self) -> String {
        let mut text = String::new();
        if let Some(stdout) = &self.stdout {
            append_tail(&mut text, "stdout", stdout);
        }
        append_tail(&mut text, "stderr", &self.stderr);
        text
    }
}

/// Appends `; its {what} ended: ...` with `tail`'s lines, if it has any.
fn append_tail(text: &mut String, what: &str, tail: &Tail) {
    let lines: Vec<String> = tail
        .lock()
        .map(|q| q.iter().cloned().collect())
        .unwrap_or_default();
    if !lines.is_empty() {
        text.push_str(&format!("; its {what} ended: {}", lines.join(" | ")));
    }
}

impl Drop for Process {
    fn drop(&mut self) {
        self.close_input();
        self.kill();
    }
}
