//! Irradiance at one point of a scene with occluders: E = ∫ L V cos θ dω
//! from every emitter, with visibility asked of the caller, by any strategy
//! and sequence of [`estimation`](crate::estimation).
//!
//! A renderer calls this once per shading point (per pixel), so the work
//! runs on the calling thread: parallelism belongs to the caller (over
//! pixels). The statistics are those of [`estimation`](crate::estimation):
//! independent samples give the mean and standard error of the per-sample
//! values; stratified and Sobol samples are split into
//! [`RQMC_REPLICATES`] independent randomizations whose means give the
//! standard error (randomized QMC; Owen 1997, L'Ecuyer & Lemieux 2002).
//! Delta lights (point, directional) are added exactly, each with one
//! visibility test ([`delta_irradiance_visible`]). The result depends only
//! on the configuration and the seed: the same, to the bit, on any thread.

use glam::DVec3;
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::sequence::{Independent, SampleSequence, Sobol, Stratified};

use crate::estimation::{mix, EstimateError, SequenceKind, RQMC_REPLICATES};
use crate::statistics::{Estimate, NeumaierSum, StatisticsError};
use crate::strategy::{delta_irradiance_visible, OccludedEmitter, Strategy};

/// How to estimate the irradiance at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointConfig {
    /// The strategy (resolved per emitter).
    pub strategy: Strategy,
    /// The sample sequence.
    pub sequence: SequenceKind,
    /// Samples per point (≥ 2; ≥ 2·16 for the randomized-QMC sequences).
    pub samples: u64,
    /// Seed of the sequence (and of the replicates' scrambles).
    pub seed: u64,
}

impl PointConfig {
    /// Checks the sample count for the sequence (errors name the field
    /// `samples`), so that a renderer validates once, not per pixel.
    pub fn validate(&self) -> Result<(), EstimateError> {
        let rqmc = self.sequence != SequenceKind::Independent;
        let minimum = if rqmc { 2 * RQMC_REPLICATES } else { 2 };
        if self.samples < minimum {
            return Err(EstimateError::Config {
                field: "samples",
                problem: format!(
                    "must be at least {minimum} for the {} sequence, got {}",
                    self.sequence, self.samples
                ),
            });
        }
        if self.sequence == SequenceKind::Stratified
            && self.samples / RQMC_REPLICATES >= u64::from(u32::MAX)
        {
            return Err(EstimateError::Config {
                field: "samples",
                problem: format!(
                    "too many for stratification ({} per replicate > 2^32 − 1)",
                    self.samples / RQMC_REPLICATES
                ),
            });
        }
        Ok(())
    }

    /// The same configuration with another seed (one per pixel).
    pub fn with_seed(self, seed: u64) -> Self {
        PointConfig { seed, ..self }
    }
}

/// A seed for stream `index` of a run seeded `seed` (SplitMix64's
/// finaliser of seed + index·golden ratio, as the estimator's chunks and
/// replicates are seeded): per-pixel seeds that are independent of each
/// other and of the order in which pixels are computed.
pub fn stream_seed(seed: u64, index: u64) -> u64 {
    mix(seed, index)
}

/// An estimate of the irradiance at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointEstimate {
    /// The estimated irradiance, W/m² (delta lights included exactly).
    pub mean: f64,
    /// Its standard error (0 when the estimate is exact: only delta
    /// lights, or every sample equal).
    pub std_error: f64,
    /// The degrees of freedom of `std_error`: n − 1 for independent
    /// samples, [`RQMC_REPLICATES`] − 1 for randomized QMC, 0 when exact
    /// (for Student-t intervals and tests).
    pub degrees_of_freedom: u64,
    /// Samples drawn (0 when there is nothing to sample).
    pub samples: u64,
}

