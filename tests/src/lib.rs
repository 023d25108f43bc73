//! Cross-crate validation suites for lambert; the suites live in `tests/`.
