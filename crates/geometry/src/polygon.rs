//! Planar convex polygons.

macro_rules! polygon_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::frame::$p::Frame;
        use crate::plane::$p::{plane_distance, point_on_plane};
        use crate::precision::$p::{wide3, Real, V2, V3};
        use crate::ray::$p::{Hit, Intersect, Ray};
        use crate::solid_angle::$p::convex_polygon_solid_angle;
        use crate::validate::$p::power_of_two_above;
        use crate::GeometryError;

        /// A planar, strictly convex polygon; its front face is the side
        /// of the right-hand-rule normal (vertices counter-clockwise seen
        /// from the front).
        ///
        /// - validation: at least 3 finite vertices; the normal by Newell's
        ///   method (robust for any planar polygon; Sutherland, Sproull &
        ///   Schumacker 1974); every vertex within 1e-9 (f64) or 1e-4 (f32)
        ///   of the polygon's extent from the plane; every turn in the
        ///   normal's sense;
        /// - area, from Newell's normal;
        /// - solid angle from a point: the fan of triangles by Van
        ///   Oosterom & Strackee;
        /// - intersection: the plane's, then the point on the inner side of
        ///   every edge; the point is projected back onto the plane;
        /// - surface parameters: coordinates (metres) along the x and y
        ///   axes of the normal's [`Frame`], from the first vertex.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// let square = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, 1.0, 2.0),")]
        /// ])?;
        /// assert_eq!(square.area(), 4.0);
        #[doc = concat!("assert_eq!(square.normal(), ", stringify!($v3), "::Z);")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct ConvexPolygon {
            vertices: Vec<V3>,
            frame: Frame,
            area: Real,
        }

        /// How far from the plane a vertex may lie, relative to the
        /// polygon's extent.
        const PLANARITY: Real = if Real::EPSILON < 1e-10 { 1e-9 } else { 1e-4 };

        impl ConvexPolygon {
            /// Validates `vertices` as a planar, strictly convex,
            /// non-degenerate polygon; errors (field `vertices`) say which
            /// vertex failed and by how much.
            pub fn new(vertices: Vec<V3>) -> Result<Self, GeometryError> {
                let shape = |problem: String| GeometryError::Shape {
                    field: "vertices",
                    problem,
                };
                if vertices.len() < 3 {
                    return Err(shape(format!(
                        "needs at least 3 vertices, got {}",
                        vertices.len()
                    )));
                }
                for (i, v) in vertices.iter().enumerate() {
                    if !v.is_finite() {
                        return Err(shape(format!(
                            "vertex {i} must be finite, got {}",
                            wide3(*v)
                        )));
                    }
                }
                // Validation runs on the vertices divided by a power of two
                // (exact), so that no product of coordinates overflows or
                // underflows: a polygon 1e-300 or 1e300 in size is checked
                // like one of size 1.
                // The coordinates are divided by a power of two so that no
                // product in Newell's sums overflows. A polygon whose extent
                // is below the fourth root of the smallest normal number
                // relative to its coordinates (1e-77 in f64: a triangle of
                // size 5 at 1e81) would still underflow the squares of
                // those products when the normal is normalised: it is
                // then taken relative to its first vertex, with the extent
                // scaled to ~1 by a second power of two.
                let largest = vertices
                    .iter()
                    .fold(0.0, |m: Real, v| m.max(v.abs().max_element()));
                let k1 = power_of_two_above(largest);
                let absolute: Vec<V3> = vertices.iter().map(|&v| v / k1).collect();
                let spread = absolute
                    .iter()
                    .fold(0.0, |m: Real, &v| m.max((v - absolute[0]).abs().max_element()));
                let (scaled, k) = if spread >= Real::MIN_POSITIVE.sqrt().sqrt() {
                    (absolute, k1)
                } else {
                    let k2 = power_of_two_above(spread);
                    let origin = absolute[0];
                    let relative = absolute.iter().map(|&v| (v - origin) / k2).collect();
                    (relative, k1 * k2)
                };
                let n = vertices.len();
                let mut newell = V3::ZERO;
                for i in 0..n {
                    let (a, b) = (scaled[i], scaled[(i + 1) % n]);
                    newell += V3::new(
                        (a.y - b.y) * (a.z + b.z),
                        (a.z - b.z) * (a.x + b.x),
                        (a.x - b.x) * (a.y + b.y),
                    );
                }
                let twice_area = newell.length();
                let extent = scaled
                    .iter()
                    .map(|v| (*v - scaled[0]).length())
                    .fold(0.0, Real::max);
                if !(twice_area > 0.0) {
                    return Err(shape(
                        "has zero area (collinear or repeated vertices)".into(),
                    ));
                }
                let normal = newell / twice_area;
                // The tolerance is relative to the extent, plus the rounding
                // of the computed plane itself: Newell's normal of vertices
                // whose coordinates are c (here ≤ 1) is off by ~ε c/extent in
                // direction, which moves a vertex's distance to the plane by
                // ~ε c. Without that term a small triangle far from the
                // origin (extent 1e-3 of its coordinates, in f32) would be
                // "not planar".
                let tolerance = PLANARITY * extent + 8.0 * Real::EPSILON;
                for (i, v) in scaled.iter().enumerate() {
                    let off = normal.dot(*v - scaled[0]).abs();
                    if off > tolerance {
                        return Err(shape(format!(
                            "is not planar: vertex {i} lies {:e} from the plane of the others (tolerance {:e})",
                            off * k,
                            tolerance * k
                        )));
                    }
                }
                for i in 0..n {
                    let (a, b, c) = (scaled[i], scaled[(i + 1) % n], scaled[(i + 2) % n]);
                    let turn = (b - a).cross(c - b).dot(normal);
                    if turn <= 0.0 {
                        return Err(shape(format!(
                            "is not strictly convex at vertex {} (vertices must turn one way, counter-clockwise seen from the front)",
                            (i + 1) % n
                        )));
                    }
                }
                Ok(ConvexPolygon {
                    vertices,
                    frame: Frame::from_normal(normal),
                    area: 0.5 * twice_area * k * k,
                })
            }

            /// The vertices, in order.
            #[inline]
            pub fn vertices(&self) -> &[V3] {
                &self.vertices
            }

            /// The unit normal (right-hand rule, by Newell's method).
            #[inline]
            pub fn normal(&self) -> V3 {
                self.frame.z
            }

            /// The frame whose z is the normal.
            #[inline]
            pub fn frame(&self) -> &Frame {
                &self.frame
            }

            /// The area, in m²: 0 when it underflows (a polygon 1e-160 m
            /// across) and ∞ when it overflows (1e160 m across). Validity
            /// and the polygon's angles do not depend on its size; what
            /// needs the area (area sampling) gives up on such polygons.
            #[inline]
            pub fn area(&self) -> Real {
                self.area
            }

            /// The solid angle, in steradians, that the polygon subtends at
            /// `point`.
            #[inline]
            pub fn solid_angle_from(&self, point: V3) -> Real {
                convex_polygon_solid_angle(point, &self.vertices)
            }

            /// Whether `point`, on the polygon's plane, lies inside it
            /// (edges included).
            #[inline]
            pub fn contains(&self, point: V3) -> bool {
                // Every edge (a, b), starting with the closing one from the
                // last vertex to the first, so that no index wraps: `% n` is
                // an integer division per edge, which cost more than the
                // edge's test. And no early exit: on random directions a
                // branch per edge mispredicts, where a few more edges of
                // arithmetic do not (the answer is the same).
                let Some(&last) = self.vertices.last() else {
                    return false;
                };
                let mut a = last;
                let mut inside = true;
                for &b in &self.vertices {
                    inside &= (b - a).cross(point - a).dot(self.frame.z) >= 0.0;
                    a = b;
                }
                inside
            }

            /// When the polygon is a rectangle (4 vertices, right angles to
            /// 1e-9, opposite corners closing to 1e-9 of the edges), its
            /// corner and two edges.
            pub fn as_rectangle(&self) -> Option<(V3, V3, V3)> {
                let v = &self.vertices;
                if v.len() != 4 {
                    return None;
                }
                let (e0, e1) = (v[1] - v[0], v[3] - v[0]);
                let opposite = v[0] + e0 + e1 - v[2];
                let square = e0.length() * e1.length();
                ((e0.dot(e1).abs() as f64) <= 1e-9 * square as f64
                    && (opposite.length() as f64) <= 1e-9 * (e0.length() + e1.length()) as f64)
                    .then_some((v[0], e0, e1))
            }
        }

        impl Intersect for ConvexPolygon {
            #[inline]
            fn hit_distance(&self, ray: &Ray, t_max: Real) -> Option<Real> {
                let t = plane_distance(ray, self.vertices[0], self.frame.z)?;
                (t < t_max && self.contains(ray.origin + ray.direction * t)).then_some(t)
            }

            #[inline]
            fn intersect(&self, ray: &Ray, t_max: Real) -> Option<Hit> {
                let t = self.hit_distance(ray, t_max)?;
                Some(Hit {
                    uv: self.surface_parameters(ray, t),
                    ..self.hit_at(ray, t)
                })
            }

            #[inline]
            fn hit_at(&self, ray: &Ray, t: Real) -> Hit {
                let (point, error) = point_on_plane(ray, t, self.vertices[0], self.frame.z);
                Hit {
                    distance: t,
                    point,
                    normal: self.frame.z,
                    error,
                    uv: V2::ZERO,
                }
            }

            #[inline]
            fn surface_parameters(&self, ray: &Ray, t: Real) -> V2 {
                let (point, _) = point_on_plane(ray, t, self.vertices[0], self.frame.z);
                let local = point - self.vertices[0];
                V2::new(local.dot(self.frame.x), local.dot(self.frame.y))
            }
        }
    };
}

