//! One file per subcommand.

pub mod analytic;
pub mod estimate;
pub mod finite;
pub mod merge;
pub mod render;
pub mod sample;
pub mod study;
pub mod validate;
