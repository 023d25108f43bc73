//! Estimating a scene's irradiance: strategies × sequences, deterministic
//! parallel runs, honest standard errors.
//!
//! Independent samples: the mean and standard error of the per-sample
//! estimates (compensated sums; each chunk reads its own window of the
//! run's SplitMix64 stream, [`crate::chunk::ChunkStream`]). Stratified and Owen-scrambled
//! Sobol samples are not independent, so their standard error comes from
//! R = 16 independent randomizations (randomized QMC; Owen 1997, L'Ecuyer &
//! Lemieux 2002): the samples are split into R replicates with independent
//! scrambles (or jitters), the estimate is the sample-weighted mean of the
//! replicate means, and its standard error is the spread of the replicate
//! means over √R, with a Student-t(R − 1) interval.
//!
//! Work is split into fixed chunks of sample indices, run on `threads`
//! threads and merged in chunk order, so results are identical to the bit
//! for any thread count (see [`crate::statistics::run_chunked`]).
//!
//! **Hits.** In the same pass as the sums, every chunk counts the samples
//! whose value is not 0 (the estimate's *hits*,
//! [`EstimateReport::hits`]) and, per part of each emitter's estimate (one
//! part per technique, two for MIS), the samples in which that part was
//! not 0. Those counts, with each part's known bound
//! ([`crate::strategy::PartBound`]), decide the interval.
//!
//! **The interval** ([`crate::interval`]). `m ± q·se` when every part had
//! at least [`CLT_MIN_EVENTS`](crate::interval::CLT_MIN_EVENTS) hits; with
//! fewer (including none), rare-event bounds from the hit counts and the
//! bounds on a sample's value: with 0 hits the interval is one-sided,
//! [0, B·(1 − α^{1/N})] ⊂ [0, B·(−ln α)/N] for a value bounded by B, since
//! P(0 hits) = (1 − p)^N ≤ α ⇒ p ≤ −ln α/N. Such estimates carry a
//! [`warning`](EstimateReport::warning).
//!
//! **The rounding floor.** The reported standard error is never below
//! (21u + 4(N + 2)u²)·(m + |δ|), u = 2⁻⁵³, δ the delta lights' irradiance:
//! a bound on the floating-point error of the accumulated mean (chunk sums
//! in windows of plain adds, merged compensated in order, the replicates' weighted mean, the delta
//! lights added), derived in [`crate::statistics::rounding`]. It binds
//! where every sample has nearly the same value (light sampling of a cap
//! 1e-7 rad wide, of a triangle of 1e-9 sr, cosine sampling of a sky),
//! where s/√N would claim digits the arithmetic did not produce. The
//! samplers' own systematic error is added to it
//! ([`PreparedEmitter::systematic_error`]): the rounding error of a
//! projected sampler's Ω⊥, which every sample of the `projected` strategy
//! carries alike.

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use glam::DVec2;
use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::{SampleSequence, Sobol, Stratified};

use crate::chunk::ChunkStream;
use crate::interval::{
    honest_interval, ErrorSource, EstimateWarning, IntervalKind, PartTally, SampleSummary, LEVEL,
};
use crate::precision::Precision;
use crate::statistics::{run_chunked_merge, Estimate, Mergeable, StatisticsError};
use crate::strategy::{
    F32Fallback, PartHits, PreparedEmitter, PreparedEmitterF32, Strategy, TechniqueFallback,
};
use crate::strength_scale::{scaled_scene, strength_exponent, unscaled_error, unscaled_report};
use lambert_light::scene::Scene;

/// Samples per parallel chunk.
pub const CHUNK_SIZE: u64 = 4096;

/// Independent randomizations of a randomized-QMC estimate.
pub const RQMC_REPLICATES: u64 = 16;

/// Which sample sequence drives the estimate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SequenceKind {
    /// Independent samples: the run's SplitMix64 stream, a window per
    /// chunk ([`crate::chunk::ChunkStream`]).
    Independent,
    /// Jittered stratification (per replicate).
    Stratified,
    /// Owen-scrambled Sobol (Burley 2020).
    Sobol,
}

impl SequenceKind {
    /// All three.
    pub const ALL: [SequenceKind; 3] = [
        SequenceKind::Independent,
        SequenceKind::Stratified,
        SequenceKind::Sobol,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            SequenceKind::Independent => "independent",
            SequenceKind::Stratified => "stratified",
            SequenceKind::Sobol => "sobol",
        }
    }
}

impl fmt::Display for SequenceKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for SequenceKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "independent" => Ok(SequenceKind::Independent),
            "stratified" => Ok(SequenceKind::Stratified),
            "sobol" => Ok(SequenceKind::Sobol),
            other => Err(format!(
                "unknown sequence {other:?} (expected independent, stratified or sobol)"
            )),
        }
    }
}

