//! `lambert estimate SCENE`: a Monte Carlo estimate of the scene's
//! irradiance with its statistics, compared with the closed form when one
//! exists. The JSON keys are fixed: mean, std_error, ci99, samples,
//! seconds, ns_per_sample, analytic, rel_error, z (issue 3), and hits,
//! interval, warning (issue 12):
//!
//! - `hits`: samples whose value was not 0 (they reached a light);
//! - `interval`: how `ci99` was formed — `clt` (m ± q·se), `rare-event`
//!   (the CLT for the well-sampled parts plus rare-event bounds) or
//!   `bounded` (from the bound on a sample's value; valid with any number
//!   of hits); see `lambert_estimator::interval`;
//! - `warning`: `null`, or why the CLT interval would not hold (no or few
//!   hits, few misses, a heavy tail);
//! - `fallback`: `null`, or which emitter did not use the technique its
//!   strategy asked for and what replaced it (a disk whose solid-angle
//!   sampler cannot be built from the receiver is cosine-sampled:
//!   `lambert_estimator::strategy::TechniqueFallback`).
//! - `precision`: `f64` or `f32` (`--precision`), and `f64_fallbacks`: with
//!   f32, the emitters run in f64 instead, each as `{emitter, kind,
//!   reason}` (`lambert_estimator::strategy::F32Fallback`); empty in f64.
//!
//! Every number is finite; `ci99`'s upper end is f64::MAX when the bound on
//! a sample's value overflows (area sampling ~1e-150 m from a light).

use std::path::PathBuf;

use clap::Args;
use lambert_estimator::estimation::{
    estimate, f32_fallbacks, EstimateConfig, EstimateError, EstimateReport,
};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::precision::Precision;
use lambert_light::Scene;
use serde_json::json;

use super::analytic::closed_form;
use super::finite;

