//! A uniform disk light (one- or two-sided) at any position and tilt.
//!
//! # Vector irradiance of a whole disk (closed form)
//! Put the receiver at the origin, the disk (radius R) in the plane at
//! height h > 0 along ẑ (ẑ = ±m pointing from p towards the disk's plane),
//! its centre at lateral offset s along x̂. The vector
//! J = ∫_Ω ω dω = ∫_disk (x − p) h / r⁴ dA (Arvo 1995's irradiance vector
//! for unit radiance) has, with Q = √((h² + (R − s)²)(h² + (R + s)²)),
//! T = h² + s² − R² and U = h² + R² − s²,
//!
//! - J_z = (π/2)(1 − T/Q) = (π/2)(Q − T)/Q — the classical form factor of a
//!   parallel disk at lateral offset (Howell's catalog, B-13),
//! - J_x = π h s (Q − T) / (Q (Q + U)) (from J_x = −(h/2) ∂H/∂s with
//!   H = ∫_disk dA/r² = π ln((U + Q)/(2h²))).
//!
//! Both are evaluated without cancellation using Q² − T² = 4R²h² and
//! Q² − U² = 4s²h²: Q − T = 4R²h²/(Q + T) when T ≥ 0 (else Q + |T|), and
//! Q + U = 4s²h²/(Q − U) when U < 0. Far lights (h, s ~ 1e6 R) keep full
//! precision: J_z → πR²h²/D⁴ computed as a product, not as 1 − (1 − ε).
//!
//! When the disk lies wholly in the receiver's upper half-space,
//! E = L n·J (closed form). When the receiver's plane cuts it, E is a
//! contour integral over the visible arc of the rim (module `rim`), by a
//! bounded adaptive Gauss–Kronrod quadrature that reports its error bound.
//!
//! # Precision
//! - The rim's height above the receiver's plane, f₀ + R g cos t
//!   (f₀ = n̂·(c − p), g = |n̂ × m̂|), decides what is visible: its top
//!   f₀ + Rg and bottom f₀ − Rg are formed from f₀ as an exact dot product
//!   (double-double) and g from the exact cross product, so a disk 1e12
//!   radii away of which a fraction 1e-12 of the diameter shows (top 1e-12 R
//!   against |c − p| = 1e12 R) has its visible part exact to rounding;
//!   rounding c − p to f64 would move it by ε|c − p|.
//! - A disk wholly above the horizon but low relative to its own angular
//!   size (a far disk just above the horizon) makes n·J a small
//!   difference of J's components (by κ = (|J_z| + |J_x|)/|n·J| ≈ 1/ε at
//!   elevation ε): when κ > 8, the sin²ε contour integral over the whole
//!   rim is evaluated and kept if it cancels by at most 8; otherwise (a far
//!   disk at an intermediate grazing elevation, where the contour cancels
//!   by ε/a, a the angular size) n·J is evaluated in double-double from
//!   the exact c − p and height over the disk's plane, error ~u²κ.
//! - Ordinary disks (clearly above the horizon, not seen nearly edge-on,
//!   κ ≤ 8) take the f64 closed form directly, at the old cost.
//! - Open: a disk cut by the horizon and seen nearly edge-on (the receiver
//!   within δ of its plane, relative to its distance): the rim integral
//!   cancels by ~1/δ; measured 4e-13 at δ = 1e-4, and below δ ≈ 1e-6 its
//!   error bound exceeds [`DISK_RELATIVE_ERROR_LIMIT`] and the answer is
//!   [`AnalyticError::Unresolved`] (with the value and the bound, which
//!   holds).
//! - Lengths are scaled by powers of two (exact), first so that c − p
//!   cannot overflow, then so that max(|c − p|, R) is in [½, 1].

use super::dd_vector::Dd3;
use super::double_double::{Dd, PI as PI_DD};
use super::error::{finite, AnalyticError};
use super::exact_sum;
use super::Emission;
use super::{rim, scaled};
use crate::receiver::Receiver;
use glam::DVec3;
use lambert_geometry::f64::Disk;
use lambert_geometry::{validate, GeometryError};
use std::f64::consts::PI;

