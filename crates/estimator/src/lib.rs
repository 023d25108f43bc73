//! # lambert-estimator
//!
//! Monte Carlo estimation of irradiance E = ∫ L cos θ dω, and the tools that
//! check estimators and samplers: radiometric quantities and solid angles
//! ([`radiometry`]), emitters ([`emitter`]) and their closed-form irradiance
//! ([`analytic`]), estimation strategies ([`strategy`]) and runs
//! ([`estimation`]), streaming statistics ([`statistics`]), and the
//! chi-square goodness-of-fit test for direction samplers
//! ([`goodness_of_fit`]).

pub mod analytic;
pub mod builtin;
pub mod emitter;
pub mod estimation;
pub mod geometry;
pub mod goodness_of_fit;
pub mod radiometry;
pub mod receiver;
pub mod scene;
pub mod statistics;
pub mod strategy;
pub mod study;

pub use emitter::{Emitter, EmitterError};
pub use receiver::Receiver;
pub use scene::{Scene, SceneError};
pub use statistics::{
    run_chunked, run_samples, ConfidenceInterval, Estimate, NeumaierSum, StatisticsError, Timing,
};
