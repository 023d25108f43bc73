//! Spheres.

macro_rules! sphere_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{wide3, Real, V2, V3, PI};
        use crate::batch::$p::{nearest_lanes, occludes_lanes, RayBatch};
        use crate::ray::$p::{gamma, Hit, Intersect, Ray};
        use crate::validate;
        use crate::GeometryError;

        /// A sphere: the points at distance `radius` from `center`.
        ///
        /// - area 4πr²;
        /// - solid angle from a point at distance d > r from the center:
        ///   the cap sin θmax = r/d, Ω = 2π(1 − cos θmax), evaluated as
        ///   2π s²/(1 + cos θmax) with cos θmax = √((d − r)(d + r))/d, which
        ///   loses nothing for tiny or distant spheres (1 − cos θmax would
        ///   round to 0) nor for nearly touching ones;
        /// - intersection: the roots of t² + 2(v·d)t + (|v|² − r²) = 0,
        ///   v = o − c, formed without cancellation (pbrt-v4 §6.8.1): the
        ///   discriminant from the squared distance of the center to the
        ///   line, the small root as c/q where the other form would cancel.
        ///   The hit point is projected back onto the sphere, which bounds
        ///   its error by γ₅ of its offset from the center plus the
        ///   rounding of adding the center (pbrt-v4 §6.8.5);
        /// - surface parameters (φ/2π, θ/π) of the outward normal, φ from
        ///   +x about +z in [0, 2π), θ from +z.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Ray, Sphere};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let s = Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 10.0), 1.0)?;")]
        #[doc = concat!("let hit = s.intersect(&Ray::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z), ", stringify!($p), "::INFINITY).unwrap();")]
        /// assert_eq!(hit.distance, 9.0);
        #[doc = concat!("assert_eq!(hit.normal, -", stringify!($v3), "::Z);")]
        /// // The Sun seen from the Earth: about 68 μsr.
        #[doc = concat!("let sun = Sphere::new(", stringify!($v3), "::new(1.496e11, 0.0, 0.0), 6.957e8)?;")]
        #[doc = concat!("assert!((sun.solid_angle_from(", stringify!($v3), "::ZERO) - 6.794e-5).abs() < 1e-8);")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Sphere {
            center: V3,
            radius: Real,
        }

        impl Sphere {
            /// The sphere of `radius` > 0 about `center`. Errors name the
            /// field: a non-finite center, a radius that is not finite and
            /// positive.
            pub fn new(center: V3, radius: Real) -> Result<Self, GeometryError> {
                validate::finite3("center", wide3(center))?;
                validate::positive("radius", radius as f64)?;
                Ok(Sphere { center, radius })
            }

            /// The center.
            #[inline]
            pub fn center(&self) -> V3 {
                self.center
            }

            /// The radius.
            #[inline]
            pub fn radius(&self) -> Real {
                self.radius
            }

            /// The surface area 4πr², in m².
            #[inline]
            pub fn area(&self) -> Real {
                4.0 * PI * self.radius * self.radius
            }

            /// Whether `point` is inside or on the sphere (|point − c| ≤ r):
            /// there the sphere covers at least a hemisphere of directions.
            /// The distance is taken without overflow (a sphere of radius
            /// 1e308 centred 1e308 away contains the origin).
            #[inline]
            pub fn contains(&self, point: V3) -> bool {
                !(self.distance_to_center(point) > self.radius)
            }

            /// |point − c|, scaled by its largest component first so that it
            /// neither overflows nor underflows where the result is a
            /// normal number (∞ only when point − c itself overflows).
            #[inline]
            pub fn distance_to_center(&self, point: V3) -> Real {
                let v = point - self.center;
                let largest = v.abs().max_element();
                if largest > 0.0 && largest.is_finite() {
                    largest * (v / largest).length()
                } else {
                    largest
                }
            }

            /// The solid angle, in steradians, that the sphere subtends at
            /// `point` (see the type's docs); 4π from inside or on it.
            #[inline]
            pub fn solid_angle_from(&self, point: V3) -> Real {
                let mut d = (point - self.center).length();
                if d == Real::INFINITY {
                    // |point − c|² overflowed: the scaled length.
                    d = self.distance_to_center(point);
                }
                let r = self.radius;
                if !(d > r) {
                    return 4.0 * PI;
                }
                let s = r / d;
                let mut c = ((d - r) * (d + r)).sqrt() / d;
                if !c.is_finite() {
                    c = ((1.0 - s) * (1.0 + s)).sqrt();
                }
                2.0 * PI * s * s / (1.0 + c)
            }

            /// The test without branches, for one ray or a batch: whether
            /// the ray from `origin` along `direction` meets the sphere at
            /// some t > 0, and the nearest such t (the far root from
            /// inside).
            #[inline(always)]
            fn lane(&self, origin: V3, direction: V3) -> (bool, Real) {
                let v = origin - self.center;
                let b = v.dot(direction);
                let perp = v - direction * b;
                let perp_length = perp.length();
                let disc = (self.radius - perp_length) * (self.radius + perp_length);
                // NaN when the line misses (disc < 0): discarded below.
                let root = disc.sqrt();
                let c = v.length_squared() - self.radius * self.radius;
                // q = −(b + sign(b)·√disc); the roots are q and c/q.
                let q = if b > 0.0 { -(b + root) } else { -b + root };
                let other = if q != 0.0 { c / q } else { 0.0 };
                let (t0, t1) = if q < other { (q, other) } else { (other, q) };
                let t = if t0 > 0.0 { t0 } else { t1 };
                (!(disc < 0.0) & (t > 0.0), t)
            }

            /// The hit point at `t` along `ray`, relative to the center and
            /// projected back onto the surface: |offset| = r up to one
            /// rounding.
            #[inline]
            fn surface_offset(&self, ray: &Ray, t: Real) -> V3 {
                let raw = ray.at(t) - self.center;
                raw * (self.radius / raw.length())
            }
        }

        impl Intersect for Sphere {
            #[inline(always)]
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
                let offset = self.surface_offset(ray, t);
                let point = self.center + offset;
                Hit {
                    distance: t,
                    point,
                    normal: (offset / self.radius).normalize(),
                    error: offset.abs() * gamma(5) + point.abs() * gamma(1),
                    uv: V2::ZERO,
                }
            }

            #[inline]
            fn surface_parameters(&self, ray: &Ray, t: Real) -> V2 {
                let normal = self.surface_offset(ray, t) / self.radius;
                let phi = normal.y.atan2(normal.x);
                let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
                let theta = normal.z.clamp(-1.0, 1.0).acos();
                V2::new(phi / (2.0 * PI), theta / PI)
            }
        }
    };
}

