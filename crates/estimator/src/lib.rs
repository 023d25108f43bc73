//! # lambert-estimator
//!
//! Monte Carlo estimation of irradiance E = ∫ L cos θ dω at a receiver:
//! estimation strategies ([`strategy`]), deterministic parallel runs over
//! any sample sequence ([`estimation`]), estimates at one point of a scene
//! with occluders through a visibility callback ([`point`]), and streaming
//! statistics with honest standard errors ([`statistics`]). Scenes, emitters and closed forms come
//! from `lambert-light`; warps and sequences from `lambert-sampling`.

pub mod chunk;
pub mod clt;
pub mod estimation;
pub mod interval;
pub mod point;
pub mod precision;
pub mod statistics;
pub mod strategy;
pub mod strength_scale;

pub use statistics::{
    run_chunked, run_samples, ConfidenceInterval, Estimate, NeumaierSum, StatisticsError, Timing,
};
