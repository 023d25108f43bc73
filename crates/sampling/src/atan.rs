//! atan2 without branches, for loops that must vectorise.
//!
//! libm's `atan2` is a call per argument that a batch kernel cannot inline
//! or vectorise, and glibc picks its build at run time (an FMA variant on
//! processors that have FMA), so its last bits depend on the machine. Here
//! the reduction is the classical one (Cody and Waite 1980, "Software
//! Manual for the Elementary Functions", ch. 17): |y| and |x| ordered so
//! that t = min/max ∈ [0, 1]; for t > tan(π/8), atan t = π/4 +
//! atan((t − 1)/(t + 1)), formed as (min − max)/(min + max) so that one
//! division serves both cases; then |t′| ≤ tan(π/8) and atan t′ =
//! t′ + t′³ P(t′²) with P a near-minimax polynomial; the octant and the
//! signs are restored by π/2 − a, π − a and the sign of y.

/// The polynomial each precision uses: P(z) ≈ (atan √z − √z)/z^{3/2} on
/// z ∈ [0, tan²(π/8)], the coefficients of its Chebyshev fit (near-minimax;
/// mpmath's `chebyfit` at 50 digits, rounded to the precision).
mod minimax {
    /// f64: 11 terms, fit error 3.2e-17 (absolute, on values near −1/3),
    /// which moves atan t′ by at most 0.05 ulp (t′² ≤ 0.172).
    pub(super) mod f64 {
        pub const ATAN_TAIL: [f64; 11] = [
            -0.333_333_333_333_333_3,
            0.199_999_999_999_955_2,
            -0.142_857_142_846_665_42,
            0.111_111_110_152_563_61,
            -0.090_909_045_781_239_03,
            0.076_921_831_908_260_87,
            -0.066_645_114_473_819_48,
            0.058_581_489_128_022_1,
            -0.050_854_497_379_402_6,
            0.039_231_658_295_587_19,
            -0.019_176_887_119_062_26,
        ];
        /// tan(π/8) = √2 − 1, rounded.
        pub const TAN_PI_8: f64 = 0.414_213_562_373_095;
    }
    /// f32: 5 terms, fit error 1.6e-8, at most 0.05 ulp of atan t′.
    pub(super) mod f32 {
        pub const ATAN_TAIL: [f32; 5] = [
            -0.333_333_3,
            0.199_995_4,
            -0.142_639_56,
            0.107_437_31,
            -0.064_519_28,
        ];
        /// tan(π/8) = √2 − 1, rounded.
        pub const TAN_PI_8: f32 = 0.414_213_57;
    }
}

macro_rules! atan_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use super::minimax::$p::{ATAN_TAIL, TAN_PI_8};
        use crate::trig::$p::estrin;
        use lambert_geometry::precision::$p::{Real, PI};

        /// atan2(y, x) ∈ [−π, π], the angle of the point (x, y), for finite
        /// arguments: within 3 ulps of the exact value (tested against
        /// libm's over 10⁶ arguments of every octant; the module docs give
        /// the method), with libm's signs of zero (atan2(±0, −0) = ±π,
        /// atan2(±0, +0) = ±0). Branch-free, so that loops calling it
        /// vectorise, and the same bits on every instruction set (no FMA,
        /// no table). NaN in either argument gives NaN; two infinite
        /// arguments give NaN (libm gives a multiple of π/4).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::atan2;")]
        #[doc = concat!("use std::", stringify!($p), "::consts::PI;")]
        /// assert_eq!(atan2(0.0, 1.0), 0.0);
        /// assert_eq!(atan2(0.0, -1.0), PI);
        /// assert!((atan2(1.0, 1.0) - PI / 4.0).abs() <= PI / 4.0 * 1e-6);
        #[doc = concat!("assert!((atan2(-2.0, -1.0) - (-2.0", stringify!($p), ").atan2(-1.0)).abs() < 1e-6);")]
        /// ```
        #[inline(always)]
        pub fn atan2(y: Real, x: Real) -> Real {
            let (ax, ay) = (x.abs(), y.abs());
            // Selects, not min/max: the same values for the ordered pairs
            // (a NaN propagates through the division either way).
            let swap = ay > ax;
            let (small, large) = if swap { (ax, ay) } else { (ay, ax) };
            let above = small > TAN_PI_8 * large;
            let (num, den) = if above {
                (small - large, small + large)
            } else {
                (small, large)
            };
            // 0/0 at the origin: the angle 0 (then π or −0, π by the signs).
            let t = if den == 0.0 { 0.0 } else { num / den };
            let z = t * t;
            let a = t + t * (z * estrin(z, &ATAN_TAIL));
            let a = if above { PI / 4.0 + a } else { a };
            let a = if swap { PI / 2.0 - a } else { a };
            let a = if x.is_sign_negative() { PI - a } else { a };
            a.copysign(y)
        }
    };
}

