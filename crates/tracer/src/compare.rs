//! Equal-time comparison of irradiance strategies on one scene: each
//! strategy renders the irradiance image with the samples per pixel that
//! fit a time budget, and its per-pixel error is measured against a
//! reference image.
//!
//! **Error.** The root-mean-square error over the image's pixels,
//! RMSE = √(Σᵢ (Eᵢ − Rᵢ)²/n), Eᵢ the strategy's irradiance and Rᵢ the
//! reference's at pixel i (every pixel counts; pixels that see no lit
//! surface are 0 in both). The reference is itself an estimate, a render
//! with many samples by a low-variance strategy and another seed, so it
//! is independent of the images it judges: the expected squared
//! difference at pixel i is then the strategy's mean squared error plus
//! the reference's variance σ²_R,i. The comparison reports the reference's
//! RMS standard error s_R = √(Σᵢ σ²_R,i/n) (from its standard-error layer)
//! and the RMSE with that share removed, √max(0, RMSE² − s_R²), beside the
//! raw one. The ratio of two strategies' RMSEs at equal time is the square
//! root of their efficiency ratio (ε = 1/(V·T), with V ∝ MSE at a fixed
//! time): a ratio of 2 means the baseline needs 4 times the time for the
//! same error.
//!
//! **Equal time.** A render's time is close to a + b·spp (a for camera
//! rays and hit records, b per sample). Two pilot renders, at p and 4p
//! samples per pixel, measure a and b for each strategy; the strategy then
//! renders with spp = ⌊(T − a)/b⌋ (at least 2) for the budget T, and its
//! measured time is reported so that the equality can be checked; on a
//! loaded machine the fit is loose (±30 %), so the comparison also gives
//! the ratio of RMSE·√t ([`Comparison::time_normalized_ratio`]), the
//! ratio at exactly equal time under MSE ∝ 1/t. A
//! [`Budget::SamplesPerPixel`] budget skips the pilots (equal samples, not
//! equal time; what tests use, since timing is not reproducible).

use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;

use crate::error::TracerError;
use crate::image::Image;
use crate::render::{render, Mode, RenderConfig, Rendered};
use crate::scene::Scene;

/// How much each compared strategy may spend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Budget {
    /// Wall-clock seconds per strategy's render (equal time).
    Seconds(f64),
    /// Samples per pixel for every strategy (equal samples).
    SamplesPerPixel(u64),
}

/// What to compare.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareConfig {
    /// The strategies, the first being the baseline of the ratios.
    pub strategies: Vec<Strategy>,
    /// The budget of each.
    pub budget: Budget,
    /// Sequence and seed of the compared renders (`samples` is set per
    /// strategy from the budget).
    pub estimate: PointConfig,
    /// The reference's strategy.
    pub reference_strategy: Strategy,
    /// The reference's samples per pixel.
    pub reference_spp: u64,
    /// Samples per pixel of the first pilot render (the second uses 4×).
    pub pilot_spp: u64,
    /// Tile side of the renders.
    pub tile: u32,
}

impl CompareConfig {
    /// Checks the fields a user sets, naming the command-line option.
    pub fn validate(&self) -> Result<(), TracerError> {
        if self.strategies.is_empty() {
            return Err(TracerError::new(
                "--compare",
                "needs at least one strategy, got none",
            ));
        }
        match self.budget {
            Budget::Seconds(s) if !(s > 0.0 && s.is_finite()) => {
                return Err(TracerError::new(
                    "--seconds",
                    format!("must be a positive number of seconds, got {s}"),
                ))
            }
            Budget::SamplesPerPixel(n) if n < 2 => {
                return Err(TracerError::new(
                    "--spp",
                    format!("must be at least 2, got {n}"),
                ))
            }
            _ => {}
        }
        if self.reference_spp < 2 {
            return Err(TracerError::new(
                "--reference-spp",
                format!("must be at least 2, got {}", self.reference_spp),
            ));
        }
        if self.pilot_spp < 2 {
            return Err(TracerError::new(
                "pilot_spp",
                format!("must be at least 2, got {}", self.pilot_spp),
            ));
        }
        Ok(())
    }
}

