//! A convex polygon's ray test for many rays from one origin.

macro_rules! polygon_from_origin_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::polygon::$p::ConvexPolygon;
        use crate::precision::$p::{Real, V3};

        /// A [`ConvexPolygon`] of exactly `N` vertices, prepared for rays
        /// from one origin `o`: whether the ray from `o` along `d` meets it
        /// is [`Intersect::hit_distance`](crate::$p::Intersect::hit_distance)`(&Ray::new(o, d), ∞).is_some()`,
        /// to the bit, at a fraction of the cost.
        ///
        /// The test is the polygon's own (the plane's distance
        /// t = n·(v₀ − o)/(n·d), then the point q = o + t·d on the inner
        /// side of every edge, (b − a) × (q − a) · n ≥ 0), with the parts
        /// that do not depend on `d` computed once: the numerator n·(v₀ − o)
        /// and the edge vectors b − a (the same operations on the same
        /// operands, so the same roundings). With `N` fixed the edge loop
        /// unrolls and has no branch, so a loop over many directions
        /// vectorises across them; the polygon's own test loops over a
        /// vertex list of any length and is called once per ray.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{ConvexPolygon, Intersect, PolygonFromOrigin, Ray};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// let triangle = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 1.0, 2.0),")]
        /// ])?;
        #[doc = concat!("let origin = ", stringify!($v3), "::ZERO;")]
        /// let seen = PolygonFromOrigin::<3>::new(&triangle, origin).unwrap();
        #[doc = concat!("let d = ", stringify!($v3), "::new(0.1, 0.0, 1.0).normalize();")]
        /// assert!(seen.hits(d));
        /// assert!(!seen.hits(-d));
        #[doc = concat!("assert_eq!(seen.hits(d), triangle.hit_distance(&Ray::new(origin, d), ", stringify!($p), "::INFINITY).is_some());")]
        /// // A polygon of another vertex count has no such form.
        /// assert!(PolygonFromOrigin::<4>::new(&triangle, origin).is_none());
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct PolygonFromOrigin<const N: usize> {
            /// The rays' origin o.
            origin: V3,
            /// The polygon's unit normal n.
            normal: V3,
            /// n·(v₀ − o): the numerator of every ray's plane distance.
            numerator: Real,
            /// Each edge's start a.
            starts: [V3; N],
            /// Each edge's vector b − a (the last closes back to v₀).
            edges: [V3; N],
        }

        impl<const N: usize> PolygonFromOrigin<N> {
            /// `polygon` seen from `origin`, or `None` if it does not have
            /// exactly `N` vertices.
            pub fn new(polygon: &ConvexPolygon, origin: V3) -> Option<Self> {
                // With exactly N vertices the padded form pads nothing.
                if polygon.vertices().len() != N {
                    return None;
                }
                Self::padded(polygon, origin)
            }

            /// `polygon` seen from `origin`, for any vertex count from 3 to
            /// `N`: the edges past the last are copies of the last (its
            /// start and vector), and a test repeated leaves the
            /// conjunction of [`hits`](Self::hits) as it was, so the answer
            /// is still the polygon's own, to the bit. One loop of `N`
            /// edges then serves every polygon up to `N` vertices (a
            /// pentagon's general test was a call per ray: 40 ns a
            /// hemisphere sample against 6 for a quadrilateral). `None`
            /// above `N` vertices.
            pub fn padded(polygon: &ConvexPolygon, origin: V3) -> Option<Self> {
                let v = polygon.vertices();
                let n = v.len();
                if n > N || n == 0 {
                    return None;
                }
                let normal = polygon.normal();
                let starts: [V3; N] = std::array::from_fn(|k| v[k.min(n - 1)]);
                let edges = std::array::from_fn(|k| {
                    let k = k.min(n - 1);
                    v[(k + 1) % n] - v[k]
                });
                Some(PolygonFromOrigin {
                    origin,
                    normal,
                    numerator: normal.dot(v[0] - origin),
                    starts,
                    edges,
                })
            }

            /// Whether the ray from the origin along `direction` meets the
            /// polygon (at a finite t > 0; either face).
            #[inline(always)]
            pub fn hits(&self, direction: V3) -> bool {
                let t = self.numerator / self.normal.dot(direction);
                let q = self.origin + direction * t;
                let mut inside = (t > 0.0) & t.is_finite();
                for k in 0..N {
                    let a = self.starts[k];
                    inside &= self.edges[k].cross(q - a).dot(self.normal) >= 0.0;
                }
                inside
            }
        }
    };
}

