//! A spherical light: a uniform Lambertian sphere.

use glam::DVec3;
use lambert_geometry::f64::Sphere;
use lambert_geometry::validate;

use super::EmitterError;

/// A sphere of uniform radiance L on its surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    /// The sphere.
    pub sphere: Sphere,
    /// L, in W/m²/sr.
    pub radiance: f64,
}

impl SphereLight {
    /// Validates the sphere (center, radius > 0) and the radiance (≥ 0).
    pub fn new(center: DVec3, radius: f64, radiance: f64) -> Result<Self, EmitterError> {
        let sphere = Sphere::new(center, radius)?;
        validate::non_negative("radiance", radiance)?;
        Ok(SphereLight { sphere, radiance })
    }
}
