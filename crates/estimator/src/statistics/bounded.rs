//! Confidence bounds that need no central limit theorem: on a hit
//! probability from a count of hits, and on the mean of bounded,
//! non-negative values.
//!
//! **The bound.** For independent X₁ … X_N in [0, 1] with mean μ and sample
//! mean X̄ (Hoeffding 1963, "Probability inequalities for sums of bounded
//! random variables", JASA 58, Theorem 1, in its relative-entropy form; for
//! Bernoulli values it is Chernoff's 1952 bound on the binomial tail):
//!
//! ```text
//! P(X̄ ≥ μ + t) ≤ exp(−N·KL(μ + t ‖ μ)),   P(X̄ ≤ μ − t) ≤ exp(−N·KL(μ − t ‖ μ)),
//! KL(a ‖ b) = a ln(a/b) + (1 − a) ln((1 − a)/(1 − b)).
//! ```
//!
//! Inverted, the one-sided bounds at level 1 − α are
//!
//! ```text
//! μ_U = max{ μ ≥ X̄ : N·KL(X̄ ‖ μ) ≤ ln(1/α) },   μ_L = min{ μ ≤ X̄ : N·KL(X̄ ‖ μ) ≤ ln(1/α) },
//! ```
//!
//! found by bisection (KL(X̄ ‖ μ) grows monotonically as μ leaves X̄) and
//! rounded outward. They hold for every N and every distribution on
//! [0, 1]: no normal approximation, so they stay valid with 0, 1 or 5 hits,
//! where `m ± q·s/√N` does not (with 0 hits s = 0 and that interval is the
//! single point 0).
//!
//! **Zero hits.** With X̄ = 0, N·KL(0 ‖ μ) = −N ln(1 − μ), so
//! μ_U = 1 − α^{1/N} exactly (formed as −expm1(ln α / N)), which is at most
//! −ln α / N: the familiar "rule of three" (−ln 0.05 ≈ 3) for a probability
//! never observed, P(0 hits) = (1 − p)^N ≤ α ⇒ p ≤ −ln α / N. A value
//! bounded by B that is non-zero only on a hit has mean ≤ B·p, hence at most
//! B·(1 − α^{1/N}) with confidence 1 − α.
//!
//! The binomial bound is Chernoff's relaxation of the exact (Clopper–Pearson
//! 1934) bound, slightly wider for k > 0 and equal for k = 0; we use it for
//! one mechanism that covers both hit counts and bounded means, computed
//! without an incomplete-beta inversion at N up to 2⁴⁰.

/// KL(a ‖ b) for a ∈ [0, 1], b ∈ (0, 1), without cancellation in the
/// (1 − a), (1 − b) factors (`ln_1p`); +∞ at b = 1 for a < 1.
#[inline]
fn relative_entropy(a: f64, b: f64) -> f64 {
    let mut d = 0.0;
    if a > 0.0 {
        d += a * (a / b).ln();
    }
    if a < 1.0 {
        d += (1.0 - a) * ((-a).ln_1p() - (-b).ln_1p());
    }
    d
}

