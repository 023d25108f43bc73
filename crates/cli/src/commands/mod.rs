//! One file per subcommand.

pub mod analytic;
pub mod estimate;
pub mod sample;
pub mod validate;