crate::both_precisions!(polygon_from_origin_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{ConvexPolygon, Intersect, PolygonFromOrigin, Ray};
    use glam::DVec3;

    /// Every direction of a dense grid on the sphere, from origins in
    /// front of, behind and in the plane of a triangle and of a tilted
    /// quadrilateral: the prepared test answers as `hit_distance` does,
    /// direction by direction (the same operations, so no tolerance), and
    /// both answers occur.
    #[test]
    fn agrees_with_the_polygon_test_exactly() {
        let triangle = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(0.0, 1.5, 2.5),
            DVec3::new(2.0, -0.5, 2.2),
        ])
        .unwrap();
        let quad = ConvexPolygon::new(vec![
            DVec3::new(1.0, -1.0, 0.1),
            DVec3::new(1.0, 1.0, 0.1),
            DVec3::new(3.0, 1.0, 2.0),
            DVec3::new(3.0, -1.0, 2.0),
        ])
        .unwrap();
        let origins = [
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 5.0),
            DVec3::new(0.0, 0.0, 2.0),
        ];
        // A tilted regular pentagon, for the padded form.
        let pentagon = ConvexPolygon::new(
            (0..5)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / 5.0;
                    DVec3::new(a.cos(), a.sin(), 2.0 + 0.3 * a.cos())
                })
                .collect(),
        )
        .unwrap();
        let mut counts = [0usize; 2];
        for origin in origins {
            let t3 = PolygonFromOrigin::<3>::new(&triangle, origin).unwrap();
            let t4 = PolygonFromOrigin::<4>::new(&quad, origin).unwrap();
            let p8 = PolygonFromOrigin::<8>::padded(&pentagon, origin).unwrap();
            let t8 = PolygonFromOrigin::<8>::padded(&triangle, origin).unwrap();
            for i in 0..200 {
                for j in 0..400 {
                    let z = 1.0 - 2.0 * (f64::from(i) + 0.5) / 200.0;
                    let phi = std::f64::consts::TAU * f64::from(j) / 400.0;
                    let r = (1.0 - z * z).sqrt();
                    let d = DVec3::new(r * phi.cos(), r * phi.sin(), z);
                    let ray = Ray::new(origin, d);
                    let cases = [
                        (t3.hits(d), &triangle),
                        (t4.hits(d), &quad),
                        (p8.hits(d), &pentagon),
                        (t8.hits(d), &triangle),
                    ];
                    for (seen, polygon) in cases {
                        let want = polygon.hit_distance(&ray, f64::INFINITY).is_some();
                        assert_eq!(seen, want, "origin {origin} direction {d}");
                        counts[usize::from(seen)] += 1;
                    }
                }
            }
        }
        assert!(counts[0] > 0 && counts[1] > 1000, "{counts:?}");
        // Only the vertex count the type names; padded, up to it.
        assert!(PolygonFromOrigin::<3>::new(&quad, DVec3::ZERO).is_none());
        assert!(PolygonFromOrigin::<4>::padded(&pentagon, DVec3::ZERO).is_none());
        assert_eq!(
            PolygonFromOrigin::<4>::padded(&quad, DVec3::ZERO),
            PolygonFromOrigin::<4>::new(&quad, DVec3::ZERO)
        );
    }

    /// Negative control for the padding: copies of the first edge in place
    /// of the last (a padding that drops the closing edge's test) answer
    /// differently from the polygon's test for some direction, so the
    /// comparison above sees a padding that loses an edge.
    #[test]
    fn padding_that_drops_an_edge_is_seen() {
        let pentagon = ConvexPolygon::new(
            (0..5)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / 5.0;
                    DVec3::new(a.cos(), a.sin(), 2.0)
                })
                .collect(),
        )
        .unwrap();
        // The first four vertices and the first again: the test of the
        // edges v₀v₁…v₃v₀, a quadrilateral missing the pentagon's corner v₄.
        let v = pentagon.vertices();
        let quad = ConvexPolygon::new(vec![v[0], v[1], v[2], v[3]]).unwrap();
        let wrong = PolygonFromOrigin::<8>::padded(&quad, DVec3::ZERO).unwrap();
        // Toward the pentagon's point nine tenths of the way from its
        // centre (0, 0, 2) to v₄, beyond the chord v₃v₀ (at 0.31 of it).
        let centre = DVec3::new(0.0, 0.0, 2.0);
        let toward_v4 = (centre + 0.9 * (v[4] - centre)).normalize();
        let ray = Ray::new(DVec3::ZERO, toward_v4);
        assert!(pentagon.hit_distance(&ray, f64::INFINITY).is_some());
        assert!(!wrong.hits(toward_v4));
    }
}
