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

            /// Whether every value [`sample`](Self::sample) returns is
            /// positive: the cone is at most a hemisphere (h ≤ 1), n_z > 0,
            /// and the cosine of the cone's direction farthest from n,
            ///
            /// min n·ω = n_z cos θmax − ρ sin θmax = cos(θₙ + θmax)
            ///
            /// (θₙ the angle from the cone's axis to n; with θmax ≤ π/2 and
            /// θₙ < π/2 the sum stays below π, where this is the minimum),
            /// exceeds 2⁻¹⁰. The margin is far above the rounding of
            /// `sample` (within 16ε of the exact value, ε = 2⁻⁵² or 2⁻²³,
            /// as this module's tests check) and of this bound itself, so
            /// a caller may drop its clamp at 0 and count every sample as
            /// a hit (the whole cone lies above the receiver's horizon, as
            /// a sphere light that the horizon does not cut).
            ///
            /// ```
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::{ConeCosine, UniformCone};")]
            #[doc = concat!("use glam::", stringify!($v3), ";")]
            /// let cone = UniformCone::from_cos_theta_max(0.99)?; // θmax ≈ 8.1°
            #[doc = concat!("let up = ", stringify!($v3), "::new(0.5, 0.0, 0.75_f64.sqrt() as _);")]
            #[doc = concat!("let grazing = ", stringify!($v3), "::new(1.0, 0.0, 0.05);")]
            /// assert!(ConeCosine::new(&cone, up).is_above_horizon()); // θₙ = 30°
            /// assert!(!ConeCosine::new(&cone, grazing.normalize()).is_above_horizon());
            /// # Ok::<(), lambert_sampling::SamplingError>(())
            /// ```
            #[inline]
            pub fn is_above_horizon(&self) -> bool {
                const MARGIN: Real = 1.0 / 1024.0;
                let sin_theta_max = (self.h * (2.0 - self.h)).max(0.0).sqrt();
                let least = self.z * (1.0 - self.h) - self.rho * sin_theta_max;
                self.h <= 1.0 && self.z > 0.0 && least > MARGIN
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

    /// Where `is_above_horizon` holds, every sample on a fine grid of u
    /// (both ends included) is positive, in both precisions; it holds
    /// exactly where the cone's lowest direction, computed apart in f64
    /// from the angles, clears the horizon by more than the margin (cases
    /// within 10⁻⁹ of the margin are skipped). Negative control: where it
    /// does not hold and the lowest direction is below the horizon, some
    /// sample is ≤ 0, so the check is not vacuous.
    #[test]
    fn above_the_horizon_every_sample_is_positive() {
        let mut held = 0;
        let mut negative = 0;
        for cos_max in [0.999_999, 0.99, 0.9, 0.5, 0.1, 0.0, -0.5] {
            let cone = crate::f64::UniformCone::from_cos_theta_max(cos_max).unwrap();
            let cone32 = crate::f32::UniformCone::from_cos_theta_max(cos_max as f32).unwrap();
            for tilt_degrees in [0.0, 10.0, 30.0, 60.0, 80.0, 84.0, 89.0, 90.0, 120.0] {
                let tilt = f64::to_radians(tilt_degrees);
                let n = DVec3::new(tilt.sin(), 0.0, tilt.cos());
                let lowest = (tilt + cos_max.acos()).cos();
                let clear = cos_max >= 0.0 && tilt < std::f64::consts::FRAC_PI_2;
                if clear && (lowest - 1.0 / 1024.0).abs() < 1e-9 {
                    continue;
                }
                let want = clear && lowest > 1.0 / 1024.0;
                let cosine = crate::f64::ConeCosine::new(&cone, n);
                let cosine32 = crate::f32::ConeCosine::new(&cone32, n.as_vec3());
                assert_eq!(
                    cosine.is_above_horizon(),
                    want,
                    "cos {cos_max} tilt {tilt_degrees}"
                );
                let grid = (0..=64).flat_map(|i| (0..=64).map(move |j| (i, j)));
                let least = grid
                    .map(|(i, j)| DVec2::new(f64::from(i) / 64.0, f64::from(j) / 64.0))
                    .map(|u| cosine.sample(u))
                    .fold(f64::INFINITY, f64::min);
                if want {
                    held += 1;
                    assert!(least > 0.0, "cos {cos_max} tilt {tilt_degrees}: {least}");
                }
                if cosine32.is_above_horizon() {
                    let least32 = (0..=64)
                        .flat_map(|i| {
                            (0..=64).map(move |j| Vec2::new(i as f32 / 64.0, j as f32 / 64.0))
                        })
                        .map(|u| cosine32.sample(u))
                        .fold(f32::INFINITY, f32::min);
                    assert!(
                        least32 > 0.0,
                        "f32 cos {cos_max} tilt {tilt_degrees}: {least32}"
                    );
                }
                if !want && lowest < 0.0 && cos_max >= 0.0 {
                    negative += 1;
                    assert!(least <= 0.0, "cos {cos_max} tilt {tilt_degrees}: {least}");
                }
            }
        }
        assert!(
            held >= 10 && negative >= 5,
            "held {held}, negative {negative}"
        );
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
