//! sin and cos of 2πu for u ∈ [0, 1], with exact range reduction, and of
//! moderate angles x (|x| ≤ 1000) by a three-part Cody–Waite reduction.

/// The polynomial coefficients each precision uses (see the module docs).
mod taylor {
    /// f64: to x¹⁶ for sin x / x and cos x.
    pub(super) mod f64 {
        type Real = f64;
        /// π/2 in three parts: the first two have 33 significant bits, so
        /// q·part is exact for |q| < 2²⁰, and the three sum to π/2 within
        /// 2⁻¹²⁰ (`sin_cos`).
        pub const HALF_PI_PARTS: [Real; 3] = [
            1.570_796_326_734_125_6,
            6.077_100_506_303_966e-11,
            2.022_266_248_795_950_6e-21,
        ];
        /// Taylor coefficients of sin x / x in x², to x¹⁶ (see `trig`).
        pub const SIN_TAYLOR: [Real; 9] = [
            1.0,
            -1.0 / 6.0,
            1.0 / 120.0,
            -1.0 / 5040.0,
            1.0 / 362880.0,
            -1.0 / 39916800.0,
            1.0 / 6227020800.0,
            -1.0 / 1307674368000.0,
            1.0 / 355687428096000.0,
        ];
        /// Taylor coefficients of cos x in x², to x¹⁶ (see `trig`).
        pub const COS_TAYLOR: [Real; 9] = [
            1.0,
            -1.0 / 2.0,
            1.0 / 24.0,
            -1.0 / 720.0,
            1.0 / 40320.0,
            -1.0 / 3628800.0,
            1.0 / 479001600.0,
            -1.0 / 87178291200.0,
            1.0 / 20922789888000.0,
        ];
        /// sin y / y ≈ P(y²) on |y| ≤ π/2, [`cos_2pi`]'s sine: the
        /// coefficients of the degree-8 Chebyshev fit of sin √x / √x on
        /// x ∈ [0, (π/2)²] (near-minimax; mpmath's `chebyfit` at 50 digits,
        /// rounded to f64). Its error, 2.1e-19, is far below half an ulp
        /// of the value, as the Taylor series' would be only from y²⁰ on
        /// (two more terms).
        ///
        /// [`cos_2pi`]: crate::f64::cos_2pi
        pub const SIN_HALF_PI: [Real; 9] = [
            1.0,
            -0.166_666_666_666_666_66,
            0.008_333_333_333_333_186,
            -0.000_198_412_698_412_086_76,
            2.755_731_921_122_960_6e-6,
            -2.505_210_689_056_952e-8,
            1.605_894_087_848_656e-10,
            -7.643_026_557_971_632e-13,
            2.721_574_942_298_344_3e-15,
        ];
        /// sin(πt/4)/t ≈ P(t²) on |t| ≤ 1, the concentric map's sine
        /// ([`sin_cos_eighth`]): the degree-6 Chebyshev fit of
        /// sin(π√x/4)/√x on x ∈ [0, 1] (near-minimax; mpmath's `chebyfit`
        /// at 50 digits, rounded to f64). Its error, 2.5e-18, is below a
        /// fortieth of an ulp of the value (≥ 0.7).
        ///
        /// [`sin_cos_eighth`]: crate::f64::sin_cos_eighth
        pub const SIN_EIGHTH: [Real; 7] = [
            // The fit's leading term rounds to π/4 itself.
            core::f64::consts::FRAC_PI_4,
            -0.080_745_512_188_280_54,
            0.002_490_394_570_188_844,
            -3.657_620_415_891_387e-5,
            3.133_616_225_433_416e-7,
            -1.757_150_074_698_393_5e-9,
            6.877_360_573_166_326e-12,
        ];
        /// (cos(πt/4) − 1)/t² ≈ Q(t²) on |t| ≤ 1, the concentric map's
        /// cosine, 1 + t²Q(t²): the degree-6 Chebyshev fit of
        /// (cos(π√x/4) − 1)/x on x ∈ [0, 1] (as [`SIN_EIGHTH`]). Its
        /// error, 1.2e-19, is below a hundredth of an ulp of the cosine.
        pub const COS_EIGHTH: [Real; 7] = [
            -0.308_425_137_534_042_44,
            0.015_854_344_243_815_488,
            -0.000_325_991_886_927_199_6,
            3.590_860_447_448_612e-6,
            -2.461_136_623_830_974_4e-8,
            1.150_067_970_094_049_6e-10,
            -3.863_156_948_832_656e-13,
        ];
    }
    /// f32: to x⁸ for sin x / x, x¹⁰ for cos x.
    pub(super) mod f32 {
        type Real = f32;
        /// π/2 in three parts: the first two have at most 12 significant
        /// bits, so q·part is exact for |q| < 2¹², and the three sum to π/2
        /// within 2⁻⁴⁷ (`sin_cos`).
        pub const HALF_PI_PARTS: [Real; 3] = [1.570_312_5, 4.837_513e-4, 7.549_79e-8];
        /// Taylor coefficients of sin x / x in x², to x⁸ (see `trig`).
        pub const SIN_TAYLOR: [Real; 5] =
            [1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0];
        /// Taylor coefficients of cos x in x², to x¹⁰ (see `trig`).
        pub const COS_TAYLOR: [Real; 6] = [
            1.0,
            -1.0 / 2.0,
            1.0 / 24.0,
            -1.0 / 720.0,
            1.0 / 40320.0,
            -1.0 / 3628800.0,
        ];
        /// sin y / y ≈ P(y²) on |y| ≤ π/2, [`cos_2pi`]'s sine: the
        /// coefficients of the degree-4 Chebyshev fit of sin √x / √x on
        /// x ∈ [0, (π/2)²] (near-minimax; mpmath's `chebyfit` at 50 digits,
        /// rounded to f32). Its error, 4.3e-9, is below a tenth of an ulp
        /// of the value; the Taylor series needs y¹² (two more terms).
        ///
        /// [`cos_2pi`]: crate::f32::cos_2pi
        pub const SIN_HALF_PI: [Real; 5] = [
            1.0,
            -0.166_666_58,
            0.008_333_05,
            -0.000_198_090_17,
            2.605_107_7e-6,
        ];
        /// sin(πt/4)/t ≈ P(t²) on |t| ≤ 1 ([`sin_cos_eighth`]): the
        /// degree-3 Chebyshev fit of sin(π√x/4)/√x on x ∈ [0, 1] (mpmath's
        /// `chebyfit` at 50 digits, rounded to f32). Its error, 2.4e-9, is
        /// below a twentieth of an ulp of the value (≥ 0.7); the Taylor
        /// series in x = πt/4 needs x⁸ (one more term) and a rounded x.
        ///
        /// [`sin_cos_eighth`]: crate::f32::sin_cos_eighth
        pub const SIN_EIGHTH: [Real; 4] = [
            // The fit's leading term rounds to π/4 itself.
            core::f32::consts::FRAC_PI_4,
            -0.080_745_436,
            0.002_490_006_9,
            -3.595_429e-5,
        ];
        /// (cos(πt/4) − 1)/t² ≈ Q(t²) on |t| ≤ 1, the cosine being
        /// 1 + t²Q(t²): the degree-3 Chebyshev fit of (cos(π√x/4) − 1)/x
        /// on x ∈ [0, 1] (as [`SIN_EIGHTH`]). Its error, 1.9e-10, is below
        /// a hundredth of an ulp of the cosine.
        pub const COS_EIGHTH: [Real; 4] = [
            -0.308_425_13,
            0.015_854_338,
            -0.000_325_961_4,
            3.541_952_8e-6,
        ];
    }
}

