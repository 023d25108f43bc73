//! A planar convex polygon light, one- or two-sided.

use glam::DVec3;
use lambert_geometry::f64::ConvexPolygon;
use lambert_geometry::validate;
use lambert_sampling::MAX_POLYGON_VERTICES;

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
    /// Validates the vertices (planar, convex, non-degenerate, at most
    /// [`MAX_POLYGON_VERTICES`], the polygon light sampler's limit) and the
    /// radiance.
    pub fn new(vertices: Vec<DVec3>, radiance: f64, two_sided: bool) -> Result<Self, EmitterError> {
        if vertices.len() > MAX_POLYGON_VERTICES {
            return Err(EmitterError::new(
                "vertices",
                format!(
                    "a polygon light has at most {MAX_POLYGON_VERTICES} vertices (its light \
                     sampler clips it to the receiver's horizon in a fixed buffer), got {}",
                    vertices.len()
                ),
            ));
        }
        let polygon = ConvexPolygon::new(vertices)?;
        validate::non_negative("radiance", radiance)?;
        Ok(PolygonLight {
            polygon,
            radiance,
            two_sided,
        })
    }
}
