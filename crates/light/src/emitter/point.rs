//! A point light: intensity I, or an isotropic flux Φ (I = Φ/4π).

use glam::DVec3;

use lambert_geometry::validate;

use super::EmitterError;

/// An isotropic point light of intensity I (W/sr) at `position`: a delta
/// light, E = I max(cos θ, 0)/r² exactly (inverse-square law).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// The position.
    pub position: DVec3,
    /// I, in W/sr.
    pub intensity: f64,
}

impl PointLight {
    /// A point light of intensity I ≥ 0.
    pub fn with_intensity(position: DVec3, intensity: f64) -> Result<Self, EmitterError> {
        validate::finite3("position", position)?;
        validate::non_negative("intensity", intensity)?;
        Ok(PointLight {
            position,
            intensity,
        })
    }

    /// An isotropic point light of flux Φ ≥ 0: I = Φ/4π.
    pub fn with_flux(position: DVec3, flux: f64) -> Result<Self, EmitterError> {
        validate::non_negative("flux", flux)?;
        Self::with_intensity(position, crate::radiometry::isotropic_intensity(flux))
    }
}
