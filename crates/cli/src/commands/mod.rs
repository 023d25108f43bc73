//! One file per subcommand.

pub mod sample;
pub mod validate;