macro_rules! trig_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use super::taylor::$p::{
            COS_EIGHTH, COS_TAYLOR, HALF_PI_PARTS, SIN_EIGHTH, SIN_HALF_PI, SIN_TAYLOR,
        };
        use lambert_geometry::precision::$p::{Real, PI};

        /// (sin x, cos x) for x ∈ [−π/4, π/4], by Estrin evaluation of the
        /// Taylor series in x² (truncation error below half an ulp on that
        /// interval).
        ///
        /// Every warp turns a uniform u into an azimuth φ = 2πu. The standard
        /// library's `sin_cos` calls libm twice, does a general (Payne–Hanek or
        /// Cody–Waite) reduction by π/2 that we do not need, and cannot be inlined
        /// or vectorised; on this project's machine it is most of the cost of a
        /// cosine-hemisphere sample. Because the argument is a fraction of a turn,
        /// the reduction is exact here: q = round(4u) is the quadrant and
        /// r = 4u − q ∈ [−½, ½] is computed without rounding error (Sterbenz), so
        /// x = (π/2) r ∈ [−π/4, π/4] carries only the one rounding of the product.
        /// On that interval, Taylor polynomials to x¹⁷ (f64) or x⁹ (f32) have a
        /// truncation error below half an ulp: (π/4)¹⁹/19! ≈ 6e-20 and
        /// (π/4)¹¹/11! ≈ 2e-9 relative to values ≥ 0.7 for cos, and to x for sin.
        /// The quadrant then permutes and negates (sin x, cos x).
        ///
        /// The concentric disk's angle (π/4)t has polynomials of its own, in t
        /// ([`sin_cos_eighth`](crate::f64::sin_cos_eighth) of each precision).
        ///
        /// # Panics
        /// Debug builds check the interval (with a few ulps of slack).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::sin_cos_quarter;")]
        /// let (s, c) = sin_cos_quarter(0.5);
        #[doc = concat!("assert!((s - 0.5", stringify!($p), ".sin()).abs() < 1e-6 && (c - 0.5", stringify!($p), ".cos()).abs() < 1e-6);")]
        /// ```
        #[inline(always)]
        pub fn sin_cos_quarter(x: Real) -> (Real, Real) {
            debug_assert!(x.abs() <= PI / 4.0 * (1.0 + 8.0 * Real::EPSILON) || x.is_nan());
            let x2 = x * x;
            (x * estrin(x2, &SIN_TAYLOR), estrin(x2, &COS_TAYLOR))
        }

        /// (sin(πt/4), cos(πt/4)) for t ∈ [−1, 1]: the angle of Shirley and
        /// Chiu's concentric map, φ = (π/4)·t, from the ratio t itself.
        /// sin = t·P(t²) and cos = 1 + t²·Q(t²), P and Q near-minimax fits
        /// in t² (4 terms each in f32, 7 in f64; see the coefficients'
        /// docs), evaluated by Estrin's scheme.
        ///
        /// [`sin_cos_quarter`] of x = (π/4)t gives the same values to within
        /// an ulp or two, but rounds x first and needs longer Taylor series
        /// (5 and 6 terms in f32, 9 and 9 in f64): folding π/4 into the
        /// coefficients takes 17 vector operations where that took 24.
        /// Measured on the cosine-hemisphere slice form with its random
        /// numbers (criterion, 1024 points, Intel Xeon host with AVX-512):
        /// 0.83 → 0.73 ns a point in f32, 1.97 → 1.80 in f64. Checked
        /// against the exact sin(πt/4), cos(πt/4) on every f32 t in
        /// [0, 1]: at most 2.3 and 1.5 ulps (the [`sin_cos_quarter`] route
        /// 2.9 and 2.3).
        ///
        /// # Panics
        /// Debug builds check the interval.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::sin_cos_eighth;")]
        /// assert_eq!(sin_cos_eighth(0.0), (0.0, 1.0));
        /// let (s, c) = sin_cos_eighth(0.5);
        #[doc = concat!("let x = std::", stringify!($p), "::consts::PI / 8.0;")]
        #[doc = concat!("assert!((s - x.sin()).abs() < 4.0 * ", stringify!($p), "::EPSILON);")]
        #[doc = concat!("assert!((c - x.cos()).abs() < 4.0 * ", stringify!($p), "::EPSILON);")]
        /// ```
        #[inline(always)]
        pub fn sin_cos_eighth(t: Real) -> (Real, Real) {
            debug_assert!(t.abs() <= 1.0 || t.is_nan());
            let t2 = t * t;
            (t * estrin(t2, &SIN_EIGHTH), 1.0 + t2 * estrin(t2, &COS_EIGHTH))
        }

        /// Σ cₖ yᵏ by Estrin's scheme: pairs cₖ + cₖ₊₁ y, then pairs of
        /// those with y², and so on. Same rounding order of magnitude as
        /// Horner's rule but a dependency chain of depth log₂ n instead of n,
        /// which is what bounds a sample-at-a-time loop (a warp feeds one
        /// sample's result to the caller while the next is computed). The
        /// loops are over constant lengths and unroll completely.
        #[inline(always)]
        pub(crate) fn estrin(y: Real, c: &[Real]) -> Real {
            let mut buf = [0.0 as Real; 16];
            let mut n = c.len();
            buf[..n].copy_from_slice(c);
            let mut power = y;
            while n > 1 {
                let half = n.div_ceil(2);
                for i in 0..half {
                    // An odd count leaves its last coefficient unpaired: it
                    // moves up as it is. Adding 0·power instead gives the
                    // same value for the finite y ≥ 0 this takes, but the
                    // compiler may not drop that multiply-add (0·∞ is NaN,
                    // −0 + 0 is +0), and it cost 3 of the 25 operations of
                    // each 9-term polynomial.
                    buf[i] = if 2 * i + 1 < n {
                        buf[2 * i] + buf[2 * i + 1] * power
                    } else {
                        buf[2 * i]
                    };
                }
                n = half;
                power = power * power;
            }
            buf[0]
        }

        /// (sin 2πu, cos 2πu) for u ∈ [0, 1] with exact range reduction
        /// (see the module docs). Accurate to about one ulp.
        ///
        /// Every warp turns a uniform u into an azimuth φ = 2πu. The standard
        /// library's `sin_cos` calls libm twice, does a general (Payne–Hanek or
        /// Cody–Waite) reduction by π/2 that we do not need, and cannot be inlined
        /// or vectorised; on this project's machine it is most of the cost of a
        /// cosine-hemisphere sample. Because the argument is a fraction of a turn,
        /// the reduction is exact here: q = round(4u) is the quadrant and
        /// r = 4u − q ∈ [−½, ½] is computed without rounding error (Sterbenz), so
        /// x = (π/2) r ∈ [−π/4, π/4] carries only the one rounding of the product.
        /// On that interval, Taylor polynomials to x¹⁷ (f64) or x⁹ (f32) have a
        /// truncation error below half an ulp: (π/4)¹⁹/19! ≈ 6e-20 and
        /// (π/4)¹¹/11! ≈ 2e-9 relative to values ≥ 0.7 for cos, and to x for sin.
        /// The quadrant then permutes and negates (sin x, cos x).
        ///
        /// The concentric disk's angle (π/4)t has polynomials of its own, in t
        /// ([`sin_cos_eighth`](crate::f64::sin_cos_eighth) of each precision).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::sin_cos_2pi;")]
        /// assert_eq!(sin_cos_2pi(0.25), (1.0, 0.0));
        /// let (s, c) = sin_cos_2pi(0.1);
        #[doc = concat!("assert!((s - (0.2 * std::", stringify!($p), "::consts::PI).sin()).abs() < 1e-6);")]
        #[doc = concat!("assert!((c - (0.2 * std::", stringify!($p), "::consts::PI).cos()).abs() < 1e-6);")]
        /// ```
        #[inline(always)]
        pub fn sin_cos_2pi(u: Real) -> (Real, Real) {
            let four_u = 4.0 * u;
            // q = round(4u): adding and subtracting 1.5·2^(p−1) (p the
            // significand width) rounds to an integer in the float unit, and
            // q's low bits are those of the sum's significand. Two additions
            // and a bit move, where `round` is a libm call on baseline
            // x86-64 and an int↔float round trip costs two conversions.
            let magic: Real = 1.5 * (1u64 << (Real::MANTISSA_DIGITS - 1)) as Real;
            let shifted = four_u + magic;
            let q_bits = shifted.to_bits() as u32;
            let r = four_u - (shifted - magic);
            let (s, c) = sin_cos_quarter(r * (PI / 2.0));
            // Rotate by q quarter turns without branches (random quadrants
            // would mispredict): odd q swaps (s, c) → (c, −s), q & 2 negates.
            let odd = (q_bits & 1) != 0;
            let (s1, c1) = if odd { (c, -s) } else { (s, c) };
            // A sign flip, not a product with ±1 (the same value, without
            // the multiplies).
            if (q_bits & 2) != 0 {
                (-s1, -c1)
            } else {
                (s1, c1)
            }
        }

        /// cos 2πu for u ∈ [0, 1], alone: one polynomial where
        /// [`sin_cos_2pi`] evaluates two.
        ///
        /// cos 2πu is even and of period 1, so it equals cos 2πt with
        /// t = min(u, 1 − u) ∈ [0, ½], and cos 2πt = sin(2π(¼ − t)). Both
        /// steps are exact for the u the samplers draw: 1 − u is exact for
        /// u ≥ ½ (Sterbenz), ¼ − t is exact for t ≥ ⅛ (Sterbenz again) and
        /// for any t on the samplers' grid (2⁻³² in f64, 2⁻²⁴ in f32: ¼ − t
        /// then needs at most 30 or 22 significant bits), and otherwise
        /// rounds where cos 2πu > 0.7, by at most half an ulp of ¼.
        /// y = 2π(¼ − t) ∈
        /// [−π/2, π/2] then carries one rounding, and sin y is y times a
        /// near-minimax polynomial in y² (9 terms in f64, 5 in f32) whose
        /// error is below half an ulp on that interval. So the result is
        /// within about an ulp of 1 of cos 2πu, and within a few ulps of
        /// itself near the zeros u = ¼, ¾ (where y is small and the
        /// polynomial relative).
        ///
        /// The cone's [`ConeCosine`](crate::f64::ConeCosine) needs only
        /// this cosine: it costs about half of [`sin_cos_2pi`].
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::cos_2pi;")]
        /// assert_eq!(cos_2pi(0.25), 0.0);
        /// assert_eq!(cos_2pi(0.5), -cos_2pi(0.0));
        #[doc = concat!("assert!((cos_2pi(0.1) - (0.2 * std::", stringify!($p), "::consts::PI).cos()).abs() < 1e-6);")]
        /// ```
        #[inline(always)]
        pub fn cos_2pi(u: Real) -> Real {
            // A select, not `f64::min`: the same value for every u (a NaN
            // u makes 1 − u NaN too), without `min`'s NaN rule, which cost
            // a compare and a blend beside the vector minimum.
            let flipped = 1.0 - u;
            let t = if flipped < u { flipped } else { u };
            let y = (0.25 - t) * (2.0 * PI);
            y * estrin(y * y, &SIN_HALF_PI)
        }

        /// (sin x, cos x) for |x| ≤ 1000, accurate to about an ulp of 1
        /// (absolute), and to about an ulp of sin x itself for |x| ≤ π/4.
        ///
        /// The spherical triangle and rectangle samplers take sines of
        /// angles in (−2π, 2π) that are not fractions of a turn, so
        /// [`sin_cos_2pi`]'s exact reduction does not apply; libm's `sin`
        /// is a call per sample that the batch kernels cannot inline or
        /// vectorise (and whose last bits depend on the platform's libm).
        /// Here q = round(2x/π) is the quadrant, and r = x − q·π/2 is formed
        /// with π/2 split in three parts P₁ + P₂ + P₃ (Cody and Waite 1980,
        /// "Software Manual for the Elementary Functions", ch. 8): q·P₁ and
        /// q·P₂ are exact, x − q·P₁ is exact (Sterbenz: x is within a
        /// factor of two of q·P₁ when q ≠ 0), so r carries two roundings of
        /// its own size. For q = 0, r = x exactly. Then the polynomials of
        /// [`sin_cos_quarter`] and the rotation of [`sin_cos_2pi`].
        ///
        /// # Panics
        /// Debug builds check |x| ≤ 1000 (q·P₁ must stay exact).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::sin_cos;")]
        /// let (s, c) = sin_cos(2.0);
        #[doc = concat!("assert!((s - 2.0", stringify!($p), ".sin()).abs() < 1e-6 && (c - 2.0", stringify!($p), ".cos()).abs() < 1e-6);")]
        /// assert_eq!(sin_cos(0.0), (0.0, 1.0));
        /// ```
        #[inline(always)]
        pub fn sin_cos(x: Real) -> (Real, Real) {
            debug_assert!(x.abs() <= 1000.0 || x.is_nan());
            let magic: Real = 1.5 * (1u64 << (Real::MANTISSA_DIGITS - 1)) as Real;
            let shifted = x * (2.0 / PI) + magic;
            let q_bits = shifted.to_bits() as u32;
            let q = shifted - magic;
            let [p1, p2, p3] = HALF_PI_PARTS;
            let r = ((x - q * p1) - q * p2) - q * p3;
            let r2 = r * r;
            let (s, c) = (r * estrin(r2, &SIN_TAYLOR), estrin(r2, &COS_TAYLOR));
            let odd = (q_bits & 1) != 0;
            let (s1, c1) = if odd { (c, -s) } else { (s, c) };
            if (q_bits & 2) != 0 {
                (-s1, -c1)
            } else {
                (s1, c1)
            }
        }

        /// sin x for |x| ≤ 1000: [`sin_cos`]'s first value.
        #[inline(always)]
        pub fn sin(x: Real) -> Real {
            sin_cos(x).0
        }
    };
}

