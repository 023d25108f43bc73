//! Two-sided confidence intervals for a mean, `m ± q·s/√n`.

use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

/// Below this many samples, confidence intervals use Student's t quantile
/// with n − 1 degrees of freedom; from it on, the normal quantile
/// ([`ConfidenceInterval`] explains why).
pub const STUDENT_T_BELOW: u64 = 30;

/// The distribution whose quantile sets the half-width of an interval.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum QuantileSource {
    /// Student's t with `dof = n − 1` degrees of freedom (n < [`STUDENT_T_BELOW`]).
    StudentT {
        /// Degrees of freedom, n − 1.
        dof: u64,
    },
    /// The standard normal distribution (n ≥ [`STUDENT_T_BELOW`]).
    Normal,
}

/// A two-sided confidence interval `[m − h, m + h]`, `h = q·s/√n`, for the
/// true mean μ at confidence `level` (so q is the `(1 + level)/2` quantile).
///
/// **Which quantile.** For n < [`STUDENT_T_BELOW`] (= 30), q is Student's t
/// quantile with n − 1 degrees of freedom ("Student", Biometrika 6 (1908)
/// 1–25), the standard allowance for the uncertainty of s with few samples;
/// it is exact only when the samples are normal. From n = 30 on, q is the
/// normal quantile (`statrs::distribution::Normal`, through erfc⁻¹), because
/// (1) a Monte Carlo integrand is rarely normal (bounded, skewed or
/// heavy-tailed), so the t interval is not "exact" either: what makes
/// (m − μ)/(s/√n) ≈ N(0, 1) is the central limit theorem, and the error of
/// that approximation (skewness/√n) dominates the t correction, which is
/// ≈ (1 + q²)/(4(n − 1)) relative; (2) statrs computes the t quantile by
/// iteratively inverting the regularised incomplete beta function, which is
/// slower and untested by us at the n (10⁶–10¹²) of Monte Carlo runs, where
/// it equals the normal quantile to ~1/n anyway. The switch is a documented jump: at n = 30
/// the 99 % half-width drops from t₀.₉₉₅,₂₉ = 2.756 to z₀.₉₉₅ = 2.576 times
/// s/√n (7 %), the 95 % one from 2.045 to 1.960 (4 %).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConfidenceInterval {
    /// The sample mean m, the centre.
    pub mean: f64,
    /// m − h.
    pub lower: f64,
    /// m + h.
    pub upper: f64,
    /// The half-width h = q · s/√n.
    pub half_width: f64,
    /// The confidence level, in (0, 1).
    pub level: f64,
    /// The quantile q.
    pub quantile: f64,
    /// Where q came from.
    pub source: QuantileSource,
}

impl ConfidenceInterval {
    /// The interval `mean ± q·std_error` for `n` samples at `level`, q as in
    /// the type's docs.
    ///
    /// # Panics
    /// In debug builds, unless 0 < level < 1, n ≥ 2 and `std_error` is finite
    /// and ≥ 0 ([`Estimate::confidence_interval`](super::Estimate::confidence_interval)
    /// checks these and returns an error instead).
    pub fn new(mean: f64, std_error: f64, n: u64, level: f64) -> Self {
        debug_assert!(level > 0.0 && level < 1.0, "level {level}");
        debug_assert!(n >= 2, "n = {n}");
        debug_assert!(
            std_error >= 0.0 && std_error.is_finite(),
            "std_error {std_error}"
        );
        let p = 0.5 + 0.5 * level;
        let (quantile, source) = if n < STUDENT_T_BELOW {
            let dof = n - 1;
            let t =
                StudentsT::new(0.0, 1.0, dof as f64).expect("dof ≥ 1 is a valid t distribution");
            (t.inverse_cdf(p), QuantileSource::StudentT { dof })
        } else {
            (Normal::standard().inverse_cdf(p), QuantileSource::Normal)
        };
        let half_width = quantile * std_error;
        Self {
            mean,
            lower: mean - half_width,
            upper: mean + half_width,
            half_width,
            level,
            quantile,
            source,
        }
    }

    /// Whether `x` lies in `[lower, upper]`.
    pub fn contains(&self, x: f64) -> bool {
        self.lower <= x && x <= self.upper
    }
}
