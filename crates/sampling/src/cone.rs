//! Uniform sampling of the directions in a cone (a spherical cap).

macro_rules! cone_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::error::SamplingError;
        use crate::spherical::$p::{azimuth_fraction, direction_from, one_minus_cos_theta};
        use lambert_geometry::precision::$p::{Real, PI, V2, V3};

        /// The uniform density on a cone of directions about +z, described
        /// by h = 1 − cos θmax ∈ (0, 2].
        ///
        /// The cap of half-angle θmax about +z has solid angle Ω = 2π(1 − cos θmax).
        /// The uniform density is p(ω) = 1/Ω per steradian on the cap. With
        /// h = 1 − cos θmax, the inverse-CDF warp (Shirley & Chiu 1997; pbrt-v4
        /// §A.5.4 `SampleUniformCone`) is
        ///
        /// 1 − cos θ = u₀ h,  sin θ = √(u₀h (2 − u₀h)),  φ = 2π u₁.
        ///
        /// Unlike pbrt-v4 (cos θ = lerp(u₀, 1, cos θmax)), every quantity is formed
        /// from h, never from cos θmax, so a cone of θmax = 1e-8 rad is sampled
        /// exactly in f64 and θmax = 1e-5 rad in f32, where cos θmax rounds to 1.
        /// h itself is built without cancellation (docs/NUMERICS.md): from sin²θmax as
        /// s²/(1 + √(1 − s²)), from θmax as 2 sin²(θmax/2).
        ///
        /// Sample, pdf and inverse are the methods [`UniformCone::sample`],
        /// [`UniformCone::pdf`] and [`UniformCone::invert`]; a cone about
        /// another axis is used through a
        /// [`Frame`](lambert_geometry::f64::Frame).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformCone;")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        /// // A cap of 1e-5 rad: cos θmax rounds to 1 in f32, 1 − cos θmax does not.
        /// let cone = UniformCone::from_theta_max(1e-5)?;
        #[doc = concat!("let w = cone.sample(", stringify!($v2), "::new(0.3, 0.7));")]
        /// assert!(w.z > 0.0 && cone.pdf(w) > 0.0);
        /// assert_eq!(cone.pdf(w), 1.0 / cone.solid_angle());
        #[doc = concat!("assert!((cone.invert(w) - ", stringify!($v2), "::new(0.3, 0.7)).abs().max_element() < 1e-3);")]
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct UniformCone {
            one_minus_cos: Real,
        }

        impl UniformCone {
            /// The cone with 1 − cos θmax = `h`, h ∈ (0, 2]; the form that
            /// loses nothing for tiny cones. Errors if h is not finite, not
            /// in (0, 2], or so small that the pdf 1/(2πh) overflows.
            pub fn from_one_minus_cos(h: Real) -> Result<Self, SamplingError> {
                crate::error::finite("one_minus_cos_theta_max", h as f64)?;
                if !(h > 0.0 && h <= 2.0) || !(1.0 / (2.0 * PI * h)).is_finite() {
                    return Err(SamplingError::OutOfRange {
                        field: "one_minus_cos_theta_max",
                        value: h as f64,
                        range: "(0, 2] with a finite pdf 1/(2π h)",
                    });
                }
                Ok(UniformCone { one_minus_cos: h })
            }

            /// The cone with cos θmax = `cos_theta_max` ∈ [−1, 1). For small
            /// cones prefer [`UniformCone::from_sin2_theta_max`] or
            /// [`UniformCone::from_theta_max`]: cos θmax itself cannot carry
            /// θmax below ~1e-8 rad (f64) or ~3e-4 rad (f32).
            pub fn from_cos_theta_max(cos_theta_max: Real) -> Result<Self, SamplingError> {
                crate::error::finite("cos_theta_max", cos_theta_max as f64)?;
                if !(-1.0..1.0).contains(&cos_theta_max) {
                    return Err(SamplingError::OutOfRange {
                        field: "cos_theta_max",
                        value: cos_theta_max as f64,
                        range: "[-1, 1)",
                    });
                }
                // Exact for cos θmax ≥ ½ (Sterbenz), one rounding otherwise.
                Self::from_one_minus_cos(1.0 - cos_theta_max)
            }

            /// The cone with sin²θmax = `sin2_theta_max` ∈ (0, 1] and
            /// θmax ≤ π/2 (a sphere of radius r at distance d has
            /// sin²θmax = (r/d)²). h = s²/(1 + √(1 − s²)), no cancellation.
            pub fn from_sin2_theta_max(sin2_theta_max: Real) -> Result<Self, SamplingError> {
                crate::error::finite("sin2_theta_max", sin2_theta_max as f64)?;
                if !(sin2_theta_max > 0.0 && sin2_theta_max <= 1.0) {
                    return Err(SamplingError::OutOfRange {
                        field: "sin2_theta_max",
                        value: sin2_theta_max as f64,
                        range: "(0, 1]",
                    });
                }
                Self::from_one_minus_cos(
                    sin2_theta_max / (1.0 + (1.0 - sin2_theta_max).max(0.0).sqrt()),
                )
            }

            /// The cone of half-angle `theta_max` ∈ (0, π] radians;
            /// h = 2 sin²(θmax/2).
            pub fn from_theta_max(theta_max: Real) -> Result<Self, SamplingError> {
                crate::error::finite("theta_max", theta_max as f64)?;
                if !(theta_max > 0.0 && theta_max <= PI) {
                    return Err(SamplingError::OutOfRange {
                        field: "theta_max",
                        value: theta_max as f64,
                        range: "(0, π]",
                    });
                }
                let s = (0.5 * theta_max).sin();
                Self::from_one_minus_cos((2.0 * s * s).min(2.0))
            }

            /// h = 1 − cos θmax.
            #[inline]
            pub fn one_minus_cos_theta_max(&self) -> Real {
                self.one_minus_cos
            }

            /// cos θmax (rounds to 1 for tiny cones; use
            /// [`UniformCone::one_minus_cos_theta_max`] for arithmetic).
            #[inline]
            pub fn cos_theta_max(&self) -> Real {
                1.0 - self.one_minus_cos
            }

            /// The cap's solid angle Ω = 2πh, in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                2.0 * PI * self.one_minus_cos
            }

            /// A direction about +z, uniform on the cap:
            /// 1 − cos θ = u₀h, φ = 2πu₁. u₀ = 0 gives the axis, u₀ = 1 the
            /// rim; every u ∈ [0, 1]² gives a unit vector of positive pdf.
            #[inline]
            pub fn sample(&self, u: V2) -> V3 {
                let one_minus_cos = u.x * self.one_minus_cos;
                let cos_theta = 1.0 - one_minus_cos;
                let sin_theta = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
                direction_from(sin_theta, cos_theta, u.y)
            }

            /// [`UniformCone::sample`] over a slice: `out[i]` for `u[i]`;
            /// independent branch-free iterations that the compiler can
            /// overlap and vectorise.
            #[inline]
            pub fn sample_batch(&self, u: &[V2], out: &mut [V3]) {
                for (o, &ui) in out.iter_mut().zip(u) {
                    *o = self.sample(ui);
                }
            }

            /// [`UniformCone::sample`] in structure-of-arrays form: the
            /// direction for `(ux[i], uy[i])` goes to `(wx[i], wy[i], wz[i])`,
            /// to the bit the one-sample warp's.
            #[inline(always)]
            pub fn sample_soa(
                &self,
                ux: &[Real],
                uy: &[Real],
                wx: &mut [Real],
                wy: &mut [Real],
                wz: &mut [Real],
            ) {
                crate::soa::map2_to3(ux, uy, wx, wy, wz, |u| self.sample(u));
            }

            /// The density 1/(2πh) per steradian of a unit direction `w`
            /// inside the cap, 0 outside. Directions within a few ulps
            /// outside the rim count as inside, so a rim sample rounded
            /// outward keeps the density it was drawn with.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if one_minus_cos_theta(w) <= self.one_minus_cos * (1.0 + 8.0 * Real::EPSILON) {
                    1.0 / (2.0 * PI * self.one_minus_cos)
                } else {
                    0.0
                }
            }

            /// The u that [`UniformCone::sample`] maps to `w` (a unit
            /// direction in the cap): u₀ = (1 − cos θ)/h, u₁ = φ/2π.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                let u0 = (one_minus_cos_theta(w) / self.one_minus_cos).clamp(0.0, 1.0);
                V2::new(u0, azimuth_fraction(w))
            }
        }
    };
}

lambert_geometry::both_precisions!(cone_impl);