lambert_geometry::both_precisions!(trig_impl);

#[cfg(test)]
mod tests {
    #[test]
    fn matches_std_to_an_ulp_or_two() {
        let n = 100_000;
        let mut worst64: f64 = 0.0;
        let mut worst32: f64 = 0.0;
        for i in 0..=n {
            let u = i as f64 / n as f64;
            let (s, c) = super::f64::sin_cos_2pi(u);
            let (s_ref, c_ref) = (2.0 * std::f64::consts::PI * u).sin_cos();
            worst64 = worst64.max((s - s_ref).abs()).max((c - c_ref).abs());
            let (s, c) = super::f32::sin_cos_2pi(u as f32);
            // Reference from the f32 input widened, so the only error is ours.
            let (s_ref, c_ref) = (2.0 * std::f64::consts::PI * (u as f32) as f64).sin_cos();
            worst32 = worst32
                .max((s as f64 - s_ref).abs())
                .max((c as f64 - c_ref).abs());
        }
        // The std reference itself carries 2πu's rounding (≤ 2π·2⁻⁵³), and
        // ours the same order: a few ulps of 1 in absolute terms.
        assert!(worst64 < 4.0 * f64::EPSILON, "f64 worst {worst64:e}");
        assert!(worst32 < 4.0 * f32::EPSILON as f64, "f32 worst {worst32:e}");
    }

