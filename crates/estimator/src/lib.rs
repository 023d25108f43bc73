//! # lambert-estimator
//!
//! Monte Carlo estimation of irradiance E = ∫ L cos θ dω, and the tools that
//! check estimators and samplers: the chi-square goodness-of-fit test for
//! direction samplers.

pub mod emitter;
pub mod geometry;
pub mod goodness_of_fit;
pub mod receiver;
pub mod strategy;

pub use emitter::{Emitter, EmitterError};
pub use receiver::Receiver;
