//! # lambert-estimator
//!
//! Monte Carlo estimation of irradiance E = ∫ L cos θ dω, and the tools that
//! check estimators and samplers: radiometric quantities and solid angles
//! ([`radiometry`]), closed-form irradiance from uniform emitters
//! ([`analytic`]) and the chi-square goodness-of-fit test for direction
//! samplers ([`goodness_of_fit`]).

pub mod analytic;
pub mod goodness_of_fit;
pub mod radiometry;
