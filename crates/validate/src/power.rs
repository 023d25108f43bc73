//! The power of a chi-square test: the probability that it rejects a
//! sampler whose true cell probabilities qᵢ differ from the claimed pᵢ.
//!
//! For n samples the statistic X² = Σ (Oᵢ − n pᵢ)²/(n pᵢ) is then
//! asymptotically noncentral χ² with k − 1 degrees of freedom and
//! noncentrality λ = n Σ (qᵢ − pᵢ)²/pᵢ (Patnaik 1949; Cochran 1952), so the
//! power at level α is P(χ²′(k − 1, λ) > x_α), x_α the central χ²'s upper-α
//! point. The noncentral survival function is the Poisson mixture of
//! central ones,
//!
//! P(χ²′(ν, λ) > x) = Σⱼ e^{−λ/2} (λ/2)ʲ / j! · P(χ²(ν + 2j) > x)
//!
//! (Johnson, Kotz & Balakrishnan, *Continuous Univariate Distributions*,
//! vol. 2, ch. 29), summed here over the Poisson weights that matter.
//!
//! ```
//! use lambert_validate::power::{
//!     chi_square_power, critical_value, noncentral_chi_square_sf, noncentrality,
//! };
//! use statrs::distribution::{ChiSquared, ContinuousCDF};
//! // The critical value is the upper-α point to ~1e-12 of α.
//! let x = critical_value(255.0, 1e-4);
//! assert!((ChiSquared::new(255.0).unwrap().sf(x) / 1e-4 - 1.0).abs() < 1e-10);
//! // λ = 0 is the central distribution: P(χ²(2) > 2 ln 2) = ½, and the
//! // power against no departure is the level itself.
//! assert!((noncentral_chi_square_sf(2.0 * 2f64.ln(), 2.0, 0.0) - 0.5).abs() < 1e-14);
//! assert!((chi_square_power(255.0, 0.0, 0.01) - 0.01).abs() < 1e-10);
//! // Two cells claimed ½, ½, truly 0.51, 0.49, with 10⁶ samples:
//! // λ = n · 2 · 0.01²/0.5 = 400, found at any reasonable level.
//! let lambda = noncentrality(&[0.51, 0.49], &[0.5, 0.5], 1_000_000);
//! assert!((lambda - 400.0).abs() < 1e-6);
//! assert!(chi_square_power(1.0, lambda, 1e-4) > 0.999);
//! ```

use statrs::distribution::{ChiSquared, ContinuousCDF};
use statrs::function::gamma::ln_gamma;

/// P(χ²′(ν, λ) > x): the survival function of the noncentral χ²
/// distribution with `dof` = ν > 0 degrees of freedom and noncentrality
/// `lambda` = λ ≥ 0, by the Poisson mixture (module docs), the terms within
/// 12 standard deviations of the Poisson mean λ/2 (the rest weigh < 1e-30).
/// NaN for invalid arguments.
pub fn noncentral_chi_square_sf(x: f64, dof: f64, lambda: f64) -> f64 {
    if !(dof > 0.0 && dof.is_finite() && lambda >= 0.0 && lambda.is_finite()) || x.is_nan() {
        return f64::NAN;
    }
    if x <= 0.0 {
        return 1.0;
    }
    let central = |nu: f64| ChiSquared::new(nu).map_or(f64::NAN, |d| d.sf(x));
    if lambda == 0.0 {
        return central(dof);
    }
    // Far below the mean ν + λ (more than 40 standard deviations): 1 to
    // far beyond f64's resolution, and the mixture would need ~λ terms.
    let sd = (2.0 * (dof + 2.0 * lambda)).sqrt();
    if x < dof + lambda - 40.0 * sd {
        return 1.0;
    }
    let mu = 0.5 * lambda;
    let spread = 12.0 * mu.sqrt() + 12.0;
    let first = (mu - spread).max(0.0).floor() as u64;
    let last = (mu + spread).ceil() as u64;
    let mut sum = 0.0;
    for j in first..=last {
        let jf = j as f64;
        let log_weight = -mu + jf * mu.ln() - ln_gamma(jf + 1.0);
        sum += log_weight.exp() * central(dof + 2.0 * jf);
    }
    sum.min(1.0)
}

/// The upper-α point x_α of the χ² distribution with `dof` degrees of
/// freedom, P(χ²(dof) > x_α) = α: statrs' inverse cdf (accurate to about
/// 1 % of α in the far tail) refined by Newton steps on the survival
/// function, x ← x + (sf(x) − α)/f(x), to ~1e-12 of α. NaN for invalid
/// arguments.
pub fn critical_value(dof: f64, alpha: f64) -> f64 {
    let Ok(d) = ChiSquared::new(dof) else {
        return f64::NAN;
    };
    if !(alpha > 0.0 && alpha < 1.0) {
        return f64::NAN;
    }
    // The χ² density in logs (statrs' own overflows to ∞ for ~250 dof).
    let half = 0.5 * dof;
    let density =
        |x: f64| ((half - 1.0) * x.ln() - 0.5 * x - half * 2f64.ln() - ln_gamma(half)).exp();
    let mut x = d.inverse_cdf(1.0 - alpha);
    for _ in 0..8 {
        let step = (d.sf(x) - alpha) / density(x);
        if !step.is_finite() {
            break;
        }
        x += step;
        if step.abs() <= 1e-14 * x {
            break;
        }
    }
    x
}

/// The power of a chi-square test with `dof` degrees of freedom at level
/// `alpha` against noncentrality `lambda`: P(χ²′(dof, λ) > x_α), x_α the
/// [`critical_value`].
pub fn chi_square_power(dof: f64, lambda: f64, alpha: f64) -> f64 {
    noncentral_chi_square_sf(critical_value(dof, alpha), dof, lambda)
}

/// The noncentrality λ = n Σ (qᵢ − pᵢ)²/pᵢ of a chi-square test of n
/// samples whose cells have true probabilities `truth` (qᵢ) and claimed
/// probabilities `claimed` (pᵢ), over the cells with pᵢ > 0 (cells with
/// pᵢ = 0 and qᵢ > 0 are immediate failures, not part of λ).
pub fn noncentrality(truth: &[f64], claimed: &[f64], n: u64) -> f64 {
    n as f64
        * truth
            .iter()
            .zip(claimed)
            .filter(|(_, &p)| p > 0.0)
            .map(|(&q, &p)| (q - p) * (q - p) / p)
            .sum::<f64>()
}
