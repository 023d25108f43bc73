//! A disk light, one- or two-sided.

use glam::DVec3;

use super::EmitterError;

/// A disk (center, unit normal, radius) of uniform radiance L. One-sided
/// disks emit only to the side their normal points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskLight {
    /// The center.
    pub center: DVec3,
    /// The unit normal (the emitting side of a one-sided disk).
    pub normal: DVec3,
    /// The radius, > 0.
    pub radius: f64,
    /// L, in W/m²/sr.
    pub radiance: f64,
    /// Whether both faces emit.
    pub two_sided: bool,
}

impl DiskLight {
    /// Validates the disk; `normal` may have any non-zero length.
    pub fn new(
        center: DVec3,
        normal: DVec3,
        radius: f64,
        radiance: f64,
        two_sided: bool,
    ) -> Result<Self, EmitterError> {
        EmitterError::check_vector("center", center)?;
        let normal = EmitterError::unit("normal", normal)?;
        EmitterError::check_positive("radius", radius)?;
        EmitterError::check_non_negative("radiance", radiance)?;
        Ok(DiskLight {
            center,
            normal,
            radius,
            radiance,
            two_sided,
        })
    }
}
