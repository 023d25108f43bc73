//! Point and directional lights (delta lights; closed forms).

use super::disk::power_of_two_above;
use super::error::{finite, finite3, unit, AnalyticError};
use super::scaled;
use glam::DVec3;

/// An isotropic point light of intensity I (W/sr) at `light`, seen from a
/// receiver at `p` with unit normal `n`: E = I max(cos θ, 0)/r², W/m²
/// (inverse-square law and Lambert's cosine law; pbrt-v4 §12.1), with
/// cos θ = n·(light − p)/r. Lengths are scaled by powers of two and
/// E = I·cos θ·(1/r)² formed without intermediate overflow or underflow,
/// so a light 1e-200 or 1e200 away gives its ordinary f64 answer. Errors:
/// non-finite input, a zero normal, `light == p`, and
/// [`AnalyticError::Overflow`] when E exceeds f64::MAX.
///
/// ```
/// use glam::DVec3;
/// use lambert_light::analytic::point_light_irradiance;
/// // An 815 lm bulb (64.86 cd), 2 m away at 60° from the normal.
/// let i = 815.0 / (4.0 * std::f64::consts::PI);
/// let l = DVec3::new(3f64.sqrt(), 0.0, 1.0);
/// let e = point_light_irradiance(i, DVec3::ZERO, DVec3::Z, l).unwrap();
/// assert!((e - i * 0.5 / 4.0).abs() < 1e-13);
/// ```
pub fn point_light_irradiance(
    intensity: f64,
    p: DVec3,
    normal: DVec3,
    light: DVec3,
) -> Result<f64, AnalyticError> {
    finite("intensity", intensity)?;
    let n = unit("normal", normal)?;
    let (light, p) = (finite3("light", light)?, finite3("p", p)?);
    // v = light − p in units of a power of two k (no overflow), then of
    // a second power of two s so that |ṽ| is near 1 (no underflow of |v|²).
    let k = power_of_two_above(light.abs().max_element().max(p.abs().max_element()));
    let v = light / k - p / k;
    let s = power_of_two_above(v.abs().max_element());
    if !(v.abs().max_element() > 0.0) {
        return Err(AnalyticError::ReceiverInsideLight {
            light: "point light",
        });
    }
    let v = v / s;
    let r = v.length();
    let cos = n.dot(v) / r;
    if !(cos > 0.0) {
        return Ok(0.0);
    }
    scaled::product(
        "irradiance",
        &[
            intensity,
            cos,
            1.0 / r,
            1.0 / r,
            1.0 / k,
            1.0 / k,
            1.0 / s,
            1.0 / s,
        ],
    )
}

/// A directional light (the Sun as a delta: all rays parallel) whose
/// irradiance on a surface facing it is E⊥ (W/m²), arriving from the unit
/// direction `to_light`: E = E⊥ max(n·d, 0), W/m² (the clamped
/// "N-dot-L"; pbrt-v4 `DistantLight`). Errors: non-finite input or non-unit
/// vectors.
pub fn directional_light_irradiance(
    irradiance_perpendicular: f64,
    normal: DVec3,
    to_light: DVec3,
) -> Result<f64, AnalyticError> {
    finite("irradiance_perpendicular", irradiance_perpendicular)?;
    let n = unit("normal", normal)?;
    let d = unit("to_light", to_light)?;
    scaled::product("irradiance", &[irradiance_perpendicular, n.dot(d).max(0.0)])
}
