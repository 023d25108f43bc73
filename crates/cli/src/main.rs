//! `lambert`: the command-line front end of the lambert toolkit.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod commands;
mod parse;

/// Physically based Monte Carlo estimation of irradiance, with statistics
/// that prove it.
#[derive(Parser, Debug)]
#[command(name = "lambert", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Write N unit directions drawn by one warp (for external checkers).
    Sample {
        #[command(subcommand)]
        warp: commands::sample::WarpCommand,
        #[command(flatten)]
        options: commands::sample::SampleOptions,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Sample { warp, options }) => commands::sample::run(&warp, &options),
        None => {
            println!("lambert: see `lambert --help`");
            Ok(())
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
