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
//!   series in v = 2u (S = (v − sin v)/2), so the result keeps full
//!   relative precision.
//! - γ > π/2: P = π − P(−a, π − γ) (the complement cap).
//!
//! # Precision: what is computed in double-double, and why
//! - **The depth sin γ − |cos β|.** A cap that barely shows (its centre
//!   below the horizon, a sliver of angular height f·γ above it) or barely
//!   clears the horizon has W² = (sin γ − |cos β|)(sin γ + |cos β|) with
//!   sin γ − |cos β| ≈ f·γ: rounding cos β and sin γ to f64 (ε ≈ 1.1e-16
//!   of sin γ each) would make it wrong by ε/f relative. The callers
//!   compute cos β from the exact f64 inputs (an exact dot product rounded
//!   to a double-double, divided by the exactly normalised lengths) and
//!   sin γ, cos γ in double-double, so that the depth, formed as
//!   sin γ·(1 − |cos β|/sin γ), is exact to ~1e-32 of sin γ.
//! - **The two terms when the centre is below the horizon (β > π/2).**
//!   They have opposite signs and cancel: S(φ₀) and sin²γ |cos β| S(τ)
//!   agree to about a fraction f of themselves (both ≈ (2/3)W³ for small
//!   f). That cancellation is inherent in the formula, and the terms are
//!   then evaluated in double-double (atan2, S), whose 106 bits leave
//!   ~1e-32/f relative: 1e-20 at f = 1e-12. This path is taken only when
//!   the f64 terms cancel by more than a factor 16; otherwise the f64
//!   evaluation (from the double-double inputs, rounded) is within a few
//!   ulps times that factor.
//!
//! Cost: the exact cos β is ~0.1 µs; the double-double terms of a
//! barely-showing cap ~1–2 µs.
//!
//! Tiny caps: the result is returned as P/sin²γ (at most π) and sin γ, and
//! S(φ₀)/sin²γ is formed as (S(φ₀)/φ₀³)·φ₀·(φ₀/sin γ)², so that nothing
//! underflows for sin γ down to ~1e-290.

use super::double_double::{self as dd, Dd, PI as PI_DD};
use std::f64::consts::PI;

/// (v − sin v), without cancellation for small v: v³ times the series of
/// [`v_minus_sin_over_cube`] below |v| = 1.5, direct above
/// (v − sin v > 0.5 v/1.5 there).
pub(crate) fn v_minus_sin(v: f64) -> f64 {
    if v.abs() >= 1.5 {
        return v - v.sin();
    }
    v_minus_sin_over_cube(v) * v * v * v
}

/// The circular segment function S(u) = u − sin u cos u = (2u − sin 2u)/2.
#[inline]
pub(crate) fn segment(u: f64) -> f64 {
    0.5 * v_minus_sin(2.0 * u)
}

/// (v − sin v)/v³ for any v (1/6 at 0), bounded, so that it neither
/// underflows nor loses digits for tiny v: the series 1/3! − v²/5! + …
/// below |v| = 1.5 (terms decrease by ≥ 2.25/20 each, summed to 1e-18
/// relative), the quotient above.
pub(crate) fn v_minus_sin_over_cube(v: f64) -> f64 {
    if v.abs() >= 1.5 {
        return (v - v.sin()) / (v * v * v);
    }
    let v2 = v * v;
    let mut term: f64 = 1.0 / 6.0;
    let mut sum = 0.0f64;
    let mut k = 1.0;
    while term.abs() > 1e-18 * sum.abs() {
        sum += term;
        term *= -v2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        k += 1.0;
    }
    sum
}

/// S(u)/u³ = 4(v − sin v)/v³ with v = 2u (2/3 at 0).
fn segment_over_cube(u: f64) -> f64 {
    4.0 * v_minus_sin_over_cube(2.0 * u)
}

/// S(u) in double-double.
fn segment_dd(u: Dd) -> Dd {
    dd::v_minus_sin(u.mul_f64(2.0)).mul_f64(0.5)
}

/// S(u)/u³ in double-double.
fn segment_over_cube_dd(u: Dd) -> Dd {
    dd::v_minus_sin_over_cube(u.mul_f64(2.0)).mul_f64(4.0)
}

/// The angles of a cap relative to the receiver, each to double-double
/// precision from the caller's exact inputs: cos β (axis against the
/// normal), sin γ ≥ 0 and cos γ (half-angle), and cos β / sin γ (which a
/// sphere has directly as n·(c − p)/(|n| r), without forming the tiny
/// sin γ first).
#[derive(Clone, Copy, Debug)]
pub(crate) struct CapAngles {
    pub(crate) cos_beta: Dd,
    pub(crate) sin_gamma: Dd,
    pub(crate) cos_gamma: Dd,
    pub(crate) cos_beta_over_sin_gamma: Dd,
}

impl CapAngles {
    /// From cos β, sin γ and cos γ taken as exact.
    pub(crate) fn new(cos_beta: Dd, sin_gamma: Dd, cos_gamma: Dd) -> CapAngles {
        let ratio = if sin_gamma.hi > 0.0 {
            cos_beta / sin_gamma
        } else {
            Dd::from(f64::INFINITY * cos_beta.hi.signum())
        };
        CapAngles {
            cos_beta,
            sin_gamma,
            cos_gamma,
            cos_beta_over_sin_gamma: ratio,
        }
    }
}

