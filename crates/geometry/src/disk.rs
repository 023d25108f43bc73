//! Disks.

macro_rules! disk_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::frame::$p::Frame;
        use crate::batch::$p::{nearest_lanes, occludes_lanes, RayBatch};
        use crate::plane::$p::{plane_lane, point_on_plane};
        use crate::precision::$p::{wide3, Real, V2, V3, PI};
        use crate::ray::$p::{Hit, Intersect, Ray};
        use crate::solid_angle::$p::disk_solid_angle_hs;
        use crate::validate;
        use crate::validate::$p::unit_vector;
        use crate::GeometryError;

        /// A disk: the points of the plane through `center` with unit
        /// `normal` within `radius` of the center. Its front face is the
        /// side the normal points to.
        ///
        /// - area πR²;
        /// - solid angle from a point: exact to max(1e-15, 4ε) relative by
        ///   a closed form along each ray of a pencil and an exponentially
        ///   convergent periodic trapezoid
        ///   ([`disk_solid_angle_hs`]);
        /// - intersection: the plane's, then |p − c|² ≤ R²; the point is
        ///   projected back onto the plane;
        /// - surface parameters (ρ/R, φ/2π) in the disk's [`Frame`].
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Disk, Intersect, Ray};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // A disk of radius 1 at height 1 facing down: a cap of 45°.
        #[doc = concat!("let d = Disk::new(", stringify!($v3), "::Z, -", stringify!($v3), "::Z, 1.0)?;")]
        #[doc = concat!("let omega = d.solid_angle_from(", stringify!($v3), "::ZERO);")]
        #[doc = concat!("let cap = 2.0 * ", "std::", stringify!($p), "::consts::PI * (1.0 - 0.5", stringify!($p), ".sqrt());")]
        /// assert!((omega - cap).abs() < 1e-6);
        #[doc = concat!("let hit = d.intersect(&Ray::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z), 10.0).unwrap();")]
        #[doc = concat!("assert!(hit.is_front(", stringify!($v3), "::Z));")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Disk {
            center: V3,
            frame: Frame,
            radius: Real,
        }

        impl Disk {
            /// The disk; `normal` may have any finite, non-zero length (it
            /// is normalised). Errors name the field: non-finite values, a
            /// zero normal, a radius that is not positive.
            pub fn new(center: V3, normal: V3, radius: Real) -> Result<Self, GeometryError> {
                validate::finite3("center", wide3(center))?;
                let normal = unit_vector("normal", normal)?;
                validate::positive("radius", radius as f64)?;
                Ok(Disk {
                    center,
                    frame: Frame::from_normal(normal),
                    radius,
                })
            }

            /// The center.
            #[inline]
            pub fn center(&self) -> V3 {
                self.center
            }

            /// The unit normal (the front side).
            #[inline]
            pub fn normal(&self) -> V3 {
                self.frame.z
            }

            /// The radius.
            #[inline]
            pub fn radius(&self) -> Real {
                self.radius
            }

            /// The frame whose z is the normal.
            #[inline]
            pub fn frame(&self) -> &Frame {
                &self.frame
            }

            /// The area πR², in m².
            #[inline]
            pub fn area(&self) -> Real {
                PI * self.radius * self.radius
            }

            /// The height h ≥ 0 of `point` above the disk's plane and the
            /// distance s ≥ 0 of its foot from the center.
            #[inline]
            pub fn height_and_offset(&self, point: V3) -> (Real, Real) {
                let v = point - self.center;
                let n = self.frame.z;
                let h = v.dot(n);
                (h.abs(), (v - n * h).length())
            }

            /// The test without branches, for one ray or a batch: whether
            /// the ray meets the disk (rim included) at a finite t > 0, and
            /// t.
            #[inline(always)]
            fn lane(&self, origin: V3, direction: V3) -> (bool, Real) {
                let (hit, t) = plane_lane(origin, direction, self.center, self.frame.z);
                // The hit point relative to the center, formed from c − o
                // (as t is) rather than from the absolute point o + t·d:
                // far from the coordinate origin (|o| ≫ radius) the absolute
                // point rounds by more than the disk's size, which made
                // every nearby direction a hit.
                let p = direction * t - (self.center - origin);
                let r2 = self.radius * self.radius;
                // r² overflows for radii above ≈ 1e154 (f64): |p|² ≤ r² would
                // then hold for every p; compare |p/r|² ≤ 1 instead (a
                // property of the disk, so the branch is the same for every
                // ray).
                let inside = if r2.is_finite() {
                    p.length_squared() <= r2
                } else {
                    (p / self.radius).length_squared() <= 1.0
                };
                (hit & inside, t)
            }

            /// The solid angle, in steradians, that the disk subtends at
            /// `point` (either side); 0 in its plane.
            pub fn solid_angle_from(&self, point: V3) -> Real {
                let (h, s) = self.height_and_offset(point);
                disk_solid_angle_hs(h, s, self.radius)
            }
        }

        impl Intersect for Disk {
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
                let (point, error) = point_on_plane(ray, t, self.center, self.frame.z);
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
                let (point, _) = point_on_plane(ray, t, self.center, self.frame.z);
                let local = self.frame.to_local(point - self.center);
                let rho = local.x.hypot(local.y);
                let phi = local.y.atan2(local.x);
                let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
                V2::new((rho / self.radius).min(1.0), phi / (2.0 * PI))
            }
        }
    };
}

crate::both_precisions!(disk_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{Disk, Intersect, Ray};
    use glam::DVec3;

    #[test]
    fn hits_inside_the_rim_only() {
        let d = Disk::new(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 0.0, -5.0), 1.0).unwrap();
        assert_eq!(d.normal(), -DVec3::Z);
        let up = |x: f64| Ray::new(DVec3::new(x, 0.0, 0.0), DVec3::Z);
        assert_eq!(d.hit_distance(&up(0.5), f64::INFINITY), Some(2.0));
        assert_eq!(d.hit_distance(&up(1.0), f64::INFINITY), Some(2.0));
        assert_eq!(d.hit_distance(&up(1.0 + 1e-15), f64::INFINITY), None);
        assert_eq!(d.hit_distance(&up(0.5), 2.0), None);
        let h = d.intersect(&up(0.5), f64::INFINITY).unwrap();
        assert!(h.is_front(DVec3::Z));
        assert!((h.uv.x - 0.5).abs() < 1e-15);
    }

    #[test]
    fn bad_input_names_the_field() {
        let e = Disk::new(DVec3::ZERO, DVec3::ZERO, 1.0).unwrap_err();
        assert_eq!(e.field(), "normal");
        let e = Disk::new(DVec3::ZERO, DVec3::Z, 0.0).unwrap_err();
        assert_eq!(e.to_string(), "radius: must be positive, got 0");
    }
}