/// A uniform disk of radiance L and radius R seen from a receiver on its
/// axis at height h, facing it: E = Lπ sin²α with sin²α = R²/(R² + h²)
/// (Ω⊥ = π sin²α; closed form, no cancellation), formed as
/// L·π·sin α·sin α with sin α = R/√(R² + h²) in lengths scaled by a power
/// of two, so that nothing overflows or underflows on the way.
///
/// Errors: a non-finite radiance or height, a radius that is not finite
/// and positive; [`AnalyticError::Overflow`] when E exceeds f64::MAX.
///
/// ```
/// use lambert_light::analytic::disk_coaxial_irradiance;
/// use std::f64::consts::PI;
/// assert!((disk_coaxial_irradiance(1.0, 1.0, 1.0)? - PI / 2.0).abs() < 1e-15);
/// # Ok::<(), lambert_light::analytic::AnalyticError>(())
/// ```
pub fn disk_coaxial_irradiance(
    radiance: f64,
    height: f64,
    radius: f64,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    finite("height", height)?;
    validate::positive("radius", radius)?;
    let k = power_of_two_above(height.abs().max(radius));
    let (h, r) = (height / k, radius / k);
    let sin_alpha = r / r.hypot(h);
    scaled::product("irradiance", &[radiance, PI, sin_alpha, sin_alpha])
}

/// A uniform disk of radiance L and radius R parallel to the receiver and
/// facing it, at height h, its centre offset laterally by s (closed form):
///
/// E = (Lπ/2)(1 − (h² + s² − R²)/√((h² + R² + s²)² − 4R²s²)),
///
/// evaluated as (Lπ/2)(Q − T)/Q with Q = √((h² + (R − s)²)(h² + (R + s)²))
/// (the same radicand, factored), T = h² + s² − R² and
/// Q − T = 4R²h²/(Q + T) when T ≥ 0: no cancellation for far or tiny disks;
/// lengths scaled by a power of two and E = L·(J_z/R²)·R·R formed without
/// intermediate overflow or underflow.
///
/// Errors: non-finite radiance, height or offset, a radius that is not
/// finite and positive, h = 0 (the receiver in the disk's plane);
/// [`AnalyticError::Overflow`] when E exceeds f64::MAX.
///
/// ```
/// use lambert_light::analytic::{disk_coaxial_irradiance, disk_parallel_offset_irradiance};
/// let (e0, e1) = (disk_parallel_offset_irradiance(1.0, 2.0, 0.0, 1.0)?, disk_coaxial_irradiance(1.0, 2.0, 1.0)?);
/// assert!((e0 - e1).abs() < 1e-15);
/// # Ok::<(), lambert_light::analytic::AnalyticError>(())
/// ```
pub fn disk_parallel_offset_irradiance(
    radiance: f64,
    height: f64,
    offset: f64,
    radius: f64,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    finite("height", height)?;
    finite("offset", offset)?;
    validate::positive("radius", radius)?;
    if height == 0.0 {
        return Err(AnalyticError::Input(GeometryError::OutOfRange {
            field: "height",
            value: height,
            range: "≠ 0 (the receiver is in the disk's plane)",
        }));
    }
    let k = power_of_two_above(height.abs().max(offset.abs()).max(radius));
    let (h, s, r) = (height.abs() / k, offset.abs() / k, radius / k);
    let (jz, _) = disk_vector_over_r2(h, s, r);
    scaled::product("irradiance", &[radiance, jz, r, r])
}

/// An irradiance with the error bound of the bounded numerical step that
/// produced it (0 for pure closed forms, which are exact to a few ulps).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundedIrradiance {
    /// E, W/m².
    pub irradiance: f64,
    /// A bound on |E − E_true| from the quadrature (W/m²), not counting the
    /// few-ulp rounding of the closed-form parts.
    pub error_bound: f64,
}

/// The relative error bound above which [`disk_irradiance`] reports
/// [`AnalyticError::Unresolved`] instead of a value: 1e-9.
pub const DISK_RELATIVE_ERROR_LIMIT: f64 = 1e-9;

