//! The regression corpus, replayed through the `lambert` binary.
//!
//! Every input the fuzzer has found failing is kept under `fuzz/corpus/`:
//! `fixed/` cases must now be answered with finite numbers or refused with
//! exit code 2 naming the field, by their recorded calls and by analytic
//! and every estimate strategy; `open/` cases document failures whose fix
//! lies outside the CLI, and are only reported on (a case that no longer
//! fails is reported as ready to move to `fixed/`).
//!
//! The binary is `$LAMBERT_BIN` if set (to replay the corpus through
//! another build, e.g. the release one), else this package's own
//! `lambert`, which cargo builds for these tests with the profile they run
//! in: under `cargo test`, the test profile, optimised and with debug
//! assertions and overflow checks, so an input that trips one of them
//! fails here (two fixed cases did: a NaN standard error, which release
//! builds passed on silently, the interval coming out [0, f64::MAX]).
//!
//! This test lives in the CLI crate, not in `lambert-fuzz` (which links no
//! lambert crate), so that it replays the binary the same `cargo test`
//! built: from the fuzz crate it had to build the CLI itself, a second,
//! release build of the whole workspace inside the test run.

use std::path::{Path, PathBuf};
use std::time::Duration;

use lambert_fuzz::corpus::{self, Entry};
use lambert_fuzz::replay::replay;

/// Per-call time limit for fixed cases, which answer in milliseconds: 5 s
/// leaves room for a loaded machine.
const LIMIT: Duration = Duration::from_secs(5);

/// Per-call time limit for open cases: a known hang is cut off after 2 s
/// (and reported, not failed).
const OPEN_LIMIT: Duration = Duration::from_secs(2);

fn corpus_dir(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fuzz/corpus")
        .join(name)
}

/// The lambert binary: `$LAMBERT_BIN`, or the one cargo built for these
/// tests.
fn lambert() -> PathBuf {
    std::env::var_os("LAMBERT_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_lambert")))
}

fn load(name: &str) -> Vec<Entry> {
    corpus::load_dir(&corpus_dir(name)).expect("the corpus directory reads")
}

#[test]
fn fixed_cases_are_answered_or_refused_correctly() {
    let binary = lambert();
    let entries = load("fixed");
    assert!(!entries.is_empty(), "the fixed corpus is empty");
    let mut failures = Vec::new();
    for e in &entries {
        let r = replay(&binary, e, true, LIMIT).expect("the binary runs");
        for (call, f) in r.failures {
            failures.push(format!(
                "{}: {}: {}: {}",
                e.path.display(),
                call.label(),
                f.class,
                f.detail
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} failing call(s):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn open_cases_are_documented_and_reported() {
    let binary = lambert();
    for e in load("open") {
        // Each open case says what it is, where it lives and how it fails,
        // and covers a class of fuzz failures (for `--open`).
        assert!(!e.place.is_empty(), "{}: no `# place:`", e.path.display());
        assert!(
            e.known_open().is_some(),
            "{}: an open case needs `# failed:` and `# matches:`",
            e.path.display()
        );
        let r = replay(&binary, &e, false, OPEN_LIMIT).expect("the binary runs");
        if r.failures.is_empty() {
            println!(
                "NOW PASSES (move to fixed/): {} — {}",
                e.path.display(),
                e.symptom
            );
        } else {
            for (call, f) in &r.failures {
                println!(
                    "still open: {}: {}: {}",
                    e.path.display(),
                    call.label(),
                    f.class
                );
            }
        }
    }
}
