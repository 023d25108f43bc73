//! Estimates of scenes whose emitters are too strong for f64 sums.
//!
//! An estimate sums its samples' values and, for the variance, their
//! squared deviations. A sky of radiance 5e307 (E = π·5e307 = 1.57e308, an
//! ordinary f64) gives samples of 1.57e308 whose sum over 64 samples
//! overflows; any sample value above ≈ 1.3e154 overflows its squared
//! deviation. Yet irradiance is linear in every emitter's strength (its
//! radiance, intensity or irradiance): E(s·scene) = s·E(scene), and the
//! same holds for every sample's value, the standard error, the interval
//! and the per-sample variance (times s²).
//!
//! So a scene whose strongest emitter exceeds [`SCALE_ABOVE`] is estimated
//! with every emitter's strength multiplied by s = 2⁻ᵏ, which brings the
//! strongest into [1, 2), and the report is multiplied back by 2ᵏ. A
//! power of two multiplies exactly while values stay in the normal range,
//! and every step of the estimate (sums, the two-pass variance, square
//! roots, MIS weights, which are ratios of densities, the honest interval's
//! bounds and rounding floor) commutes with it, so the report is, to the
//! bit, that of the unscaled estimate wherever that one does not overflow
//! (tested: a scene at 2¹⁰⁰ times the strength gives the estimate at 1
//! times 2¹⁰⁰, bit for bit). What it cannot keep: an emitter more than
//! ≈ 2¹⁰⁰⁰ weaker than the strongest lands in the subnormals or at 0, a
//! contribution below 1e-300 of the total. Where the unscaled answer
//! itself leaves the f64 range, the estimate is an
//! [`EstimateError::Overflow`] naming the quantity.

use crate::estimation::{EstimateError, EstimateReport};
use lambert_light::scene::Scene;

/// Scenes whose strongest emitter is stronger than this (2⁶⁴ ≈ 1.8e19) are
/// estimated scaled. Below it no sample value of an ordinary scene comes
/// near the ≈ 1.3e154 where squared deviations overflow, and the scene is
/// estimated as given.
pub const SCALE_ABOVE: f64 = 18_446_744_073_709_551_616.0;

/// The power of two 2ᵏ by which a scene's strengths are divided: k = 0
/// (no scaling) unless the strongest emitter exceeds [`SCALE_ABOVE`], else
/// the exponent that brings it into [1, 2).
pub fn strength_exponent(scene: &Scene) -> i32 {
    let strongest = scene
        .emitters
        .iter()
        .map(|e| e.strength())
        .fold(0.0f64, f64::max);
    if strongest > SCALE_ABOVE && strongest.is_finite() {
        // The binary exponent of a normal f64: its biased exponent bits.
        ((strongest.to_bits() >> 52) & 0x7ff) as i32 - 1023
    } else {
        0
    }
}

/// The scene with every emitter's strength multiplied by 2⁻ᵏ.
pub fn scaled_scene(scene: &Scene, k: i32) -> Scene {
    let factor = 2f64.powi(-k);
    Scene {
        receiver: scene.receiver,
        emitters: scene
            .emitters
            .iter()
            .map(|e| e.with_strength_scaled(factor))
            .collect(),
    }
}

/// The report of the scaled scene multiplied back by 2ᵏ (its variance by
/// 2²ᵏ, saturating at f64::MAX), or the quantity that leaves the f64 range.
pub fn unscaled_report(report: EstimateReport, k: i32) -> Result<EstimateReport, EstimateError> {
    let factor = 2f64.powi(k);
    // The upper end is already f64::MAX where the bound on one sample's
    // value overflows (the report's docs); it stays so when scaling carries
    // it past the range.
    let upper = (report.ci99.1 * factor).min(f64::MAX);
    let scaled = EstimateReport {
        mean: report.mean * factor,
        std_error: report.std_error * factor,
        ci99: (report.ci99.0 * factor, upper),
        // V ~ E² leaves the range once E ≳ 1e154 although E does not: V is
        // reported saturated at f64::MAX (its docs say so); the estimate,
        // its standard error and interval are what an estimate is for.
        sample_variance: (report.sample_variance * factor * factor).min(f64::MAX),
        ..report
    };
    for (value, quantity) in [
        (scaled.mean, "the estimate"),
        (scaled.std_error, "the standard error"),
        (scaled.ci99.0, "the interval's lower end"),
        (scaled.ci99.1, "the interval's upper end"),
    ] {
        if !value.is_finite() {
            return Err(EstimateError::Overflow { quantity });
        }
    }
    Ok(scaled)
}

/// An error of the scaled scene's estimate in the scene's own units: a
/// non-finite sample's values multiplied back by 2ᵏ.
pub fn unscaled_error(error: EstimateError, k: i32) -> EstimateError {
    let factor = 2f64.powi(k);
    match error {
        EstimateError::NonFiniteSample {
            emitter,
            kind,
            sample,
            randomization,
            value,
            total,
        } => EstimateError::NonFiniteSample {
            emitter,
            kind,
            sample,
            randomization,
            value: value * factor,
            total: total * factor,
        },
        other => other,
    }
}
