//! Triangles.

macro_rules! triangle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{wide3, Real, V2, V3};
        use crate::ray::$p::{gamma, Hit, Intersect, Ray};
        use crate::solid_angle::$p::triangle_solid_angle;
        use crate::validate;
        use crate::validate::$p::power_of_two_above;
        use crate::GeometryError;

        /// A triangle with vertices v₀, v₁, v₂; its front face is the side
        /// of the right-hand-rule normal (v₁ − v₀) × (v₂ − v₀)
        /// (counter-clockwise seen from the front).
        ///
        /// - area |(v₁ − v₀) × (v₂ − v₀)|/2;
        /// - solid angle from a point: Van Oosterom & Strackee's atan2
        ///   form with the triple product from the edges
        ///   ([`triangle_solid_angle`]);
        /// - intersection: the watertight algorithm of Woop, Benthin & Wald
        ///   ("Watertight ray/triangle intersection", JCGT 2(1), 2013; the
        ///   form of pbrt-v4 §6.5.3): the vertices are translated to the
        ///   ray's origin, permuted and sheared so the ray is +z, and the
        ///   edge functions are evaluated there; rays through a shared edge
        ///   or vertex hit one of the triangles that share it, never none,
        ///   and t is accepted only when it exceeds its own error bound. The
        ///   point is interpolated from barycentrics, with the error bound
        ///   γ₇ Σ|bᵢvᵢ| (pbrt-v4 §6.8.5);
        /// - surface parameters (b₁, b₂), the barycentrics of v₁ and v₂.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Ray, Triangle};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// let t = Triangle::new(
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 0.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 0.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 1.0, 1.0),")]
        /// )?;
        /// assert_eq!(t.area(), 0.5);
        #[doc = concat!("let ray = Ray::new(", stringify!($v3), "::new(0.25, 0.25, 0.0), ", stringify!($v3), "::Z);")]
        #[doc = concat!("let hit = t.intersect(&ray, ", stringify!($p), "::INFINITY).unwrap();")]
        /// assert_eq!(hit.distance, 1.0);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Triangle {
            vertices: [V3; 3],
            normal: V3,
            area: Real,
        }

        impl Triangle {
            /// The triangle (v0, v1, v2). Errors name the field: a
            /// non-finite vertex (`v0`, `v1`, `v2`), or collinear or
            /// repeated vertices (`vertices`), judged at any size.
            pub fn new(v0: V3, v1: V3, v2: V3) -> Result<Self, GeometryError> {
                validate::finite3("v0", wide3(v0))?;
                validate::finite3("v1", wide3(v1))?;
                validate::finite3("v2", wide3(v2))?;
                // The cross product of the edges divided by a power of two
                // (exact), so that it neither overflows nor underflows.
                // The edges are divided by a power of two twice: first the
                // vertices, so that the differences cannot overflow, then
                // the edges, so that their cross product neither overflows
                // nor underflows (a triangle of size 5 at 1e160).
                let k1 = power_of_two_above(v0.abs().max(v1.abs()).max(v2.abs()).max_element());
                let (e1, e2) = (v1 / k1 - v0 / k1, v2 / k1 - v0 / k1);
                let k2 = power_of_two_above(e1.abs().max(e2.abs()).max_element());
                let k = k1 * k2;
                let n = (e1 / k2).cross(e2 / k2);
                let len = n.length();
                if !(len > 0.0) {
                    return Err(GeometryError::Shape {
                        field: "vertices",
                        problem: "has zero area (collinear or repeated vertices)".into(),
                    });
                }
                Ok(Triangle {
                    vertices: [v0, v1, v2],
                    normal: n / len,
                    area: 0.5 * len * k * k,
                })
            }

            /// The vertices.
            #[inline]
            pub fn vertices(&self) -> [V3; 3] {
                self.vertices
            }

            /// The unit normal (right-hand rule).
            #[inline]
            pub fn normal(&self) -> V3 {
                self.normal
            }

            /// The area, in m²: 0 when it underflows, ∞ when it overflows
            /// (validity does not depend on size).
            #[inline]
            pub fn area(&self) -> Real {
                self.area
            }

            /// The solid angle, in steradians, that the triangle subtends
            /// at `point`.
            #[inline]
            pub fn solid_angle_from(&self, point: V3) -> Real {
                let [a, b, c] = self.vertices;
                triangle_solid_angle(point, a, b, c)
            }

            /// The watertight test: (t, b₀, b₁, b₂) of the hit with
            /// 0 < t < t_max.
            #[inline]
            fn hit(&self, ray: &Ray, t_max: Real) -> Option<(Real, Real, Real, Real)> {
                let d = ray.direction;
                // Permute so that the largest component of d is z.
                let ad = d.abs();
                let kz = if ad.x > ad.y {
                    if ad.x > ad.z { 0 } else { 2 }
                } else if ad.y > ad.z {
                    1
                } else {
                    2
                };
                // (x, y, z) → (k_x, k_y, k_z) with k_x = k_z + 1, k_y = k_x + 1
                // (mod 3): one copy of the test per permutation, so the
                // permutation costs no branch or index per vector.
                match kz {
                    0 => self.hit_permuted(ray, t_max, |v: V3| V3::new(v.y, v.z, v.x)),
                    1 => self.hit_permuted(ray, t_max, |v: V3| V3::new(v.z, v.x, v.y)),
                    _ => self.hit_permuted(ray, t_max, |v: V3| v),
                }
            }

            /// The watertight test in the coordinates `perm` gives, whose
            /// z is the largest component of the ray's direction.
            #[inline(always)]
            fn hit_permuted(
                &self,
                ray: &Ray,
                t_max: Real,
                perm: impl Fn(V3) -> V3,
            ) -> Option<(Real, Real, Real, Real)> {
                let dp = perm(ray.direction);
                if dp.z == 0.0 {
                    return None;
                }
                let sx = -dp.x / dp.z;
                let sy = -dp.y / dp.z;
                let sz = 1.0 / dp.z;
                let [v0, v1, v2] = self.vertices;
                let (a, b, c) = (
                    perm(v0 - ray.origin),
                    perm(v1 - ray.origin),
                    perm(v2 - ray.origin),
                );
                // Shear so the ray is +z (z is scaled later).
                let (ax, ay) = (a.x + sx * a.z, a.y + sy * a.z);
                let (bx, by) = (b.x + sx * b.z, b.y + sy * b.z);
                let (cx, cy) = (c.x + sx * c.z, c.y + sy * c.z);
                let mut e0 = bx * cy - by * cx;
                let mut e1 = cx * ay - cy * ax;
                let mut e2 = ax * by - ay * bx;
                if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
                    // On an edge to this precision: decide in f64.
                    let f = |x: Real| x as f64;
                    e0 = (f(bx) * f(cy) - f(by) * f(cx)) as Real;
                    e1 = (f(cx) * f(ay) - f(cy) * f(ax)) as Real;
                    e2 = (f(ax) * f(by) - f(ay) * f(bx)) as Real;
                }
                if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
                    return None;
                }
                let det = e0 + e1 + e2;
                if det == 0.0 {
                    return None;
                }
                let (az, bz, cz) = (a.z * sz, b.z * sz, c.z * sz);
                let t_scaled = e0 * az + e1 * bz + e2 * cz;
                if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
                    return None;
                }
                if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
                    return None;
                }
                let inv = 1.0 / det;
                let (b0, b1, b2) = (e0 * inv, e1 * inv, e2 * inv);
                let t = t_scaled * inv;
                // t must exceed its own rounding error (pbrt-v4 §6.8.4).
                let max_z = az.abs().max(bz.abs()).max(cz.abs());
                let delta_z = gamma(3) * max_z;
                let max_x = ax.abs().max(bx.abs()).max(cx.abs());
                let max_y = ay.abs().max(by.abs()).max(cy.abs());
                let delta_x = gamma(5) * (max_x + max_z);
                let delta_y = gamma(5) * (max_y + max_z);
                let delta_e = 2.0 * (gamma(2) * max_x * max_y + delta_y * max_x + delta_x * max_y);
                let max_e = e0.abs().max(e1.abs()).max(e2.abs());
                let delta_t =
                    3.0 * (gamma(3) * max_e * max_z + delta_e * max_z + delta_z * max_e) * inv.abs();
                (t > delta_t).then_some((t, b0, b1, b2))
            }

            /// The hit record of the test's (t, b₀, b₁, b₂).
            #[inline]
            fn record(&self, (t, b0, b1, b2): (Real, Real, Real, Real)) -> Hit {
                let [a, b, c] = self.vertices;
                let point = a * b0 + b * b1 + c * b2;
                let error = ((a * b0).abs() + (b * b1).abs() + (c * b2).abs()) * gamma(7);
                Hit {
                    distance: t,
                    point,
                    normal: self.normal,
                    error,
                    uv: V2::new(b1, b2),
                }
            }

            /// The full record of the hit at `t`, from the test run again.
            #[inline]
            fn hit_at_with_parameters(&self, ray: &Ray, t: Real) -> Hit {
                let hit = self
                    .hit(ray, Real::INFINITY)
                    .expect("t must come from hit_distance for this ray");
                debug_assert_eq!(hit.0, t);
                self.record(hit)
            }
        }

        impl Intersect for Triangle {
            #[inline]
            fn hit_distance(&self, ray: &Ray, t_max: Real) -> Option<Real> {
                self.hit(ray, t_max).map(|h| h.0)
            }

            #[inline]
            fn intersect(&self, ray: &Ray, t_max: Real) -> Option<Hit> {
                self.hit(ray, t_max).map(|h| self.record(h))
            }

            #[inline]
            fn hit_at(&self, ray: &Ray, t: Real) -> Hit {
                // The point comes from the test's barycentrics: run it again.
                Hit {
                    uv: V2::ZERO,
                    ..self.hit_at_with_parameters(ray, t)
                }
            }

            #[inline]
            fn surface_parameters(&self, ray: &Ray, t: Real) -> V2 {
                self.hit_at_with_parameters(ray, t).uv
            }
        }
    };
}

