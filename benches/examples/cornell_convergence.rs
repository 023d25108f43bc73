//! Time to 1 % relative RMSE per strategy on the `cornell` irradiance
//! image: each strategy renders the image at 64 independent samples per
//! pixel, its relative RMSE over the pixels, √(mean_p ((E_p − R_p)/R_p)²),
//! is measured against a reference (light sampling, Sobol, 2048 samples
//! per pixel; its own error, from its standard-error layer, is removed in
//! quadrature), and the time to 1 % follows from MSE ∝ 1/n for unbiased
//! estimators: t₁% = t₆₄ (rmse₆₄ / 0.01)². Pixels with a reference below
//! 1 % of the mean irradiance (umbrae, the ceiling) are left out: their
//! relative error is unbounded.
//!
//! `cargo run --release -p lambert-benches --example cornell_convergence [SIZE]`
//! (SIZE defaults to 128; the criterion bench `tracer_cornell` times 256).

use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::{Heuristic, Strategy};
use lambert_tracer::{builtin, render_with_threads, Image, Mode, RenderConfig};

fn image(size: u32, strategy: Strategy, sequence: SequenceKind, samples: u64) -> (Image, f64) {
    let scene = builtin::cornell().with_size(size, size).unwrap();
    let config = RenderConfig {
        mode: Mode::Irradiance,
        estimate: PointConfig {
            strategy,
            sequence,
            samples,
            seed: 12345,
        },
        ..RenderConfig::default()
    };
    let out = render_with_threads(&scene, &config, 2, &|_, _| {}).unwrap();
    (out.image, out.stats.seconds)
}

fn main() {
    let size: u32 = std::env::args()
        .nth(1)
        .map_or(128, |s| s.parse().expect("SIZE is a number"));
    let (reference, ref_seconds) = image(size, Strategy::Light, SequenceKind::Sobol, 2048);
    let e = reference.irradiance_layer();
    let se = reference.std_error_layer().unwrap();
    let mean = e.iter().map(|&v| v as f64).sum::<f64>() / e.len() as f64;
    let pixels: Vec<usize> = (0..e.len())
        .filter(|&i| e[i] as f64 > 0.01 * mean)
        .collect();
    let ref_mse = pixels
        .iter()
        .map(|&i| (se[i] as f64 / e[i] as f64).powi(2))
        .sum::<f64>()
        / pixels.len() as f64;
    println!(
        "cornell {size}x{size}: reference {:.1} s, {} of {} pixels, reference relative RMSE {:.2e}",
        ref_seconds,
        pixels.len(),
        e.len(),
        ref_mse.sqrt()
    );
    println!(
        "{:<20} {:>10} {:>14} {:>14}",
        "strategy", "seconds", "rel RMSE@64", "t(1 %) s"
    );
    for strategy in [
        Strategy::Light,
        Strategy::Area,
        Strategy::Mis(Heuristic::Power),
        Strategy::CosineHemisphere,
        Strategy::UniformHemisphere,
    ] {
        let (img, seconds) = image(size, strategy, SequenceKind::Independent, 64);
        let v = img.irradiance_layer();
        let mse = pixels
            .iter()
            .map(|&i| ((v[i] as f64 - e[i] as f64) / e[i] as f64).powi(2))
            .sum::<f64>()
            / pixels.len() as f64;
        let rmse = (mse - ref_mse).max(0.0).sqrt();
        println!(
            "{:<20} {:>10.3} {:>14.4} {:>14.1}",
            strategy.name(),
            seconds,
            rmse,
            seconds * (rmse / 0.01).powi(2)
        );
    }
}