/// What to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimateConfig {
    /// The strategy (resolved per emitter).
    pub strategy: Strategy,
    /// The sample sequence.
    pub sequence: SequenceKind,
    /// Total samples (≥ 2; ≥ 2·16 for the randomized-QMC sequences).
    pub samples: u64,
    /// Seed of the sequence (and of the replicates' scrambles).
    pub seed: u64,
    /// Worker threads (≥ 1); the result does not depend on it.
    pub threads: usize,
    /// The precision of the per-sample arithmetic
    /// ([`crate::precision`]; accumulation is always f64).
    pub precision: Precision,
}

/// An estimate of a scene's irradiance, with its statistics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimateReport {
    /// The estimated irradiance, W/m².
    pub mean: f64,
    /// Its standard error: s/√N (randomized QMC: the spread of the
    /// replicate means over √R), never below the rounding floor (module
    /// docs), so never 0 for a non-zero estimate.
    pub std_error: f64,
    /// The confidence interval at [`level`](Self::level) — 99 % from
    /// [`estimate`], hence the name; [`estimate_at_level`] sets another —
    /// formed as [`interval`](Self::interval) says (module docs). Both ends
    /// are finite and hold `mean`; the upper end is f64::MAX only when the
    /// bound on a sample's value overflows f64.
    pub ci99: (f64, f64),
    /// The confidence level of `ci99`.
    pub level: f64,
    /// How `ci99` was formed.
    pub interval: IntervalKind,
    /// Why `ci99` is not the plain CLT interval (few or no hits, few
    /// misses, a heavy tail); `None` when it is.
    pub warning: Option<EstimateWarning>,
    /// The first emitter (its index in the scene's list) whose requested
    /// technique could not be used and was replaced
    /// ([`TechniqueFallback`]), with the replacement; `None` when every
    /// emitter used the technique its strategy resolves to.
    pub fallback: Option<(usize, TechniqueFallback)>,
    /// Samples whose value was not 0 (of the sampled lights; delta lights
    /// are exact and not sampled).
    pub hits: u64,
    /// Samples used.
    pub samples: u64,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Wall time per sample, ns.
    pub ns_per_sample: f64,
    /// Variance of one sample's estimate (for efficiency 1/(V·T)); for
    /// randomized QMC, the replicate-mean variance times the samples per
    /// replicate. V ~ E² exceeds the f64 range for emitters strong enough
    /// that E ≳ 1e154 (E itself still in range, [`crate::strength_scale`]):
    /// it is then reported as f64::MAX, a lower bound.
    pub sample_variance: f64,
    /// The precision asked for.
    pub precision: Precision,
    /// With [`Precision::F32`], how many emitters ran in f64 instead
    /// ([`f32_fallbacks`] names them and says why); 0 in f64.
    pub f64_fallbacks: usize,
}

/// Why an estimate could not be run.
#[derive(Clone, Debug, PartialEq)]
pub enum EstimateError {
    /// A configuration value out of range.
    Config {
        /// The field.
        field: &'static str,
        /// The problem.
        problem: String,
    },
    /// A sample's value is not a finite number: an emitter's one-sample
    /// estimate is NaN or ±∞, or adding it to the estimates of the emitters
    /// before it (in scene order) overflowed. The first such sample is
    /// reported (lowest index; for the randomized-QMC sequences, in the
    /// first randomization that has one).
    NonFiniteSample {
        /// Index of the emitter in the scene's list (`emitters[i]`) whose
        /// estimate made the sample's value non-finite.
        emitter: usize,
        /// Its kind (`sphere`, `disk`, …).
        kind: &'static str,
        /// The sample's index (within its randomization for the
        /// randomized-QMC sequences).
        sample: u64,
        /// The randomization, 0 … 15, for the randomized-QMC sequences;
        /// `None` for independent samples.
        randomization: Option<u64>,
        /// That emitter's estimate for the sample.
        value: f64,
        /// The sample's value once that estimate is added (NaN or ±∞).
        total: f64,
    },
    /// Every sample is finite but a sum over them, or the estimate plus
    /// the exact irradiance of the delta lights, exceeds the largest f64
    /// (about 1.8e308 W/m²).
    Overflow {
        /// What overflowed, in words.
        quantity: &'static str,
    },
    /// The statistics failed.
    Statistics(StatisticsError),
}

