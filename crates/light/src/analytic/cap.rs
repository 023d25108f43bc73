//! The projected solid angle of a spherical cap of directions cut by the
//! receiver's horizon: the core of the sky-cap and sphere formulas.
//!
//! Let the receiver normal be n, the cap's unit axis a at angle β from n
//! (cos β = n·a) and its half-angle γ. Then
//! P = ∫_{cap ∩ {n·ω > 0}} n·ω dω (sr), and E = L P.
//!
//! # Derivation (closed form, Snyder 1996 rewritten without cancellation)
//! P is the area of the region's orthographic projection onto the plane
//! ⊥ n (Nusselt's analogue). For γ ≤ π/2:
//! - cos β ≥ sin γ (wholly above): the cap's rim projects to an ellipse of
//!   semi-axes sin γ cos β and sin γ, so P = π sin²γ cos β (the
//!   disk light π sin²α when β = 0).
//! - cos β ≤ −sin γ (wholly below): P = 0.
//! - otherwise the rim crosses the horizon at azimuths ±φ₀ and the projected
//!   region is the unit disk's circular segment beyond the chord joining
//!   the crossings plus (β < π/2) or minus (β > π/2) the part of the ellipse
//!   on the other side of that chord. With
//!   W = √((sin γ − |cos β|)(sin γ + |cos β|)) (= √(sin²β − cos²γ)),
//!   φ₀ = atan2(W, cos γ), τ = atan2(W, −cos γ cos β) and the segment
//!   function S(u) = u − sin u cos u,
//!
//!   P = S(φ₀) + sin²γ cos β S(τ).
//!
//!   Expanding S gives Snyder's (and Frostbite's, Lagarde & de Rousiers
//!   2014) P = φ₀ + sin²γ cos β τ − W cos γ, which, for a small cap
//!   straddling the horizon, is a difference of terms of order γ giving a
//!   result of order γ³ (all digits lost at γ = 1e-8). Here both terms are
//!   ≥ 0 when β ≤ π/2, and S(u) for small u is summed from its Taylor
//!   series in v = 2u (S = (v − sin v)/2) below v = 1.5, so the result keeps
//!   full relative precision. When the cap's centre is below the horizon
//!   (β > π/2) the two terms have opposite signs; the cancellation factor is
//!   about γ/h with h the angular height of the visible sliver, so a cap
//!   that barely peeks above the horizon loses log₁₀(γ/h) digits (that is
//!   the conditioning of the problem in these variables, not of the
//!   formula's rounding of β).
//! - γ > π/2: P = π − P(−a, π − γ) (the complement cap).

use std::f64::consts::PI;

/// (v − sin v), without cancellation for small v: Taylor series
/// v³/3! − v⁵/5! + … below v = 1.5 (terms decrease by ≥ 2.25/20 each, summed
/// to 1e-17 relative), direct above (v − sin v > 0.5 v/1.5 there).
pub(crate) fn v_minus_sin(v: f64) -> f64 {
    if v.abs() >= 1.5 {
        return v - v.sin();
    }
    let v2 = v * v;
    let mut term = v * v2 / 6.0;
    let mut sum = 0.0f64;
    let mut k = 1.0;
    while term.abs() > 1e-18 * sum.abs() {
        sum += term;
        term *= -v2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        k += 1.0;
    }
    sum
}

/// The circular segment function S(u) = u − sin u cos u = (2u − sin 2u)/2.
#[inline]
pub(crate) fn segment(u: f64) -> f64 {
    0.5 * v_minus_sin(2.0 * u)
}

/// The projected solid angle (sr) of a cap of directions of half-angle γ
/// ∈ [0, π] whose axis makes angle β ∈ [0, π] with the receiver's normal,
/// clipped to the receiver's hemisphere: P = ∫_{cap ∩ H²(n)} cos θ dω
/// (closed form; see the module docs for the formula and its derivation).
///
/// The angles are passed as sines and cosines so that callers keep the
/// precision they have (a sphere of radius r at distance d has
/// sin γ = r/d and cos γ = √((d − r)(d + r))/d exactly to rounding;
/// cos β = n·a). sin γ ≥ 0 with sin²γ + cos²γ = 1 to rounding; cos β ∈ [−1, 1].
///
/// ```
/// use lambert_light::analytic::cap_projected_solid_angle;
/// use std::f64::consts::PI;
/// // A disk light straight overhead is a cap, P = π sin²α.
/// let a: f64 = 0.4;
/// assert!((cap_projected_solid_angle(1.0, a.sin(), a.cos()) - PI * a.sin().powi(2)).abs() < 1e-15);
/// // Half a sky over a vertical receiver: a dome (γ = π/2) tilted by 90°.
/// assert!((cap_projected_solid_angle(0.0, 1.0, 0.0) - PI / 2.0).abs() < 1e-15);
/// ```
pub fn cap_projected_solid_angle(cos_beta: f64, sin_gamma: f64, cos_gamma: f64) -> f64 {
    if cos_gamma < 0.0 {
        // The complement of the cap is the cap about −a of half-angle π − γ.
        return PI - small_cap(-cos_beta, sin_gamma, -cos_gamma);
    }
    small_cap(cos_beta, sin_gamma, cos_gamma)
}

/// γ ≤ π/2.
fn small_cap(cb: f64, sg: f64, cg: f64) -> f64 {
    if cb >= sg {
        return PI * sg * sg * cb;
    }
    if cb <= -sg {
        return 0.0;
    }
    let w = ((sg - cb.abs()) * (sg + cb.abs())).sqrt();
    let phi0 = w.atan2(cg);
    let tau = w.atan2(-cg * cb);
    (segment(phi0) + sg * sg * cb * segment(tau)).max(0.0)
}

/// (P/sin²γ, sin γ) for γ ≤ π/2 (P ≤ π sin²γ, so the quotient is at most
/// π and does not underflow for tiny caps), (P, 1) for γ > π/2: the
/// caller forms L·q·s·s without intermediate underflow.
pub(crate) fn cap_over_sin2(cb: f64, sg: f64, cg: f64) -> (f64, f64) {
    if cg < 0.0 || !(sg > 0.0) {
        return (cap_projected_solid_angle(cb, sg, cg), 1.0);
    }
    if cb >= sg {
        return (PI * cb, sg);
    }
    if cb <= -sg {
        return (0.0, sg);
    }
    // Straddling: P/sg² = S(φ₀)/sg² + cos β S(τ).
    let w = ((sg - cb.abs()) * (sg + cb.abs())).sqrt();
    let phi0 = w.atan2(cg);
    let tau = w.atan2(-cg * cb);
    ((segment(phi0) / sg / sg + cb * segment(tau)).max(0.0), sg)
}