/// A strategy's image against the reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelError {
    /// √(Σᵢ (Eᵢ − Rᵢ)²/n), W/m².
    pub rmse: f64,
    /// The RMSE with the reference's own variance removed,
    /// √max(0, RMSE² − s_R²) (module docs).
    pub corrected_rmse: f64,
    /// The mean reference irradiance over the image, W/m² (to state the
    /// RMSE relative to it).
    pub mean_reference: f64,
    /// Pixels compared.
    pub pixels: usize,
}

/// The per-pixel error of `image`'s irradiance layer against
/// `reference`'s, with the reference's RMS standard error `reference_rms`
/// removed in quadrature (module docs).
///
/// ```
/// use lambert_tracer::compare::pixel_error;
/// use lambert_tracer::Image;
/// let layer = |e: Vec<f32>| Image::from_layers(2, 1, vec![[0.0; 3]; 2], e, None).unwrap();
/// // Differences 0 and 2: RMSE √(4/2) = √2; a reference error of 1 leaves 1.
/// let e = pixel_error(&layer(vec![1.0, 4.0]), &layer(vec![1.0, 2.0]), 1.0)?;
/// assert_eq!((e.rmse, e.corrected_rmse), (2f64.sqrt(), 1.0));
/// # Ok::<(), lambert_tracer::TracerError>(())
/// ```
///
/// # Errors
/// Images of different sizes (`reference`).
pub fn pixel_error(
    image: &Image,
    reference: &Image,
    reference_rms: f64,
) -> Result<PixelError, TracerError> {
    if (image.width(), image.height()) != (reference.width(), reference.height()) {
        return Err(TracerError::new(
            "reference",
            format!(
                "is {}×{}, the image {}×{}",
                reference.width(),
                reference.height(),
                image.width(),
                image.height()
            ),
        ));
    }
    let (e, r) = (image.irradiance_layer(), reference.irradiance_layer());
    let n = e.len();
    let squares: f64 = e
        .iter()
        .zip(r)
        .map(|(&a, &b)| (f64::from(a) - f64::from(b)).powi(2))
        .sum();
    let mean_reference = r.iter().map(|&b| f64::from(b)).sum::<f64>() / n.max(1) as f64;
    let mse = squares / n.max(1) as f64;
    Ok(PixelError {
        rmse: mse.sqrt(),
        corrected_rmse: (mse - reference_rms * reference_rms).max(0.0).sqrt(),
        mean_reference,
        pixels: n,
    })
}

/// √(Σᵢ σ²ᵢ/n) of an image's standard-error layer (0 without one).
pub fn rms_std_error(image: &Image) -> f64 {
    match image.std_error_layer() {
        Some(s) if !s.is_empty() => {
            (s.iter().map(|&x| f64::from(x).powi(2)).sum::<f64>() / s.len() as f64).sqrt()
        }
        _ => 0.0,
    }
}

/// One strategy's render in the comparison.
#[derive(Clone, Debug)]
pub struct StrategyRun {
    /// The strategy.
    pub strategy: Strategy,
    /// Samples per pixel it rendered with.
    pub spp: u64,
    /// The per-sample time b and fixed time a the pilots measured, seconds
    /// (`None` for an equal-samples budget).
    pub pilot: Option<(f64, f64)>,
    /// Its image and statistics (`stats.seconds` is the measured time).
    pub rendered: Rendered,
    /// Its error against the reference.
    pub error: PixelError,
}

/// The reference and every strategy's run.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The reference render.
    pub reference: Rendered,
    /// Its strategy and samples per pixel.
    pub reference_strategy: Strategy,
    /// Its samples per pixel.
    pub reference_spp: u64,
    /// Its RMS standard error s_R, W/m² (module docs).
    pub reference_rms_std_error: f64,
    /// The compared strategies, in the order asked.
    pub runs: Vec<StrategyRun>,
}

impl Comparison {
    /// The baseline's RMSE over run `i`'s (both corrected for the
    /// reference's error): > 1 where run `i` has the smaller error.
    /// `None` where run `i`'s corrected RMSE is 0 (exact to the
    /// reference's resolution: the ratio is unbounded).
    pub fn rmse_ratio(&self, i: usize) -> Option<f64> {
        let base = self.runs.first()?.error.corrected_rmse;
        let other = self.runs.get(i)?.error.corrected_rmse;
        (other > 0.0).then(|| base / other)
    }
}