    /// Against std (libm, itself within an ulp): over |x| ≤ 2π the error is
    /// bounded by an ulp of 1 from r's two roundings plus the reference's
    /// own ulp, so 4ε of 1 absolute (f64; f32's reference is computed in
    /// f64 from the same f32 input, so only our error counts). For
    /// |x| ≤ π/4 the reduction is exact and the bound is relative: 4 ulps
    /// of the value, down to x = 1e-300.
    #[test]
    fn general_sin_cos_matches_std() {
        let n = 200_000;
        let (mut worst64, mut worst32, mut worst_rel): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for i in 0..=n {
            let x = (2.0 * i as f64 / n as f64 - 1.0) * 2.0 * std::f64::consts::PI;
            let (s, c) = super::f64::sin_cos(x);
            worst64 = worst64.max((s - x.sin()).abs()).max((c - x.cos()).abs());
            let xf = x as f32;
            let (s, c) = super::f32::sin_cos(xf);
            let (s_ref, c_ref) = (xf as f64).sin_cos();
            worst32 = worst32
                .max((s as f64 - s_ref).abs())
                .max((c as f64 - c_ref).abs());
        }
        for k in 0..=600 {
            let x = (std::f64::consts::PI / 4.0) * 10f64.powf(-(k as f64) / 2.0);
            for x in [x, -x] {
                let s = super::f64::sin(x);
                worst_rel = worst_rel.max(((s - x.sin()) / x.sin()).abs());
            }
        }
        assert!(worst64 < 4.0 * f64::EPSILON, "f64 worst {worst64:e}");
        assert!(worst32 < 4.0 * f32::EPSILON as f64, "f32 worst {worst32:e}");
        assert!(
            worst_rel < 4.0 * f64::EPSILON,
            "relative worst {worst_rel:e}"
        );
        assert_eq!(super::f64::sin_cos(0.0), (0.0, 1.0));
        assert_eq!(super::f32::sin_cos(-0.0), (-0.0, 1.0));
    }

