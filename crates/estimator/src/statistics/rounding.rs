//! The rounding floor: a bound on the floating-point error of an
//! accumulated mean of non-negative samples, below which no standard error
//! is reported.
//!
//! When every sample has (nearly) the same value, as with light sampling of
//! a cap 1e-7 rad wide (values agreeing to ~1e-17 relative), the sample
//! standard error s/√N can fall below the rounding error of the mean
//! itself: an interval `m ± q·s/√N` would then claim more digits than the
//! arithmetic produced. The estimators therefore report
//! `max(s/√N, floor)`, with `floor` this bound.
//!
//! **The bound.** Let u = 2⁻⁵³ (the unit roundoff of f64), x₁ … x_N ≥ 0 the
//! computed sample values and m = Σxᵢ/N their exact mean. The estimators
//! form m̂ as follows, and each step's error is bounded (Higham, *Accuracy
//! and Stability of Numerical Algorithms*, 2nd ed., 2002, §2.2 and §4.3):
//!
//! 1. Each chunk's sum ([`Estimate::from_values`](super::Estimate::from_values)):
//!    plain sums of at most k = 16 values per lane and window, within
//!    γ₁₅·(their sum) of exact, γ_j = j·u/(1 − j·u) (Higham §4.2, for terms
//!    ≥ 0); the window sums then join compensated (Neumaier 1974) lane
//!    totals, which merge compensated, as do the chunks, kept as an
//!    unevaluated pair s + c: the pair is the exact sum of what it was
//!    given up to the roundings of the compensation term, ≤ 2N·u²·Σ (each
//!    of at most 2N additions into c rounds a term no larger than u·Σ).
//!    Together |(s + c) − Σxᵢ| ≤ (γ₁₅ + 2N·u²·(1 + γ₁₅))·Σxᵢ
//!    ≤ (15u + 226u² + 2(N + 1)·u²)·Σxᵢ. (A chunk of equal values is summed
//!    exactly, and one with a negative value fully compensated: both within
//!    this.)
//! 2. The mean of the pair as a double-length `hi + lo` ([`Estimate`](super::Estimate)
//!    module docs): `hi = fl(s/N)` with an exact remainder, `lo` rounded, so
//!    a relative error ≤ 2u²; then one rounding of hi + lo: ≤ u.
//! 3. Randomized QMC only: each of R replicate means (steps 1–2), times its
//!    sample count (one rounding, u), summed compensated (≤ u + O(R u²)
//!    after the final rounding of s + c) and divided by N (u): together ≤ 3u
//!    more.
//! 4. Adding the exactly known irradiance δ of the delta lights: one
//!    rounding, ≤ u·(m + |δ|).
//!
//! With Σ|xᵢ| = N·m (the values are non-negative), the total is at most
//!
//! ```text
//! |m̂ − (m + δ)| ≤ (21u + 4(N + 2)·u²) · (m + |δ|)  =: floor,
//! ```
//!
//! (the 20u of steps 1–4 plus one u that holds the 226u² of γ₁₅ and the
//! products of the steps' small factors), which is ≈ 2.3e-15 relative for
//! any N below 2⁴⁰. Until the chunk sums took plain adds within windows
//! (for speed: `Estimate::from_values`) step 1 was fully compensated and
//! the floor 5u + 4(N + 2)u². It bounds the
//! arithmetic of the accumulation only: each sample value carries the
//! rounding error of its own evaluation (a few u relative for the samplers
//! of this crate, some of it shared by every sample), which no averaging
//! removes and which the floor does not claim to bound; the tests check the
//! intervals against closed forms accurate to a few u on the cases where
//! the floor binds.

/// The unit roundoff of f64, u = 2⁻⁵³.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// The rounding floor of the module docs: a bound on |m̂ − (m + δ)|, the
/// floating-point error of a mean of `n` non-negative sample values
/// accumulated as this crate does (chunk sums in windows of plain adds, merged compensated in order,
/// optionally R randomized-QMC replicates, plus the delta lights' δ), where
/// `magnitude` = m + |δ|:
///
/// ```text
/// floor = (21u + 4(n + 2)·u²) · magnitude,   u = 2⁻⁵³.
/// ```
///
/// ```
/// use lambert_estimator::statistics::rounding::mean_rounding_floor;
/// // π from 2²⁰ samples: about 7.3e-15.
/// let floor = mean_rounding_floor(std::f64::consts::PI, 1 << 20);
/// assert!(floor > 7.3e-15 && floor < 7.4e-15);
/// ```
pub fn mean_rounding_floor(magnitude: f64, n: u64) -> f64 {
    let u = UNIT_ROUNDOFF;
    (21.0 * u + 4.0 * (n as f64 + 2.0) * u * u) * magnitude.abs()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statistics::Estimate;

    /// The bound holds, with room, on the accumulation's worst practical
    /// case here: 2²⁰ values spread over 30 binades (every one rounds in the
    /// sum), against the exact mean from an integer (i128) sum of their
    /// mantissas scaled to a common exponent.
    #[test]
    fn bounds_the_error_of_a_compensated_mean() {
        let n = 1u64 << 20;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let values: Vec<f64> = (0..n)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let mantissa = (state >> 11) as f64; // < 2⁵³, exact
                let exponent = (state % 30) as i32;
                mantissa * 2f64.powi(exponent - 60)
            })
            .collect();
        // Exact sum: every value is k·2^(e − 60) with integer k < 2⁵³ and
        // e < 30, so k·2^e is an integer below 2⁸³ and the sum fits i128.
        let exact: i128 = values.iter().map(|&x| (x * 2f64.powi(60)) as i128).sum();
        let exact_mean = exact as f64 / 2f64.powi(60) / n as f64;
        let mut e = Estimate::new();
        for chunk in values.chunks(4096) {
            e.merge(&Estimate::from_values(chunk));
        }
        let m = e.mean().unwrap();
        let floor = mean_rounding_floor(m, n);
        // exact_mean itself carries two roundings (the i128 → f64
        // conversion and the division): ≤ 2u relative.
        let slack = 2.0 * UNIT_ROUNDOFF * exact_mean;
        assert!(
            (m - exact_mean).abs() <= floor + slack,
            "{m} {exact_mean} {floor}"
        );
    }
}
