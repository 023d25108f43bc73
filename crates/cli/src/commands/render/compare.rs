//! `lambert render … --compare A,B,…`: the equal-time comparison of
//! irradiance strategies against a reference image
//! (`lambert_tracer::compare`), printed as a table or one JSON line, with
//! every image written as OpenEXR.

use std::path::{Path, PathBuf};

use lambert_estimator::strategy::Strategy;
use lambert_tracer::compare::{compare_with_threads, Budget, CompareConfig, Comparison};
use lambert_tracer::output::write_outputs;
use lambert_tracer::scene::Scene;
use lambert_tracer::RenderConfig;
use serde_json::json;

use super::RenderOptions;

/// Parses the strategies, runs the comparison, writes the images, prints
/// the result.
pub fn run(
    options: &RenderOptions,
    names: &[String],
    scene: &Scene,
    render: &RenderConfig,
    threads: usize,
) -> Result<(), String> {
    let strategies = names
        .iter()
        .map(|n| {
            n.trim()
                .parse::<Strategy>()
                .map_err(|e| format!("--compare: {e}"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let reference_strategy: Strategy = options
        .reference_strategy
        .parse()
        .map_err(|e| format!("--reference-strategy: {e}"))?;
    let budget = match options.seconds {
        Some(s) => Budget::Seconds(s),
        None => Budget::SamplesPerPixel(options.spp),
    };
    let config = CompareConfig {
        strategies,
        budget,
        estimate: render.estimate,
        reference_strategy,
        reference_spp: options.reference_spp,
        pilot_spp: 2,
        tile: render.tile,
    };
    config.validate().map_err(|e| e.to_string())?;
    let progress = |what: &str| {
        if !options.json {
            eprintln!("render {} (irradiance): {what}", options.scene);
        }
    };
    let result =
        compare_with_threads(scene, &config, threads, &progress).map_err(|e| e.to_string())?;
    // Every image goes beside --out: FILE.reference.exr, FILE.<strategy>.exr.
    let mut written = vec![(
        "reference".to_owned(),
        write(&result.reference.image, &options.out, "reference")?,
    )];
    for run in &result.runs {
        let name = run.strategy.name();
        written.push((
            name.to_owned(),
            write(&run.rendered.image, &options.out, name)?,
        ));
    }
    if options.json {
        println!("{}", as_json(options, &config, &result, &written, threads));
    } else {
        print_table(options, &config, &result, &written);
    }
    Ok(())
}

/// `FILE.exr` → `FILE.<tag>.exr`.
fn tagged(out: &Path, tag: &str) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out
        .extension()
        .map_or_else(|| "exr".to_owned(), |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}.{tag}.{ext}"))
}

fn write(image: &lambert_tracer::Image, out: &Path, tag: &str) -> Result<PathBuf, String> {
    let (exr, _) = write_outputs(image, &tagged(out, tag)).map_err(|e| e.to_string())?;
    Ok(exr)
}

fn ratio_text(ratio: Option<f64>) -> String {
    match ratio {
        Some(r) => format!("{r:.3}"),
        None => "∞ (exact)".into(),
    }
}

fn print_table(
    options: &RenderOptions,
    config: &CompareConfig,
    result: &Comparison,
    written: &[(String, PathBuf)],
) {
    let reference = &result.reference;
    let mean = result.runs.first().map_or(0.0, |r| r.error.mean_reference);
    println!(
        "{} (irradiance, {}×{}), {}",
        options.scene,
        reference.image.width(),
        reference.image.height(),
        match config.budget {
            Budget::Seconds(s) => format!("equal time: {s} s per strategy"),
            Budget::SamplesPerPixel(n) => format!("equal samples: {n} spp per strategy"),
        }
    );
    println!(
        "reference: {} × {} spp, {:.2} s, RMS standard error {:.4e} W/m² ({:.3e} of the mean irradiance {:.4e} W/m²)",
        result.reference_strategy,
        result.reference_spp,
        reference.stats.seconds,
        result.reference_rms_std_error,
        result.reference_rms_std_error / mean,
        mean
    );
    println!(
        "| strategy | spp | seconds | RMSE (W/m²) | RMSE − reference | relative RMSE | RMSE ratio ({0} / strategy) | at equal time, RMSE·√t ({0} / strategy) |",
        result.runs.first().map_or("", |r| r.strategy.name())
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (i, run) in result.runs.iter().enumerate() {
        println!(
            "| {} | {} | {:.2} | {:.4e} | {:.4e} | {:.3e} | {} | {} |",
            run.strategy,
            run.spp,
            run.rendered.stats.seconds,
            run.error.rmse,
            run.error.corrected_rmse,
            run.error.corrected_rmse / mean,
            ratio_text(result.rmse_ratio(i)),
            ratio_text(result.time_normalized_ratio(i))
        );
    }
    for (what, path) in written {
        println!("wrote {what}: {}", path.display());
    }
}

fn as_json(
    options: &RenderOptions,
    config: &CompareConfig,
    result: &Comparison,
    written: &[(String, PathBuf)],
    threads: usize,
) -> serde_json::Value {
    let runs: Vec<_> = result
        .runs
        .iter()
        .enumerate()
        .zip(&written[1..])
        .map(|((i, run), (_, path))| {
            json!({
                "strategy": run.strategy.name(),
                "spp": run.spp,
                "seconds": run.rendered.stats.seconds,
                "pilot_seconds_per_spp": run.pilot.map(|p| p.0),
                "pilot_fixed_seconds": run.pilot.map(|p| p.1),
                "rmse": run.error.rmse,
                "rmse_corrected": run.error.corrected_rmse,
                "relative_rmse": run.error.corrected_rmse / run.error.mean_reference,
                "rmse_ratio": result.rmse_ratio(i),
                "rmse_ratio_time_normalized": result.time_normalized_ratio(i),
                "exr": path.display().to_string(),
            })
        })
        .collect();
    json!({
        "scene": options.scene,
        "width": result.reference.image.width(),
        "height": result.reference.image.height(),
        "budget": match config.budget {
            Budget::Seconds(s) => json!({"seconds": s}),
            Budget::SamplesPerPixel(n) => json!({"spp": n}),
        },
        "reference": {
            "strategy": result.reference_strategy.name(),
            "spp": result.reference_spp,
            "seconds": result.reference.stats.seconds,
            "rms_std_error": result.reference_rms_std_error,
            "mean_irradiance": result.runs.first().map(|r| r.error.mean_reference),
            "exr": written[0].1.display().to_string(),
        },
        "runs": runs,
        "threads": threads,
    })
}
