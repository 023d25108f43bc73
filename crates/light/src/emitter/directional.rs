//! A directional light: parallel rays from a direction.

use glam::DVec3;

use lambert_geometry::{f64::unit_vector, validate};

use super::EmitterError;

/// Parallel light from `direction` (unit, toward the light) giving
/// irradiance E⊥ on a surface facing it: a delta light,
/// E = E⊥ max(n·d, 0) exactly (Lambert's cosine law).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    /// Unit direction toward the light.
    pub direction: DVec3,
    /// E⊥, in W/m².
    pub irradiance: f64,
}

impl DirectionalLight {
    /// Validates the light; `direction` may have any non-zero length.
    pub fn new(direction: DVec3, irradiance: f64) -> Result<Self, EmitterError> {
        let direction = unit_vector("direction", direction)?;
        validate::non_negative("irradiance", irradiance)?;
        Ok(DirectionalLight {
            direction,
            irradiance,
        })
    }
}