impl fmt::Display for EstimateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EstimateError::Config { field, problem } => write!(f, "{field}: {problem}"),
            EstimateError::NonFiniteSample {
                emitter,
                kind,
                sample,
                randomization,
                value,
                total,
            } => {
                write!(f, "emitters[{emitter}] (a {kind}): sample {sample}")?;
                if let Some(r) = randomization {
                    write!(f, " of randomization {r}")?;
                }
                if value.is_finite() {
                    write!(
                        f,
                        " is not finite: its estimate {value:e} W/m² made the sample's sum over the emitters {total} (overflow)"
                    )
                } else {
                    write!(f, " is not finite: its estimate is {value}")
                }
            }
            EstimateError::Overflow { quantity } => write!(
                f,
                "{quantity} overflowed: it exceeds the largest f64 (about 1.8e308)"
            ),
            EstimateError::Statistics(e) => write!(f, "statistics: {e}"),
        }
    }
}

impl std::error::Error for EstimateError {}

impl From<StatisticsError> for EstimateError {
    fn from(e: StatisticsError) -> Self {
        EstimateError::Statistics(e)
    }
}

/// The scene's emitters prepared at its receiver for `strategy`, and the
/// exact sum of its delta lights.
pub fn prepare(scene: &Scene, strategy: Strategy) -> (Vec<PreparedEmitter>, f64) {
    let mut prepared = Vec::new();
    let mut delta = 0.0;
    for e in &scene.emitters {
        if e.is_delta() {
            delta += e.delta_irradiance(&scene.receiver);
        } else {
            prepared.push(PreparedEmitter::new(e, &scene.receiver, strategy));
        }
    }
    (prepared, delta)
}

/// The f32 forms of `prepared` (the scene's emitters prepared by
/// [`prepare`]), `None` for each emitter that runs in f64, and those
/// emitters with the reasons ([`PreparedEmitterF32::new`]).
pub fn prepare_f32(
    scene: &Scene,
    prepared: &[PreparedEmitter],
) -> (Vec<Option<PreparedEmitterF32>>, Vec<F32Fallback>) {
    let mut fallbacks = Vec::new();
    let f32s = prepared
        .iter()
        .enumerate()
        .map(|(k, p)| match PreparedEmitterF32::new(p, &scene.receiver) {
            Ok(q) => Some(q),
            Err(reason) => {
                let emitter = scene_index(scene, k);
                fallbacks.push(F32Fallback {
                    emitter,
                    kind: scene.emitters[emitter].kind(),
                    reason,
                });
                None
            }
        })
        .collect();
    (f32s, fallbacks)
}

/// The emitters of `scene` that an f32 estimate with `strategy` runs in
/// f64, and why (empty when every emitter runs in f32; delta lights are
/// exact and never listed).
///
/// ```
/// use lambert_estimator::estimation::f32_fallbacks;
/// use lambert_estimator::strategy::Strategy;
/// use lambert_light::builtin::builtin_scenes;
/// let scene = &builtin_scenes()[0].scene;
/// for f in f32_fallbacks(scene, Strategy::Light) {
///     println!("{f}"); // "emitters[i] (a …) runs in f64: …"
/// }
/// ```
pub fn f32_fallbacks(scene: &Scene, strategy: Strategy) -> Vec<F32Fallback> {
    let (prepared, _) = prepare(scene, strategy);
    prepare_f32(scene, &prepared).1
}

/// One sample of the scene's irradiance (without the delta lights).
#[inline]
pub fn sample_scene<S: SampleSequence>(
    prepared: &[PreparedEmitter],
    scene: &Scene,
    sequence: &mut S,
) -> f64 {
    prepared
        .iter()
        .map(|p| p.evaluate(&scene.receiver, sequence))
        .sum()
}