    /// `cos_2pi` against std over [0, 1] (4ε of 1 absolute, as for
    /// `sin_cos_2pi`: our two roundings and the reference's own), and
    /// relative to the value near the zero at u = ¼, where y = 2π(¼ − u)
    /// is formed exactly and the polynomial is relative: 4 ulps of the
    /// value, for ¼ − u from 2⁻³ down to 2⁻³².
    #[test]
    fn cos_2pi_matches_std() {
        let n = 100_000;
        let (mut worst64, mut worst32, mut worst_rel): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for i in 0..=n {
            let u = i as f64 / n as f64;
            let c_ref = (2.0 * std::f64::consts::PI * u).cos();
            worst64 = worst64.max((super::f64::cos_2pi(u) - c_ref).abs());
            let uf = u as f32;
            let c_ref = (2.0 * std::f64::consts::PI * f64::from(uf)).cos();
            worst32 = worst32.max((f64::from(super::f32::cos_2pi(uf)) - c_ref).abs());
        }
        for k in 3..=32 {
            let d = 2f64.powi(-k);
            for u in [0.25 - d, 0.25 + d, 0.75 - d, 0.75 + d] {
                // cos 2πu = ±sin 2πd, computed from the exact d.
                let exact = (2.0 * std::f64::consts::PI * d).sin();
                let got = super::f64::cos_2pi(u).abs();
                worst_rel = worst_rel.max(((got - exact) / exact).abs());
            }
        }
        assert!(worst64 < 4.0 * f64::EPSILON, "f64 worst {worst64:e}");
        assert!(worst32 < 4.0 * f32::EPSILON as f64, "f32 worst {worst32:e}");
        assert!(
            worst_rel < 4.0 * f64::EPSILON,
            "relative worst {worst_rel:e}"
        );
        assert_eq!(super::f64::cos_2pi(0.25), 0.0);
        assert_eq!(super::f32::cos_2pi(0.75), 0.0);
        assert_eq!(super::f64::cos_2pi(0.5), -super::f64::cos_2pi(0.0));
        assert_eq!(super::f64::cos_2pi(1.0), super::f64::cos_2pi(0.0));
        assert!((super::f64::cos_2pi(0.0) - 1.0).abs() <= f64::EPSILON);
        assert!((super::f32::cos_2pi(0.0) - 1.0).abs() <= f32::EPSILON);
    }

