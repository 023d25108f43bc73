//! The cosine between a fixed direction and a direction drawn uniformly from
//! a cone, without the direction itself.

macro_rules! cone_cosine_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::cone::$p::UniformCone;
        use crate::trig::$p::cos_2pi;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// n·ω for ω drawn uniformly from a cone about +z ([`UniformCone`]),
        /// with the azimuth measured from n's projection on the xy plane.
        ///
        /// With ρ = √(n_x² + n_y²) and the cone's warp
        /// 1 − cos θ = u₀h, sin θ = √(u₀h (2 − u₀h)), φ = 2πu₁,
        ///
        /// n·ω = ρ sin θ cos φ + n_z cos θ.
        ///
        /// A rotation about +z maps the cap onto itself and keeps its
        /// uniform density 1/Ω, so this is n·ω for the direction ω that
        /// [`UniformCone::sample`] draws from u, rotated by n's azimuth:
        /// the values have the distribution of n·ω under the cone's density
        /// (not the same value for the same u). An integrand that depends
        /// on ω only through n·ω, such as the irradiance L max(n·ω, 0)/p of
        /// a uniformly bright sphere, or the cosine density of the other
        /// half of MIS, needs nothing else; and cos φ alone is one
        /// polynomial ([`cos_2pi`]) where sin φ and cos φ are two, and the
        /// dot product is two products where it was three (pbrt-v4's
        /// `SampleUniformCone`, §A.5.4, builds the direction).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{ConeCosine, UniformCone};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// let cone = UniformCone::from_cos_theta_max(0.9)?;
        /// // n in the xz plane: its azimuth is 0, so the direction is the cone's own.
        #[doc = concat!("let n = ", stringify!($v3), "::new(0.6, 0.0, 0.8);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.4, 0.3);")]
        /// let cosine = ConeCosine::new(&cone, n).sample(u);
        /// assert!((cosine - n.dot(cone.sample(u))).abs() < 1e-6);
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ConeCosine {
            /// The cone's h = 1 − cos θmax.
            h: Real,
            /// ρ = √(n_x² + n_y²).
            rho: Real,
            /// n_z.
            z: Real,
        }

        impl ConeCosine {
            /// The cosines between `n` (a unit vector in the cone's frame)
            /// and the directions of `cone`.
            #[inline]
            pub fn new(cone: &UniformCone, n: V3) -> Self {
                ConeCosine {
                    h: cone.one_minus_cos_theta_max(),
                    rho: n.x.hypot(n.y),
                    z: n.z,
                }
            }

            /// n·ω for the direction drawn from `u` (the type's docs):
            /// ρ sin θ cos 2πu₁ + n_z cos θ.
            #[inline(always)]
            pub fn sample(&self, u: V2) -> Real {
                let one_minus_cos = u.x * self.h;
                let cos_theta = 1.0 - one_minus_cos;
                let sin_theta = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
                self.rho * sin_theta * cos_2pi(u.y) + self.z * cos_theta
            }
        }
    };
}

lambert_geometry::both_precisions!(cone_cosine_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec2, Vec3};

    /// The directions of the cone rotated about +z by n's azimuth φₙ.
    fn rotated(w: DVec3, n: DVec3) -> DVec3 {
        let (s, c) = n.y.atan2(n.x).sin_cos();
        DVec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

    fn normals() -> Vec<DVec3> {
        [
            DVec3::new(0.3, -0.5, 0.81),
            DVec3::new(-0.9, 0.2, -0.1),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.01, 1.0, 0.0),
        ]
        .map(|n| n.normalize())
        .to_vec()
    }

    /// n·ω against the rotated cone direction, on a grid of u with both
    /// ends, for cones from 10⁻⁶ rad to the whole sphere. The two sides are
    /// computed differently (a cosine polynomial against libm's sin_cos
    /// and atan2 with a 3-vector dot product), each within a few ulps of 1
    /// of the exact value (|n·ω| ≤ 1): 16ε in f64, 16ε in f32 (whose
    /// reference is computed in f64 from the same f32 inputs).
    #[test]
    fn is_the_cosine_of_the_rotated_direction() {
        for h in [2.0, 1.0, 0.1, 1e-6, 5e-13] {
            let cone = crate::f64::UniformCone::from_one_minus_cos(h).unwrap();
            let cone32 = crate::f32::UniformCone::from_one_minus_cos(h as f32).unwrap();
            for n in normals() {
                let cosine = crate::f64::ConeCosine::new(&cone, n);
                let cosine32 = crate::f32::ConeCosine::new(&cone32, n.as_vec3());
                for i in 0..=40 {
                    for j in 0..=40 {
                        let u = DVec2::new(f64::from(i) / 40.0, f64::from(j) / 40.0);
                        let exact = n.dot(rotated(cone.sample(u), n));
                        let got = cosine.sample(u);
                        assert!(
                            (got - exact).abs() <= 16.0 * f64::EPSILON,
                            "h {h}, n {n}, u {u}: {got} vs {exact}"
                        );
                        let u32 = Vec2::new(u.x as f32, u.y as f32);
                        let cone64 = crate::f64::UniformCone::from_one_minus_cos(f64::from(
                            cone32.one_minus_cos_theta_max(),
                        ))
                        .unwrap();
                        let n32: Vec3 = n.as_vec3();
                        let exact32 = n32
                            .as_dvec3()
                            .dot(rotated(cone64.sample(u32.as_dvec2()), n32.as_dvec3()));
                        let got32 = cosine32.sample(u32);
                        assert!(
                            (f64::from(got32) - exact32).abs() <= 16.0 * f64::from(f32::EPSILON),
                            "f32 h {h}, n {n}, u {u}: {got32} vs {exact32}"
                        );
                    }
                }
            }
        }
    }

    /// Negative control: without the rotation (n·ω for the cone's own
    /// direction) the values differ, by far more than the tolerance above,
    /// for a normal with an azimuth.
    #[test]
    fn unrotated_direction_gives_other_values() {
        let cone = crate::f64::UniformCone::from_cos_theta_max(0.5).unwrap();
        let n = DVec3::new(0.3, -0.5, 0.81).normalize();
        let cosine = crate::f64::ConeCosine::new(&cone, n);
        let u = DVec2::new(0.7, 0.2);
        assert!((cosine.sample(u) - n.dot(cone.sample(u))).abs() > 0.1);
    }
}