pub(crate) fn mix(seed: u64, k: u64) -> u64 {
    // SplitMix64 finaliser of seed + k·golden: independent replicate seeds.
    let mut z = seed.wrapping_add(k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Estimates the scene's irradiance as configured, with its 99 % interval.
pub fn estimate(scene: &Scene, config: &EstimateConfig) -> Result<EstimateReport, EstimateError> {
    estimate_at_level(scene, config, LEVEL)
}

/// [`estimate`] with the interval (`ci99`) at confidence `level` instead of
/// 0.99: for judging a family of estimates at a Šidák-corrected level, or
/// for a 95 % interval. The samples, mean and standard error are those of
/// [`estimate`], to the bit.
///
/// # Errors
/// As [`estimate`], and [`EstimateError::Config`] (field `level`) unless
/// 0 < level < 1.
pub fn estimate_at_level(
    scene: &Scene,
    config: &EstimateConfig,
    level: f64,
) -> Result<EstimateReport, EstimateError> {
    estimate_with_isa(scene, config, level, Isa::selected())
}

/// [`estimate_at_level`] with its kernels run for instruction set `isa`
/// (or the widest narrower set the processor has) instead of the one the
/// process selected ([`Isa::selected`]). The result is the same, to the
/// bit, for every set: this is how the tests check it.
///
/// # Errors
/// As [`estimate_at_level`].
pub fn estimate_with_isa(
    scene: &Scene,
    config: &EstimateConfig,
    level: f64,
    isa: Isa,
) -> Result<EstimateReport, EstimateError> {
    if !(level > 0.0 && level < 1.0) {
        return Err(EstimateError::Config {
            field: "level",
            problem: format!("must lie in (0, 1), got {level}"),
        });
    }
    if config.threads == 0 {
        return Err(EstimateError::Config {
            field: "threads",
            problem: "must be at least 1, got 0".into(),
        });
    }
    let rqmc = config.sequence != SequenceKind::Independent;
    let minimum = if rqmc { 2 * RQMC_REPLICATES } else { 2 };
    if config.samples < minimum {
        return Err(EstimateError::Config {
            field: "samples",
            problem: format!(
                "must be at least {minimum} for the {} sequence, got {}",
                config.sequence, config.samples
            ),
        });
    }
    let k = strength_exponent(scene);
    if k != 0 {
        // Emitters too strong for f64 sums: estimate at 2⁻ᵏ the strength and
        // scale the report back (crate::strength_scale).
        return estimate_with_isa(&scaled_scene(scene, k), config, level, isa)
            .map_err(|e| unscaled_error(e, k))
            .and_then(|r| unscaled_report(r, k));
    }
    let start = Instant::now();
    let (prepared, delta) = prepare(scene, config.strategy);
    if !delta.is_finite() {
        return Err(EstimateError::Overflow {
            quantity: "the summed irradiance of the point and directional lights",
        });
    }
    let part_count: usize = prepared.iter().map(|p| p.parts().len()).sum();
    let n = config.samples;
    // f32: each emitter's f32 form, or None where it runs in f64 (an empty
    // list in f64 mode: the f64 chunks).
    let (f32s, f64_fallbacks) = match config.precision {
        Precision::F64 => (Vec::new(), 0),
        Precision::F32 => {
            let (f32s, fallbacks) = prepare_f32(scene, &prepared);
            (f32s, fallbacks.len())
        }
    };
    let mut systematic: f64 = prepared.iter().map(PreparedEmitter::systematic_error).sum();
    systematic += f32s
        .iter()
        .flatten()
        .map(PreparedEmitterF32::error_bound)
        .sum::<f64>();
    // Randomized QMC: per part, the hit count of every replicate when they
    // were all equal (crate::interval explains why that matters).
    let mut fixed_counts: Vec<Option<u64>> = Vec::new();
    let (sampled, part_hits, summary, variance) = if prepared.is_empty() {
        // Only delta lights: exact (to the rounding floor).
        let summary = SampleSummary {
            n,
            mean: delta,
            sampled_mean: 0.0,
            delta,
            std_error: 0.0,
            source: ErrorSource::Samples,
            systematic,
        };
        (Estimate::new(), Vec::new(), summary, 0.0)
    } else if !rqmc {
        let c: ChunkStats = run_chunked_merge(n, CHUNK_SIZE, config.threads, |_, range| {
            independent_chunk(
                (&prepared, &f32s),
                part_count,
                scene,
                config.seed,
                range,
                isa,
            )
        })?;
        if c.estimate.non_finite() > 0 {
            if f32s.iter().any(Option::is_some) {
                return Err(NON_FINITE_F32);
            }
            return Err(first_non_finite_independent(
                &prepared,
                scene,
                config.seed,
                config.samples,
            ));
        }
        let sampled_mean = c.estimate.mean().ok_or(EstimateError::Overflow {
            quantity: "the sum of the samples",
        })?;
        if !(sampled_mean + delta).is_finite() {
            return Err(EstimateError::Overflow {
                quantity: "the mean plus the delta lights",
            });
        }
        let std_error = c.estimate.std_error().ok_or(EstimateError::Overflow {
            quantity: "the sum of the squared deviations (the variance)",
        })?;
        let summary = SampleSummary {
            n,
            mean: sampled_mean + delta,
            sampled_mean,
            delta,
            std_error,
            source: ErrorSource::Samples,
            systematic,
        };
        let variance = c.estimate.variance().unwrap_or(0.0);
        (c.estimate, c.part_hits, summary, variance)
    } else {
        let r = RQMC_REPLICATES;
        let mut replicate_means = Estimate::new();
        let mut weighted = crate::statistics::NeumaierSum::new();
        let mut all = ChunkStats::default();
        // Per part: the hits of every replicate, while they are all equal.
        let mut same: Option<Vec<Option<u64>>> = None;
        for k in 0..r {
            let n_k = n / r + u64::from(k < n % r);
            let seed = mix(config.seed, k);
            let c: ChunkStats = match config.sequence {
                SequenceKind::Sobol => replicate_estimate(
                    (&prepared, &f32s),
                    part_count,
                    scene,
                    &Sobol::new(seed),
                    n_k,
                    config.threads,
                    k,
                    isa,
                )?,
                SequenceKind::Stratified => {
                    let strata = u32::try_from(n_k).map_err(|_| EstimateError::Config {
                        field: "samples",
                        problem: format!(
                            "too many for stratification ({n_k} per replicate > 2^32 − 1)"
                        ),
                    })?;
                    let seq = Stratified::new(strata, seed).map_err(|e| EstimateError::Config {
                        field: "samples",
                        problem: e.to_string(),
                    })?;
                    replicate_estimate(
                        (&prepared, &f32s),
                        part_count,
                        scene,
                        &seq,
                        n_k,
                        config.threads,
                        k,
                        isa,
                    )?
                }
                SequenceKind::Independent => unreachable!(),
            };
            let m = c.estimate.mean().ok_or(EstimateError::Overflow {
                quantity: "the sum of one randomization's samples",
            })?;
            replicate_means.push(m);
            weighted.add(m * n_k as f64);
            match &mut same {
                None => same = Some(c.part_hits.iter().map(|&h| Some(h)).collect()),
                Some(same) => {
                    for (s, &h) in same.iter_mut().zip(&c.part_hits) {
                        if *s != Some(h) {
                            *s = None;
                        }
                    }
                }
            }
            all.merge(&c);
        }
        fixed_counts = same.unwrap_or_default();
        let sampled_mean = weighted.sum() / n as f64;
        if !(sampled_mean + delta).is_finite() {
            return Err(EstimateError::Overflow {
                quantity: "the mean over the randomizations plus the delta lights",
            });
        }
        let se = replicate_means.std_error().ok_or(EstimateError::Overflow {
            quantity: "the spread of the randomizations' means",
        })?;
        let per_replicate = (n / r) as f64;
        let summary = SampleSummary {
            n,
            mean: sampled_mean + delta,
            sampled_mean,
            delta,
            std_error: se,
            source: ErrorSource::Replicates(r),
            systematic,
        };
        (
            all.estimate,
            all.part_hits,
            summary,
            se * se * r as f64 * per_replicate,
        )
    };
    // The sampled emitters' indices in the scene (prepare() skips the delta
    // lights), beside each of their parts.
    let sampled_emitters = (0..scene.emitters.len()).filter(|&i| !scene.emitters[i].is_delta());
    let tallies: Vec<PartTally> = prepared
        .iter()
        .zip(sampled_emitters)
        .flat_map(|(p, emitter)| p.parts().iter().map(move |&bound| (emitter, bound)))
        .zip(part_hits.iter().copied().chain(std::iter::repeat(0)))
        .zip(fixed_counts.iter().copied().chain(std::iter::repeat(None)))
        .map(|(((emitter, bound), hits), replicate_hits)| PartTally {
            emitter,
            bound,
            hits,
            replicate_hits,
        })
        .collect();
    let honest = honest_interval(&summary, &tallies, level);
    for (value, quantity) in [
        (honest.std_error, "the standard error"),
        (honest.ci.0, "the interval's lower end"),
        (honest.ci.1, "the interval's upper end"),
        (variance, "the variance of one sample's estimate"),
    ] {
        if !value.is_finite() {
            return Err(EstimateError::Overflow { quantity });
        }
    }
    let seconds = start.elapsed().as_secs_f64();
    Ok(EstimateReport {
        mean: summary.mean,
        std_error: honest.std_error,
        ci99: honest.ci,
        level,
        interval: honest.kind,
        warning: honest.warning,
        fallback: prepared
            .iter()
            .zip((0..scene.emitters.len()).filter(|&i| !scene.emitters[i].is_delta()))
            .find_map(|(p, i)| p.fallback.map(|f| (i, f))),
        hits: sampled.nonzero(),
        samples: config.samples,
        seconds,
        ns_per_sample: seconds * 1e9 / config.samples as f64,
        sample_variance: variance,
        precision: config.precision,
        f64_fallbacks,
    })
}

/// A chunk's estimate and, for every part of every emitter's estimate (in
/// emitter order), the samples in which that part was not 0.
#[derive(Clone, Debug, Default, PartialEq)]
struct ChunkStats {
    estimate: Estimate,
    part_hits: Vec<u64>,
}

impl ChunkStats {
    /// Collects the hit counts that [`PreparedEmitter::evaluate_batch`]
    /// returned for each emitter.
    fn new(estimate: Estimate, per_emitter: &[(usize, PartHits)], part_count: usize) -> Self {
        let mut part_hits = Vec::with_capacity(part_count);
        for &(parts, hits) in per_emitter {
            part_hits.extend_from_slice(&hits[..parts]);
        }
        ChunkStats {
            estimate,
            part_hits,
        }
    }
}

impl Mergeable for ChunkStats {
    fn merge(&mut self, other: &Self) {
        self.estimate.merge(&other.estimate);
        if self.part_hits.len() < other.part_hits.len() {
            self.part_hits.resize(other.part_hits.len(), 0);
        }
        for (a, b) in self.part_hits.iter_mut().zip(&other.part_hits) {
            *a += b;
        }
    }
}

/// Generates the uniform points of one chunk of an independent-sample
/// estimate and hands them to `visit(k, u, u2)`, emitter by emitter (`u2`
/// holds the second point of two-dimensional techniques): the chunk's
/// window of the run's stream ([`ChunkStream`]), the same numbers
/// [`crate::chunk::independent_chunk`] draws. The slow path that finds a
/// failed estimate's first non-finite sample reads its points from here,
/// so that it sees the estimate's points.
fn independent_points(
    prepared: &[PreparedEmitter],
    seed: u64,
    start: u64,
    n: usize,
    mut visit: impl FnMut(usize, &[DVec2], &[DVec2]),
) {
    let stream = chunk_stream(prepared, seed, start);
    let (mut x, mut y) = (vec![0.0; n], vec![0.0; n]);
    let mut points = |offset: u64, u: &mut [DVec2]| {
        stream.fill_2d_in(Isa::Baseline, offset, &mut x, &mut y);
        for (p, (&x, &y)) in u.iter_mut().zip(x.iter().zip(&y)) {
            *p = DVec2::new(x, y);
        }
    };
    let mut u = vec![DVec2::ZERO; n];
    let mut u2 = vec![DVec2::ZERO; n];
    let mut offset = 0u64;
    for (k, p) in prepared.iter().enumerate() {
        points(offset, &mut u);
        if p.technique.dimensions() > 1 {
            points(offset + n as u64, &mut u2);
        }
        offset += (p.technique.dimensions() * n) as u64;
        visit(k, &u, &u2);
    }
}

/// The window of the run's stream that the chunk starting at sample
/// `start` reads ([`ChunkStream`]: D the emitters' dimensions per sample).
fn chunk_stream(prepared: &[PreparedEmitter], seed: u64, start: u64) -> ChunkStream {
    let dimensions = crate::strategy::sample_dimensions(prepared);
    ChunkStream::new(seed, dimensions as u64, start)
}

/// One chunk of an independent-sample estimate: the chunk's window of the
/// run's stream (fixed by the run's seed and the chunk's first sample, so
/// the chunk's values do not depend on which thread runs it) gives the
/// uniform points of every
/// emitter, the emitters add their estimates into a buffer (counting their
/// parts' hits), and the buffer is summarised by two passes
/// ([`Estimate::from_values`], which counts the samples' hits). The work is
/// [`crate::chunk::independent_chunk`]'s: cache-sized blocks, the
/// instruction set `isa`.
fn independent_chunk(
    (prepared, f32s): Emitters<'_>,
    part_count: usize,
    scene: &Scene,
    seed: u64,
    range: std::ops::Range<u64>,
    isa: Isa,
) -> ChunkStats {
    let n = (range.end - range.start) as usize;
    let receiver = &scene.receiver;
    let stream = chunk_stream(prepared, seed, range.start);
    let c = if f32s.is_empty() {
        crate::chunk::independent_chunk(prepared, receiver, stream, n, isa)
    } else {
        crate::chunk::independent_chunk_f32(prepared, f32s, receiver, stream, n, isa)
    };
    chunk_stats(prepared, c, part_count)
}

/// The prepared emitters, and their f32 forms in an f32 estimate (empty
/// in f64; `None` for each emitter that runs in f64).
type Emitters<'a> = (&'a [PreparedEmitter], &'a [Option<PreparedEmitterF32>]);

/// The points of samples `range` of a randomized-QMC sequence, handed to
/// `visit(k, u, u2)` emitter by emitter: sample i's points are read from
/// the sequence at index i (each emitter's dimensions in emitter order, as
/// [`sample_scene`] reads them), as [`crate::chunk::sequence_chunk`]
/// reads them too; the slow path that finds a failed estimate's first
/// non-finite sample uses this one. The points are filled one 2-D request
/// (dimension pair) at a time for the whole chunk by
/// [`SampleSequence::fill_2d`], which gives the values of reading them
/// sample by sample, to the bit, at a fraction of the cost.
fn sequence_points<S: SampleSequence>(
    prepared: &[PreparedEmitter],
    sequence: &S,
    range: std::ops::Range<u64>,
    mut visit: impl FnMut(usize, &[DVec2], &[DVec2]),
) {
    let n = (range.end - range.start) as usize;
    let dims = crate::strategy::sample_dimensions(prepared);
    let mut points = vec![DVec2::ZERO; n * dims];
    for (request, block) in points.chunks_exact_mut(n).enumerate() {
        sequence.fill_2d(range.start, request as u64, block);
    }
    let mut d = 0;
    for (k, p) in prepared.iter().enumerate() {
        let u = &points[d * n..(d + 1) * n];
        let u2 = if p.technique.dimensions() > 1 {
            &points[(d + 1) * n..(d + 2) * n]
        } else {
            u
        };
        visit(k, u, u2);
        d += p.technique.dimensions();
    }
}

/// One chunk of a randomized-QMC estimate: the sequence's points for
/// samples `range`, evaluated emitter by emitter in the instruction set
/// `isa` ([`crate::chunk::sequence_chunk`]), counting the parts' hits.
fn sequence_chunk<S: SampleSequence>(
    (prepared, f32s): Emitters<'_>,
    part_count: usize,
    scene: &Scene,
    sequence: &S,
    range: std::ops::Range<u64>,
    isa: Isa,
) -> ChunkStats {
    let receiver = &scene.receiver;
    let c = if f32s.is_empty() {
        crate::chunk::sequence_chunk(prepared, receiver, sequence, range, isa)
    } else {
        crate::chunk::sequence_chunk_f32(prepared, f32s, receiver, sequence, range, isa)
    };
    chunk_stats(prepared, c, part_count)
}

/// A chunk's result with its hit counts laid out part by part.
fn chunk_stats(
    prepared: &[PreparedEmitter],
    c: crate::chunk::ChunkResult,
    part_count: usize,
) -> ChunkStats {
    let hits: Vec<(usize, PartHits)> = prepared
        .iter()
        .zip(c.hits)
        .map(|(p, h)| (p.parts().len(), h))
        .collect();
    ChunkStats::new(c.estimate, &hits, part_count)
}

/// Randomization `k` of a randomized-QMC estimate: samples `0..n` of
/// `sequence`, or the first non-finite one as an error.
#[allow(clippy::too_many_arguments)]
fn replicate_estimate<S: SampleSequence>(
    (prepared, f32s): Emitters<'_>,
    part_count: usize,
    scene: &Scene,
    sequence: &S,
    n: u64,
    threads: usize,
    k: u64,
    isa: Isa,
) -> Result<ChunkStats, EstimateError> {
    let c: ChunkStats = run_chunked_merge(n, CHUNK_SIZE, threads, |_, range| {
        sequence_chunk((prepared, f32s), part_count, scene, sequence, range, isa)
    })?;
    if c.estimate.non_finite() > 0 {
        if f32s.iter().any(Option::is_some) {
            return Err(NON_FINITE_F32);
        }
        return Err(with_randomization(
            first_non_finite_in(prepared, scene, sequence, n),
            k,
        ));
    }
    Ok(c)
}

/// The first non-finite sample of a chunk whose points `points` hands out
/// (as [`independent_points`] or [`sequence_points`] do): each emitter's
/// estimates are computed on their own and added to the samples' running
/// sums in emitter order, exactly as the estimate adds them, and the lowest
/// sample whose sum turns non-finite is reported with the emitter that
/// turned it. `first` is the chunk's first sample index. The slow path of a
/// failed estimate only.
fn first_non_finite_of_chunk(
    prepared: &[PreparedEmitter],
    scene: &Scene,
    first: u64,
    n: usize,
    points: impl FnOnce(&mut dyn FnMut(usize, &[DVec2], &[DVec2])),
) -> Option<EstimateError> {
    let mut sums = vec![0.0f64; n];
    let mut culprit: Vec<Option<(usize, f64)>> = vec![None; n];
    let mut own = vec![0.0f64; n];
    points(&mut |k, u, u2| {
        own.fill(0.0);
        prepared[k].evaluate_batch(&scene.receiver, u, u2, &mut own);
        for ((sum, c), &v) in sums.iter_mut().zip(culprit.iter_mut()).zip(&own) {
            *sum += v;
            if c.is_none() && !sum.is_finite() {
                *c = Some((k, v));
            }
        }
    });
    let j = culprit.iter().position(Option::is_some)?;
    let (k, value) = culprit[j]?;
    let emitter = scene_index(scene, k);
    Some(EstimateError::NonFiniteSample {
        emitter,
        kind: scene.emitters[emitter].kind(),
        sample: first + j as u64,
        randomization: None,
        value,
        total: sums[j],
    })
}

/// The index in `scene.emitters` of the `k`-th prepared (non-delta)
/// emitter ([`prepare`] keeps the non-delta emitters in scene order).
fn scene_index(scene: &Scene, k: usize) -> usize {
    scene
        .emitters
        .iter()
        .enumerate()
        .filter(|(_, e)| !e.is_delta())
        .nth(k)
        .map_or(k, |(i, _)| i)
}

/// The first non-finite sample of an independent-sample estimate of
/// `samples` samples with `seed` over the emitters `prepared` from
/// `scene` by [`prepare`], found by evaluating its chunks again in order
/// and adding each emitter's values to the samples' running sums in the
/// estimate's order: an [`EstimateError::NonFiniteSample`] naming the
/// lowest sample whose sum turns NaN or ±∞ and the emitter that turned it,
/// or an [`EstimateError::Overflow`] if every sum stays finite.
///
/// The slow path [`estimate`] takes when a sum of its samples is not
/// finite. Public for diagnosis and for the integration tests: strength
/// scaling ([`crate::strength_scale`]) keeps an estimate's own scenes
/// from reaching it, and a scene prepared unscaled can.
///
/// ```
/// use glam::DVec3;
/// use lambert_estimator::estimation::{first_non_finite_independent, prepare, EstimateError};
/// use lambert_estimator::strategy::Strategy;
/// use lambert_light::emitter::{Emitter, Sky};
/// use lambert_light::{receiver::Receiver, Scene};
/// let sky = || Emitter::Sky(Sky::new(f64::MAX / 4.0).unwrap());
/// let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
/// let scene = Scene::new(receiver, vec![sky(), sky()]).unwrap();
/// // Cosine samples of a sky are π·L: the second sky overflows sample 0.
/// let (prepared, _) = prepare(&scene, Strategy::CosineHemisphere);
/// let error = first_non_finite_independent(&prepared, &scene, 1, 8);
/// assert!(matches!(error, EstimateError::NonFiniteSample { emitter: 1, sample: 0, .. }));
/// ```
pub fn first_non_finite_independent(
    prepared: &[PreparedEmitter],
    scene: &Scene,
    seed: u64,
    samples: u64,
) -> EstimateError {
    let chunks = samples.div_ceil(CHUNK_SIZE);
    (0..chunks)
        .find_map(|chunk| {
            let start = chunk * CHUNK_SIZE;
            let n = (CHUNK_SIZE.min(samples - start)) as usize;
            first_non_finite_of_chunk(prepared, scene, start, n, |visit| {
                independent_points(prepared, seed, start, n, visit)
            })
        })
        .unwrap_or(NON_FINITE_NOT_FOUND)
}

/// [`first_non_finite_independent`] for samples `0..samples` of
/// `sequence` (one randomization of a randomized-QMC estimate; the error's
/// `randomization` is `None`, for the caller to fill in).
pub fn first_non_finite_in<S: SampleSequence>(
    prepared: &[PreparedEmitter],
    scene: &Scene,
    sequence: &S,
    samples: u64,
) -> EstimateError {
    let chunks = samples.div_ceil(CHUNK_SIZE);
    (0..chunks)
        .find_map(|chunk| {
            let start = chunk * CHUNK_SIZE;
            let end = (start + CHUNK_SIZE).min(samples);
            first_non_finite_of_chunk(prepared, scene, start, (end - start) as usize, |visit| {
                sequence_points(prepared, sequence, start..end, visit)
            })
        })
        .unwrap_or(NON_FINITE_NOT_FOUND)
}

/// Reported if the search for a non-finite sample found none (the
/// evaluation is deterministic, so it always finds the one the estimate
/// saw).
const NON_FINITE_NOT_FOUND: EstimateError = EstimateError::Overflow {
    quantity: "a sample (not found again)",
};

/// Reported when an f32 estimate has a non-finite sample (an f32
/// geometric factor that overflowed: the preparation's range checks are
/// meant to rule it out). The f64 search for the sample would evaluate
/// other arithmetic, so none is run.
const NON_FINITE_F32: EstimateError = EstimateError::Overflow {
    quantity: "a sample's f32 value (run with precision f64 to locate it)",
};

/// `error` with its randomization set to `k`.
fn with_randomization(error: EstimateError, k: u64) -> EstimateError {
    match error {
        EstimateError::NonFiniteSample {
            emitter,
            kind,
            sample,
            value,
            total,
            ..
        } => EstimateError::NonFiniteSample {
            emitter,
            kind,
            sample,
            randomization: Some(k),
            value,
            total,
        },
        other => other,
    }
}
