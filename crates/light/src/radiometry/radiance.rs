//! Irradiance from uniform radiance L, in W/(m²·sr): E = L Ω⊥, with Ω⊥ the
//! projected solid angle ∫ cos θ dω of the directions it comes from.

use std::f64::consts::PI;

/// Irradiance under a uniform hemisphere of radiance L:
/// E = ∫_{H²} L cos θ dω = L ∫₀^{2π}∫₀^{π/2} cos θ sin θ dθ dφ = Lπ, W/m².
/// The sky's closed form is this.
///
/// ```
/// use lambert_light::radiometry::uniform_hemisphere_irradiance;
/// assert_eq!(uniform_hemisphere_irradiance(1.0), std::f64::consts::PI);
/// ```
#[inline]
pub fn uniform_hemisphere_irradiance(radiance: f64) -> f64 {
    radiance * PI
}

/// The projected solid angle of a disk seen on its axis under angular
/// radius α, from sin²α: Ω⊥ = ∫₀^{2π}∫₀^α cos θ sin θ dθ dφ = π sin²α, in
/// sr. (Geometrically: the disk projects onto the unit disk as a circle of
/// radius sin α.) For a disk of radius R at height h pass
/// sin²α = R²/(R² + h²), which has no cancellation.
///
/// ```
/// use lambert_light::radiometry::disk_projected_solid_angle;
/// use std::f64::consts::PI;
/// // α = 30°: Ω⊥ = π/4.
/// let s = 30f64.to_radians().sin();
/// assert!((disk_projected_solid_angle(s * s) - PI / 4.0).abs() < 1e-15);
/// // α = 90° is the whole hemisphere, E = Lπ.
/// assert_eq!(disk_projected_solid_angle(1.0), PI);
/// ```
#[inline]
pub fn disk_projected_solid_angle(sin2_alpha: f64) -> f64 {
    PI * sin2_alpha
}