/// A uniform `disk` (centre c, unit normal m, radius R) of radiance L,
/// one-sided (emitting towards m) or two-sided, seen from the `receiver` at
/// p with unit normal n.
///
/// Closed form (E = L n·J, module docs) when the disk lies wholly above the
/// receiver's plane (in double-double, or as the rim's sin²ε contour
/// integral, when it lies low and n·J cancels); when the receiver's plane
/// cuts the disk, the contour integral over the visible arc of the rim in
/// the form that does not cancel (sin²ε dφ, with no chord term, for low
/// visible parts; Lambert's cos²ε dφ plus the chord's angle for high
/// ones; see the `rim` module), by Gauss–Kronrod quadrature bounded to
/// 30 720 evaluations. The rim's heights over the receiver's plane are
/// exact (module docs). 0 when the disk is wholly below the horizon, when
/// `p` is in the disk's plane, or when a one-sided disk is seen from
/// behind.
///
/// Lengths are first rescaled by a power of two and then by
/// max(|c − p|, R), so no intermediate overflows or underflows for any
/// finite input; E = L · (P/s²) · s · s (s = R in those units) is formed
/// without intermediate overflow or underflow ([`crate::analytic`]'s
/// `scaled` products): a disk of radius 1e-300 and radiance 1e300 at
/// distance 1 gives π·1e-300.
///
/// Errors: a non-finite radiance;
/// [`AnalyticError::Overflow`] when E exceeds f64::MAX;
/// [`AnalyticError::Unresolved`] when the quadrature's error bound after its
/// work budget exceeds [`DISK_RELATIVE_ERROR_LIMIT`] of the value (see
/// [`disk_irradiance_with_error_bound`] for the value and bound).
///
/// ```
/// use glam::DVec3;
/// use lambert_geometry::f64::Disk;
/// use lambert_light::analytic::{disk_coaxial_irradiance, disk_irradiance, Emission};
/// use lambert_light::Receiver;
/// let disk = Disk::new(DVec3::new(0.0, 0.0, 2.0), -DVec3::Z, 1.0)?;
/// let up = Receiver::new(DVec3::ZERO, DVec3::Z)?;
/// let e = disk_irradiance(&disk, Emission::OneSided, 1.0, &up)?;
/// assert!((e - disk_coaxial_irradiance(1.0, 2.0, 1.0)?).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn disk_irradiance(
    disk: &Disk,
    emission: Emission,
    radiance: f64,
    receiver: &Receiver,
) -> Result<f64, AnalyticError> {
    let b = disk_irradiance_with_error_bound(disk, emission, radiance, receiver)?;
    // A bound below the smallest normal f64 is the subnormal range's own
    // granularity, not an unresolved quadrature.
    if b.error_bound <= DISK_RELATIVE_ERROR_LIMIT * b.irradiance.abs()
        || b.error_bound < f64::MIN_POSITIVE
    {
        Ok(b.irradiance)
    } else {
        Err(AnalyticError::Unresolved {
            what: "the integral over the visible rim of a disk cut by the receiver's plane",
            value: b.irradiance,
            error_bound: b.error_bound,
        })
    }
}

/// [`disk_irradiance`] with the error bound its quadrature achieved
/// (0 when the disk is wholly above or below the horizon: closed form).
/// The work is bounded (at most 30 720 evaluations of the rim integrand);
/// the bound is what was reached, whether or not it met the 1e-14 target.
pub fn disk_irradiance_with_error_bound(
    disk: &Disk,
    emission: Emission,
    radiance: f64,
    receiver: &Receiver,
) -> Result<BoundedIrradiance, AnalyticError> {
    finite("radiance", radiance)?;
    let (p, n) = (receiver.point, receiver.normal);
    let (c, m, r) = (disk.center(), disk.normal(), disk.radius());
    let (q, err, s) = disk_projected(p, n, c, m, r, emission);
    Ok(BoundedIrradiance {
        irradiance: scaled::product("irradiance", &[radiance, q, s, s])?,
        error_bound: scaled::product("irradiance error bound", &[radiance.abs(), err, s, s])?,
    })
}

/// The smallest power of two ≥ x for finite x > 0 (clamped to the normal
/// range, 2⁻¹⁰²² … 2¹⁰²³), 1 for x = 0: dividing by it is exact and
/// brings the largest coordinate into [1/2, 1].
pub(crate) fn power_of_two_above(x: f64) -> f64 {
    if !(x > 0.0) {
        return 1.0;
    }
    let e = x.log2().ceil() as i32;
    // 2^e may be subnormal or 2^1024 (= ∞): clamp to the finite range.
    2f64.powi(e.clamp(-1022, 1023))
}

