//! A uniform spherical light.

use super::cap::cap_projected_solid_angle;
use super::error::{finite, finite3, positive, unit, AnalyticError};
use glam::DVec3;

/// A uniform sphere of radiance L (centre `center`, radius r) seen from a
/// receiver at `p` with unit normal `n` (closed form).
///
/// Seen from outside, the sphere covers the cap of directions of axis
/// a = (c − p)/d and angular radius α, sin α = r/d, so E = L P(β, α) with
/// cos β = n·a ([`cap_projected_solid_angle`]): E = Lπ sin²α cos β when the
/// sphere is wholly above the horizon (β + α ≤ π/2), Snyder's (1996)
/// horizon-clipped form rewritten without cancellation when it straddles,
/// 0 below. sin α = r/d and cos α = √((d − r)(d + r))/d are exact to
/// rounding for α = 1e-8 and for receivers almost touching the sphere.
///
/// Errors: non-finite input, a non-unit normal, r ≤ 0, or `p` inside or on
/// the sphere ([`AnalyticError::ReceiverInsideLight`]).
///
/// ```
/// use glam::DVec3;
/// use lambert_light::analytic::sphere_irradiance;
/// use std::f64::consts::PI;
/// // r = 1 at d = 2 overhead: sin²α = 1/4, E = Lπ/4.
/// let e = sphere_irradiance(1.0, DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 0.0, 2.0), 1.0).unwrap();
/// assert!((e - PI / 4.0).abs() < 1e-15);
/// ```
pub fn sphere_irradiance(
    radiance: f64,
    p: DVec3,
    normal: DVec3,
    center: DVec3,
    radius: f64,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    let p = finite3("p", p)?;
    let n = unit("normal", normal)?;
    let c = finite3("center", center)?;
    let r = positive("radius", radius)?;
    let v = c - p;
    let d = v.length();
    if !(d > r) {
        return Err(AnalyticError::ReceiverInsideLight { light: "sphere" });
    }
    let sg = r / d;
    let cg = ((d - r) * (d + r)).sqrt() / d;
    let cb = n.dot(v) / d;
    Ok(radiance * cap_projected_solid_angle(cb, sg, cg))
}
