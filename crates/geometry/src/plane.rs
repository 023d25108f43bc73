//! Infinite planes, and the plane intersection every planar shape shares.

macro_rules! plane_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::frame::$p::Frame;
        use crate::precision::$p::{wide3, Real, V2, V3};
        use crate::batch::$p::{nearest_lanes, occludes_lanes, RayBatch};
        use crate::ray::$p::{gamma, Hit, Intersect, Ray};
        use crate::validate;
        use crate::validate::$p::unit_vector;
        use crate::GeometryError;

        /// The parameter t > 0 at which `ray` meets the plane through
        /// `on_plane` with unit normal `normal`: t = n·(q − o)/(n·d), or
        /// `None` when the ray is parallel to the plane or the plane is
        /// behind it.
        #[inline]
        pub(crate) fn plane_distance(ray: &Ray, on_plane: V3, normal: V3) -> Option<Real> {
            let (hit, t) = plane_lane(ray.origin, ray.direction, on_plane, normal);
            hit.then_some(t)
        }

        /// [`plane_distance`] without branches, for batches: (whether the
        /// plane is met at a finite t > 0, t).
        #[inline(always)]
        pub(crate) fn plane_lane(origin: V3, direction: V3, on_plane: V3, normal: V3) -> (bool, Real) {
            let denom = normal.dot(direction);
            let t = normal.dot(on_plane - origin) / denom;
            ((t > 0.0) & t.is_finite(), t)
        }

        /// The point at `t` along `ray`, projected onto the plane through
        /// `on_plane` with unit normal `normal`, and a bound on the
        /// absolute error of each of its components.
        ///
        /// o + t·d lies off the plane by the error of t times |d|, which is
        /// large at grazing incidence; projecting back, p − n(n·(p − q)),
        /// leaves only the roundings of the projection: the dot product
        /// (4 roundings of terms bounded by |p| + |q|), the product with n
        /// and the subtraction, γ₇(|p| + |q|) per component.
        #[inline]
        pub(crate) fn point_on_plane(ray: &Ray, t: Real, on_plane: V3, normal: V3) -> (V3, V3) {
            let raw = ray.at(t);
            let point = raw - normal * normal.dot(raw - on_plane);
            let error = (point.abs() + on_plane.abs()) * gamma(7);
            (point, error)
        }

        /// An infinite plane through a point, with a unit normal.
        ///
        /// - area ∞; solid angle from a point off the plane 2π (a
        ///   half-space of directions), 0 on it;
        /// - intersection: t = n·(q − o)/(n·d); the hit point is projected
        ///   back onto the plane (see the crate docs on error bounds);
        /// - surface parameters: the point's coordinates (metres) along the
        ///   x and y axes of the [`Frame`] of the normal, from the given
        ///   point (for checkerboards and other planar textures).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Plane, Ray};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let floor = Plane::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z)?;")]
        #[doc = concat!("let ray = Ray::new(", stringify!($v3), "::new(1.0, 2.0, 3.0), -", stringify!($v3), "::Z);")]
        #[doc = concat!("let hit = floor.intersect(&ray, ", stringify!($p), "::INFINITY).unwrap();")]
        /// assert_eq!(hit.distance, 3.0);
        #[doc = concat!("assert_eq!(hit.point, ", stringify!($v3), "::new(1.0, 2.0, 0.0));")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Plane {
            point: V3,
            frame: Frame,
        }

        impl Plane {
            /// The plane through `point` with normal `normal` (any finite,
            /// non-zero length; it is normalised). Errors name the field.
            pub fn new(point: V3, normal: V3) -> Result<Self, GeometryError> {
                validate::finite3("point", wide3(point))?;
                let normal = unit_vector("normal", normal)?;
                Ok(Plane {
                    point,
                    frame: Frame::from_normal(normal),
                })
            }

            /// The point the plane was given through.
            #[inline]
            pub fn point(&self) -> V3 {
                self.point
            }

            /// The unit normal.
            #[inline]
            pub fn normal(&self) -> V3 {
                self.frame.z
            }

            /// The frame whose z is the normal (its x and y span the plane).
            #[inline]
            pub fn frame(&self) -> &Frame {
                &self.frame
            }

            /// The signed distance of `point` from the plane (positive on
            /// the side the normal points to).
            #[inline]
            pub fn signed_distance(&self, point: V3) -> Real {
                self.frame.z.dot(point - self.point)
            }

            /// 2π sr from a point off the plane, 0 from a point on it.
            #[inline]
            pub fn solid_angle_from(&self, point: V3) -> Real {
                if self.signed_distance(point) != 0.0 {
                    2.0 * crate::precision::$p::PI
                } else {
                    0.0
                }
            }
        }

        impl Intersect for Plane {
            #[inline]
            fn hit_distance(&self, ray: &Ray, t_max: Real) -> Option<Real> {
                plane_distance(ray, self.point, self.frame.z).filter(|&t| t < t_max)
            }

            #[inline(always)]
            fn nearest_in_batch(
                &self,
                rays: &RayBatch,
                id: u32,
                nearest: &mut [Real],
                ids: &mut [u32],
            ) {
                let (q, n) = (self.point, self.frame.z);
                nearest_lanes(rays, id, nearest, ids, |o, d| plane_lane(o, d, q, n));
            }

            #[inline(always)]
            fn occludes_in_batch(&self, rays: &RayBatch, t_max: &[Real], blocked: &mut [bool]) {
                let (q, n) = (self.point, self.frame.z);
                occludes_lanes(rays, t_max, blocked, |o, d| plane_lane(o, d, q, n));
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
                let (point, error) = point_on_plane(ray, t, self.point, self.frame.z);
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
                let (point, _) = point_on_plane(ray, t, self.point, self.frame.z);
                let local = point - self.point;
                V2::new(local.dot(self.frame.x), local.dot(self.frame.y))
            }
        }
    };
}

crate::both_precisions!(plane_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{Intersect, Plane, Ray};
    use glam::DVec3;

    #[test]
    fn grazing_hits_are_projected_onto_the_plane() {
        let plane = Plane::new(DVec3::new(0.0, 0.0, 1.0), DVec3::new(0.0, 0.3, 1.0)).unwrap();
        for k in 1..40 {
            let slope = 10f64.powi(-k / 4);
            let d = DVec3::new(1.0, 0.0, slope).normalize();
            let ray = Ray::new(DVec3::new(0.0, 0.0, -2.0), d);
            let Some(h) = plane.intersect(&ray, f64::INFINITY) else {
                continue;
            };
            let off = plane.signed_distance(h.point).abs();
            assert!(off <= plane.normal().abs().dot(h.error), "{slope}: {off}");
            // A reflected ray never re-hits the plane it leaves.
            let r = h.spawn_ray(d - 2.0 * d.dot(h.normal) * h.normal);
            assert_eq!(plane.hit_distance(&r, f64::INFINITY), None, "{slope}");
        }
    }

    #[test]
    fn bad_normals_are_named() {
        let e = Plane::new(DVec3::ZERO, DVec3::ZERO).unwrap_err();
        assert_eq!(e.to_string(), "normal: must be a non-zero vector");
        let huge = Plane::new(DVec3::ZERO, DVec3::new(1e300, 1e300, 0.0)).unwrap();
        assert!((huge.normal().length() - 1.0).abs() < 1e-15);
    }
}
