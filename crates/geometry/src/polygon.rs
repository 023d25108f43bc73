//! Planar convex polygons: validation, ray intersection, inside test.

use glam::DVec3;

use crate::ray_plane;

/// A planar convex polygon with its unit normal by the right-hand rule
/// (counter-clockwise seen from the front).
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexPolygon {
    /// The vertices, in order.
    pub vertices: Vec<DVec3>,
    /// The unit normal (Newell's method, then normalised).
    pub normal: DVec3,
    /// The area.
    pub area: f64,
}

impl ConvexPolygon {
    /// Validates `vertices` as a planar, convex, non-degenerate polygon.
    ///
    /// Planarity tolerance: every vertex within 1e-9 of the largest
    /// extent of the polygon from its plane. Convexity: every turn has the
    /// same orientation as the normal. Errors say which vertex failed.
    pub fn new(vertices: Vec<DVec3>) -> Result<Self, String> {
        if vertices.len() < 3 {
            return Err(format!("needs at least 3 vertices, got {}", vertices.len()));
        }
        for (i, v) in vertices.iter().enumerate() {
            if !v.is_finite() {
                return Err(format!("vertex {i} must be finite, got {v}"));
            }
        }
        // Newell's normal: robust for any planar polygon.
        let n = vertices.len();
        let mut newell = DVec3::ZERO;
        for i in 0..n {
            let (a, b) = (vertices[i], vertices[(i + 1) % n]);
            newell += DVec3::new(
                (a.y - b.y) * (a.z + b.z),
                (a.z - b.z) * (a.x + b.x),
                (a.x - b.x) * (a.y + b.y),
            );
        }
        let twice_area = newell.length();
        let extent = vertices
            .iter()
            .map(|v| (*v - vertices[0]).length())
            .fold(0.0, f64::max);
        if !twice_area.is_finite() || !extent.is_finite() {
            // Otherwise the normal would be NaN and every check below pass.
            return Err(format!(
                "is too large: its area or extent overflows (area {:e}, extent {extent:e})",
                0.5 * twice_area
            ));
        }
        if !(twice_area > 0.0) {
            return Err("has zero area (collinear or repeated vertices)".into());
        }
        let normal = newell / twice_area;
        for (i, v) in vertices.iter().enumerate() {
            let off = normal.dot(*v - vertices[0]).abs();
            if off > 1e-9 * extent {
                return Err(format!(
                    "is not planar: vertex {i} lies {off:e} from the plane of the others (tolerance {:e})",
                    1e-9 * extent
                ));
            }
        }
        for i in 0..n {
            let (a, b, c) = (vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]);
            let turn = (b - a).cross(c - b).dot(normal);
            if turn <= 0.0 {
                return Err(format!(
                    "is not strictly convex at vertex {} (vertices must turn one way, counter-clockwise seen from the front)",
                    (i + 1) % n
                ));
            }
        }
        Ok(ConvexPolygon {
            vertices,
            normal,
            area: 0.5 * twice_area,
        })
    }
}

/// Whether the point `p` on the polygon's plane lies inside it (edges
/// included).
#[inline]
pub fn convex_polygon_contains(polygon: &ConvexPolygon, p: DVec3) -> bool {
    let v = &polygon.vertices;
    let n = v.len();
    (0..n).all(|i| {
        let (a, b) = (v[i], v[(i + 1) % n]);
        (b - a).cross(p - a).dot(polygon.normal) >= 0.0
    })
}

/// The distance t > 0 at which the ray meets the polygon, or `None`.
#[inline]
pub fn ray_convex_polygon(origin: DVec3, w: DVec3, polygon: &ConvexPolygon) -> Option<f64> {
    let t = ray_plane(origin, w, polygon.vertices[0], polygon.normal)?;
    convex_polygon_contains(polygon, origin + w * t).then_some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_and_intersects() {
        let square = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ])
        .unwrap();
        assert_eq!(square.normal, DVec3::Z);
        assert_eq!(square.area, 4.0);
        assert_eq!(
            ray_convex_polygon(DVec3::ZERO, DVec3::Z, &square),
            Some(2.0)
        );
        assert!(ray_convex_polygon(DVec3::ZERO, DVec3::X, &square).is_none());
        let bent = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.5),
            DVec3::new(-1.0, 1.0, 2.0),
        ]);
        assert!(bent.unwrap_err().contains("not planar"));
        let concave = ConvexPolygon::new(vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ]);
        assert!(concave.unwrap_err().contains("convex"));
        assert!(ConvexPolygon::new(vec![DVec3::ZERO, DVec3::X]).is_err());
    }
}
