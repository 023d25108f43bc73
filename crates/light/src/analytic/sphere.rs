//! A uniform spherical light.

use super::cap::{cap_over_sin2, clear_of_horizon, CapAngles};
use super::disk::power_of_two_above;
use super::double_double::Dd;
use super::error::{finite, AnalyticError};
use super::exact_sum;
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
/// 0 below.
///
/// A sphere clearly outside (d ≥ 2r) and clearly above or below the
/// horizon (cos β ≥ 1/4) takes the f64 path; every other configuration
/// has its angles from the exact inputs to double-double precision
/// (module `cap`): c − p exactly (TwoSum per component), d = |c − p|,
/// sin α = r/d, cos α = √((d − r)(d + r))/d, cos β = n·(c − p)/(|n| d)
/// and cos β / sin α = n·(c − p)/(|n| r) from the exact dot product. So a
/// sphere 1e-8 in angular size whose centre lies 1e-20 above the horizon,
/// or one that barely shows above it, or a receiver 1e-10 of the radius
/// from the surface, keeps its digits.
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
    let (c, p, r) = (c / k, p / k, r / k);
    // Ordinary spheres, clearly outside and clearly off the horizon: f64.
    let v = c - p;
    let d = v.length();
    if d >= 2.0 * r && r > 0.0 {
        if let Some((q, s)) = clear_of_horizon(n.dot(v) / d, r / d) {
            return scaled::product("irradiance", &[radiance, q, s, s]);
        }
    }
    let v = [Dd::sum(c.x, -p.x), Dd::sum(c.y, -p.y), Dd::sum(c.z, -p.z)];
    let d = exact_sum::length(v);
    if !(r > 0.0) {
        // The radius underflowed against the distances: E = Lπ(r/d)²
        // underflows too, unless the receiver is at the centre.
        return if d.hi > 0.0 {
            Ok(0.0)
        } else {
            Err(AnalyticError::ReceiverInsideLight { light: "sphere" })
        };
    }
    let r_dd = Dd::from(r);
    if !((d - r_dd).hi > 0.0) {
        return Err(AnalyticError::ReceiverInsideLight { light: "sphere" });
    }
    let n_dot_v = exact_sum::dot_of_difference(n, c, p) / exact_sum::length_f64(n);
    let angles = CapAngles {
        cos_beta: n_dot_v / d,
        sin_gamma: r_dd / d,
        cos_gamma: ((d - r_dd) * (d + r_dd)).sqrt() / d,
        cos_beta_over_sin_gamma: n_dot_v.div_f64(r),
    };
    // E = L · (P/sin²γ) · sin γ · sin γ, without underflow of sin²γ.
    let (q, s) = cap_over_sin2(&angles);
    scaled::product("irradiance", &[radiance, q, s, s])
}
