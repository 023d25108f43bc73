//! Rays, hit records, and rays that leave a surface without hitting it
//! again.
//!
//! A hit point computed in floating point lies off the true surface by a
//! few roundings, on either side. A secondary ray started exactly there can
//! hit the same surface again at a tiny distance ("acne"), and a ray started
//! on the wrong side leaks through a surface it touches. Following pbrt-v4
//! (Pharr, Jakob & Humphreys, *Physically Based Rendering*, 4th ed.,
//! §6.8), every intersection reports a conservative bound on the absolute
//! error of each component of its point, and [`Hit::spawn_ray`] moves the
//! origin along the normal, to the side the new ray leaves toward, by the
//! projection of that error box on the normal, then one ulp further away
//! (so rounding of the addition cannot bring it back). The offset is the
//! smallest that provably leaves the surface's error box, so there is no
//! scene-scale "epsilon" to tune and contacts (a sphere resting on a plane)
//! neither leak nor shadow themselves.
//!
//! Error bounds use γₙ = n·u/(1 − n·u), u = ε/2 the unit roundoff (Higham,
//! *Accuracy and Stability of Numerical Algorithms*, §3.1): n roundings
//! of a computation multiply its exact value by at most (1 ± γₙ).

macro_rules! ray_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::batch::$p::RayBatch;
        use crate::precision::$p::{Real, V2, V3};

        /// γₙ = n·u/(1 − n·u), the relative error bound of n roundings
        /// (u = ε/2).
        #[inline]
        pub fn gamma(n: u32) -> Real {
            let nu = n as Real * (0.5 * Real::EPSILON);
            nu / (1.0 - nu)
        }

        /// A ray: the points `origin + t·direction`, t > 0. Intersections
        /// report `t`; with a unit `direction` that is the distance.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Ray;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let ray = Ray::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("assert_eq!(ray.at(2.0), ", stringify!($v3), "::new(0.0, 0.0, 2.0));")]
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Ray {
            /// Where the ray starts.
            pub origin: V3,
            /// Its direction (unit, for `t` to be a distance).
            pub direction: V3,
        }

        impl Ray {
            /// The ray from `origin` along `direction`.
            #[inline]
            pub fn new(origin: V3, direction: V3) -> Self {
                Ray { origin, direction }
            }

            /// The point at parameter `t`: origin + t·direction.
            #[inline]
            pub fn at(&self, t: Real) -> V3 {
                self.origin + self.direction * t
            }
        }

        /// Where a ray met a surface, and what shading and the next ray
        /// need.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Hit {
            /// The ray parameter t > 0 of the hit (the distance along a unit
            /// direction).
            pub distance: Real,
            /// The point, on the surface to within `error`.
            pub point: V3,
            /// The unit geometric normal: outward for a sphere, the shape's
            /// own (right-hand-rule) normal for planar shapes, whichever side
            /// the ray came from.
            pub normal: V3,
            /// A bound on the absolute error of each component of `point`.
            pub error: V3,
            /// Surface parameters, for textures: see each shape.
            pub uv: V2,
        }

        impl Hit {
            /// Whether a ray travelling along `direction` arrived on the
            /// side the normal points to (the front face).
            #[inline]
            pub fn is_front(&self, direction: V3) -> bool {
                direction.dot(self.normal) < 0.0
            }

            /// The normal turned to face against `direction` (toward where
            /// a ray along `direction` came from).
            #[inline]
            pub fn facing_normal(&self, direction: V3) -> V3 {
                if self.is_front(direction) {
                    self.normal
                } else {
                    -self.normal
                }
            }

            /// The origin of a ray leaving the surface toward `direction`:
            /// [`offset_origin`] of the point past its error bound.
            #[inline]
            pub fn spawn_origin(&self, direction: V3) -> V3 {
                offset_origin(self.point, self.error, self.normal, direction)
            }

            /// A ray leaving the surface along `direction` that cannot hit
            /// the surface it leaves at its origin (see the module docs).
            #[inline]
            pub fn spawn_ray(&self, direction: V3) -> Ray {
                Ray::new(self.spawn_origin(direction), direction)
            }

            /// A shadow ray from the surface toward `target` (a light's
            /// point): a unit direction, and the distance at which to stop,
            /// short of `target` by the relative margin [`SHADOW_EPSILON`]
            /// so that the light's own surface does not count as an
            /// occluder. `None` when `target` coincides with the origin.
            #[inline]
            pub fn spawn_ray_to(&self, target: V3) -> Option<(Ray, Real)> {
                let origin = self.spawn_origin(target - self.point);
                let to = target - origin;
                let length = to.length();
                (length > 0.0 && length.is_finite()).then(|| {
                    (
                        Ray::new(origin, to / length),
                        length * (1.0 - SHADOW_EPSILON),
                    )
                })
            }
        }

        /// The relative margin by which a shadow ray stops short of the
        /// light point it aims at (pbrt-v4's `ShadowEpsilon`, 10⁻⁴ in both
        /// precisions): larger than any rounding of the distance, far
        /// smaller than any occluder's distance from the light that
        /// matters.
        pub const SHADOW_EPSILON: Real = 1e-4;

        /// `point` moved along ±`normal`, to the side `direction` points to,
        /// by d = |normal|·`error` (the error box's extent along the
        /// normal), then rounded one ulp further from `point` per
        /// component (pbrt-v4 §6.8.6, "Robust spawned ray origins").
        ///
        /// The rounding is written without branches (the signs it depends
        /// on vary from ray to ray, and mispredicted branches cost more
        /// than the arithmetic); it is `next_up`/`next_down` to the bit.
        #[inline]
        pub fn offset_origin(point: V3, error: V3, normal: V3, direction: V3) -> V3 {
            let d = normal.abs().dot(error);
            let d = if direction.dot(normal) < 0.0 { -d } else { d };
            let offset = normal * d;
            let origin = point + offset;
            V3::new(
                away(origin.x, offset.x),
                away(origin.y, offset.y),
                away(origin.z, offset.z),
            )
        }

        /// `x.next_up()` for `offset` > 0, `x.next_down()` for `offset` < 0,
        /// `x` otherwise, without branches: for finite non-zero `x` one step
        /// of the bit pattern (up in magnitude when `x` and `offset` have
        /// the same sign, down otherwise); ±0 steps to the smallest
        /// subnormal of the offset's sign; an infinity stays where the
        /// step would leave the numbers, and NaN stays NaN.
        #[inline(always)]
        pub(crate) fn away(x: Real, offset: Real) -> Real {
            let bits = x.to_bits();
            let outward = x.is_sign_negative() == offset.is_sign_negative();
            let stepped = Real::from_bits(if outward {
                bits.wrapping_add(1)
            } else {
                bits.wrapping_sub(1)
            });
            let moved = if x.is_nan() | stepped.is_nan() { x } else { stepped };
            let moved = if x == 0.0 {
                Real::from_bits(1).copysign(offset)
            } else {
                moved
            };
            if (offset == 0.0) | offset.is_nan() {
                x
            } else {
                moved
            }
        }

        /// Ray intersection, implemented by every shape.
        ///
        /// [`Intersect::intersect`] is the composition of three steps that
        /// can also be called alone, for tracers that test many shapes and
        /// need the record of the nearest only, and surface parameters only
        /// where a texture is looked up: [`Intersect::hit_distance`] (the
        /// decision and t), [`Intersect::hit_at`] (the record at that t,
        /// without the parameters) and [`Intersect::surface_parameters`]
        /// (the parameters at that t). For every shape of this crate
        /// `intersect(ray, t_max)` is, to the bit,
        /// `Hit { uv: surface_parameters(ray, t), ..hit_at(ray, t) }` with
        /// `t = hit_distance(ray, t_max)?`.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Ray, Sphere};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let s = Sphere::new(", stringify!($v3), "::new(0.3, 0.0, 10.0), 1.0)?;")]
        #[doc = concat!("let ray = Ray::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let full = s.intersect(&ray, ", stringify!($p), "::INFINITY).unwrap();")]
        #[doc = concat!("let t = s.hit_distance(&ray, ", stringify!($p), "::INFINITY).unwrap();")]
        /// let record = s.hit_at(&ray, t);
        /// assert_eq!((record.point, record.normal, record.error), (full.point, full.normal, full.error));
        /// assert_eq!(s.surface_parameters(&ray, t), full.uv);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        pub trait Intersect {
            /// The nearest hit with 0 < t < `t_max`, with its point, normal,
            /// error bound and surface parameters.
            fn intersect(&self, ray: &Ray, t_max: Real) -> Option<Hit>;

            /// The parameter t of the nearest hit with 0 < t < `t_max`
            /// only: the same decision as [`Intersect::intersect`], without
            /// building the hit record (shadow rays, radiance lookups).
            fn hit_distance(&self, ray: &Ray, t_max: Real) -> Option<Real>;

            /// The record of the hit at `t`, a value that
            /// [`Intersect::hit_distance`] returned for `ray`: what
            /// [`Intersect::intersect`] reports, except that the surface
            /// parameters `uv` are left at zero (a tracer asks for them
            /// with [`Intersect::surface_parameters`] where a material
            /// needs them). The shapes of this crate build it from `t`
            /// without repeating the test, except the triangle, whose point
            /// is interpolated from the barycentrics of the test.
            ///
            /// # Panics
            /// The default (for shapes outside this crate) takes the record
            /// from `intersect(ray, ∞)` and panics if that finds no hit, as
            /// it cannot when `t` came from `hit_distance`.
            #[inline]
            fn hit_at(&self, ray: &Ray, t: Real) -> Hit {
                let _ = t;
                let hit = self
                    .intersect(ray, Real::INFINITY)
                    .expect("hit_at: t must come from hit_distance for this ray");
                Hit {
                    uv: V2::ZERO,
                    ..hit
                }
            }

            /// The surface parameters (u, v) of the hit at `t`, a value that
            /// [`Intersect::hit_distance`] returned for `ray`: the `uv` that
            /// [`Intersect::intersect`] reports (see each shape).
            ///
            /// # Panics
            /// As [`Intersect::hit_at`]'s default.
            #[inline]
            fn surface_parameters(&self, ray: &Ray, t: Real) -> V2 {
                let _ = t;
                self.intersect(ray, Real::INFINITY)
                    .expect("surface_parameters: t must come from hit_distance for this ray")
                    .uv
            }

            /// The nearest-hit search of a tracer, one shape against many
            /// rays: for every ray i of `rays` that meets the shape at
            /// 0 < t < `nearest[i]`, sets `nearest[i] = t` and
            /// `ids[i] = id`. Per ray that is, to the bit,
            /// `hit_distance(ray_i, nearest[i])`; spheres, planes, disks
            /// and parallelograms run it as a loop the compiler vectorises
            /// (see [`RayBatch`]).
            ///
            /// # Panics
            /// If `nearest` or `ids` is not as long as `rays`.
            #[inline]
            fn nearest_in_batch(
                &self,
                rays: &RayBatch,
                id: u32,
                nearest: &mut [Real],
                ids: &mut [u32],
            ) {
                assert!(
                    nearest.len() == rays.len() && ids.len() == rays.len(),
                    "one entry per ray"
                );
                for i in 0..rays.len() {
                    if let Some(t) = self.hit_distance(&rays.get(i), nearest[i]) {
                        nearest[i] = t;
                        ids[i] = id;
                    }
                }
            }

            /// The shadow-ray test of a tracer, one shape against many
            /// rays: sets `blocked[i]` for every ray i of `rays` that meets
            /// the shape at 0 < t < `t_max[i]` (and leaves the others as
            /// they are): per ray, `hit_distance(ray_i, t_max[i]).is_some()`
            /// (see [`Intersect::nearest_in_batch`]).
            ///
            /// # Panics
            /// If `t_max` or `blocked` is not as long as `rays`.
            #[inline]
            fn occludes_in_batch(&self, rays: &RayBatch, t_max: &[Real], blocked: &mut [bool]) {
                assert!(
                    t_max.len() == rays.len() && blocked.len() == rays.len(),
                    "one entry per ray"
                );
                for i in 0..rays.len() {
                    if !blocked[i] && self.hit_distance(&rays.get(i), t_max[i]).is_some() {
                        blocked[i] = true;
                    }
                }
            }
        }
    };
}

