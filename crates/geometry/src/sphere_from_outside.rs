//! A sphere's ray test for many rays from one origin outside it.

macro_rules! sphere_from_outside_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{Real, V3};
        use crate::sphere::$p::Sphere;

        /// A [`Sphere`] prepared for rays from one origin `o` strictly
        /// outside it: whether the ray from `o` along `d` meets it is
        /// [`Intersect::hit_distance`](crate::$p::Intersect::hit_distance)`(&Ray::new(o, d), ∞).is_some()`,
        /// to the bit, without the roots.
        ///
        /// The sphere's test forms v = o − c, b = v·d, the discriminant
        /// D = (r − |v − b·d|)(r + |v − b·d|), c' = |v|² − r², the roots
        /// q = −b + √D (b ≤ 0) or −(b + √D) (b > 0) and c'/q, and takes the
        /// nearer positive one, t, if it is below ∞. From outside (c' > 0)
        /// the roots have the sign of q, so the answer needs only b and D:
        /// a hit exactly when D is finite and non-negative, b ≤ 0 and not
        /// both b = 0 and D = 0 (then q = 0: the ray starts on the tangent
        /// cone's apex line and touches nothing ahead). D and b are the
        /// test's own (the same operations on the same operands, v formed
        /// once), so the answer is the same, grazing rays included; it saves
        /// the second square root, the division and the root selection.
        /// Where c' ≤ 0 (the origin on or inside the sphere, where every
        /// direction may hit) there is no such form: use the sphere's test.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Ray, Sphere, SphereFromOutside};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let ball = Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 10.0), 1.0)?;")]
        #[doc = concat!("let origin = ", stringify!($v3), "::ZERO;")]
        /// let seen = SphereFromOutside::new(&ball, origin).unwrap();
        #[doc = concat!("let d = ", stringify!($v3), "::new(0.05, 0.0, 1.0).normalize();")]
        /// assert!(seen.hits(d));
        /// assert!(!seen.hits(-d));
        #[doc = concat!("assert_eq!(seen.hits(d), ball.hit_distance(&Ray::new(origin, d), ", stringify!($p), "::INFINITY).is_some());")]
        /// // From inside the sphere there is no such form.
        #[doc = concat!("assert!(SphereFromOutside::new(&ball, ", stringify!($v3), "::new(0.0, 0.0, 10.5)).is_none());")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphereFromOutside {
            /// v = o − c, the origin relative to the center.
            to_origin: V3,
            /// The sphere's radius r.
            radius: Real,
        }

        impl SphereFromOutside {
            /// `sphere` seen from `origin`, or `None` unless `origin` is
            /// strictly outside it as the sphere's test computes it
            /// (|o − c|² − r² > 0; not for a NaN origin either).
            pub fn new(sphere: &Sphere, origin: V3) -> Option<Self> {
                let to_origin = origin - sphere.center();
                let radius = sphere.radius();
                let outside = to_origin.length_squared() - radius * radius > 0.0;
                outside.then_some(SphereFromOutside { to_origin, radius })
            }

            /// Whether the ray from the origin along `direction` meets the
            /// sphere at a finite t > 0 (type docs). No branches, so a loop
            /// over many directions vectorises.
            #[inline(always)]
            pub fn hits(&self, direction: V3) -> bool {
                let v = self.to_origin;
                let b = v.dot(direction);
                let perp = v - direction * b;
                let perp_length = perp.length();
                let disc = (self.radius - perp_length) * (self.radius + perp_length);
                let finite_and_non_negative = (0.0..Real::INFINITY).contains(&disc);
                finite_and_non_negative & (b <= 0.0) & !((b == 0.0) & (disc == 0.0))
            }
        }
    };
}

crate::both_precisions!(sphere_from_outside_impl);

