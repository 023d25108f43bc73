//! Running the binary as a script would: a child process with no standard
//! input, its output captured, killed when it outlives its time limit.

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use wait_timeout::ChildExt;

/// Output kept per stream; more is dropped (a well-behaved call prints one
/// line of JSON or one error message).
pub const MAX_CAPTURE: usize = 64 * 1024;

/// How a call ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// It exited with this code.
    Code(i32),
    /// It was killed by this signal (or ended without a code).
    Signal(Option<i32>),
    /// It ran past its time limit and was killed.
    TimedOut,
}

/// What one call did.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// How it ended.
    pub exit: Exit,
    /// Its standard output (at most [`MAX_CAPTURE`] bytes, lossy UTF-8).
    pub stdout: String,
    /// Its standard error (likewise).
    pub stderr: String,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// Runs `binary args…`, killing it after `limit`.
///
/// # Errors
/// When the binary cannot be started or waited for.
pub fn run(binary: &Path, args: &[String], limit: Duration) -> std::io::Result<Outcome> {
    let start = Instant::now();
    let mut child = Command::new(binary)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    // Drain both pipes on their own threads, so that a chatty child never
    // blocks on a full pipe while we wait for it.
    let out = drain(child.stdout.take());
    let err = drain(child.stderr.take());
    let exit = wait(&mut child, limit)?;
    let stdout = out.join().unwrap_or_default();
    let stderr = err.join().unwrap_or_default();
    Ok(Outcome {
        exit,
        stdout,
        stderr,
        seconds: start.elapsed().as_secs_f64(),
    })
}

fn wait(child: &mut Child, limit: Duration) -> std::io::Result<Exit> {
    match child.wait_timeout(limit)? {
        Some(status) => Ok(match status.code() {
            Some(code) => Exit::Code(code),
            None => Exit::Signal(signal(&status)),
        }),
        None => {
            // Killing a child that exited in between is harmless.
            let _ = child.kill();
            child.wait()?;
            Ok(Exit::TimedOut)
        }
    }
}

#[cfg(unix)]
fn signal(status: &std::process::ExitStatus) -> Option<i32> {
    use std::os::unix::process::ExitStatusExt;
    status.signal()
}

#[cfg(not(unix))]
fn signal(_: &std::process::ExitStatus) -> Option<i32> {
    None
}

fn drain<R: Read + Send + 'static>(pipe: Option<R>) -> JoinHandle<String> {
    std::thread::spawn(move || {
        let Some(mut pipe) = pipe else {
            return String::new();
        };
        let mut kept = Vec::new();
        let mut buf = [0u8; 8192];
        loop {
            match pipe.read(&mut buf) {
                Ok(0) | Err(_) => break,
                Ok(n) => {
                    let room = MAX_CAPTURE.saturating_sub(kept.len());
                    kept.extend_from_slice(&buf[..n.min(room)]);
                }
            }
        }
        String::from_utf8_lossy(&kept).into_owned()
    })
}
