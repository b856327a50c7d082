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
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, SyncSender, TrySendError};
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
    /// Lines for the writing thread: a child that stops reading its input blocks that thread,
    /// never platbench, whose wait for the reply then times out.
    writer: Option<SyncSender<Vec<u8>>>,
    /// The writing thread's written lines, handed back to be written into again: no buffer is
    /// allocated per step once the first few are.
    spare: Receiver<Vec<u8>>,
    /// Whether the lines travel over TCP (for messages).
    tcp: bool,
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

/// Writes each line it receives to `to` and hands its buffer back, until the channel closes or
/// a write fails; then closes its input (drops `to`, and shuts down the sending half of
/// `socket`).
fn write_lines(
    mut to: Box<dyn Write + Send>,
    socket: Option<TcpStream>,
) -> (SyncSender<Vec<u8>>, Receiver<Vec<u8>>) {
    let (tx, lines) = mpsc::sync_channel::<Vec<u8>>(1);
    let (back, spare) = mpsc::sync_channel::<Vec<u8>>(2);
    std::thread::spawn(move || {
        for line in lines {
            if to.write_all(&line).and_then(|()| to.flush()).is_err() {
                break;
            }
            let _ = back.try_send(line);
        }
        drop(to);
        if let Some(socket) = socket {
            let _ = socket.shutdown(Shutdown::Write);
        }
    });
    (tx, spare)
}

/// Kills `child` and its process group (a wrapper script's own children with it), and waits for
/// it.
fn kill_tree(child: &mut Child) {
    #[cfg(unix)]
    if let Ok(pid) = i32::try_from(child.id()) {
        // SAFETY: kill(2) with a negative pid signals the process group the child leads (it was
        // started in a group of its own, below); it touches no memory of ours.
        unsafe {
            libc::kill(-pid, libc::SIGKILL);
        }
    }
    let _ = child.kill();
    let _ = child.wait();
}

/// Kills and waits for `child`, returning `failure`.
fn abandon(child: &mut Child, failure: String) -> Failure {
    kill_tree(child);
    failure
}

/// Starts the child in a process group of its own (so that killing it kills what it started)
/// and, on Linux, asks the kernel to kill it when platbench dies, however it dies (SIGKILL
/// included): it never outlives platbench, whether or not it reads the end of its input.
fn contain(command: &mut Command) {
    #[cfg(unix)]
    {
        use std::os::unix::process::CommandExt;
        command.process_group(0);
        #[cfg(target_os = "linux")]
        // SAFETY: the closure runs in the child between fork and exec and calls only prctl(2),
        // which is async-signal-safe, allocating nothing.
        unsafe {
            command.pre_exec(|| {
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL) == -1 {
                    return Err(std::io::Error::last_os_error());
                }
                Ok(())
            });
        }
    }
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
        contain(&mut command);
        let mut child = command.spawn().map_err(|e| start_failure(file, &e))?;
        let (Some(stdout), Some(stderr)) = (child.stdout.take(), child.stderr.take()) else {
            return Err(abandon(&mut child, "its pipes could not be opened".into()));
        };
        let stderr = keep_tail(stderr);
        let Some(listener) = listener else {
            let Some(stdin) = child.stdin.take() else {
                return Err(abandon(&mut child, "its stdin could not be opened".into()));
            };
            let (writer, spare) = write_lines(Box::new(stdin), None);
            return Ok(Process {
                child,
                writer: Some(writer),
                spare,
                tcp: false,
                lines: read_lines(stdout),
                stderr,
                stdout: None,
            });
        };
        let stdout = keep_tail(stdout);
        let socket = Self::accept(&listener, &mut child, file.start_timeout).map_err(|e| {
            let tails = tails_of(Some(&stdout), &stderr);
            abandon(&mut child, format!("{e}{tails}"))
        })?;
        let connection = socket
            .set_nodelay(true)
            .and_then(|()| socket.try_clone())
            .and_then(|r| socket.try_clone().map(|w| (r, w)));
        let (reader, writer) = match connection {
            Ok(c) => c,
            Err(e) => return Err(abandon(&mut child, format!("its connection failed: {e}"))),
        };
        let (writer, spare) = write_lines(Box::new(writer), Some(socket));
        Ok(Process {
            child,
            writer: Some(writer),
            spare,
            tcp: true,
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

    /// Hands `message`, as one line, to the writing thread. A child that has not read the line
    /// before (it stopped reading) fails here; one that stops during this line is caught by the
    /// reply's timeout.
    pub(crate) fn send(&mut self, message: &impl Serialize) -> Result<(), Failure> {
        let Some(writer) = self.writer.as_ref() else {
            return Err("its input is closed".into());
        };
        let mut line = self.spare.try_recv().unwrap_or_default();
        line.clear();
        serde_json::to_writer(&mut line, message).map_err(|e| format!("cannot encode: {e}"))?;
        line.push(b'\n');
        match writer.try_send(line) {
            Ok(()) => Ok(()),
            Err(TrySendError::Full(_)) => {
                self.kill();
                Err(format!(
                    "it does not read its input: the previous message is still being written (killed){}",
                    self.tails()
                ))
            }
            Err(TrySendError::Disconnected(_)) => Err(self.gone("cannot write to it")),
        }
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
            Err(RecvTimeoutError::Disconnected) => Err(self.gone(if self.tcp {
                "it closed the connection"
            } else {
                "its stdout closed"
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

    /// Closes its input once the writing thread has written what it holds.
    fn close_input(&mut self) {
        self.writer = None;
    }

    fn kill(&mut self) {
        kill_tree(&mut self.child);
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
    pub(crate) fn tails(&self) -> String {
        tails_of(self.stdout.as_ref(), &self.stderr)
    }
}

/// `; its stdout ended: ...; its stderr ended: ...` with the lines each tail kept, or nothing.
fn tails_of(stdout: Option<&Tail>, stderr: &Tail) -> String {
    let mut text = String::new();
    for (what, tail) in [("stdout", stdout), ("stderr", Some(stderr))] {
        let lines: Vec<String> = tail
            .and_then(|t| t.lock().ok().map(|q| q.iter().cloned().collect()))
            .unwrap_or_default();
        if !lines.is_empty() {
            text.push_str(&format!("; its {what} ended: {}", lines.join(" | ")));
        }
    }
    text
}

impl Drop for Process {
    fn drop(&mut self) {
        self.close_input();
        self.kill();
    }
}

/// Why `file`'s program did not start, with what to check.
fn start_failure(file: &ControllerFile, e: &std::io::Error) -> Failure {
    let dir = &file.working_directory;
    if !dir.is_dir() {
        return format!(
            "cannot start `{}`: its working directory {} is not a directory",
            file.command.display(),
            dir.display()
        );
    }
    let mut text = format!(
        "cannot start `{}` in {}: {e}",
        file.command.display(),
        dir.display()
    );
    let bare = file.command.components().count() == 1;
    if e.kind() == std::io::ErrorKind::NotFound && bare && dir.join(&file.command).is_file() {
        text.push_str(&format!(
            " (a command without `/` is looked up on the PATH; for the file beside the controller file write \"./{}\")",
            file.command.display()
        ));
    }
    text
}
