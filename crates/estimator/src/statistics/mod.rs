//! Streaming statistics for Monte Carlo estimates, and a deterministic
//! parallel runner.
//!
//! | item | what | follows |
//! |------|------|---------|
//! | [`NeumaierSum`] | compensated sum, error ≈ one rounding for n < 1/ε | Neumaier 1974 |
//! | [`Estimate`] | count, mean, variance, standard error, CI, z, merge | Welford 1962; Chan, Golub & LeVeque 1983 |
//! | [`ConfidenceInterval`] | `m ± q·s/√n`, Student's t for n < 30, normal after | Student 1908 |
//! | [`bounded`] | bounds without the CLT: hit probability from hit counts (0 hits: p ≤ 1 − α^{1/N} ≤ −ln α/N), mean of values in [0, B] | Chernoff 1952; Hoeffding 1963 |
//! | [`rounding`] | the rounding floor: a bound on the floating-point error of an accumulated mean | Higham 2002 |
//! | [`Timing`] | wall time, ns/sample, efficiency 1/(V·T) | Hammersley & Handscomb 1964 |
//! | [`run_chunked`], [`run_samples`] | fixed chunks merged in order: same bits on any thread count | |
//!
//! Statistics that are undefined (the mean of 0 samples, the variance of 1,
//! anything after a NaN sample) are `None` or an error, never NaN.
//!
//! ```
//! use lambert_estimator::statistics::run_samples;
//! use lambert_sampling::sequence::{SampleSequence, Sobol};
//! // ∫₀¹ x² dx = 1/3 with Owen-scrambled Sobol points, on 1 and 2 threads.
//! let seq = Sobol::new(3);
//! let f = |s: &mut Sobol| s.next_1d().powi(2);
//! let a = run_samples(&seq, 1 << 16, 1 << 12, 1, f).unwrap();
//! let b = run_samples(&seq, 1 << 16, 1 << 12, 2, f).unwrap();
//! assert_eq!(a.mean().unwrap().to_bits(), b.mean().unwrap().to_bits());
//! assert!(a.relative_error(1.0 / 3.0).unwrap() < 1e-4);
//! ```

pub mod bounded;
pub mod confidence;
pub mod error;
pub mod estimate;
pub mod neumaier;
pub mod parallel;
pub mod rounding;
pub mod timing;

pub use confidence::{ConfidenceInterval, QuantileSource, STUDENT_T_BELOW};
pub use error::StatisticsError;
pub use estimate::Estimate;
pub use neumaier::NeumaierSum;
pub use parallel::{
    run_chunked, run_chunked_merge, run_chunked_timed, run_samples, Mergeable, TimedEstimate,
    BATCH_CHUNKS,
};
pub use timing::Timing;
