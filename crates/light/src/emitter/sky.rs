//! A uniform sky: radiance L from every direction.

use lambert_geometry::validate;

use super::EmitterError;

/// Radiance `radiance` (W/m²/sr) from every direction; a receiver sees
/// E = Lπ whatever its normal (the uniform hemisphere).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// L, in W/m²/sr.
    pub radiance: f64,
}

impl Sky {
    /// A sky of radiance L ≥ 0.
    pub fn new(radiance: f64) -> Result<Self, EmitterError> {
        validate::non_negative("radiance", radiance)?;
        Ok(Sky { radiance })
    }
}
