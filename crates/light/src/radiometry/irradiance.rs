//! Irradiance E, in W/m²: Lambert's cosine law and the inverse-square law.

/// Lambert's cosine law (Lambert 1760, *Photometria*): a beam of flux Φ
/// and cross-section A falling at angle θ on a surface spreads over
/// A/cos θ, so E = Φ max(cos θ, 0)/A, in W/m². A surface facing away
/// receives nothing (`cos_theta` is clamped at 0).
///
/// ```
/// use lambert_light::radiometry::lambert_cosine_irradiance;
/// // 1 W over 1 m², seen at 60°: half of it.
/// let e = lambert_cosine_irradiance(1.0, 1.0, 60f64.to_radians().cos());
/// assert!((e - 0.5).abs() < 1e-15);
/// assert_eq!(lambert_cosine_irradiance(1.0, 1.0, -0.3), 0.0);
/// ```
#[inline]
pub fn lambert_cosine_irradiance(flux_w: f64, beam_area_m2: f64, cos_theta: f64) -> f64 {
    flux_w * cos_theta.max(0.0) / beam_area_m2
}

/// Inverse-square falloff from a point source of intensity I (W/sr) at
/// distance r (m), seen at angle θ from the receiver's normal:
/// E = I max(cos θ, 0)/r², in W/m² (pbrt-v4 §4.1.1, §12.1). The point
/// emitter's irradiance is this.
///
/// ```
/// use lambert_light::radiometry::{inverse_square_irradiance, isotropic_intensity};
/// // An 815 lm bulb 2 m above a desk: 64.86 cd / 4 m² ≈ 16.2 lux.
/// let i = isotropic_intensity(815.0);
/// let e = inverse_square_irradiance(i, 2.0, 1.0);
/// assert!((e - 815.0 / (16.0 * std::f64::consts::PI)).abs() < 1e-12);
/// // Twice as far: a quarter.
/// assert!((inverse_square_irradiance(i, 4.0, 1.0) * 4.0 - e).abs() < 1e-12);
/// ```
#[inline]
pub fn inverse_square_irradiance(intensity_w_sr: f64, distance_m: f64, cos_theta: f64) -> f64 {
    intensity_w_sr * cos_theta.max(0.0) / (distance_m * distance_m)
}