/// The projected solid angle (sr) of a cap of directions of half-angle γ
/// ∈ [0, π] whose axis makes angle β ∈ [0, π] with the receiver's normal,
/// clipped to the receiver's hemisphere: P = ∫_{cap ∩ H²(n)} cos θ dω
/// (closed form; see the module docs for the formula, its derivation and
/// its precision).
///
/// The angles are passed as sines and cosines, taken as exact, so that
/// callers keep the precision they have (a sphere of radius r at distance
/// d has sin γ = r/d and cos γ = √((d − r)(d + r))/d; cos β = n·a).
/// sin γ ≥ 0 with sin²γ + cos²γ = 1; cos β ∈ [−1, 1].
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
    let (q, s) = cap_over_sin2(&CapAngles::new(
        Dd::from(cos_beta),
        Dd::from(sin_gamma),
        Dd::from(cos_gamma),
    ));
    q * s * s
}

/// The f64 fast path for a cap (γ ≤ π/2) clearly off the horizon, from
/// f64 values of cos β (absolute error ≤ 8u, u = 2⁻⁵³, as formed by the
/// callers from normalised f64 vectors) and sin γ (relative error ≤ 4u):
/// wholly above with cos β ≥ 1/4 gives (π cos β, sin γ), relative error
/// ≤ 40u; wholly below gives 0. `None` when the cap may cross the horizon
/// or cos β is small (its absolute error would matter): the caller then
/// takes the exact path.
pub(crate) fn clear_of_horizon(cos_beta: f64, sin_gamma: f64) -> Option<(f64, f64)> {
    let e = 4.0 * f64::EPSILON; // 8u
    let margin = sin_gamma * (1.0 + e) + e;
    if cos_beta >= margin && cos_beta >= 0.25 {
        Some((PI * cos_beta, sin_gamma))
    } else if cos_beta <= -margin {
        Some((0.0, sin_gamma))
    } else {
        None
    }
}

/// Caps with sin γ below this (2⁻⁷²⁰) are points (see [`cap_over_sin2`]).
const TINY: f64 = 1.813_022_199_912_223_6e-217;

/// (q, s) with P = q·s²: (P/sin²γ, sin γ) for γ ≤ π/2 (P ≤ π sin²γ, so q
/// ≤ π and does not underflow for tiny caps), (P, 1) for γ > π/2; the
/// caller forms L·q·s·s without intermediate underflow.
pub(crate) fn cap_over_sin2(a: &CapAngles) -> (f64, f64) {
    let sg = a.sin_gamma;
    if a.cos_gamma.hi < 0.0 || !(sg.hi > 0.0) {
        if a.cos_gamma.hi >= 0.0 {
            return (0.0, 1.0); // γ = 0
        }
        // The complement: the cap about −a of half-angle π − γ (same
        // sin γ, cos γ negated); P = π − its P, in double-double (it may
        // be close to π).
        let complement = CapAngles {
            cos_beta: -a.cos_beta,
            sin_gamma: sg,
            cos_gamma: -a.cos_gamma,
            cos_beta_over_sin_gamma: -a.cos_beta_over_sin_gamma,
        };
        let p_small = if sg.hi > 0.0 {
            small_cap_dd(&complement) * sg.square()
        } else {
            Dd::ZERO
        };
        return ((PI_DD - p_small).to_f64().max(0.0), 1.0);
    }
    let s = sg.to_f64();
    if s < TINY {
        // A cap this small is a point: wholly above, P = π sin²γ cos β;
        // otherwise P ≤ (1 + π) sin³γ < 2⁻²¹⁵⁷, and L·P < 2¹⁰²⁴·2⁻²¹⁵⁷ is
        // below half the smallest f64 for any finite L (and cos β / sin γ
        // could overflow).
        return if (a.cos_beta - sg).at_least(0.0) {
            (PI * a.cos_beta.to_f64(), s)
        } else {
            (0.0, s)
        };
    }
    let cbt = a.cos_beta_over_sin_gamma;
    if cbt.at_least(1.0) {
        return (PI * a.cos_beta.to_f64(), s);
    }
    if cbt.at_most(-1.0) {
        return (0.0, s);
    }
    // Straddling, in f64 from the double-double inputs: W̃ = W/sin γ.
    let wt = ((Dd::ONE - cbt.abs()) * (Dd::ONE + cbt.abs()))
        .sqrt()
        .to_f64();
    let (c, t) = (a.cos_gamma.to_f64(), cbt.to_f64());
    let phi0 = (s * wt).atan2(c);
    let tau = wt.atan2(-c * t);
    let first = segment_over_cube(phi0) * phi0 * (phi0 / s) * (phi0 / s);
    let q = first + t * s * segment(tau);
    if t >= 0.0 || first <= 16.0 * q {
        return (q.max(0.0), s);
    }
    (small_cap_dd(a).to_f64().max(0.0), s)
}

/// P/sin²γ for γ ≤ π/2, sin γ > 0, in double-double throughout.
fn small_cap_dd(a: &CapAngles) -> Dd {
    let (sg, cg, cbt) = (a.sin_gamma, a.cos_gamma, a.cos_beta_over_sin_gamma);
    if cbt.at_least(1.0) {
        return PI_DD * a.cos_beta;
    }
    if cbt.at_most(-1.0) {
        return Dd::ZERO;
    }
    let wt = ((Dd::ONE - cbt.abs()) * (Dd::ONE + cbt.abs())).sqrt();
    let phi0 = Dd::atan2(sg * wt, cg);
    let tau = Dd::atan2(wt, -(cg * cbt));
    let ratio = phi0 / sg;
    segment_over_cube_dd(phi0) * phi0 * ratio.square() + cbt * sg * segment_dd(tau)
}