    /// `sin_cos_eighth` against the exact sin(πt/4), cos(πt/4), in ulps
    /// of the exact value. f32: every 61st f32 in [0, 1] (17 million t,
    /// every binade) against f64's libm on the widened t, whose own error
    /// (≈ 2⁻⁵³ relative) is invisible at f32's ulp. The whole range was
    /// checked once (every f32 in [0, 1]): sin at most 2.32 ulps, cos 1.49,
    /// from the fits' errors (below 0.05 ulp) and at most four roundings
    /// of the evaluation; the bound asserted is 2.5. f64: 10⁶ t spread
    /// over [0, 1] and down to 2⁻¹⁰⁰⁰, against libm at πt/4 carried as
    /// two f64 (hi + lo, the product's error by a fused multiply-add),
    /// corrected to first order in lo; libm adds up to an ulp of its own,
    /// so the bound is 2.5 + 1 ulps. Both are odd/even in t, so t ≥ 0
    /// covers the interval. Negative control: the same check of
    /// `sin_cos_quarter` at the f32 product (π/4)·t, whose rounding of
    /// the argument alone costs up to half an ulp more, exceeds 2.5 ulps.
    #[test]
    fn sin_cos_eighth_is_within_ulps_of_exact() {
        fn ulps32(got: f32, exact: f64) -> f64 {
            let rounded = exact as f32;
            let ulp = f64::from(f32::from_bits(rounded.to_bits() + 1) - rounded);
            (f64::from(got) - exact).abs() / ulp
        }
        fn ulps64(got: f64, exact: f64) -> f64 {
            let ulp = f64::from_bits(exact.to_bits() + 1) - exact;
            (got - exact).abs() / ulp
        }
        let quarter = std::f64::consts::FRAC_PI_4;
        let (mut worst32, mut worst_quarter): (f64, f64) = (0.0, 0.0);
        for bits in (0..=1f32.to_bits()).step_by(61) {
            let t = f32::from_bits(bits);
            let x = quarter * f64::from(t);
            let (s, c) = super::f32::sin_cos_eighth(t);
            worst32 = worst32.max(ulps32(s, x.sin())).max(ulps32(c, x.cos()));
            let (s, c) = super::f32::sin_cos_quarter(std::f32::consts::FRAC_PI_4 * t);
            worst_quarter = worst_quarter
                .max(ulps32(s, x.sin()))
                .max(ulps32(c, x.cos()));
        }
        assert!(worst32 <= 2.5, "f32 worst {worst32} ulps");
        assert!(worst_quarter > 2.5, "control: {worst_quarter} ulps");
        // π/4 = hi + lo to 2⁻¹⁰⁷.
        let lo = 3.061_616_997_868_383e-17;
        let mut worst64: f64 = 0.0;
        let mut h = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..1_000_000 {
            h = h
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let m = (h >> 11) as f64 / (1u64 << 53) as f64;
            // Half the points uniform in [0, 1], half log-uniform below.
            let t = if i % 2 == 0 { m } else { (-1000.0 * m).exp2() };
            let hi = quarter * t;
            let x_lo = quarter.mul_add(t, -hi) + lo * t;
            let (s_ref, c_ref) = (hi.sin() + hi.cos() * x_lo, hi.cos() - hi.sin() * x_lo);
            let (s, c) = super::f64::sin_cos_eighth(t);
            worst64 = worst64.max(ulps64(s, s_ref)).max(ulps64(c, c_ref));
        }
        assert!(worst64 <= 3.5, "f64 worst {worst64} ulps");
        assert_eq!(super::f64::sin_cos_eighth(0.0), (0.0, 1.0));
        assert_eq!(super::f32::sin_cos_eighth(-0.0), (-0.0, 1.0));
    }

