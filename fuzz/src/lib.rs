//! A structure-aware fuzzer for the `lambert` command line.
//!
//! It writes random scene files in the TOML format `lambert` reads — every
//! emitter kind, several emitters, receivers and emitters at ordinary and
//! extreme coordinates, magnitudes from 5e-324 to 1.8e308, degenerate and
//! near-degenerate shapes, one invalid field in a quarter of the scenes and
//! garbled text in an eighth — and runs each through `lambert analytic
//! --json`, `lambert estimate --json` with every strategy and, when the
//! binary has it, `lambert render`, as a user's script would: a child
//! process per call, killed at a time limit.
//!
//! Every call must either **answer** (exit code 0, the documented JSON,
//! every number finite, the numbers consistent) or **refuse** (exit code
//! 2, nothing on stdout, a message naming the field, option or line); a
//! panic, a signal, a hang, a `null` or non-finite number, another exit
//! code or a message naming nothing is a failure ([`oracle`]).
//!
//! Runs are deterministic from `--seed` (case `i` depends only on the seed
//! and `i`). Inputs found failing are kept in the regression corpus
//! (`fuzz/corpus/`, [`corpus`]), replayed by `cargo test` (the CLI crate's
//! `tests/fuzz_corpus.rs`, through the `lambert` binary that run built).
//!
//! Structure-aware generation in the manner of grammar-based fuzzers
//! (Godefroid, Kiezun & Levin 2008, "Grammar-based whitebox fuzzing"),
//! with a differential check between `analytic` and `estimate`
//! (McKeeman 1998, "Differential testing for software").

pub mod calls;
pub mod campaign;
pub mod corpus;
pub mod generate;
pub mod mutate;
pub mod numbers;
pub mod oracle;
pub mod replay;
pub mod run;
pub mod scene;
pub mod shrink;

use std::path::PathBuf;

/// The `lambert` binary to drive: `$LAMBERT_BIN` if set, else `lambert`
/// beside the running executable (cargo puts both in the same target
/// directory), else beside its parent directory (for test executables in
/// `target/<profile>/deps/`).
pub fn default_lambert() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("LAMBERT_BIN") {
        return Some(PathBuf::from(p));
    }
    let exe = std::env::current_exe().ok()?;
    let name = format!("lambert{}", std::env::consts::EXE_SUFFIX);
    exe.ancestors()
        .skip(1)
        .take(2)
        .map(|d| d.join(&name))
        .find(|p| p.is_file())
}