/// (q, error of q, s) with P = q s² the projected solid angle (sr) of the
/// disk's visible part: s is the radius in units of a power of two near
/// max(|c − p|, R), q is computed in those units (all lengths ≤ 1,
/// nothing overflows).
fn disk_projected(
    p: DVec3,
    n: DVec3,
    c: DVec3,
    m: DVec3,
    r: f64,
    emission: Emission,
) -> (f64, f64, f64) {
    // Exact power-of-two scaling: c − p cannot overflow.
    let k = power_of_two_above(c.abs().max_element().max(p.abs().max_element()).max(r));
    let (c, p, r) = (c / k, p / k, r / k);
    if let Some(q) = clearly_above(c - p, n, m, r, emission) {
        return q;
    }
    // c − p exactly (double-double per component), then a second exact
    // scaling so that max(|c − p|, R) is in [½, 1].
    let v_dd = [Dd::sum(c.x, -p.x), Dd::sum(c.y, -p.y), Dd::sum(c.z, -p.z)];
    let l0 = power_of_two_above(exact_sum::length(v_dd).hi.max(r));
    let v = DVec3::new(v_dd[0].to_f64(), v_dd[1].to_f64(), v_dd[2].to_f64()) / l0;
    let r = r / l0;
    if !(r > 0.0) {
        return (0.0, 0.0, 0.0);
    }
    // The receiver's height over the disk's plane, m̂·(c − p), exactly: a
    // one-sided disk emits towards +m (p must be on that side, hv < 0).
    let (n_len, m_len) = (exact_sum::length_f64(n), exact_sum::length_f64(m));
    let hv_dd = (exact_sum::dot_of_difference(m, c, p) / m_len).div_f64(l0);
    let hv = hv_dd.to_f64();
    if hv == 0.0 || (emission == Emission::OneSided && hv > 0.0) {
        return (0.0, 0.0, r);
    }
    // The disk centre's height over the receiver's plane, n̂·(c − p), and
    // the rim's height amplitude R|n̂ × m̂|, exactly; the rim's top and
    // bottom heights without cancellation.
    let f0 = (exact_sum::dot_of_difference(n, c, p) / n_len).div_f64(l0);
    let g = exact_sum::length(exact_sum::cross(n, m)) / (n_len * m_len);
    let rg = g.mul_f64(r);
    let (top, bottom) = (f0 + rg, f0 - rg);
    if top.at_most(0.0) || r < TINY {
        // A disk this small (r < 2⁻⁷²⁰ with |v| ≈ 1) has P/r² ≤ 4π, so
        // E = L·(P/r²)·r·r < 2¹⁰²⁴·4π·2⁻¹⁴⁴⁰ is below the smallest f64.
        return (0.0, 0.0, r);
    }
    let rim = rim::Rim {
        v,
        n,
        m,
        r,
        f0: f0.to_f64(),
        g: g.to_f64(),
        top: top.to_f64(),
        bottom: bottom.to_f64(),
    };
    if bottom.at_least(0.0) {
        let (closed, kappa) = closed_form_over_r2(v, hv, n, m, r);
        if !(kappa > TRY_CONTOUR_ABOVE) {
            return (closed, 0.0, r);
        }
        if let Some((i, contour_kappa)) = rim.whole_over_r2() {
            if contour_kappa <= ACCEPT_CONTOUR_UP_TO {
                return (i.value, i.error, r);
            }
        }
        // Both cancel (a far disk at a grazing elevation, one seen nearly
        // edge-on): n·J in double-double.
        let inv = Dd::from(1.0 / l0);
        let v_exact = Dd3 {
            x: v_dd[0] * inv,
            y: v_dd[1] * inv,
            z: v_dd[2] * inv,
        };
        return (closed_form_over_r2_dd(v_exact, hv_dd, n, m, r), 0.0, r);
    }
    let i = rim.straddling_over_r2();
    (i.value, i.error, r)
}

/// Disks with radius below this (2⁻⁷²⁰, in units where max(|c − p|, R) is
/// about 1) are too small for any irradiance.
const TINY: f64 = 1.813_022_199_912_223_6e-217;

/// (n·J/R², κ) for a disk wholly above the horizon (module docs), in
/// lengths where max(|v|, R) ≈ 1, with κ = (|J_z| + |J_x|)/|n·J| the factor
/// by which the rounding of J's components (relative to |J|) is amplified.
fn closed_form_over_r2(v: DVec3, hv: f64, n: DVec3, m: DVec3, r: f64) -> (f64, f64) {
    let h = hv.abs();
    let z = m * hv.signum();
    let lateral = v - m * hv;
    let s = lateral.length();
    let (jz, jx) = disk_vector_over_r2(h, s, r);
    let x = if s > 0.0 { lateral / s } else { DVec3::ZERO };
    let (a, b) = (jz * n.dot(z), jx * n.dot(x));
    ((a + b).max(0.0), (jz.abs() + jx.abs()) / (a + b).abs())
}

