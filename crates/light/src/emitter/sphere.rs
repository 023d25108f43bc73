//! A spherical light: a uniform Lambertian sphere.

use glam::DVec3;

use super::EmitterError;

/// A sphere (center, radius) of uniform radiance L on its surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    /// The center.
    pub center: DVec3,
    /// The radius, > 0.
    pub radius: f64,
    /// L, in W/m²/sr.
    pub radiance: f64,
}

impl SphereLight {
    /// Validates the sphere.
    pub fn new(center: DVec3, radius: f64, radiance: f64) -> Result<Self, EmitterError> {
        EmitterError::check_vector("center", center)?;
        EmitterError::check_positive("radius", radius)?;
        EmitterError::check_non_negative("radiance", radiance)?;
        Ok(SphereLight {
            center,
            radius,
            radiance,
        })
    }
}