    #[test]
    fn exact_at_quarter_turns() {
        assert_eq!(super::f64::sin_cos_2pi(0.0), (0.0, 1.0));
        assert_eq!(super::f64::sin_cos_2pi(0.25), (1.0, -0.0));
        assert_eq!(super::f64::sin_cos_2pi(1.0), (0.0, 1.0));
        assert_eq!(super::f32::sin_cos_2pi(0.5), (-0.0, -1.0));
    }

    /// Estrin with an unpaired coefficient moved up as it is gives, for
    /// y ≥ 0, the bits of the form that pads it with 0 (c + 0·yᵏ), which
    /// every sample value before that change was computed with: asserted
    /// exactly over odd and even lengths (9, 8, 5, 6, 3) and the whole
    /// range the sines take, y ∈ [0, (π/4)²], plus y = 0. A negative
    /// control shows the comparison sees a one-ulp change.
    #[test]
    fn unpaired_coefficients_give_the_padded_bits() {
        fn padded(y: f64, c: &[f64]) -> f64 {
            let mut buf = [0.0; 16];
            let mut n = c.len();
            buf[..n].copy_from_slice(c);
            let mut power = y;
            while n > 1 {
                let half = n.div_ceil(2);
                for i in 0..half {
                    let hi = if 2 * i + 1 < n { buf[2 * i + 1] } else { 0.0 };
                    buf[i] = buf[2 * i] + hi * power;
                }
                n = half;
                power = power * power;
            }
            buf[0]
        }
        let coefficients = super::taylor::f64::SIN_TAYLOR;
        let top = (std::f64::consts::PI / 4.0).powi(2);
        for len in [9, 8, 5, 6, 3] {
            let c = &coefficients[..len];
            for i in 0..=20_000 {
                let y = top * f64::from(i) / 20_000.0;
                assert_eq!(
                    super::f64::estrin(y, c).to_bits(),
                    padded(y, c).to_bits(),
                    "{len} terms at y = {y:e}"
                );
            }
        }
        let y = 0.3;
        let nudged = f64::from_bits(padded(y, &coefficients).to_bits() + 1);
        assert_ne!(
            super::f64::estrin(y, &coefficients).to_bits(),
            nudged.to_bits()
        );
    }
}