/// The f64 fast path of [`disk_projected`]: the closed form when the disk
/// is clearly above the horizon (its bottom higher than 16u(|v| + R), the
/// bound on the f64 heights' error), not seen nearly edge-on
/// (|m·v| ≥ |v|/8, so the receiver's height over its plane has a relative
/// error ≤ 40u) and n·J does not cancel (κ ≤ 8); `None` otherwise.
fn clearly_above(
    v: DVec3,
    n: DVec3,
    m: DVec3,
    r: f64,
    emission: Emission,
) -> Option<(f64, f64, f64)> {
    let l0 = power_of_two_above(v.length().max(r));
    let (v, r) = (v / l0, r / l0);
    let d = v.length();
    let hv = m.dot(v);
    let bottom = n.dot(v) - r * n.cross(m).length();
    if !(r > 0.0 && hv.abs() >= d / 8.0 && bottom > 8.0 * f64::EPSILON * (d + r)) {
        return None;
    }
    if emission == Emission::OneSided && hv > 0.0 {
        return Some((0.0, 0.0, r));
    }
    let (closed, kappa) = closed_form_over_r2(v, hv, n, m, r);
    (kappa <= TRY_CONTOUR_ABOVE).then_some((closed, 0.0, r))
}

/// [`closed_form_over_r2`]'s value in double-double throughout, from the
/// exact c − p and receiver height `hv` (scaled): its error is ~u²κ.
fn closed_form_over_r2_dd(v: Dd3, hv: Dd, n: DVec3, m: DVec3, r: f64) -> f64 {
    let (n, m3) = (Dd3::from_f64(n), Dd3::from_f64(m));
    let h = hv.abs();
    let lateral = v - m3.scale(hv);
    let s = lateral.length();
    let (h2, s2, r2) = (h.square(), s.square(), Dd::from(r * r));
    let r_dd = Dd::from(r);
    let q = (h2 + (r_dd - s).square()).sqrt() * (h2 + (r_dd + s).square()).sqrt();
    let t = h2 + s2 - Dd::product(r, r);
    let u = h2 + Dd::product(r, r) - s2;
    let q_minus_t_over_r2 = if t.hi >= 0.0 {
        h2.mul_f64(4.0) / (q + t)
    } else {
        (q - t) / r2
    };
    let q_plus_u = if u.hi >= 0.0 {
        q + u
    } else {
        (s2 * h2).mul_f64(4.0) / (q - u)
    };
    let jz = (q_minus_t_over_r2 / q).mul_f64(0.5) * PI_DD;
    let n_z = n.dot(m3).mul_f64(hv.hi.signum());
    let mut p = jz * n_z;
    if s.hi > 0.0 {
        let jx = PI_DD * h * s * q_minus_t_over_r2 / (q * q_plus_u);
        p = p + jx * (n.dot(lateral) / s);
    }
    p.to_f64().max(0.0)
}

/// The contour form's cancellation factor up to which it is kept for a
/// disk above the horizon (beyond, n·J is redone in double-double, which
/// is cheaper than the quadrature and exact to ~u²κ): the quadrature's
/// error bound, whose floor is 50ε∫|f|, stays below 1e-13 of the value.
const ACCEPT_CONTOUR_UP_TO: f64 = 8.0;

/// The closed form's cancellation factor above which the contour
/// integral over the whole rim is tried as well.
const TRY_CONTOUR_ABOVE: f64 = 8.0;

/// (J_z, J_x)/R² of the module docs, for h > 0, s ≥ 0, R > 0 with
/// max(h, s, R) ≤ 2, with the factor R² taken out
/// (Q − T = 4R²h²/(Q + T) when T ≥ 0), so a tiny far disk does not
/// underflow.
fn disk_vector_over_r2(h: f64, s: f64, r: f64) -> (f64, f64) {
    let h2 = h * h;
    let q = (h2 + (r - s) * (r - s)).sqrt() * (h2 + (r + s) * (r + s)).sqrt();
    let t = h2 + s * s - r * r;
    let u = h2 + r * r - s * s;
    let q_minus_t_over_r2 = if t >= 0.0 {
        4.0 * h2 / (q + t)
    } else {
        (q - t) / (r * r)
    };
    let q_plus_u = if u >= 0.0 {
        q + u
    } else {
        4.0 * s * s * h2 / (q - u)
    };
    let jz = 0.5 * PI * q_minus_t_over_r2 / q;
    let jx = if s > 0.0 {
        PI * h * s * q_minus_t_over_r2 / (q * q_plus_u)
    } else {
        0.0
    };
    (jz, jx)
}
