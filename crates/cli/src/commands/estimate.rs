//! `lambert estimate SCENE`: a Monte Carlo estimate of the scene's
//! irradiance with its statistics, compared with the closed form when one
//! exists. The JSON keys are fixed (issue 3): mean, std_error, ci99,
//! samples, seconds, ns_per_sample, analytic, rel_error, z.

use std::path::PathBuf;

use clap::Args;
use lambert_estimator::estimation::{estimate, EstimateConfig, EstimateError, SequenceKind};
use lambert_estimator::strategy::Strategy;
use lambert_light::Scene;
use serde_json::json;

use super::analytic::closed_form;

/// Options of `lambert estimate`.
#[derive(Args, Debug, Clone)]
pub struct EstimateOptions {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// auto | uniform-hemisphere | cosine-hemisphere | light | area | mis | mis-balance.
    #[arg(long, default_value = "auto")]
    pub strategy: String,
    /// independent | stratified | sobol.
    #[arg(long, default_value = "independent")]
    pub sequence: String,
    /// Number of samples.
    #[arg(long, default_value_t = 1 << 20)]
    pub samples: u64,
    /// Seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (the result does not depend on it).
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs the command.
pub fn run(options: &EstimateOptions) -> Result<(), String> {
    let strategy: Strategy = options
        .strategy
        .parse()
        .map_err(|e| format!("--strategy: {e}"))?;
    let sequence: SequenceKind = options
        .sequence
        .parse()
        .map_err(|e| format!("--sequence: {e}"))?;
    let scene =
        Scene::load(&options.scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let config = EstimateConfig {
        strategy,
        sequence,
        samples: options.samples,
        seed: options.seed,
        threads: options.threads,
    };
    let report = estimate(&scene, &config).map_err(|e| match e {
        // A configuration error names a command-line option.
        EstimateError::Config { .. } => format!("--{e}"),
        _ => format!("{}: {e}", options.scene.display()),
    })?;
    let analytic = closed_form(&scene).map(|c| c.total);
    let rel_error = analytic.and_then(|a| (a != 0.0).then(|| (report.mean - a) / a));
    let z = analytic
        .and_then(|a| (report.std_error > 0.0).then(|| (report.mean - a) / report.std_error));
    if options.json {
        let value = json!({
            "mean": report.mean,
            "std_error": report.std_error,
            "ci99": [report.ci99.0, report.ci99.1],
            "samples": report.samples,
            "seconds": report.seconds,
            "ns_per_sample": report.ns_per_sample,
            "analytic": analytic,
            "rel_error": rel_error,
            "z": z,
        });
        println!("{value}");
    } else {
        println!(
            "E = {:.10} W/m² ± {:.3e} (standard error)",
            report.mean, report.std_error
        );
        println!(
            "99 % interval [{:.10}, {:.10}]",
            report.ci99.0, report.ci99.1
        );
        println!(
            "{} samples, {strategy} × {sequence}, {:.3} s, {:.2} ns/sample",
            report.samples, report.seconds, report.ns_per_sample
        );
        match analytic {
            Some(a) => println!(
                "closed form {a:.10} W/m²: relative error {:.3e}, z = {}",
                rel_error.unwrap_or(0.0),
                z.map(|z| format!("{z:.3}"))
                    .unwrap_or_else(|| "— (exact)".into())
            ),
            None => println!("no closed form for this scene"),
        }
    }
    Ok(())
}
