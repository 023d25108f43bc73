//! A planar convex polygon light, one- or two-sided.

use glam::DVec3;
use lambert_geometry::f64::ConvexPolygon;
use lambert_geometry::validate;

use super::EmitterError;

/// A planar convex polygon of uniform radiance L; its front face is given
/// by the right-hand rule (counter-clockwise seen from the front).
/// One-sided polygons are dark seen from behind.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonLight {
    /// The validated polygon.
    pub polygon: ConvexPolygon,
    /// L, in W/m²/sr.
    pub radiance: f64,
    /// Whether both faces emit.
    pub two_sided: bool,
}

impl PolygonLight {
    /// Validates the vertices (planar, convex, non-degenerate) and the
    /// radiance.
    pub fn new(vertices: Vec<DVec3>, radiance: f64, two_sided: bool) -> Result<Self, EmitterError> {
        let polygon = ConvexPolygon::new(vertices)?;
        validate::non_negative("radiance", radiance)?;
        Ok(PolygonLight {
            polygon,
            radiance,
            two_sided,
        })
    }
}
