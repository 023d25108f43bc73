//! A sky cap: radiance L from the directions within a cone.

use glam::DVec3;
use lambert_geometry::f64::{unit_vector, Frame};
use lambert_geometry::validate;
use lambert_sampling::f64::UniformCone;

use super::EmitterError;

/// Radiance `radiance` from the directions within `half_angle` of `axis`
/// (a cap of directions, independent of position, like a sky). It may cross
/// the receiver's horizon; a dome over a tilted receiver is a cap of
/// half-angle π/2 about the zenith.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyCap {
    /// Unit axis of the cap.
    pub axis: DVec3,
    /// Half-angle γ ∈ (0, π], radians.
    pub half_angle: f64,
    /// The cone of directions (1 − cos γ without cancellation).
    pub cone: UniformCone,
    /// The cap's frame (z = axis).
    pub frame: Frame,
    /// L, in W/m²/sr.
    pub radiance: f64,
}

impl SkyCap {
    /// A cap about `axis` (any non-zero length) of half-angle γ ∈ (0, π].
    pub fn new(axis: DVec3, half_angle: f64, radiance: f64) -> Result<Self, EmitterError> {
        let axis = unit_vector("axis", axis)?;
        validate::finite("half_angle", half_angle)?;
        if !(half_angle > 0.0 && half_angle <= std::f64::consts::PI) {
            return Err(EmitterError::new(
                "half_angle",
                format!("must lie in (0, π] radians, got {half_angle}"),
            ));
        }
        validate::non_negative("radiance", radiance)?;
        let cone = UniformCone::from_theta_max(half_angle)
            .map_err(|e| EmitterError::new("half_angle", e.to_string()))?;
        Ok(SkyCap {
            axis,
            half_angle,
            cone,
            frame: Frame::from_normal(axis),
            radiance,
        })
    }

    /// Whether the unit direction `w` is in the cap.
    #[inline]
    pub fn contains(&self, w: DVec3) -> bool {
        self.cone.pdf(self.frame.to_local(w)) > 0.0
    }
}