#[cfg(test)]
mod tests {
    /// The prepared test answers as the sphere's own, to the bit, in both
    /// precisions: random spheres and origins outside them (near, far,
    /// just off the surface, and f32 spheres so large that D overflows),
    /// and directions random, toward the tangent cone (grazing, where a
    /// rounding decides), exactly perpendicular to v (b = 0) and toward
    /// and away from the center. Negative control: the answer for −d
    /// differs from the sphere's answer for d on some direction, so the
    /// comparison sees a wrong answer.
    macro_rules! same_as_sphere_test {
        ($name:ident, $p:ident, $real:ty, $v3:ty, $huge:expr) => {
            #[test]
            fn $name() {
                use crate::$p::{Intersect, Ray, Sphere, SphereFromOutside};
                let mut h = 0x9e37_79b9_7f4a_7c15u64;
                let mut next = || {
                    h ^= h << 13;
                    h ^= h >> 7;
                    h ^= h << 17;
                    (h >> 11) as $real / (1u64 << 53) as $real
                };
                let (mut compared, mut hits, mut flipped_differs) = (0u32, 0u32, false);
                for case in 0..4000 {
                    let scale: $real = match case % 4 {
                        0 => 1.0,
                        1 => 1e-3,
                        2 => 1e3,
                        _ => $huge,
                    };
                    let center =
                        <$v3>::new(next() - 0.5, next() - 0.5, next() - 0.5) * (4.0 * scale);
                    let radius = (0.05 + next()) * scale;
                    let sphere = Sphere::new(center, radius).unwrap();
                    let dir = <$v3>::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize();
                    // Origins from just outside the surface to far away.
                    let distance = radius
                        * (1.0
                            + <$real>::EPSILON * 4.0
                            + next() * [0.0, 1e-3, 1.0, 30.0][case % 4]);
                    let origin = center + dir * distance;
                    let Some(seen) = SphereFromOutside::new(&sphere, origin) else {
                        continue;
                    };
                    let v = origin - center;
                    let to_center = -v.normalize();
                    // A direction perpendicular to v, for b = 0.
                    let side = v.cross(<$v3>::new(0.3, -0.7, 0.2)).normalize();
                    let sin_max = (radius / v.length()).min(1.0);
                    let cos_max = (1.0 - sin_max * sin_max).max(0.0).sqrt();
                    let mut directions = vec![to_center, -to_center, side];
                    for _ in 0..8 {
                        let random =
                            <$v3>::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize();
                        directions.push(random);
                        // On the tangent cone, nudged in and out.
                        let around = (random - to_center * random.dot(to_center)).normalize();
                        for nudge in [-2.0, -0.5, 0.0, 0.5, 2.0] {
                            let c = cos_max + nudge * <$real>::EPSILON;
                            let s = (1.0 - c * c).max(0.0).sqrt();
                            directions.push((to_center * c + around * s).normalize());
                        }
                    }
                    for d in directions {
                        if !d.is_finite() {
                            continue;
                        }
                        let expected = sphere
                            .hit_distance(&Ray::new(origin, d), <$real>::INFINITY)
                            .is_some();
                        assert_eq!(
                            seen.hits(d),
                            expected,
                            "sphere {sphere:?}, origin {origin:?}, d {d:?}"
                        );
                        compared += 1;
                        hits += u32::from(expected);
                        flipped_differs |= seen.hits(-d) != expected;
                    }
                }
                // Both answers occur often (the comparison is not of a
                // constant), and the negative control fires.
                assert!(
                    compared > 100_000 && hits > 10_000 && compared - hits > 10_000,
                    "{compared} {hits}"
                );
                assert!(flipped_differs);
                // Inside and on the surface: no prepared form.
                let unit = Sphere::new(<$v3>::ZERO, 1.0).unwrap();
                assert!(SphereFromOutside::new(&unit, <$v3>::new(0.0, 0.5, 0.0)).is_none());
                assert!(SphereFromOutside::new(&unit, <$v3>::X).is_none());
                assert!(SphereFromOutside::new(&unit, <$v3>::NAN).is_none());
            }
        };
    }
    same_as_sphere_test!(same_as_sphere_f64, f64, f64, glam::DVec3, 1e150);
    same_as_sphere_test!(same_as_sphere_f32, f32, f32, glam::Vec3, 1e20);
}
