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
//! E = L n·J (closed form). When the receiver's plane cuts it, E is
//! Lambert's contour integral over the clipped boundary (Arvo 1995):
//! E = (L/2) |∫_{visible rim} n·(R × R′)/|R|² dt + θ_chord σ|, where the
//! chord, lying in the receiver's plane, contributes its subtended angle
//! θ_chord with sign σ = sign n·(R_a × R_b); the rim integral is computed by
//! adaptive Gauss–Kronrod (7, 15) quadrature to a relative tolerance 1e-14
//! on |K − G| (measured accuracy ~1e-15 for lights within 1e3 radii; the
//! integrand's terms are of size R/D and cancel to a result of size
//! (R/D)², so a straddling disk at distance D loses about log₁₀(D/R)
//! digits).

use super::error::{finite, AnalyticError};
use super::Emission;
use super::{rim, scaled};
use crate::receiver::Receiver;
use glam::DVec3;
use lambert_geometry::f64::Disk;
use std::f64::consts::PI;

/// A uniform disk of radiance L and radius R seen from a receiver on its
/// axis at height h, facing it: E = Lπ sin²α with sin²α = R²/(R² + h²)
/// (Ω⊥ = π sin²α; closed form, no cancellation).
///
/// ```
/// use lambert_light::analytic::disk_coaxial_irradiance;
/// use std::f64::consts::PI;
/// assert!((disk_coaxial_irradiance(1.0, 1.0, 1.0) - PI / 2.0).abs() < 1e-15);
/// ```
#[inline]
pub fn disk_coaxial_irradiance(radiance: f64, height: f64, radius: f64) -> f64 {
    let r2 = radius * radius;
    radiance * PI * r2 / (r2 + height * height)
}

/// A uniform disk of radiance L and radius R parallel to the receiver and
/// facing it, at height h, its centre offset laterally by s (closed form):
///
/// E = (Lπ/2)(1 − (h² + s² − R²)/√((h² + R² + s²)² − 4R²s²)),
///
/// evaluated as (Lπ/2)(Q − T)/Q with Q = √((h² + (R − s)²)(h² + (R + s)²))
/// (the same radicand, factored), T = h² + s² − R² and
/// Q − T = 4R²h²/(Q + T) when T ≥ 0: no cancellation for far or tiny disks.
///
/// ```
/// use lambert_light::analytic::{disk_coaxial_irradiance, disk_parallel_offset_irradiance};
/// let (e0, e1) = (disk_parallel_offset_irradiance(1.0, 2.0, 0.0, 1.0), disk_coaxial_irradiance(1.0, 2.0, 1.0));
/// assert!((e0 - e1).abs() < 1e-15);
/// ```
#[inline]
pub fn disk_parallel_offset_irradiance(
    radiance: f64,
    height: f64,
    offset: f64,
    radius: f64,
) -> f64 {
    radiance * disk_vector(height.abs(), offset.abs(), radius).0
}

/// (J_z, J_x) of the module docs, for h > 0, s ≥ 0, R > 0.
pub(crate) fn disk_vector(h: f64, s: f64, r: f64) -> (f64, f64) {
    let h2 = h * h;
    let q = (h2 + (r - s) * (r - s)).sqrt() * (h2 + (r + s) * (r + s)).sqrt();
    let t = h2 + s * s - r * r;
    let u = h2 + r * r - s * s;
    let q_minus_t = if t >= 0.0 {
        4.0 * r * r * h2 / (q + t)
    } else {
        q - t
    };
    let q_plus_u = if u >= 0.0 {
        q + u
    } else {
        4.0 * s * s * h2 / (q - u)
    };
    let jz = 0.5 * PI * q_minus_t / q;
    let jx = if s > 0.0 {
        PI * h * s * q_minus_t / (q * q_plus_u)
    } else {
        0.0
    };
    (jz, jx)
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
/// receiver's plane; when the receiver's plane cuts the disk, the contour
/// integral over the visible arc of the rim in the form that does not
/// cancel (sin²ε dφ, with no chord term, for low visible parts; Lambert's
/// cos²ε dφ plus the chord's angle for high ones; see the `rim` module),
/// by Gauss–Kronrod quadrature bounded to 30 720 evaluations. 0 when the
/// disk is wholly below the horizon, when `p` is in the disk's plane, or
/// when a one-sided disk is seen from behind.
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
/// assert!((e - disk_coaxial_irradiance(1.0, 2.0, 1.0)).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn disk_irradiance(
    disk: &Disk,
    emission: Emission,
    radiance: f64,
    receiver: &Receiver,
) -> Result<f64, AnalyticError> {
    let b = disk_irradiance_with_error_bound(disk, emission, radiance, receiver)?;
    if b.error_bound <= DISK_RELATIVE_ERROR_LIMIT * b.irradiance.abs() {
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
/// disk's visible part: s is the radius in units of max(|c − p|, R), q is
/// computed in those units (all lengths ≤ 1, nothing overflows).
fn disk_projected(
    p: DVec3,
    n: DVec3,
    c: DVec3,
    m: DVec3,
    r: f64,
    emission: Emission,
) -> (f64, f64, f64) {
    // Exact power-of-two scaling first (c − p may overflow), then by the
    // characteristic length.
    let k = power_of_two_above(c.abs().max_element().max(p.abs().max_element()).max(r));
    let v = c / k - p / k;
    let (r1, d1) = (r / k, v.length());
    let l0 = d1.max(r1);
    let (v, r) = (v / l0, r1 / l0);
    if !(r > 0.0) {
        return (0.0, 0.0, 0.0);
    }
    let hv = v.dot(m);
    // A one-sided disk emits towards +m: p must be on that side (hv < 0).
    if hv == 0.0 || (emission == Emission::OneSided && hv > 0.0) {
        return (0.0, 0.0, r);
    }
    // Height of the disk's centre above the receiver's plane and the
    // amplitude of the rim's height about it.
    let f0 = n.dot(v);
    let g = n.cross(m).length();
    if f0 + r * g <= 0.0 {
        return (0.0, 0.0, r);
    }
    if f0 - r * g >= 0.0 {
        let h = hv.abs();
        let z = m * hv.signum();
        let lateral = v - m * hv;
        let s = lateral.length();
        let (jz, jx) = disk_vector_over_r2(h, s, r);
        let x = if s > 0.0 { lateral / s } else { DVec3::ZERO };
        return ((jz * n.dot(z) + jx * n.dot(x)).max(0.0), 0.0, r);
    }
    let i = rim::straddling_over_r2(v, n, m, r);
    (i.value, i.error, r)
}

/// (J_z, J_x)/R² of the module docs, for h > 0, s ≥ 0, R > 0 with
/// max(h, s, R) ≤ 2: as [`disk_vector`] with the factor R² taken out
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