/// The irradiance E = ∫ L V max(cos θ, 0) dω at `receiver` from
/// `emitters`, with `visible(origin, direction, max_distance)` deciding
/// whether each direction reaches its emitter (see [`OccludedEmitter`]).
///
/// ```
/// use glam::DVec3;
/// use lambert_estimator::estimation::SequenceKind;
/// use lambert_estimator::point::{estimate_at, PointConfig};
/// use lambert_estimator::strategy::Strategy;
/// use lambert_light::emitter::{Emitter, SphereLight};
/// use lambert_light::Receiver;
/// let light = Emitter::Sphere(SphereLight::new(DVec3::new(0.0, 0.0, 4.0), 1.0, 1.0)?);
/// let receiver = Receiver::new(DVec3::ZERO, DVec3::Z)?;
/// let config = PointConfig { strategy: Strategy::Light, sequence: SequenceKind::Independent, samples: 64, seed: 1 };
/// // An opaque plane at z = 2 hides the whole light: exactly 0.
/// let blocked = |_: DVec3, _: DVec3, far: f64| far < 2.0;
/// let e = estimate_at(&receiver, std::slice::from_ref(&light), &blocked, &config).unwrap();
/// assert_eq!((e.mean, e.std_error), (0.0, 0.0));
/// // Nothing in the way: the closed form π sin²α = π/16, to within the error.
/// let e = estimate_at(&receiver, &[light], &|_, _, _| true, &config).unwrap();
/// assert!((e.mean - std::f64::consts::PI / 16.0).abs() < 5.0 * e.std_error + 1e-12);
/// # Ok::<(), lambert_light::EmitterError>(())
/// ```
///
/// # Errors
/// [`EstimateError::Config`] for a sample count the sequence cannot use
/// ([`PointConfig::validate`]); [`EstimateError::Statistics`] when a sample
/// is not finite (a radiance so large that L cos θ / p overflows).
pub fn estimate_at<V>(
    receiver: &Receiver,
    emitters: &[Emitter],
    visible: &V,
    config: &PointConfig,
) -> Result<PointEstimate, EstimateError>
where
    V: Fn(DVec3, DVec3, f64) -> bool,
{
    config.validate()?;
    let mut delta = NeumaierSum::new();
    let mut prepared = Vec::with_capacity(emitters.len());
    for e in emitters {
        if e.is_delta() {
            delta.add(delta_irradiance_visible(e, receiver, visible));
        } else {
            prepared.push(OccludedEmitter::new(e, receiver, config.strategy));
        }
    }
    let delta = delta.sum();
    if prepared.is_empty() {
        return Ok(PointEstimate {
            mean: delta,
            std_error: 0.0,
            degrees_of_freedom: 0,
            samples: 0,
        });
    }
    let run = |sequence: &mut dyn FnMut(u64) -> f64, n: u64| -> Result<Estimate, EstimateError> {
        let mut e = Estimate::new();
        for i in 0..n {
            e.push(sequence(i));
        }
        if e.non_finite() > 0 {
            return Err(StatisticsError::NonFinite {
                count: e.non_finite(),
            }
            .into());
        }
        Ok(e)
    };
    match config.sequence {
        SequenceKind::Independent => {
            let mut seq = Independent::new(config.seed);
            let e = run(
                &mut |i| sample_all(&prepared, receiver, visible, &mut seq, i),
                config.samples,
            )?;
            let mean = e.mean().unwrap_or(0.0);
            Ok(PointEstimate {
                mean: mean + delta,
                std_error: e.std_error().unwrap_or(0.0),
                degrees_of_freedom: config.samples - 1,
                samples: config.samples,
            })
        }
        SequenceKind::Stratified | SequenceKind::Sobol => {
            let r = RQMC_REPLICATES;
            let mut replicate_means = Estimate::new();
            let mut weighted = NeumaierSum::new();
            for k in 0..r {
                let n_k = config.samples / r + u64::from(k < config.samples % r);
                let seed = mix(config.seed, k);
                let e = if config.sequence == SequenceKind::Sobol {
                    let mut seq = Sobol::new(seed);
                    run(
                        &mut |i| sample_all(&prepared, receiver, visible, &mut seq, i),
                        n_k,
                    )?
                } else {
                    // n_k < 2^32 by `validate`.
                    let mut seq =
                        Stratified::new(n_k as u32, seed).map_err(|e| EstimateError::Config {
                            field: "samples",
                            problem: e.to_string(),
                        })?;
                    run(
                        &mut |i| sample_all(&prepared, receiver, visible, &mut seq, i),
                        n_k,
                    )?
                };
                let m = e.mean().unwrap_or(0.0);
                replicate_means.push(m);
                weighted.add(m * n_k as f64);
            }
            Ok(PointEstimate {
                mean: weighted.sum() / config.samples as f64 + delta,
                std_error: replicate_means.std_error().unwrap_or(0.0),
                degrees_of_freedom: r - 1,
                samples: config.samples,
            })
        }
    }
}

/// Sample `i` of the sum over the emitters, each reading its own
/// dimensions in emitter order (as [`crate::estimation::sample_scene`]).
#[inline]
fn sample_all<S, V>(
    prepared: &[OccludedEmitter<'_>],
    receiver: &Receiver,
    visible: &V,
    sequence: &mut S,
    i: u64,
) -> f64
where
    S: SampleSequence,
    V: Fn(DVec3, DVec3, f64) -> bool,
{
    sequence.start_sample(i);
    prepared
        .iter()
        .map(|p| p.evaluate(receiver, sequence, visible))
        .sum()
}
