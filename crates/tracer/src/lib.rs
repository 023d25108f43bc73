//! # lambert-tracer
//!
//! Ray casting and Whitted-style ray tracing of small scenes (planned; see
//! the project's issues).
