//! Irradiance E, in watts per square metre; Lambert's cosine law and the
//! inverse-square law.

use super::{RadiantFlux, RadiantIntensity};

/// Irradiance E = dΦ/dA, in W/m² (photometric: lm/m² = lux) (lecture;
/// pbrt-v4 §4.1.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct Irradiance(pub f64);

impl Irradiance {
    /// The irradiance, W/m².
    #[inline]
    pub fn watts_per_m2(self) -> f64 {
        self.0
    }

    /// The flux through area `area_m2`: Φ = E A, W.
    #[inline]
    pub fn flux_through(self, area_m2: f64) -> RadiantFlux {
        RadiantFlux(self.0 * area_m2)
    }
}

/// Lambert's cosine law (Lambert 1760, *Photometria*; lecture): a beam of
/// flux Φ and cross-section A falling at angle θ on a surface spreads over
/// A' = A / cos θ, so E = Φ cos θ / A, W/m². A surface facing away
/// receives nothing: `cos_theta` is clamped at 0 (the lecture's
/// `max(0, dot(N, L))`).
///
/// ```
/// use lambert_light::radiometry::lambert_cosine_irradiance;
/// // 1 W over 1 m², seen at 60°: half of it.
/// let e = lambert_cosine_irradiance(1.0, 1.0, 60f64.to_radians().cos());
/// assert!((e.0 - 0.5).abs() < 1e-15);
/// assert_eq!(lambert_cosine_irradiance(1.0, 1.0, -0.3).0, 0.0);
/// ```
#[inline]
pub fn lambert_cosine_irradiance(flux_w: f64, beam_area_m2: f64, cos_theta: f64) -> Irradiance {
    Irradiance(flux_w * cos_theta.max(0.0) / beam_area_m2)
}

/// Inverse-square falloff from a point source of intensity I at distance r,
/// seen at angle θ from the receiver's normal: E = I max(cos θ, 0) / r², W/m²
/// (pbrt-v4 §4.1.1, §12.1).
///
/// ```
/// use lambert_light::radiometry::{inverse_square_irradiance, RadiantFlux, RadiantIntensity};
/// // The lecture's 815 lm bulb, 2 m above a desk: 64.86 cd / 4 m² ≈ 16.2 lux.
/// let i = RadiantIntensity::isotropic(RadiantFlux(815.0));
/// let e = inverse_square_irradiance(i, 2.0, 1.0);
/// assert!((e.0 - 815.0 / (16.0 * std::f64::consts::PI)).abs() < 1e-12);
/// // Twice as far: a quarter.
/// assert!((inverse_square_irradiance(i, 4.0, 1.0).0 * 4.0 - e.0).abs() < 1e-12);
/// ```
#[inline]
pub fn inverse_square_irradiance(
    intensity: RadiantIntensity,
    distance_m: f64,
    cos_theta: f64,
) -> Irradiance {
    Irradiance(intensity.0 * cos_theta.max(0.0) / (distance_m * distance_m))
}