lambert_geometry::both_precisions!(atan_impl);

#[cfg(test)]
mod tests {
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    /// ulps of `ours` from `reference` (an f64 computed to about ½ ulp),
    /// in units of the ulp of the reference's magnitude in `eps`.
    fn ulps(ours: f64, reference: f64, eps: f64) -> f64 {
        let unit = (reference.abs().max(f64::MIN_POSITIVE) * eps).max(f64::MIN_POSITIVE);
        (ours - reference).abs() / unit
    }

    /// Within 3 ulps of libm's atan2 (itself within 1 ulp in f64, and
    /// the f64 value is exact to far below an f32 ulp) over 10⁶ random
    /// points of every octant, of magnitudes from 1e-30 to 1e30, and on
    /// the octant boundaries. The bound: the rounded π/4, π/2, π and the
    /// reduction's division and sums each add at most ½ ulp of the result
    /// (π/4 + a with a ∈ [−π/8, π/8] magnifies a's error at most 2×),
    /// the polynomial 0.05; measured at most 1.27 (f64) and 1.54 (f32). A
    /// negative control: libm's atan2 of y shifted by 1e-9 relative misses
    /// by far more.
    #[test]
    fn matches_libm_to_three_ulps() {
        let mut rng = Pcg64::seed_from_u64(7);
        let (mut worst64, mut worst32, mut shifted_far) = (0.0f64, 0.0f64, 0);
        let count = 1_000_000;
        for i in 0..count {
            let scale = 10f64.powf(rng.random_range(-30.0..30.0));
            let (y, x) = (
                rng.random_range(-1.0..1.0) * scale,
                rng.random_range(-1.0..1.0) * scale * 10f64.powf(rng.random_range(-3.0..3.0)),
            );
            let reference = y.atan2(x);
            worst64 = worst64.max(ulps(super::f64::atan2(y, x), reference, f64::EPSILON));
            let (y32, x32) = (y as f32, x as f32);
            let reference32 = (y32 as f64).atan2(x32 as f64);
            worst32 = worst32.max(ulps(
                super::f32::atan2(y32, x32) as f64,
                reference32,
                f32::EPSILON as f64,
            ));
            if i < 1000 {
                let shifted = (y * (1.0 + 1e-9)).atan2(x);
                shifted_far += usize::from(ulps(shifted, reference, f64::EPSILON) > 3.0);
            }
        }
        assert!(worst64 <= 3.0, "f64: {worst64} ulps");
        assert!(worst32 <= 3.0, "f32: {worst32} ulps");
        assert!(shifted_far > 900, "negative control: {shifted_far}");
    }

    /// Exact where the result is a rounded constant, with libm's signs.
    #[test]
    fn axes_diagonals_and_signed_zeros() {
        use std::f64::consts::PI;
        let a = super::f64::atan2;
        assert_eq!(a(0.0, 1.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(a(-0.0, 1.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(a(0.0, -0.0), PI);
        assert_eq!(a(-0.0, -0.0), -PI);
        assert_eq!(a(0.0, 0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(a(1.0, 0.0), PI / 2.0);
        assert_eq!(a(-1.0, 0.0), -PI / 2.0);
        assert_eq!(a(0.0, -3.0), PI);
        assert_eq!(a(2.0, 2.0), PI / 4.0);
        assert_eq!(a(-2.0, -2.0), -(PI - PI / 4.0));
        assert_eq!(a(f64::INFINITY, 1.0), PI / 2.0);
        assert!(a(f64::NAN, 1.0).is_nan() && a(1.0, f64::NAN).is_nan());
        assert_eq!(super::f32::atan2(1.0, 0.0), std::f32::consts::FRAC_PI_2);
    }
}
