//! Parallelograms (rectangles among them).

macro_rules! parallelogram_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::batch::$p::{nearest_lanes, occludes_lanes, RayBatch};
        use crate::plane::$p::{plane_lane, point_on_plane};
        use crate::precision::$p::{wide3, Real, V2, V3};
        use crate::ray::$p::{Hit, Intersect, Ray};
        use crate::solid_angle::$p::triangle_solid_angle;
        use crate::validate;
        use crate::validate::$p::power_of_two_above;
        use crate::GeometryError;

        /// The parallelogram corner + s·edge0 + t·edge1, (s, t) ∈ [0, 1]²;
        /// its front face is the side of the normal edge0 × edge1.
        ///
        /// - area |edge0 × edge1|;
        /// - solid angle from a point: its two triangles by Van Oosterom &
        ///   Strackee (they have the same orientation from any viewpoint,
        ///   so the sum does not cancel);
        /// - intersection: the plane's, then (s, t) from the dual basis,
        ///   s = ((p − c) × e₁)·N/|N|², t = (e₀ × (p − c))·N/|N|² with
        ///   N = e₀ × e₁; the point is projected back onto the plane;
        /// - surface parameters (s, t).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Parallelogram;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // A face of the cube [−1, 1]³ seen from its centre: 4π/6.
        /// let face = Parallelogram::new(
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(2.0, 0.0, 0.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 2.0, 0.0),")]
        /// )?;
        #[doc = concat!("let o = face.solid_angle_from(", stringify!($v3), "::ZERO);")]
        #[doc = concat!("assert!((o - 4.0 * ", "std::", stringify!($p), "::consts::PI / 6.0).abs() < 1e-6);")]
        /// assert!(face.is_rectangle());
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Parallelogram {
            corner: V3,
            edge0: V3,
            edge1: V3,
            normal: V3,
            area: Real,
            /// N/|N|², for the parameters (s, t) of a point.
            dual: V3,
        }

        impl Parallelogram {
            /// The parallelogram. Errors name the field: a non-finite
            /// corner or edge, parallel or zero edges (`edges`), or an area
            /// that overflows.
            pub fn new(corner: V3, edge0: V3, edge1: V3) -> Result<Self, GeometryError> {
                validate::finite3("corner", wide3(corner))?;
                validate::finite3("edge0", wide3(edge0))?;
                validate::finite3("edge1", wide3(edge1))?;
                // Judged on the edges divided by a power of two (exact).
                let k = power_of_two_above(edge0.abs().max(edge1.abs()).max_element());
                let scaled = (edge0 / k).cross(edge1 / k);
                if !(scaled.length() > 0.0) {
                    return Err(GeometryError::Shape {
                        field: "edges",
                        problem: "span zero area (parallel or zero edges)".into(),
                    });
                }
                let n = edge0.cross(edge1);
                let area = n.length();
                let normal = scaled / scaled.length();
                Ok(Parallelogram {
                    corner,
                    edge0,
                    edge1,
                    normal,
                    area,
                    // N/|N|² = n̂/|N|, finite whenever |N| is.
                    dual: normal / area,
                })
            }

            /// The corner.
            #[inline]
            pub fn corner(&self) -> V3 {
                self.corner
            }

            /// The first edge from the corner.
            #[inline]
            pub fn edge0(&self) -> V3 {
                self.edge0
            }

            /// The second edge from the corner.
            #[inline]
            pub fn edge1(&self) -> V3 {
                self.edge1
            }

            /// The unit normal edge0 × edge1 / |edge0 × edge1|.
            #[inline]
            pub fn normal(&self) -> V3 {
                self.normal
            }

            /// The area |edge0 × edge1|, in m².
            #[inline]
            pub fn area(&self) -> Real {
                self.area
            }

            /// The four corners, counter-clockwise seen from the front.
            #[inline]
            pub fn vertices(&self) -> [V3; 4] {
                let c = self.corner;
                [c, c + self.edge0, c + self.edge0 + self.edge1, c + self.edge1]
            }

            /// Whether the edges are perpendicular to 1e-9 of their lengths'
            /// product (the spherical-rectangle sampler needs a rectangle).
            #[inline]
            pub fn is_rectangle(&self) -> bool {
                self.edge0.dot(self.edge1).abs() as f64
                    <= 1e-9 * (self.edge0.length() * self.edge1.length()) as f64
            }

            /// The solid angle, in steradians, that the parallelogram
            /// subtends at `point`.
            #[inline]
            pub fn solid_angle_from(&self, point: V3) -> Real {
                let [a, b, c, d] = self.vertices();
                triangle_solid_angle(point, a, b, c) + triangle_solid_angle(point, a, c, d)
            }

            /// The test without branches, for one ray or a batch: whether
            /// the ray meets the parallelogram (edges included) at a finite
            /// t > 0, and t.
            #[inline(always)]
            fn lane(&self, origin: V3, direction: V3) -> (bool, Real) {
                let (hit, t) = plane_lane(origin, direction, self.corner, self.normal);
                let st = self.parameters(Ray::new(origin, direction).at(t));
                let inside = (st.x >= 0.0) & (st.x <= 1.0) & (st.y >= 0.0) & (st.y <= 1.0);
                (hit & inside, t)
            }

            /// The parameters (s, t) of `point` (on the plane).
            #[inline]
            pub fn parameters(&self, point: V3) -> V2 {
                let v = point - self.corner;
                V2::new(
                    v.cross(self.edge1).dot(self.dual),
                    self.edge0.cross(v).dot(self.dual),
                )
            }
        }

        impl Intersect for Parallelogram {
            #[inline]
            fn hit_distance(&self, ray: &Ray, t_max: Real) -> Option<Real> {
                let (hit, t) = self.lane(ray.origin, ray.direction);
                (hit && t < t_max).then_some(t)
            }

            #[inline(always)]
            fn nearest_in_batch(
                &self,
                rays: &RayBatch,
                id: u32,
                nearest: &mut [Real],
                ids: &mut [u32],
            ) {
                nearest_lanes(rays, id, nearest, ids, |o, d| self.lane(o, d));
            }

            #[inline(always)]
            fn occludes_in_batch(&self, rays: &RayBatch, t_max: &[Real], blocked: &mut [bool]) {
                occludes_lanes(rays, t_max, blocked, |o, d| self.lane(o, d));
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
                let (point, error) = point_on_plane(ray, t, self.corner, self.normal);
                Hit {
                    distance: t,
                    point,
                    normal: self.normal,
                    error,
                    uv: V2::ZERO,
                }
            }

            #[inline]
            fn surface_parameters(&self, ray: &Ray, t: Real) -> V2 {
                let (point, _) = point_on_plane(ray, t, self.corner, self.normal);
                self.parameters(point).clamp(V2::ZERO, V2::ONE)
            }
        }
    };
}

crate::both_precisions!(parallelogram_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{Intersect, Parallelogram, Ray};
    use glam::DVec3;

    #[test]
    fn parameters_and_hits() {
        let p = Parallelogram::new(
            DVec3::new(0.0, 0.0, 2.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        )
        .unwrap();
        assert!(!p.is_rectangle());
        assert_eq!(p.area(), 2.0);
        let uv = p.parameters(DVec3::new(1.5, 0.5, 2.0));
        assert!((uv - glam::DVec2::new(0.5, 0.5)).length() < 1e-15);
        let up = |x: f64, y: f64| Ray::new(DVec3::new(x, y, 0.0), DVec3::Z);
        assert_eq!(p.hit_distance(&up(1.5, 0.5), f64::INFINITY), Some(2.0));
        assert_eq!(p.hit_distance(&up(0.1, 0.5), f64::INFINITY), None);
        let e = Parallelogram::new(DVec3::ZERO, DVec3::X, DVec3::X * 3.0).unwrap_err();
        assert_eq!(e.field(), "edges");
    }
}
