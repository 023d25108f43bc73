//! A planar convex polygon light, one- or two-sided.

use glam::DVec3;

use super::EmitterError;
use lambert_geometry::ConvexPolygon;

/// A planar convex polygon of uniform radiance L; its front face is given
/// by the right-hand rule (counter-clockwise seen from the front). One-sided
/// polygons are dark seen from behind.
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
    /// Validates the vertices (planar, convex, non-degenerate).
    pub fn new(vertices: Vec<DVec3>, radiance: f64, two_sided: bool) -> Result<Self, EmitterError> {
        let polygon = ConvexPolygon::new(vertices).map_err(|p| EmitterError::new("vertices", p))?;
        EmitterError::check_non_negative("radiance", radiance)?;
        Ok(PolygonLight {
            polygon,
            radiance,
            two_sided,
        })
    }

    /// When the polygon is a rectangle (4 vertices, right angles to 1e-9),
    /// its corner and two edges.
    pub fn as_rectangle(&self) -> Option<(DVec3, DVec3, DVec3)> {
        let v = &self.polygon.vertices;
        if v.len() != 4 {
            return None;
        }
        let (e0, e1) = (v[1] - v[0], v[3] - v[0]);
        let opposite = v[0] + e0 + e1 - v[2];
        let square = e0.length() * e1.length();
        (e0.dot(e1).abs() <= 1e-9 * square
            && opposite.length() <= 1e-9 * (e0.length() + e1.length()))
        .then_some((v[0], e0, e1))
    }
}
