//! Uniform directions on the whole sphere: p(ω) = 1/(4π) per steradian,
//! by cos θ = 1 − 2u₀, φ = 2πu₁ (Archimedes' hat-box theorem; pbrt-v4
//! §A.5.1).

macro_rules! sphere_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::spherical::$p::{azimuth_fraction, direction_from, one_minus_cos_theta};
        use lambert_geometry::precision::$p::{Real, PI, V2, V3};

        /// A direction uniform on the unit sphere: cos θ = 1 − 2u₀,
        /// sin θ = 2√(u₀(1 − u₀)) (no cancellation near the poles), φ = 2πu₁.
        ///
        /// Uniform directions on the whole sphere: p(ω) = 1/(4π) per steradian,
        /// by cos θ = 1 − 2u₀, φ = 2πu₁ (Archimedes' hat-box theorem; pbrt-v4
        /// §A.5.1).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{invert_uniform_sphere, pdf_uniform_sphere, sample_uniform_sphere};")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.75, 0.25);")]
        /// let w = sample_uniform_sphere(u);
        /// assert!(w.z < 0.0, "u₀ > ½ is the lower half");
        #[doc = concat!("assert_eq!(pdf_uniform_sphere(w), 0.25 / std::", stringify!($p), "::consts::PI);")]
        /// assert!((invert_uniform_sphere(w) - u).length() < 1e-5);
        /// ```
        #[inline]
        pub fn sample_uniform_sphere(u: V2) -> V3 {
            let z = 1.0 - 2.0 * u.x;
            let r = 2.0 * (u.x * (1.0 - u.x)).max(0.0).sqrt();
            direction_from(r, z, u.y)
        }

        /// [`sample_uniform_sphere`] over a slice: `out[i]` for `u[i]`.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{sample_uniform_sphere, sample_uniform_sphere_batch};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let u = [", stringify!($v2), "::new(0.1, 0.2)];")]
        #[doc = concat!("let mut w = [", stringify!($v3), "::ZERO];")]
        /// sample_uniform_sphere_batch(&u, &mut w);
        /// assert_eq!(w[0], sample_uniform_sphere(u[0]));
        /// ```
        #[inline]
        pub fn sample_uniform_sphere_batch(u: &[V2], out: &mut [V3]) {
            for (o, &ui) in out.iter_mut().zip(u) {
                *o = sample_uniform_sphere(ui);
            }
        }

        /// [`sample_uniform_sphere`] in structure-of-arrays form: the
        /// direction for `(ux[i], uy[i])` goes to `(wx[i], wy[i], wz[i])`,
        /// to the bit the one-sample warp's.
        #[inline(always)]
        pub fn sample_uniform_sphere_soa(
            ux: &[Real],
            uy: &[Real],
            wx: &mut [Real],
            wy: &mut [Real],
            wz: &mut [Real],
        ) {
            crate::soa::map2_to3(ux, uy, wx, wy, wz, |u| sample_uniform_sphere(u));
        }

        /// The density of [`sample_uniform_sphere`]: 1/(4π) per steradian
        /// everywhere.
        #[inline]
        pub fn pdf_uniform_sphere(_w: V3) -> Real {
            1.0 / (4.0 * PI)
        }

        /// The u that [`sample_uniform_sphere`] maps to `w`:
        /// u₀ = (1 − cos θ)/2, u₁ = φ/2π.
        #[inline]
        pub fn invert_uniform_sphere(w: V3) -> V2 {
            V2::new(
                (0.5 * one_minus_cos_theta(w)).clamp(0.0, 1.0),
                azimuth_fraction(w),
            )
        }
    };
}

lambert_geometry::both_precisions!(sphere_impl);