crate::both_precisions!(polygon_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{ConvexPolygon, Intersect, Ray};
    use glam::DVec3;

    fn square_vertices() -> [DVec3; 4] {
        [
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ]
    }

    #[test]
    fn validates_and_intersects() {
        let square = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ])
        .unwrap();
        assert_eq!(square.normal(), DVec3::Z);
        assert_eq!(square.area(), 4.0);
        let ray = |d: DVec3| Ray::new(DVec3::ZERO, d);
        assert_eq!(
            square.hit_distance(&ray(DVec3::Z), f64::INFINITY),
            Some(2.0)
        );
        assert!(square.hit_distance(&ray(DVec3::X), f64::INFINITY).is_none());
        assert!(square.as_rectangle().is_some());
        let bent = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.5),
            DVec3::new(-1.0, 1.0, 2.0),
        ]);
        assert!(bent.unwrap_err().to_string().contains("not planar"));
        let concave = ConvexPolygon::new(vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ]);
        assert!(concave.unwrap_err().to_string().contains("convex"));
        // Validity does not depend on size: 1e-300 and 1e300 squares are
        // squares (their areas are beyond f64 and say so with 0 and ∞).
        let tiny = ConvexPolygon::new(square_vertices().map(|v| v * 1e-300).to_vec()).unwrap();
        assert_eq!((tiny.normal(), tiny.area()), (DVec3::Z, 0.0));
        let huge = ConvexPolygon::new(square_vertices().map(|v| v * 1e300).to_vec()).unwrap();
        assert_eq!((huge.normal(), huge.area()), (DVec3::Z, f64::INFINITY));
        // Small far from the origin: a triangle of size 5 at y = −2.8e81
        // (Newell's products would underflow without the translation).
        let far: Vec<DVec3> = [DVec3::ZERO, DVec3::X * 5.0, DVec3::Z * 5.0]
            .map(|v| v + DVec3::new(0.0, -2.8e81, 0.0))
            .to_vec();
        let p = ConvexPolygon::new(far).unwrap();
        assert_eq!(p.normal(), -DVec3::Y);
        let e = ConvexPolygon::new(vec![DVec3::ZERO, DVec3::X]).unwrap_err();
        assert_eq!(e.to_string(), "vertices: needs at least 3 vertices, got 2");
    }
}