/// Options of `lambert estimate`.
#[derive(Args, Debug, Clone)]
pub struct EstimateOptions {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// auto | uniform-hemisphere | cosine-hemisphere | light | area | mis | mis-balance |
    /// projected | control-variate.
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
    /// f64 | f32: the precision of the per-sample arithmetic (directions,
    /// warps, densities, cos θ/p); sums are f64 either way. f32 runs twice
    /// as many samples per vector instruction (measured on a sphere light:
    /// 0.45–0.75× the time of f64 for most strategies and sequences;
    /// `projected` 0.57× there, and 0.75–0.9× on polygons and on caps
    /// across the horizon, measured on an AVX2 host; README); an
    /// emitter whose f32 error bound
    /// exceeds 1.2e-4 of its irradiance (small or far emitters under
    /// hit-testing strategies, lights grazing the horizon, lengths beyond
    /// [1e-15, 1e15] m) runs in f64 and is named in the output, and the
    /// f32 error bound is added to the standard error's floor
    /// (docs/NUMERICS.md, "The f32 estimator").
    #[arg(long, default_value = "f64")]
    pub precision: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs the command.
pub fn run(options: &EstimateOptions) -> Result<(), String> {
    let (strategy, sequence) =
        crate::parse::strategy_and_sequence(&options.strategy, &options.sequence)?;
    let precision: Precision = options
        .precision
        .parse()
        .map_err(|e| format!("--precision: {e}"))?;
    let scene =
        Scene::load(&options.scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let fallbacks = match precision {
        Precision::F32 => f32_fallbacks(&scene, strategy),
        Precision::F64 => Vec::new(),
    };
    let config = EstimateConfig {
        strategy,
        sequence,
        samples: options.samples,
        seed: options.seed,
        threads: options.threads,
        precision,
    };
    // An irradiance beyond the f64 range cannot be estimated either: refuse
    // before sampling, naming the emitter.
    let analytic = closed_form(&scene)
        .map_err(|e| format!("{}: {e}", options.scene.display()))?
        .ok()
        .map(|c| c.total);
    let report = checked_estimate(&scene, &config, &options.scene.display().to_string())?;
    let rel_error = match analytic {
        Some(a) if a != 0.0 => Some(finite::ratio(
            "rel_error",
            "relative error (mean − analytic)/analytic =",
            report.mean - a,
            a,
        )?),
        _ => None,
    };
    // z is a normal score only where the interval is the CLT one; with
    // rare-event or bounded intervals (few or no hits) the standard error
    // does not describe the error, and z is null (the warning says why).
    let z = match analytic {
        Some(a) if report.std_error > 0.0 && report.interval == IntervalKind::CentralLimit => {
            Some(finite::ratio(
                "z",
                "z-score (mean − analytic)/std_error =",
                report.mean - a,
                report.std_error,
            )?)
        }
        _ => None,
    };
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
            "hits": report.hits,
            "interval": report.interval.name(),
            "warning": report.warning.map(|w| w.to_string()),
            "fallback": report.fallback.map(|(i, f)| format!("emitters[{i}]: {f}")),
            "precision": precision.name(),
            "f64_fallbacks": fallbacks.iter().map(|f| json!({
                "emitter": f.emitter,
                "kind": f.kind,
                "reason": f.reason.to_string(),
            })).collect::<Vec<_>>(),
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
            "{} samples ({} hits), {strategy} × {sequence}, {precision}, {:.3} s, {:.2} ns/sample",
            report.samples, report.hits, report.seconds, report.ns_per_sample
        );
        for f in &fallbacks {
            println!("{f}");
        }
        if let Some(w) = report.warning {
            println!("warning ({} interval): {w}", report.interval);
        }
        if let Some((i, f)) = report.fallback {
            println!("fallback: emitters[{i}]: {f}");
        }
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

/// The estimate, with every reported number finite.
///
/// # Errors
/// A configuration error names its option (`--samples: …`). When the
/// statistics fail (a sample value or a running sum left the f64 range, or
/// a sample was NaN) or the mean, standard error or interval is not
/// finite, the message names the emitter(s) responsible, found by
/// estimating each emitter alone with the same configuration, after the
/// scene's `origin` (its file).
pub fn checked_estimate(
    scene: &Scene,
    config: &EstimateConfig,
    origin: &str,
) -> Result<EstimateReport, String> {
    let cause = match estimate(scene, config) {
        Err(EstimateError::Config { field, problem }) => {
            return Err(format!("--{field}: {problem}"))
        }
        // Names the emitter and the sample already.
        Err(e @ EstimateError::NonFiniteSample { .. }) => return Err(format!("{origin}: {e}")),
        Err(e) => format!("the estimator reported: {e}"),
        Ok(r) => match non_finite_quantity(&r) {
            None => return Ok(r),
            Some(q) => q,
        },
    };
    Err(format!("{origin}: {}", blame(scene, config, &cause)))
}

/// The first of the report's quantities that is not finite, as `key = value`.
fn non_finite_quantity(r: &EstimateReport) -> Option<String> {
    [
        ("mean", r.mean),
        ("std_error", r.std_error),
        ("ci99", r.ci99.0),
        ("ci99", r.ci99.1),
    ]
    .into_iter()
    .find(|(_, v)| !v.is_finite())
    .map(|(k, v)| format!("{k} = {v}"))
}

/// A message naming the emitters whose estimate alone is not finite (or,
/// if each alone is finite, all the sampled emitters, whose sum is not).
fn blame(scene: &Scene, config: &EstimateConfig, cause: &str) -> String {
    let alone = |e: &lambert_light::Emitter| {
        let single = Scene::new(scene.receiver, vec![e.clone()]).ok()?;
        estimate(&single, config)
            .ok()
            .filter(|r| non_finite_quantity(r).is_none())
    };
    let culprits: Vec<String> = scene
        .emitters
        .iter()
        .enumerate()
        .filter(|(_, e)| alone(e).is_none())
        .map(|(i, e)| finite::describe(i, e))
        .collect();
    if culprits.is_empty() {
        let all: Vec<String> = scene
            .emitters
            .iter()
            .enumerate()
            .map(|(i, e)| finite::describe(i, e))
            .collect();
        format!(
            "{}: each emitter's estimate is finite but their sum is not ({cause}; --strategy {})",
            all.join(", "),
            config.strategy
        )
    } else {
        format!(
            "{}: the Monte Carlo estimate of its irradiance is not finite with --strategy {} --sequence {}: a sample value or a sum of them left the f64 range, or a sample was NaN ({cause})",
            culprits.join(", "),
            config.strategy,
            config.sequence
        )
    }
}
