//! A disk light, one- or two-sided.

use glam::DVec3;
use lambert_geometry::f64::Disk;
use lambert_geometry::validate;

use super::EmitterError;

/// A disk of uniform radiance L. One-sided disks emit only to the side
/// their normal points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskLight {
    /// The disk (its normal is the emitting side of a one-sided disk).
    pub disk: Disk,
    /// L, in W/m²/sr.
    pub radiance: f64,
    /// Whether both faces emit.
    pub two_sided: bool,
}

impl DiskLight {
    /// Validates the disk (`normal` may have any non-zero length) and the
    /// radiance.
    pub fn new(
        center: DVec3,
        normal: DVec3,
        radius: f64,
        radiance: f64,
        two_sided: bool,
    ) -> Result<Self, EmitterError> {
        let disk = Disk::new(center, normal, radius)?;
        validate::non_negative("radiance", radiance)?;
        Ok(DiskLight {
            disk,
            radiance,
            two_sided,
        })
    }
}
