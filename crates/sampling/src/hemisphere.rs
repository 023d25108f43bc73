//! Uniform and cosine-weighted hemispheres about +z.

macro_rules! hemisphere_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::disk::$p::{concentric_unsigned, concentric_wedge, invert_concentric_disk};
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
        // Always inlined: the estimator's kernels call it per sample inside
        // their vector loops, and since the concentric map's polynomials
        // moved into it (sin_cos_eighth) the compiler left the f64 form out
        // of line there, a call per sample: cosine-hemisphere sampling of a
        // sphere light in f64 took 31 ns a sample instead of 4.
        #[inline(always)]
        pub fn sample_cosine_hemisphere(u: V2) -> V3 {
            lift_to_hemisphere(concentric_wedge(u))
        }

        /// The lift of [`sample_cosine_hemisphere`]: the concentric
        /// wedge's disk point den·(cos ψ, sin ψ) (see
        /// [`concentric_unsigned`]), its signed radius den capped to
        /// |den| < 1, to (den cos ψ, den sin ψ, √((1 − den)(1 + den))).
        ///
        /// The signed radius carries the point's side in the products
        /// themselves: the same bits as flipping the signs of cos ψ and
        /// sin ψ where den < 0 and scaling by |den| (products of the same
        /// magnitudes, with the same sign; (1 − den)(1 + den) is the same
        /// two factors), without the flip's three operations. The caps are
        /// selects, which the compiler makes a single vector minimum and
        /// maximum.
        #[inline(always)]
        fn lift_to_hemisphere((t, den, a_wins): (Real, Real, bool)) -> V3 {
            let (cos_psi, sin_psi) = concentric_unsigned(t, a_wins);
            let r = if den < ONE_MINUS_EPSILON { den } else { ONE_MINUS_EPSILON };
            let r = if r > -ONE_MINUS_EPSILON { r } else { -ONE_MINUS_EPSILON };
            let z = ((1.0 - r) * (1.0 + r)).sqrt();
            V3::new(r * cos_psi, r * sin_psi, z)
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
        ///
        /// Blocks of 256 points take two loops: the concentric map's wedge
        /// and its division, kept in three small arrays, then the sine,
        /// cosine and lift. A sample's whole warp is one long chain of
        /// dependent operations (division, polynomial, square root), and
        /// in one loop few samples' chains overlapped: on the Zen 2 host
        /// (AVX2, 4096 points, medians of 11) a point took 1.29 ns in one
        /// loop and 1.01 in two in f32, 3.64 and 2.78 in f64.
        #[inline(always)]
        pub fn sample_cosine_hemisphere_soa(
            ux: &[Real],
            uy: &[Real],
            wx: &mut [Real],
            wy: &mut [Real],
            wz: &mut [Real],
        ) {
            use crate::soa::SOA_BLOCK;
            let n = crate::soa::common_len(ux, uy, wx, wy, wz);
            let mut t = [0.0 as Real; SOA_BLOCK];
            let mut den = [0.0 as Real; SOA_BLOCK];
            let mut a_wins = [0u32; SOA_BLOCK];
            for start in (0..n).step_by(SOA_BLOCK) {
                let m = SOA_BLOCK.min(n - start);
                let (t, den, a_wins) = (&mut t[..m], &mut den[..m], &mut a_wins[..m]);
                let (ux, uy) = (&ux[start..start + m], &uy[start..start + m]);
                for k in 0..m {
                    let wins;
                    (t[k], den[k], wins) = concentric_wedge(V2::new(ux[k], uy[k]));
                    a_wins[k] = u32::from(wins);
                }
                let (wx, wy, wz) = (
                    &mut wx[start..start + m],
                    &mut wy[start..start + m],
                    &mut wz[start..start + m],
                );
                for k in 0..m {
                    let w = lift_to_hemisphere((t[k], den[k], a_wins[k] != 0));
                    (wx[k], wy[k], wz[k]) = (w.x, w.y, w.z);
                }
            }
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

#[cfg(test)]
mod tests {
    use crate::isa::Isa;

    /// Each slice form gives its one-sample warp's bits with every
    /// instruction set, for lengths inside one block, at its end and past
    /// it, on points that include the disk's center (a zero denominator),
    /// the square's edges and corners and its diagonals (|a| = |b|, the
    /// wedges' border). Negative control: the cosine form fed its
    /// coordinates swapped gives other directions, so the comparison sees
    /// a wrong input.
    macro_rules! slice_forms_test {
        ($name:ident, $p:ident, $real:ty, $v2:ty) => {
            #[test]
            fn $name() {
                use crate::$p::{
                    sample_cosine_hemisphere, sample_cosine_hemisphere_soa,
                    sample_uniform_hemisphere, sample_uniform_hemisphere_soa,
                };
                type Warp = fn(&[$real], &[$real], &mut [$real], &mut [$real], &mut [$real]);
                let special: [$real; 7] = [
                    0.0,
                    0.5,
                    1.0,
                    0.25,
                    0.75,
                    1.0 - <$real>::EPSILON / 2.0,
                    1e-9,
                ];
                let mut h = 0x2545_f491_4f6c_dd1du64;
                let mut next = || {
                    h = h
                        .wrapping_mul(6_364_136_223_846_793_005)
                        .wrapping_add(1_442_695_040_888_963_407);
                    (h >> 40) as $real / (1u64 << 24) as $real
                };
                let mut ux: Vec<$real> = Vec::new();
                let mut uy: Vec<$real> = Vec::new();
                for &a in &special {
                    for &b in &special {
                        ux.push(a);
                        uy.push(b);
                    }
                }
                while ux.len() < 700 {
                    ux.push(next());
                    uy.push(next());
                }
                let forms: [(Warp, fn($v2) -> _); 2] = [
                    (sample_cosine_hemisphere_soa, sample_cosine_hemisphere),
                    (sample_uniform_hemisphere_soa, sample_uniform_hemisphere),
                ];
                for (soa, one) in forms {
                    for len in [0usize, 1, 49, 255, 256, 257, 700] {
                        for isa in Isa::available() {
                            let (mut x, mut y, mut z) =
                                (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
                            isa.run(|| soa(&ux[..len], &uy[..len], &mut x, &mut y, &mut z));
                            for k in 0..len {
                                let w = one(<$v2>::new(ux[k], uy[k]));
                                let got = [x[k], y[k], z[k]].map(<$real>::to_bits);
                                assert_eq!(
                                    got,
                                    [w.x, w.y, w.z].map(<$real>::to_bits),
                                    "{isa} len {len} k {k}"
                                );
                            }
                        }
                    }
                }
                let (mut x, mut y, mut z) = (vec![0.0; 700], vec![0.0; 700], vec![0.0; 700]);
                sample_cosine_hemisphere_soa(&uy, &ux, &mut x, &mut y, &mut z);
                assert!((0..700).any(|k| {
                    let w = sample_cosine_hemisphere(<$v2>::new(ux[k], uy[k]));
                    (x[k], y[k]) != (w.x, w.y)
                }));
            }
        };
    }

    slice_forms_test!(
        f32_slice_forms_are_the_one_sample_warps,
        f32,
        f32,
        glam::Vec2
    );
    slice_forms_test!(
        f64_slice_forms_are_the_one_sample_warps,
        f64,
        f64,
        glam::DVec2
    );
}