crate::both_precisions!(triangle_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{Intersect, Ray, Triangle};
    use glam::DVec3;

    #[test]
    fn shared_edges_are_watertight() {
        // Two triangles sharing the diagonal of the unit square at z = 1:
        // every ray through the diagonal hits at least one of them.
        let a = Triangle::new(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
        )
        .unwrap();
        let b = Triangle::new(
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        )
        .unwrap();
        let origin = DVec3::new(0.31, 0.77, -0.4);
        for i in 0..=1000 {
            let s = i as f64 / 1000.0;
            let target = DVec3::new(s, s, 1.0);
            let ray = Ray::new(origin, (target - origin).normalize());
            let hits = a.hit_distance(&ray, f64::INFINITY).is_some() as u32
                + b.hit_distance(&ray, f64::INFINITY).is_some() as u32;
            assert!(hits >= 1, "a ray through the shared edge at {s} leaked");
        }
    }

    #[test]
    fn hit_points_and_spawned_rays() {
        let t = Triangle::new(
            DVec3::new(-1.0, -1.0, 3.0),
            DVec3::new(2.0, -0.5, 3.5),
            DVec3::new(0.0, 1.5, 2.5),
        )
        .unwrap();
        for i in 0..100 {
            let a = i as f64 * 0.061;
            let d = DVec3::new(0.2 * a.cos(), 0.2 * a.sin(), 1.0).normalize();
            let Some(h) = t.intersect(&Ray::new(DVec3::ZERO, d), f64::INFINITY) else {
                continue;
            };
            let off = t.normal().dot(h.point - t.vertices()[0]).abs();
            assert!(off <= t.normal().abs().dot(h.error) + 1e-300, "{off}");
            let back = h.spawn_ray(-d);
            assert_eq!(t.hit_distance(&back, f64::INFINITY), None);
            let through = h.spawn_ray(d);
            assert_eq!(t.hit_distance(&through, f64::INFINITY), None);
        }
    }

    #[test]
    fn degenerate_triangles_are_named() {
        let e = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::X * 2.0).unwrap_err();
        assert_eq!(e.field(), "vertices");
        assert!(e.to_string().contains("zero area"));
        // Any size: a 1e-300 triangle is a triangle.
        let tiny = Triangle::new(DVec3::ZERO, DVec3::X * 1e-300, DVec3::Y * 1e-300).unwrap();
        assert_eq!(tiny.normal(), DVec3::Z);
        assert_eq!(tiny.area(), 0.0, "its area underflows, and says so");
        let o = DVec3::new(0.0, 1e160, 0.0);
        let far = Triangle::new(o, o + DVec3::X * 5.0, o + DVec3::Z * 5.0).unwrap();
        assert_eq!(far.normal(), -DVec3::Y);
        let e = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::new(f64::NAN, 0.0, 0.0));
        assert_eq!(e.unwrap_err().field(), "v2");
    }
}
