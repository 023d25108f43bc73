//! A uniform spherical light.

use super::cap::cap_over_sin2;
use super::disk::power_of_two_above;
use super::error::{finite, AnalyticError};
use super::scaled;
use crate::receiver::Receiver;
use lambert_geometry::f64::Sphere;

/// A uniform `sphere` (centre c, radius r) of radiance L seen from the
/// `receiver` at p with unit normal n (closed form).
///
/// Seen from outside, the sphere covers the cap of directions of axis
/// a = (c − p)/d and angular radius α, sin α = r/d, so E = L P(β, α) with
/// cos β = n·a ([`super::cap_projected_solid_angle`]): E = Lπ sin²α cos β when the
/// sphere is wholly above the horizon (β + α ≤ π/2), Snyder's (1996)
/// horizon-clipped form rewritten without cancellation when it straddles,
/// 0 below. sin α = r/d and cos α = √((d − r)(d + r))/d are exact to
/// rounding for α = 1e-8 and for receivers almost touching the sphere.
///
/// Lengths are rescaled by a power of two first (no overflow of c − p or
/// of |c − p|²), and E = L·(P/sin²α)·sin α·sin α is formed without
/// intermediate underflow or overflow.
///
/// Errors: a non-finite radiance, p inside or on the sphere ([`AnalyticError::ReceiverInsideLight`]), or E beyond
/// f64::MAX ([`AnalyticError::Overflow`]).
///
/// ```
/// use glam::DVec3;
/// use lambert_geometry::f64::Sphere;
/// use lambert_light::{analytic::sphere_irradiance, Receiver};
/// use std::f64::consts::PI;
/// // r = 1 at d = 2 overhead: sin²α = 1/4, E = Lπ/4.
/// let sphere = Sphere::new(DVec3::new(0.0, 0.0, 2.0), 1.0)?;
/// let up = Receiver::new(DVec3::ZERO, DVec3::Z)?;
/// let e = sphere_irradiance(&sphere, 1.0, &up)?;
/// assert!((e - PI / 4.0).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sphere_irradiance(
    sphere: &Sphere,
    radiance: f64,
    receiver: &Receiver,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    let (p, n) = (receiver.point, receiver.normal);
    let (c, r) = (sphere.center(), sphere.radius());
    // Exact power-of-two rescaling (c − p and |c − p|² may overflow or
    // underflow otherwise): a receiver on a sphere of radius 1e308 centred
    // 1e308 away is on it, not at an infinite distance.
    let k = power_of_two_above(c.abs().max_element().max(p.abs().max_element()).max(r));
    let v = c / k - p / k;
    let r = r / k;
    let d = v.length();
    if !(d > r) {
        return Err(AnalyticError::ReceiverInsideLight { light: "sphere" });
    }
    let sg = r / d;
    let cg = ((d - r) * (d + r)).sqrt() / d;
    let cb = n.dot(v) / d;
    // E = L · (P/sin²γ) · sin γ · sin γ, without underflow of sin²γ.
    let (q, s) = cap_over_sin2(cb, sg, cg);
    scaled::product("irradiance", &[radiance, q, s, s])
}
