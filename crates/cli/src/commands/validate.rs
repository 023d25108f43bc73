//! `lambert validate`: the chi-square suite of every direction warp, in both
//! precisions, at ordinary and hard parameters, as a table.

use std::time::Instant;

use clap::Args;
use lambert_validate::sidak_level;
use lambert_validate::warp_suite::{partition_for, run_case, runs};

/// Options of `lambert validate`.
#[derive(Args, Debug, Clone)]
pub struct ValidateOptions {
    /// Samples per test.
    #[arg(long, default_value_t = 1_000_000)]
    pub samples: u64,
    /// Seed of the sample streams.
    #[arg(long, default_value_t = 20261122)]
    pub seed: u64,
    /// Family-wise significance level (Šidák-corrected per test).
    #[arg(long, default_value_t = 0.01)]
    pub alpha: f64,
}

/// Runs the suite; `Ok(false)` when a warp failed its test.
pub fn run(options: &ValidateOptions) -> Result<bool, String> {
    if options.samples == 0 {
        return Err("--samples: must be at least 1, got 0".into());
    }
    if !(options.alpha > 0.0 && options.alpha < 1.0) {
        return Err(format!(
            "--alpha: must lie in (0, 1), got {}",
            options.alpha
        ));
    }
    let runs = runs();
    let alpha = sidak_level(options.alpha, runs.len());
    println!(
        "lambert validate: chi-square goodness of fit of every direction warp\n\
         {} tests, {} samples each, family-wise α = {} (Šidák: α = {:.3e} per test)\n",
        runs.len(),
        options.samples,
        options.alpha,
        alpha
    );
    println!(
        "{:<26} {:>4} {:>9} {:>11} {:>5} {:>9} {:>8}  verdict",
        "warp", "prec", "binning", "X²", "dof", "p", "seconds"
    );
    let mut failed = 0;
    for (case, precision) in &runs {
        let start = Instant::now();
        let outcome = run_case(case, *precision, options.samples, options.seed, alpha);
        let seconds = start.elapsed().as_secs_f64();
        let binning = if partition_for(&case.spec, *precision).is_some() {
            "partition"
        } else {
            "cells"
        };
        let verdict = if outcome.passed() {
            "pass".to_string()
        } else {
            failed += 1;
            format!(
                "FAIL {}",
                outcome.failure.map(|f| f.to_string()).unwrap_or_default()
            )
        };
        println!(
            "{:<26} {:>4} {:>9} {:>11.1} {:>5} {:>9.3} {:>8.2}  {verdict}",
            case.label,
            precision.name(),
            binning,
            outcome.statistic,
            outcome.degrees_of_freedom,
            outcome.p_value,
            seconds
        );
    }
    println!("\n{} passed, {} failed", runs.len() - failed, failed);
    Ok(failed == 0)
}
