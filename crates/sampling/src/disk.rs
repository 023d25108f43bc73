//! Uniform maps from the unit square to the unit disk: the concentric map
//! (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", in
//! the single-branch form attributed to Dave Cline) and the polar map.

macro_rules! disk_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::spherical::$p::azimuth_fraction;
        use crate::trig::$p::{sin_cos_2pi, sin_cos_eighth};
        use lambert_geometry::precision::$p::{Real, PI, V2, V3};

        /// The concentric map in polar form: (r, sin φ, cos φ) with r ≥ 0.
        ///
        /// With a = 2u₀ − 1, b = 2u₁ − 1: if |a| > |b|, r = |a| and
        /// φ = (π/4)(b/a) (+π if a < 0); otherwise r = |b| and
        /// φ = π/2 − (π/4)(a/b) (+π if b < 0). r is exactly max(|a|, |b|),
        /// which callers use to form 1 − r² without cancellation.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::concentric_polar;")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let (r, s, c) = concentric_polar(", stringify!($v2), "::new(1.0, 0.5));")]
        /// assert_eq!(r, 1.0);
        /// assert!((s * s + c * c - 1.0).abs() < 1e-6);
        /// ```
        #[inline(always)]
        pub fn concentric_polar(u: V2) -> (Real, Real, Real) {
            concentric_polar_from(concentric_wedge(u))
        }

        /// The first half of [`concentric_polar`]: the wedge of `u`,
        /// `(t, den, a_wins)` with t = numerator/denominator ∈ [−1, 1],
        /// den the signed radius, `a_wins` whether |a| > |b| (a = 2u₀ − 1,
        /// b = 2u₁ − 1). The slice forms run the two halves in separate
        /// loops (see `sample_cosine_hemisphere_soa`).
        #[inline(always)]
        pub(crate) fn concentric_wedge(u: V2) -> (Real, Real, bool) {
            let a = 2.0 * u.x - 1.0;
            let b = 2.0 * u.y - 1.0;
            // Both wedges at once, resolved by selects rather than branches
            // (the wedge is random, so a branch would mispredict half the
            // time): t = numerator/denominator ∈ [−1, 1], signed radius den.
            let a_wins = a.abs() > b.abs();
            let (num, den) = if a_wins { (b, a) } else { (a, b) };
            let t = if den == 0.0 { 0.0 } else { num / den };
            (t, den, a_wins)
        }

        /// (cos ψ, sin ψ) of the wedge [`concentric_wedge`] found, where
        /// the point is den·(cos ψ, sin ψ): φ = ψ, or ψ + π where den < 0.
        /// a wins: ψ = (π/4)t, (cos ψ, sin ψ) = (c, s); b wins:
        /// ψ = π/2 − (π/4)t, (cos ψ, sin ψ) = (s, c), with
        /// (s, c) = [`sin_cos_eighth`]`(t)`.
        #[inline(always)]
        pub(crate) fn concentric_unsigned(t: Real, a_wins: bool) -> (Real, Real) {
            let (s, c) = sin_cos_eighth(t);
            if a_wins {
                (c, s)
            } else {
                (s, c)
            }
        }

        /// The second half of [`concentric_polar`]: (r, sin φ, cos φ) from
        /// the wedge [`concentric_wedge`] found.
        #[inline(always)]
        pub(crate) fn concentric_polar_from((t, den, a_wins): (Real, Real, bool)) -> (Real, Real, Real) {
            let (cos_phi, sin_phi) = concentric_unsigned(t, a_wins);
            // The sign of den, as a flip rather than a product with ±1
            // (the same value, without the multiplies): den's sign bit
            // xored into both, which is negation where den < 0 (or −0).
            // Written as bits because the compiler's form of the select
            // `if den < 0 { −s } else { s }` took a compare, two negations
            // and three blends a vector; these are an and and two xors
            // (cosine-hemisphere f32 slice form on the Zen 2 host, warp
            // alone: 1.00 → 0.92 ns a point, the same bits).
            let sign = den.to_bits() & (-0.0 as Real).to_bits();
            (
                den.abs(),
                Real::from_bits(sin_phi.to_bits() ^ sign),
                Real::from_bits(cos_phi.to_bits() ^ sign),
            )
        }

        /// A point of the unit disk, uniform in area (density 1/π per unit
        /// area), by Shirley and Chiu's concentric map; low distortion, so
        /// stratification of `u` survives.
        ///
        /// Uniform maps from the unit square to the unit disk: the concentric map
        /// (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", in
        /// the single-branch form attributed to Dave Cline) and the polar map.
        ///
        /// Both have density 1/π per unit area on the unit disk.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{invert_concentric_disk, pdf_concentric_disk, sample_concentric_disk};")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.8, 0.3);")]
        /// let p = sample_concentric_disk(u);
        /// assert!(p.length() <= 1.0);
        #[doc = concat!("assert_eq!(pdf_concentric_disk(p), 1.0 / std::", stringify!($p), "::consts::PI);")]
        /// assert!((invert_concentric_disk(p) - u).length() < 1e-5);
        /// ```
        #[inline(always)]
        pub fn sample_concentric_disk(u: V2) -> V2 {
            let (r, s, c) = concentric_polar(u);
            V2::new(r * c, r * s)
        }

        /// The density of [`sample_concentric_disk`]: 1/π per unit area on
        /// the closed unit disk, 0 outside.
        #[inline]
        pub fn pdf_concentric_disk(p: V2) -> Real {
            if p.length_squared() <= 1.0 + 4.0 * Real::EPSILON {
                1.0 / PI
            } else {
                0.0
            }
        }

        /// The u that [`sample_concentric_disk`] maps to `p` (a point of the
        /// unit disk). Undoes the wedge map: for |x| ≥ |y|, a = ±r and
        /// b = a·(4/π)·atan(y/x); otherwise b = ±r and a = b·(4/π)·atan(x/y).
        #[inline]
        pub fn invert_concentric_disk(p: V2) -> V2 {
            let r = p.length();
            let (a, b) = if r == 0.0 {
                (0.0, 0.0)
            } else if p.x.abs() >= p.y.abs() {
                let a = if p.x < 0.0 { -r } else { r };
                (a, a * (4.0 / PI) * (p.y / p.x).atan())
            } else {
                let b = if p.y < 0.0 { -r } else { r };
                (b * (4.0 / PI) * (p.x / p.y).atan(), b)
            };
            V2::new(
                ((a + 1.0) * 0.5).clamp(0.0, 1.0),
                ((b + 1.0) * 0.5).clamp(0.0, 1.0),
            )
        }

        /// A point of the unit disk, uniform in area, by the polar map
        /// r = √u₀, φ = 2πu₁ (density 1/π per unit area). Simpler than the
        /// concentric map but it distorts strata near the center.
        ///
        /// Uniform maps from the unit square to the unit disk: the concentric map
        /// (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", in
        /// the single-branch form attributed to Dave Cline) and the polar map.
        ///
        /// Both have density 1/π per unit area on the unit disk.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{invert_uniform_disk, pdf_uniform_disk, sample_uniform_disk};")]
        #[doc = concat!("use glam::", stringify!($v2), ";")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.25, 0.5);")]
        /// let p = sample_uniform_disk(u);
        /// assert!((p.length() - 0.5).abs() < 1e-6, "r = √u₀");
        #[doc = concat!("assert_eq!(pdf_uniform_disk(p), 1.0 / std::", stringify!($p), "::consts::PI);")]
        /// assert!((invert_uniform_disk(p) - u).length() < 1e-5);
        /// ```
        #[inline]
        pub fn sample_uniform_disk(u: V2) -> V2 {
            let r = u.x.sqrt();
            let (s, c) = sin_cos_2pi(u.y);
            V2::new(r * c, r * s)
        }

        /// The density of [`sample_uniform_disk`]: 1/π per unit area on the
        /// closed unit disk, 0 outside.
        #[inline]
        pub fn pdf_uniform_disk(p: V2) -> Real {
            pdf_concentric_disk(p)
        }

        /// The u that [`sample_uniform_disk`] maps to `p`: u₀ = r²,
        /// u₁ = φ/2π.
        #[inline]
        pub fn invert_uniform_disk(p: V2) -> V2 {
            let f = azimuth_fraction(V3::new(p.x, p.y, 0.0));
            V2::new(p.length_squared().min(1.0), f)
        }
    };
}

lambert_geometry::both_precisions!(disk_impl);