crate::both_precisions!(ray_impl);

#[cfg(test)]
mod tests {
    use super::f64::{gamma, offset_origin};
    use glam::DVec3;

    #[test]
    fn the_branch_free_step_is_next_up_and_next_down() {
        let xs = [
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1.0,
            -1.0,
            0.3,
            -7.5e200,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::from_bits(0x7ff0_0000_0000_0001),
        ];
        let offsets = [
            1e-300,
            -1e-300,
            5e-324,
            -5e-324,
            0.0,
            -0.0,
            2.0,
            -2.0,
            f64::NAN,
        ];
        for x in xs {
            for o in offsets {
                let want = if o > 0.0 {
                    x.next_up()
                } else if o < 0.0 {
                    x.next_down()
                } else {
                    x
                };
                let got = super::f64::away(x, o);
                assert!(
                    got.to_bits() == want.to_bits() || got.is_nan() && want.is_nan(),
                    "{x:e} {o:e}: {got:e} vs {want:e}"
                );
                let (x, o) = (x as f32, o as f32);
                let want = if o > 0.0 {
                    x.next_up()
                } else if o < 0.0 {
                    x.next_down()
                } else {
                    x
                };
                let got = super::f32::away(x, o);
                assert!(
                    got.to_bits() == want.to_bits() || got.is_nan() && want.is_nan(),
                    "{x:e} {o:e}: {got:e} vs {want:e}"
                );
            }
        }
    }

    #[test]
    fn gamma_bounds_n_roundings() {
        assert_eq!(gamma(0), 0.0);
        assert!(gamma(1) > f64::EPSILON / 2.0 && gamma(1) < f64::EPSILON / 2.0 * 1.001);
        assert!(gamma(5) > 5.0 * f64::EPSILON / 2.0);
    }

    #[test]
    fn offsets_leave_the_error_box_on_the_side_of_the_direction() {
        let p = DVec3::new(1.0, 2.0, 0.0);
        let err = DVec3::splat(1e-12);
        let up = offset_origin(p, err, DVec3::Z, DVec3::new(0.3, 0.0, 1.0));
        assert!(up.z > 1e-12, "{up}");
        let down = offset_origin(p, err, DVec3::Z, DVec3::new(0.3, 0.0, -1.0));
        assert!(down.z < -1e-12, "{down}");
        // An exact point needs no offset.
        let exact = offset_origin(p, DVec3::ZERO, DVec3::Z, DVec3::Z);
        assert_eq!(exact, p);
    }
}
