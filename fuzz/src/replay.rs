//! Replaying the regression corpus: each case through its recorded calls
//! (and, for fixed cases, through analytic and every strategy), judged by
//! the same oracle as a fuzz run.

use std::path::Path;
use std::time::Duration;

use crate::calls::{with_closed_form, Call};
use crate::campaign::run_calls;
use crate::corpus::{replay_calls, Entry};
use crate::oracle::{Failure, Verdict};

/// The failures of one replayed case (empty: it kept the contract).
#[derive(Clone, Debug)]
pub struct Replayed {
    /// The calls made.
    pub calls: usize,
    /// Each failed call with its failure.
    pub failures: Vec<(Call, Failure)>,
}

/// Replays `entry`: its own calls, plus [`replay_calls`] when `full`, with
/// analytic first (so the estimates are checked against it), each within
/// `limit`, in a temporary directory.
///
/// # Errors
/// When the binary cannot be run.
pub fn replay(
    binary: &Path,
    entry: &Entry,
    full: bool,
    limit: Duration,
) -> Result<Replayed, String> {
    let mut calls = if full { replay_calls() } else { Vec::new() };
    for c in &entry.calls {
        if !calls.contains(c) {
            calls.push(c.clone());
        }
    }
    let calls = with_closed_form(&calls);
    let dir = tempfile::Builder::new()
        .prefix("lambert-replay-")
        .tempdir()
        .map_err(|e| e.to_string())?;
    let path = dir.path().join("scene.toml");
    let results = run_calls(binary, &entry.text, &calls, &path, limit)
        .map_err(|e| format!("{}: {e}", binary.display()))?;
    let failures = results
        .into_iter()
        .filter_map(|(call, verdict, _)| match verdict {
            Verdict::Failed(f) => Some((call, f)),
            _ => None,
        })
        .collect();
    Ok(Replayed {
        calls: calls.len(),
        failures,
    })
}