/// The largest μ ∈ [x̄, 1] with n·KL(x̄ ‖ μ) ≤ ln(1/α): the upper
/// confidence bound at level 1 − α on the mean of `n` independent values in
/// [0, 1] whose sample mean is `mean` (module docs; Hoeffding 1963).
///
/// With `mean` = 0 it is 1 − α^{1/n} ≤ −ln α / n.
///
/// ```
/// use lambert_estimator::statistics::bounded::upper_bound_01;
/// // No hit in 1000 samples: p ≤ 1 − 0.01^(1/1000) ≈ 4.595e-3 (≤ ln 100 / 1000).
/// let p = upper_bound_01(0.0, 1000, 0.01);
/// assert!((p - 4.595e-3).abs() < 1e-6 && p <= 100f64.ln() / 1000.0);
/// ```
///
/// # Panics
/// In debug builds, unless n ≥ 1 and 0 < α < 1.
pub fn upper_bound_01(mean: f64, n: u64, alpha: f64) -> f64 {
    debug_assert!(n >= 1 && alpha > 0.0 && alpha < 1.0, "n {n}, alpha {alpha}");
    let x = if mean.is_nan() {
        0.0
    } else {
        mean.clamp(0.0, 1.0)
    };
    if x >= 1.0 {
        return 1.0;
    }
    let log_alpha = alpha.ln();
    if x == 0.0 {
        // 1 − α^{1/n}, rounded up by one ulp-sized step.
        let p = -(log_alpha / n as f64).exp_m1();
        return (p * (1.0 + f64::EPSILON)).min(1.0);
    }
    let target = -log_alpha / n as f64;
    let (mut inside, mut outside) = (x, 1.0);
    for _ in 0..256 {
        let mid = 0.5 * (inside + outside);
        if mid <= inside || mid >= outside {
            break;
        }
        if relative_entropy(x, mid) <= target {
            inside = mid;
        } else {
            outside = mid;
        }
    }
    outside
}

/// The smallest μ ∈ [0, x̄] with n·KL(x̄ ‖ μ) ≤ ln(1/α): the lower
/// confidence bound at level 1 − α (mirror of [`upper_bound_01`]). With
/// `mean` = 1 it is α^{1/n}.
///
/// # Panics
/// In debug builds, unless n ≥ 1 and 0 < α < 1.
pub fn lower_bound_01(mean: f64, n: u64, alpha: f64) -> f64 {
    1.0 - upper_bound_01(1.0 - mean.clamp(0.0, 1.0), n, alpha)
}

/// The upper confidence bound on a probability p after `hits` successes
/// in `n` independent trials, at level 1 − α (Chernoff's binomial bound,
/// module docs): `upper_bound_01(hits / n, n, α)`. For 0 hits,
/// 1 − α^{1/n} ≤ −ln α / n.
///
/// ```
/// use lambert_estimator::statistics::bounded::hit_probability_upper;
/// let p0 = hit_probability_upper(0, 1_000_000, 0.01);
/// assert!(p0 <= 100f64.ln() / 1e6 && p0 > 4.6e-6);
/// // More hits, a larger bound; never below the observed fraction.
/// assert!(hit_probability_upper(3, 1_000_000, 0.01) > 3e-6);
/// ```
pub fn hit_probability_upper(hits: u64, n: u64, alpha: f64) -> f64 {
    upper_bound_01(hits as f64 / n as f64, n, alpha)
}