crate::both_precisions!(sphere_impl);

#[cfg(test)]
mod tests {
    use super::f64::Sphere;
    use crate::f64::{Intersect, Ray};
    use glam::DVec3;

    #[test]
    fn hits_misses_and_far_spheres() {
        let s = Sphere::new(DVec3::new(0.0, 0.0, 10.0), 1.0).unwrap();
        let hit = |o: DVec3, d: DVec3| s.hit_distance(&Ray::new(o, d), f64::INFINITY);
        assert_eq!(hit(DVec3::ZERO, DVec3::Z), Some(9.0));
        assert_eq!(hit(DVec3::ZERO, DVec3::X), None);
        assert_eq!(hit(DVec3::ZERO, -DVec3::Z), None);
        assert_eq!(s.hit_distance(&Ray::new(DVec3::ZERO, DVec3::Z), 9.0), None);
        // 1e6 away: the near root keeps full relative precision.
        let far = Sphere::new(DVec3::new(0.0, 0.0, 1e6), 1.0).unwrap();
        let t = far.hit_distance(&Ray::new(DVec3::ZERO, DVec3::Z), f64::INFINITY);
        assert_eq!(t, Some(1e6 - 1.0));
        // From inside: the far root.
        let big = Sphere::new(DVec3::ZERO, 2.0).unwrap();
        let t = big.hit_distance(&Ray::new(DVec3::ZERO, DVec3::Z), f64::INFINITY);
        assert_eq!(t, Some(2.0));
    }

    #[test]
    fn hit_points_lie_within_their_error_bound_and_spawned_rays_leave() {
        let s = Sphere::new(DVec3::new(0.3, -0.2, 5.0), 1.7).unwrap();
        for i in 0..200 {
            let a = i as f64 * 0.0137;
            let d = DVec3::new(a.sin() * 0.3, a.cos() * 0.3, 1.0).normalize();
            let Some(h) = s.intersect(&Ray::new(DVec3::ZERO, d), f64::INFINITY) else {
                continue;
            };
            // The exact surface passes through the error box.
            let off = ((h.point - s.center()).length() - s.radius()).abs();
            assert!(off <= h.error.length(), "{off} > {}", h.error);
            // Leaving outward (reflection) never re-hits the sphere.
            let out = h.spawn_ray(h.normal);
            assert_eq!(s.hit_distance(&out, f64::INFINITY), None);
            // Entering (refraction) hits the far side, not the entry point.
            let inward = h.spawn_ray(d);
            let t = s.hit_distance(&inward, f64::INFINITY).unwrap();
            assert!(t > 1e-6, "{t}");
        }
    }

    #[test]
    fn bad_input_names_the_field() {
        let e = Sphere::new(DVec3::ZERO, -1.0).unwrap_err();
        assert_eq!(e.to_string(), "radius: must be positive, got -1");
        let e = Sphere::new(DVec3::new(f64::NAN, 0.0, 0.0), 1.0).unwrap_err();
        assert_eq!(e.field(), "center");
        assert!(Sphere::new(DVec3::ZERO, 0.0).is_err());
        assert!(Sphere::new(DVec3::ZERO, f64::INFINITY).is_err());
    }

    #[test]
    fn solid_angles_of_tiny_and_close_spheres() {
        // 1e-8 rad: Ω = π θ² to rounding.
        let s = Sphere::new(DVec3::new(0.0, 0.0, 1e8), 1.0).unwrap();
        let o = s.solid_angle_from(DVec3::ZERO);
        assert!((o / (std::f64::consts::PI * 1e-16) - 1.0).abs() < 1e-15);
        // Touching: a hemisphere.
        let near = Sphere::new(DVec3::new(0.0, 0.0, 1.0 + 1e-12), 1.0).unwrap();
        let o = near.solid_angle_from(DVec3::ZERO);
        assert!((o - 2.0 * std::f64::consts::PI).abs() < 1e-5);
        assert_eq!(
            near.solid_angle_from(DVec3::new(0.0, 0.0, 0.5)),
            4.0 * std::f64::consts::PI
        );
    }
}