impl Comparison {
    /// [`rmse_ratio`](Self::rmse_ratio) with each RMSE scaled to the same
    /// time, RMSE·√t (t the measured seconds; MSE ∝ 1/t at a fixed cost
    /// per sample): the ratio at exactly equal time, which corrects the
    /// pilots' imperfect fit of spp to the budget on a loaded machine. Its
    /// square is the efficiency ratio ε_i/ε_baseline.
    pub fn time_normalized_ratio(&self, i: usize) -> Option<f64> {
        let scaled = |r: &StrategyRun| r.error.corrected_rmse * r.rendered.stats.seconds.sqrt();
        let base = scaled(self.runs.first()?);
        let other = scaled(self.runs.get(i)?);
        (other > 0.0).then(|| base / other)
    }
}

/// The seed of the reference's render, distinct from the compared ones so
/// that their errors are independent.
fn reference_seed(seed: u64) -> u64 {
    seed ^ 0x5245_4645_5245_4e43 // "REFERENC"
}

/// Runs the comparison on the current rayon pool (see the module docs).
/// `progress(what)` is called before each render.
///
/// # Errors
/// A bad configuration (naming its option), a scene that cannot be
/// rendered in irradiance mode.
pub fn compare(
    scene: &Scene,
    config: &CompareConfig,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Comparison, TracerError> {
    config.validate()?;
    let quiet = |_: u64, _: u64| {};
    let render_at = |strategy: Strategy, spp: u64, seed: u64| {
        let c = RenderConfig {
            mode: Mode::Irradiance,
            estimate: PointConfig {
                strategy,
                samples: spp,
                seed,
                ..config.estimate
            },
            analytic: false,
            tile: config.tile,
            ..RenderConfig::default()
        };
        render(scene, &c, &quiet)
    };
    progress(&format!(
        "reference: {} × {} spp",
        config.reference_strategy, config.reference_spp
    ));
    let reference = render_at(
        config.reference_strategy,
        config.reference_spp,
        reference_seed(config.estimate.seed),
    )?;
    let reference_rms = rms_std_error(&reference.image);
    let mut runs = Vec::with_capacity(config.strategies.len());
    for &strategy in &config.strategies {
        let (spp, pilot) = match config.budget {
            Budget::SamplesPerPixel(n) => (n, None),
            Budget::Seconds(budget) => {
                progress(&format!("{strategy}: pilot renders"));
                let p = config.pilot_spp;
                let t1 = render_at(strategy, p, config.estimate.seed)?.stats.seconds;
                let t2 = render_at(strategy, 4 * p, config.estimate.seed)?
                    .stats
                    .seconds;
                // t ≈ a + b·spp; timing noise can make t2 < t1: b is then
                // taken from t2 alone (a = 0), an overestimate of b.
                let mut per_sample = (t2 - t1) / (3 * p) as f64;
                let mut fixed = t1 - per_sample * p as f64;
                if !(per_sample > 0.0) || fixed < 0.0 {
                    per_sample = t2 / (4 * p) as f64;
                    fixed = 0.0;
                }
                let spp = ((budget - fixed) / per_sample).floor();
                let spp = if spp.is_finite() {
                    spp.max(2.0) as u64
                } else {
                    2
                };
                (spp, Some((per_sample, fixed)))
            }
        };
        progress(&format!("{strategy}: {spp} spp"));
        let rendered = render_at(strategy, spp, config.estimate.seed)?;
        let error = pixel_error(&rendered.image, &reference.image, reference_rms)?;
        runs.push(StrategyRun {
            strategy,
            spp,
            pilot,
            rendered,
            error,
        });
    }
    Ok(Comparison {
        reference,
        reference_strategy: config.reference_strategy,
        reference_spp: config.reference_spp,
        reference_rms_std_error: reference_rms,
        runs,
    })
}

/// [`compare`] on a pool of `threads` threads (the images do not depend
/// on the number; the equal-time spp do, through the pilots' timings).
pub fn compare_with_threads(
    scene: &Scene,
    config: &CompareConfig,
    threads: usize,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<Comparison, TracerError> {
    if threads == 0 {
        return Err(TracerError::new("--threads", "must be at least 1, got 0"));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| TracerError::new("--threads", e.to_string()))?;
    pool.install(|| compare(scene, config, progress))
}
