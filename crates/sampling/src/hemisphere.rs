//! Uniform and cosine-weighted hemispheres about +z.

macro_rules! hemisphere_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::disk::$p::{concentric_polar, invert_concentric_disk};
        use crate::spherical::$p::{azimuth_fraction, direction_from, one_minus_cos_theta};
        use lambert_geometry::precision::$p::{Real, ONE_MINUS_EPSILON, PI, V2, V3};

        /// A direction uniform on the upper hemisphere (cos θ ≥ 0):
        /// cos θ = 1 − u₀, sin θ = √(u₀(2 − u₀)), φ = 2πu₁.
        ///
        /// Uniform: p(ω) = 1/(2π) per steradian for cos θ ≥ 0, by z = 1 − u₀,
        /// φ = 2πu₁ (pbrt-v4 §A.5.2 uses z = u₀; 1 − u₀ keeps u₀ ∈ [0, 1) off the
        /// horizon, so every sample from the half-open square has z > 0). Cosine-weighted: p(ω) = cos θ/π per steradian, by
        /// Malley's method, lifting a concentric-disk sample to the hemisphere
        /// (Shirley & Chiu 1997; pbrt-v4 §A.5.3), which keeps its low distortion.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{invert_uniform_hemisphere, pdf_uniform_hemisphere, sample_uniform_hemisphere};")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.4, 0.9);")]
        /// let w = sample_uniform_hemisphere(u);
        /// assert!(w.z > 0.0 && (w.length() - 1.0).abs() < 1e-6);
        #[doc = concat!("assert_eq!(pdf_uniform_hemisphere(w), 0.5 / std::", stringify!($p), "::consts::PI);")]
        /// assert!((invert_uniform_hemisphere(w) - u).length() < 1e-5);
        /// ```
        #[inline]
        pub fn sample_uniform_hemisphere(u: V2) -> V3 {
            let z = 1.0 - u.x;
            let r = (u.x * (2.0 - u.x)).max(0.0).sqrt();
            direction_from(r, z, u.y)
        }

        /// [`sample_uniform_hemisphere`] over a slice (see
        /// [`sample_cosine_hemisphere_batch`] for why batches are faster).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{sample_uniform_hemisphere, sample_uniform_hemisphere_batch};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let u = [", stringify!($v2), "::new(0.1, 0.2), ", stringify!($v2), "::new(0.7, 0.4)];")]
        #[doc = concat!("let mut w = [", stringify!($v3), "::ZERO; 2];")]
        /// sample_uniform_hemisphere_batch(&u, &mut w);
        /// assert_eq!(w[1], sample_uniform_hemisphere(u[1]));
        /// ```
        #[inline]
        pub fn sample_uniform_hemisphere_batch(u: &[V2], out: &mut [V3]) {
            for (o, &ui) in out.iter_mut().zip(u) {
                *o = sample_uniform_hemisphere(ui);
            }
        }

        /// [`sample_uniform_hemisphere`] in structure-of-arrays form: the
        /// direction for `(ux[i], uy[i])` goes to `(wx[i], wy[i], wz[i])`
        /// (the shortest length wins). The same bits as the one-sample
        /// warp; run inside [`Isa::run`](crate::isa::Isa::run) to use the
        /// processor's widest vectors.
        #[inline(always)]
        pub fn sample_uniform_hemisphere_soa(
            ux: &[Real],
            uy: &[Real],
            wx: &mut [Real],
            wy: &mut [Real],
            wz: &mut [Real],
        ) {
            crate::soa::map2_to3(ux, uy, wx, wy, wz, |u| sample_uniform_hemisphere(u));
        }

        /// The density of [`sample_uniform_hemisphere`]: 1/(2π) per
        /// steradian for w_z ≥ 0, else 0.
        #[inline]
        pub fn pdf_uniform_hemisphere(w: V3) -> Real {
            if w.z >= 0.0 {
                1.0 / (2.0 * PI)
            } else {
                0.0
            }
        }

        /// The u that [`sample_uniform_hemisphere`] maps to `w`:
        /// u₀ = 1 − cos θ (cancellation-free), u₁ = φ/2π.
        #[inline]
        pub fn invert_uniform_hemisphere(w: V3) -> V2 {
            V2::new(one_minus_cos_theta(w).clamp(0.0, 1.0), azimuth_fraction(w))
        }

        /// A direction with density cos θ/π per steradian (Malley's method):
        /// a concentric-disk point (r, φ) lifted to z = √((1 − r)(1 + r)).
        ///
        /// Uniform: p(ω) = 1/(2π) per steradian for cos θ ≥ 0, by z = 1 − u₀,
        /// φ = 2πu₁ (pbrt-v4 §A.5.2 uses z = u₀; 1 − u₀ keeps u₀ ∈ [0, 1) off the
        /// horizon, so every sample from the half-open square has z > 0). Cosine-weighted: p(ω) = cos θ/π per steradian, by
        /// Malley's method, lifting a concentric-disk sample to the hemisphere
        /// (Shirley & Chiu 1997; pbrt-v4 §A.5.3), which keeps its low distortion.
        ///
        /// r is capped at the largest value below 1, so u on the square's
        /// edge (u exactly 0 or 1) gives z ≥ √ε (1.5e-8 in f64, 3.5e-4 in
        /// f32) instead of a horizon direction of pdf 0; the capped set has
        /// probability 0 for u ∈ [0, 1)², so the density is unchanged.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{invert_cosine_hemisphere, pdf_cosine_hemisphere, sample_cosine_hemisphere};")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.3, 0.8);")]
        /// let w = sample_cosine_hemisphere(u);
        #[doc = concat!("assert!((pdf_cosine_hemisphere(w) - w.z / std::", stringify!($p), "::consts::PI).abs() < 1e-6);")]
        /// assert!((invert_cosine_hemisphere(w) - u).length() < 1e-4);
        /// // u on the square's edge still gives a direction of positive density.
        #[doc = concat!("assert!(pdf_cosine_hemisphere(sample_cosine_hemisphere(", stringify!($v2), "::new(1.0, 0.0))) > 0.0);")]
        /// ```
        #[inline]
        pub fn sample_cosine_hemisphere(u: V2) -> V3 {
            let (r, s, c) = concentric_polar(u);
            let r = r.min(ONE_MINUS_EPSILON);
            let z = ((1.0 - r) * (1.0 + r)).sqrt();
            V3::new(r * c, r * s, z)
        }

        /// [`sample_cosine_hemisphere`] over a slice: `out[i]` is the
        /// direction for `u[i]` (the shorter length wins). A loop of
        /// independent, branch-free samples lets the compiler overlap and
        /// vectorise them, which a sample-at-a-time loop that feeds each
        /// result into the next step cannot.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{sample_cosine_hemisphere, sample_cosine_hemisphere_batch};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let u = [", stringify!($v2), "::new(0.1, 0.2), ", stringify!($v2), "::new(0.7, 0.4)];")]
        #[doc = concat!("let mut w = [", stringify!($v3), "::ZERO; 2];")]
        /// sample_cosine_hemisphere_batch(&u, &mut w);
        /// assert_eq!(w[0], sample_cosine_hemisphere(u[0]));
        /// ```
        #[inline]
        pub fn sample_cosine_hemisphere_batch(u: &[V2], out: &mut [V3]) {
            for (o, &ui) in out.iter_mut().zip(u) {
                *o = sample_cosine_hemisphere(ui);
            }
        }

        /// [`sample_cosine_hemisphere`] in structure-of-arrays form: the
        /// direction for `(ux[i], uy[i])` goes to `(wx[i], wy[i], wz[i])`
        /// (the shortest length wins), to the bit the one-sample warp's.
        /// Branch-free, so it vectorises: run it inside
        /// [`Isa::run`](crate::isa::Isa::run) to use the processor's widest
        /// vectors.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{sample_cosine_hemisphere, sample_cosine_hemisphere_soa};")]
        /// use lambert_sampling::isa::Isa;
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        /// let (ux, uy) = ([0.1, 0.7], [0.2, 0.4]);
        /// let (mut x, mut y, mut z) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        /// Isa::selected().run(|| sample_cosine_hemisphere_soa(&ux, &uy, &mut x, &mut y, &mut z));
        #[doc = concat!("let w = sample_cosine_hemisphere(", stringify!($v2), "::new(0.7, 0.4));")]
        /// assert_eq!((x[1], y[1], z[1]), (w.x, w.y, w.z));
        /// ```
        #[inline(always)]
        pub fn sample_cosine_hemisphere_soa(
            ux: &[Real],
            uy: &[Real],
            wx: &mut [Real],
            wy: &mut [Real],
            wz: &mut [Real],
        ) {
            crate::soa::map2_to3(ux, uy, wx, wy, wz, |u| sample_cosine_hemisphere(u));
        }

        /// The density of [`sample_cosine_hemisphere`]: cos θ/π per
        /// steradian for w_z > 0, else 0.
        #[inline]
        pub fn pdf_cosine_hemisphere(w: V3) -> Real {
            w.z.max(0.0) * (1.0 / PI)
        }

        /// The u that [`sample_cosine_hemisphere`] maps to `w`: the
        /// concentric-disk inverse of (w_x, w_y).
        #[inline]
        pub fn invert_cosine_hemisphere(w: V3) -> V2 {
            invert_concentric_disk(V2::new(w.x, w.y))
        }
    };
}

lambert_geometry::both_precisions!(hemisphere_impl);