/// A confidence interval at level 1 − α for the mean of `n` independent
/// values in [0, `bound`] whose sample mean is `mean`, valid for any
/// distribution and any n (module docs): two-sided with α/2 per side, and
/// one-sided where the sample mean sits on an end of the range (all values
/// 0, or all equal to `bound`), since the mean cannot leave [0, bound]:
/// `[0, bound·(1 − α^{1/n})]` when every value is 0.
///
/// A non-finite or negative `bound` gives `[0, ∞)`; `bound` = 0 gives
/// `[0, 0]`.
///
/// ```
/// use lambert_estimator::statistics::bounded::bounded_mean_interval;
/// // 10⁵ samples of a value bounded by π, all 0: one-sided.
/// let (lo, hi) = bounded_mean_interval(0.0, std::f64::consts::PI, 100_000, 0.01);
/// assert_eq!(lo, 0.0);
/// assert!(hi <= std::f64::consts::PI * 100f64.ln() / 1e5);
/// ```
pub fn bounded_mean_interval(mean: f64, bound: f64, n: u64, alpha: f64) -> (f64, f64) {
    if !(bound >= 0.0) || !bound.is_finite() {
        return (0.0, f64::INFINITY);
    }
    if bound == 0.0 {
        return (0.0, 0.0);
    }
    let x = (mean / bound).clamp(0.0, 1.0);
    let (lo, hi) = if x == 0.0 {
        (0.0, upper_bound_01(0.0, n, alpha))
    } else if x == 1.0 {
        (lower_bound_01(1.0, n, alpha), 1.0)
    } else {
        (
            lower_bound_01(x, n, 0.5 * alpha),
            upper_bound_01(x, n, 0.5 * alpha),
        )
    };
    // Outward by a few ulps: the scaling by `bound` rounds.
    let widen = 1.0 + 4.0 * f64::EPSILON;
    (
        (lo * bound / widen).max(0.0),
        (hi * bound * widen).min(bound),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Zero hits: the closed form 1 − α^{1/n}, to the ulp-sized outward
    /// step.
    #[test]
    fn zero_hits_give_one_minus_alpha_to_the_one_over_n() {
        for (n, alpha) in [(1u64, 0.01), (10, 0.05), (1 << 20, 0.01), (1 << 40, 1e-3)] {
            let p = upper_bound_01(0.0, n, alpha);
            let exact = 1.0 - alpha.powf(1.0 / n as f64);
            assert!(
                p >= exact && p <= exact * (1.0 + 1e-9) + 1e-16,
                "{n} {alpha}: {p} vs {exact}"
            );
            assert!(p <= -alpha.ln() / n as f64 * (1.0 + 1e-12));
        }
    }

    /// The bound inverts the relative entropy: n·KL(x̄ ‖ μ_U) = ln(1/α) to
    /// 1e-9 relative (bisection to the ulp), and the lower bound mirrors it.
    #[test]
    fn bounds_solve_the_relative_entropy_equation() {
        for (x, n, alpha) in [
            (0.3, 100u64, 0.01),
            (1e-6, 1 << 22, 0.005),
            (0.999, 5000, 0.05),
        ] {
            let hi = upper_bound_01(x, n, alpha);
            let lo = lower_bound_01(x, n, alpha);
            assert!(lo < x && x < hi);
            let target = -f64::ln(alpha);
            let at = |m: f64| n as f64 * relative_entropy(x, m);
            assert!((at(hi) - target).abs() <= 1e-9 * target, "{x}: {}", at(hi));
            assert!((at(lo) - target).abs() <= 1e-9 * target, "{x}: {}", at(lo));
        }
    }

    /// Exact binomial coverage for small n: for every p on a grid, the
    /// probability that the upper bound at α = 0.05 falls below p is at most
    /// 0.05 (the bound is valid, not only asymptotically). The binomial pmf
    /// is summed exactly in f64.
    #[test]
    fn binomial_upper_bound_is_valid_for_small_n() {
        for n in [5u64, 20, 60] {
            for i in 1..200 {
                let p = i as f64 / 200.0;
                let mut fail = 0.0;
                let mut log_pmf = n as f64 * (1.0 - p).ln();
                for k in 0..=n {
                    if hit_probability_upper(k, n, 0.05) < p {
                        fail += log_pmf.exp();
                    }
                    if k < n {
                        log_pmf += ((n - k) as f64 / (k + 1) as f64).ln() + (p / (1.0 - p)).ln();
                    }
                }
                assert!(fail <= 0.05 + 1e-12, "n {n}, p {p}: {fail}");
            }
        }
    }

    #[test]
    fn bounded_interval_edges() {
        assert_eq!(bounded_mean_interval(1.0, 0.0, 10, 0.01), (0.0, 0.0));
        assert_eq!(
            bounded_mean_interval(1.0, f64::INFINITY, 10, 0.01),
            (0.0, f64::INFINITY)
        );
        assert_eq!(
            bounded_mean_interval(1.0, f64::NAN, 10, 0.01),
            (0.0, f64::INFINITY)
        );
        // All values at the bound: one-sided below.
        let (lo, hi) = bounded_mean_interval(2.0, 2.0, 1000, 0.01);
        assert_eq!(hi, 2.0);
        assert!(lo < 2.0 && lo > 2.0 * (1.0 - 100f64.ln() / 1000.0) * (1.0 - 1e-12));
        // Inside: two-sided, containing the mean.
        let (lo, hi) = bounded_mean_interval(0.5, 2.0, 1000, 0.01);
        assert!(lo < 0.5 && 0.5 < hi);
    }
}
