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
    /// A convergence study: error against N and against time, per scene,
    /// strategy and sequence (the default job: the built-in study).
    Study(commands::study::StudyOptions),
    /// Combine the results of a study's shards into the result of one run.
    Merge(commands::merge::MergeOptions),
    /// Chi-square tests of every direction warp in both precisions.
    Validate(commands::validate::ValidateOptions),
    /// Estimate a scene's irradiance by Monte Carlo.
    Estimate(commands::estimate::EstimateOptions),
    /// The closed-form irradiance of a scene.
    Analytic(commands::analytic::AnalyticOptions),
    /// Render a scene: ray casting, Whitted ray tracing or an irradiance
    /// image with occlusion, as OpenEXR with a PNG preview.
    Render(commands::render::RenderOptions),
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
        Some(Command::Sample { warp, options }) => {
            commands::sample::run(&warp, &options).map(|()| true)
        }
        Some(Command::Validate(options)) => commands::validate::run(&options),
        Some(Command::Estimate(options)) => commands::estimate::run(&options).map(|()| true),
        Some(Command::Analytic(options)) => commands::analytic::run(&options).map(|()| true),
        Some(Command::Render(options)) => commands::render::run(&options).map(|()| true),
        Some(Command::Study(options)) => commands::study::run(&options).map(|()| true),
        Some(Command::Merge(options)) => commands::merge::run(&options).map(|()| true),
        None => commands::study::run(&commands::study::StudyOptions::default()).map(|()| true),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        // A failed statistical test is a finding, not a usage error.
        Ok(false) => ExitCode::from(1),
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}
