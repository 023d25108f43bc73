//! One file per subcommand.

pub mod sample;
