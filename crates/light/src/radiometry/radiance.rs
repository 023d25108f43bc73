//! Radiance L, in W/(m²·sr); irradiance from uniform radiance.

use super::Irradiance;

/// Radiance L = d²Φ / (dA dω cos θ), in W/(m²·sr) (photometric: cd/m² =
/// nit) (lecture; pbrt-v4 §4.1.1). Constant along rays in vacuum.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct Radiance(pub f64);

impl Radiance {
    /// The radiance, W/(m²·sr).
    #[inline]
    pub fn value(self) -> f64 {
        self.0
    }

    /// Irradiance from this radiance over a set of directions of projected
    /// solid angle Ω⊥ = ∫ cos θ dω: E = L Ω⊥ (lecture).
    #[inline]
    pub fn irradiance_from_projected_solid_angle(self, projected_sr: f64) -> Irradiance {
        Irradiance(self.0 * projected_sr)
    }
}

/// Irradiance under a uniform hemisphere of radiance L:
/// E = ∫_{H²} L cos θ dω = L ∫₀^{2π}∫₀^{π/2} cos θ sin θ dθ dφ = Lπ, W/m²
/// (lecture's worked example).
///
/// ```
/// use lambert_light::radiometry::{uniform_hemisphere_irradiance, Radiance};
/// assert_eq!(uniform_hemisphere_irradiance(Radiance(1.0)).0, std::f64::consts::PI);
/// ```
#[inline]
pub fn uniform_hemisphere_irradiance(radiance: Radiance) -> Irradiance {
    Irradiance(radiance.0 * std::f64::consts::PI)
}

/// The projected solid angle of a disk seen on its axis under angular
/// radius α, from sin²α: Ω⊥ = ∫₀^{2π}∫₀^α cos θ sin θ dθ dφ = π sin²α
/// (lecture, "uniform disk light parallel to the plane"; sr). For a disk of
/// radius R at height h, pass sin²α = R²/(R² + h²), which has no
/// cancellation.
///
/// ```
/// use lambert_light::radiometry::disk_projected_solid_angle;
/// use std::f64::consts::PI;
/// // α = 30°: Ω⊥ = π/4 (the lecture's geometric derivation: the disk
/// // projects to a circle of radius sin α on the unit disk).
/// let s = 30f64.to_radians().sin();
/// assert!((disk_projected_solid_angle(s * s) - PI / 4.0).abs() < 1e-15);
/// // α = 90° is the whole hemisphere, E = Lπ.
/// assert_eq!(disk_projected_solid_angle(1.0), PI);
/// ```
#[inline]
pub fn disk_projected_solid_angle(sin2_alpha: f64) -> f64 {
    std::f64::consts::PI * sin2_alpha
}
