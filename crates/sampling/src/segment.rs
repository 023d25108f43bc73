//! Circular segments of the unit disk: area as a function of height, and
//! its inverse, without cancellation for thin segments.
//!
//! A chord at distance 1 − k from the center of the unit disk cuts off a
//! segment of height k ∈ [0, 2]. With φ the half-angle the chord subtends
//! (cos φ = 1 − k, φ = 2 asin √(k/2)), its area is
//!
//! S(k) = φ − sin φ cos φ = (v − sin v)/2,  v = 2φ,
//!
//! and dS/dk = 2 sin φ = 2√(k(2 − k)), the chord's length. For thin segments
//! v − sin v ≈ v³/6 is the difference of two nearly equal numbers, so it is
//! summed from its Taylor series below v = 1 (terms shrink by ≥ 20× each),
//! and taken directly above (where v − sin v ≥ 0.15 v: at most one digit is
//! lost). The projected-cap sampler
//! (`ProjectedCap`) slices its regions into such
//! segments of the unit disk and of an ellipse (an affine image of it).
//!
//! The inverse, the height of the segment of a given area, has no closed form
//! (2φ − sin 2φ = 2A is Kepler's equation at eccentricity 1); it is found by
//! Halley's iteration on φ. Areas above π/2 are solved through the
//! complementary segment (S(φ) + S(π − φ) = π), so φ ∈ [0, π/2]. The first
//! guess is φ₀ = t·P(t²), t = (3A/2)^{1/3}: the leading term t is exact to
//! first order for thin segments (S ≈ 2φ³/3, and φ = t + t³/15 + … from the
//! series of S), and P, a polynomial of degree 8 in t² fitted to the root's
//! ratio φ/t on t ∈ [0, (3π/4)^{1/3}] (iteratively reweighted least squares
//! in the relative error; `SEGMENT_SEED`), brings φ₀ within 7.2e-8 of the
//! root, relative (measured against a 90-digit solve at 3,000 points). One
//! Halley step then leaves an error of ~(7e-8)³, below ε, and its own size
//! is below ¼ε^{1/3} φ, the test that ends the iteration (a step that small
//! leaves ~step³ ≲ ε/64): the iteration takes one step (measured, f64 and
//! f32; `SEGMENT_MAX_ITERATIONS` bounds it all the same), and the result's
//! error is that of evaluating S itself, a few ulps. The cube root is our
//! own (`cube_root`): the guess needs ~1e-8, not correct rounding.
//!
//! (The guess was t alone until it was measured as the cost of projected
//! cap sampling: within 16 % of the root at A = π/2, it took three Halley
//! steps for almost every area, and the standard library's correctly
//! rounded cube root cost as much again as one step.)

/// The Taylor coefficients (v − sin v)/v³ = Σ (−1)ᵏ v²ᵏ/(2k + 3)! each
/// precision sums (`v_minus_sin`).
mod series {
    pub(super) mod f64 {
        /// 1/3!, −1/5!, …, 1/19!: the next term, v²⁰/21! ≤ 2e-20, is below
        /// ε/4 of the sum (≥ 0.158 for v ≤ 1).
        pub const V_MINUS_SIN_TAYLOR: [f64; 9] = [
            1.0 / 6.0,
            -1.0 / 120.0,
            1.0 / 5040.0,
            -1.0 / 362880.0,
            1.0 / 39916800.0,
            -1.0 / 6227020800.0,
            1.0 / 1307674368000.0,
            -1.0 / 355687428096000.0,
            1.0 / 121645100408832000.0,
        ];

        /// The coefficients of P in the first guess φ₀ = t·P(t²) of the
        /// segment solve (module docs), from t⁰: fitted to φ/t on
        /// t ∈ [0, (3π/4)^{1/3}], at most 7.2e-8 off relative (measured).
        pub const SEGMENT_SEED: [f64; 9] = [
            1.000_000_072_009_223_5,
            0.066_660_485_743_251_26,
            0.011_515_479_161_034_835,
            0.002_073_421_266_355_051_5,
            0.001_872_886_478_004_041_6,
            -0.001_620_064_582_831_856_6,
            0.001_513_942_451_643_778_7,
            -0.000_627_610_870_861_161_6,
            0.000_126_078_222_658_643_2,
        ];
    }
    pub(super) mod f32 {
        /// 1/3!, …, 1/13!: the next term, v¹⁴/15! ≤ 8e-13, is below ε/4
        /// of the sum.
        pub const V_MINUS_SIN_TAYLOR: [f32; 6] = [
            1.0 / 6.0,
            -1.0 / 120.0,
            1.0 / 5040.0,
            -1.0 / 362880.0,
            1.0 / 39916800.0,
            -1.0 / 6227020800.0,
        ];

        /// [`super::f64::SEGMENT_SEED`] rounded to f32 (its 7.2e-8 fit
        /// error and the rounding are far inside f32's one-step bound,
        /// ¼ε^{1/3} ≈ 1.2e-3).
        pub const SEGMENT_SEED: [f32; 9] = {
            let c = super::f64::SEGMENT_SEED;
            [
                c[0] as f32,
                c[1] as f32,
                c[2] as f32,
                c[3] as f32,
                c[4] as f32,
                c[5] as f32,
                c[6] as f32,
                c[7] as f32,
                c[8] as f32,
            ]
        };
    }
}

/// x^{1/3} for x ∈ [`f64::MIN_POSITIVE`], 1e300] to within 2e-14 relative
/// (measured at 300,000 log-uniform points of that range); other x (0,
/// subnormals, NaN) by the standard library.
///
/// Not `f64::cbrt`: there it is correctly rounded and took, per projected
/// cap sample, as long as one Halley step of the segment solve it seeds,
/// which needs ~1e-8 only. The guess divides the exponent by three through
/// the bits (Kahan, "Computing a real cube root", 1991: an integer
/// division of the bit pattern, plus a constant, approximates the cube
/// root's exponent and mantissa; the constant here is one in common use,
/// 3.2 % off at worst, measured); two Halley steps for y³ = x,
/// y ← y (y³ + 2x)/(2y³ + x) (cubic: 3.2 % → ≲ 3e-5 → ≲ 2e-14), with the
/// ratio formed first so that nothing underflows.
#[inline(always)]
fn cube_root(x: f64) -> f64 {
    if !(f64::MIN_POSITIVE..=1e300).contains(&x) {
        return x.cbrt();
    }
    cube_root_in_range(x)
}

/// [`cube_root`] without a branch: its value, and whether that is
/// [`cube_root`]'s (x in its range, or ±0, which it returns as it is);
/// for other x the value is meaningless (a vectorised loop sends those
/// lanes to [`cube_root`]).
#[inline(always)]
fn cube_root_branch_free(x: f64) -> (f64, bool) {
    let y = cube_root_in_range(x);
    let in_range = (f64::MIN_POSITIVE..=1e300).contains(&x);
    let zero = x == 0.0;
    (if zero { x } else { y }, in_range || zero)
}

/// The guess and two Halley steps of [`cube_root`], for x in its range.
#[inline(always)]
fn cube_root_in_range(x: f64) -> f64 {
    let mut y = f64::from_bits(third_of(x.to_bits()) + 0x2A9F_7893_782D_A1CE);
    for _ in 0..2 {
        let y3 = y * y * y;
        y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
    }
    y
}

/// ⌊b/3⌋ for any b, from 32-bit pieces: with b = H·2³² + L and
/// H = 3a + r, ⌊b/3⌋ = a·2³² + r·⌊2³²/3⌋ + ⌊L/3⌋ + [L mod 3 + r ≥ 3]
/// (2³² = 3⌊2³²/3⌋ + 1). The same value as `b / 3`, which compiles to a
/// 64-bit high multiply that AVX2 and AVX-512 lack, so a loop holding it
/// does not vectorise; divisions of 32-bit words by 3 do.
#[inline(always)]
fn third_of(b: u64) -> u64 {
    const THIRD_OF_2_POW_32: u32 = 1_431_655_765;
    let (high, low) = ((b >> 32) as u32, b as u32);
    let (a, r) = (high / 3, high % 3);
    let carry = u32::from(low % 3 + r >= 3);
    ((a as u64) << 32) + (r * THIRD_OF_2_POW_32 + low / 3 + carry) as u64
}

macro_rules! segment_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use super::series::$p::{SEGMENT_SEED, V_MINUS_SIN_TAYLOR};
        use crate::trig::$p::{estrin, sin, sin_cos};
        use lambert_geometry::precision::$p::{Real, PI};
        /// ε^{1/3} of the precision, rounded up (the acceptance scale of a
        /// last Halley step: it leaves an error of ~step³), as a constant
        /// (`cbrt` is not evaluated at compile time).
        pub const CBRT_EPSILON: Real = if Real::EPSILON < 1e-10 {
            6.055_454_452_393_35e-6_f64 as Real
        } else {
            4.921_566e-3
        };

        /// The most Halley steps [`segment_height`] takes (it stops earlier
        /// when a step changes φ by ≤ 4ε relative; see the module docs).
        pub const SEGMENT_MAX_ITERATIONS: usize = 8;

        /// v − sin v for v ≥ 0, without cancellation: below v = 1 the
        /// Taylor series v³ (1/3! − v²/5! + v⁴/7! − …), cut where a term
        /// falls below ε/4 of the sum at v = 1 (to v¹⁹/19! in f64, v¹³/13!
        /// in f32) and evaluated by Estrin's scheme in v² (no division, no
        /// loop, so it inlines into the samplers' solves); the direct
        /// difference above, with [`sin`] (libm's for v > 1000, beyond its
        /// range reduction).
        #[inline(always)]
        pub fn v_minus_sin(v: Real) -> Real {
            if v >= 1.0 {
                let s = if v <= 1000.0 { sin(v) } else { v.sin() };
                return v - s;
            }
            let v2 = v * v;
            v * v2 * estrin(v2, &V_MINUS_SIN_TAYLOR)
        }

        /// [`v_minus_sin`] for v ∈ [0, 1000], to the bit, without a branch:
        /// both forms computed and one selected, so that a loop calling it
        /// vectorises (the arcs of [`ProjectedPolygon`](crate::f64::ProjectedPolygon)'s
        /// sectors, v ≤ π).
        #[inline(always)]
        pub fn v_minus_sin_branch_free(v: Real) -> Real {
            let v2 = v * v;
            let series = v * v2 * estrin(v2, &V_MINUS_SIN_TAYLOR);
            let direct = v - sin(v);
            if v >= 1.0 {
                direct
            } else {
                series
            }
        }

        /// The area φ − sin φ cos φ of the unit-disk segment of half-angle
        /// φ ∈ [0, π] (the segment of height 1 − cos φ).
        #[inline]
        pub fn segment_area_of_angle(phi: Real) -> Real {
            0.5 * v_minus_sin(2.0 * phi)
        }

        /// The half-angle φ = 2 asin √(k/2) ∈ [0, π] of the segment of
        /// height k ∈ [0, 2] (clamped).
        #[inline]
        pub fn segment_angle_of_height(k: Real) -> Real {
            2.0 * (0.5 * k.clamp(0.0, 2.0)).sqrt().min(1.0).asin()
        }

        /// The area S(k) of the segment of height k ∈ [0, 2] of the unit
        /// disk (see the module docs), in units of the disk's radius squared.
        #[inline]
        pub fn segment_area(k: Real) -> Real {
            segment_area_of_angle(segment_angle_of_height(k))
        }

        /// The half-angle φ ∈ [0, π] of the unit-disk segment of area
        /// `area` ∈ [0, π] (clamped), by Halley's iteration (module docs).
        #[inline]
        pub fn segment_angle_of_area(area: Real) -> Real {
            segment_angle_and_steps(area).0
        }

        /// [`segment_angle_of_area`] and the number of Halley steps taken.
        #[inline]
        pub(crate) fn segment_angle_and_steps(area: Real) -> (Real, usize) {
            let area = area.clamp(0.0, PI);
            // Solve for the smaller of the segment and its complement.
            let (target, flip) = if area > 0.5 * PI {
                (PI - area, true)
            } else {
                (area, false)
            };
            // φ₀ = t·P(t²), t = (3A/2)^{1/3} (module docs).
            let t = super::cube_root((1.5 * target) as f64) as Real;
            let mut phi = t * estrin(t * t, &SEGMENT_SEED);
            let mut steps = 0;
            if target > 0.0 {
                while steps < SEGMENT_MAX_ITERATIONS {
                    steps += 1;
                    let (s, c) = sin_cos(phi);
                    let f = segment_area_of_angle(phi) - target;
                    let f1 = 2.0 * s * s;
                    let f2 = 4.0 * s * c;
                    let denominator = 2.0 * f1 * f1 - f * f2;
                    if !(denominator > 0.0) {
                        break;
                    }
                    let step = 2.0 * f * f1 / denominator;
                    phi = (phi - step).clamp(0.0, 0.5 * PI);
                    // Halley's error after a step of relative size s is
                    // ~s³: below ¼ε^{1/3} that is ≲ ε/64, no need to
                    // evaluate S again.
                    if step.abs() <= 0.25 * CBRT_EPSILON * phi {
                        break;
                    }
                }
            }
            (if flip { PI - phi } else { phi }, steps)
        }

        /// [`segment_height`] without a branch on the area, for loops that
        /// vectorise: the first Halley step taken for every area, and the
        /// height from φ by both of its forms, one selected. Returns the
        /// height and whether it is [`segment_height`]'s to the bit: true
        /// where that iteration stops after its first step, which it does
        /// for every area (measured; module docs) but NaN and areas whose
        /// cube root [`cube_root`] leaves to the standard library
        /// (subnormal ones); the caller sends those to [`segment_height`].
        #[inline(always)]
        pub(crate) fn segment_height_branch_free(area: Real) -> (Real, bool) {
            let area = area.clamp(0.0, PI);
            let flip = area > 0.5 * PI;
            let target = if flip { PI - area } else { area };
            let (t, root_answered) = super::cube_root_branch_free((1.5 * target) as f64);
            let t = t as Real;
            let seed = t * estrin(t * t, &SEGMENT_SEED);
            // One step of `segment_angle_and_steps`, in its order.
            let (s, c) = sin_cos(seed);
            let f = 0.5 * v_minus_sin_branch_free(2.0 * seed) - target;
            let f1 = 2.0 * s * s;
            let f2 = 4.0 * s * c;
            let denominator = 2.0 * f1 * f1 - f * f2;
            let step = 2.0 * f * f1 / denominator;
            let stepped = (seed - step).clamp(0.0, 0.5 * PI);
            let stops = step.abs() <= 0.25 * CBRT_EPSILON * stepped;
            // No step for area 0, nor when the denominator is not
            // positive: φ stays the guess.
            let steps = target > 0.0;
            let usable = denominator > 0.0;
            let phi = if steps && usable { stepped } else { seed };
            let answered = root_answered && (!steps || !usable || stops);
            let phi = if flip { PI - phi } else { phi };
            let low = phi <= 0.5 * PI;
            let s = sin(0.5 * if low { phi } else { PI - phi });
            let height = if low { 2.0 * s * s } else { 2.0 - 2.0 * s * s };
            (height, answered)
        }

        /// The height k ∈ [0, 2] of the unit-disk segment of area
        /// `area` ∈ [0, π]: k = 1 − cos φ with φ from
        /// [`segment_angle_of_area`], formed as 2 sin²(φ/2) (no
        /// cancellation for thin segments) or 2 − 2 sin²((π − φ)/2).
        #[inline]
        pub fn segment_height(area: Real) -> Real {
            let phi = segment_angle_of_area(area);
            if phi <= 0.5 * PI {
                let s = sin(0.5 * phi);
                2.0 * s * s
            } else {
                let s = sin(0.5 * (PI - phi));
                2.0 - 2.0 * s * s
            }
        }
    };
}

lambert_geometry::both_precisions!(segment_impl);

#[cfg(test)]
mod tests {
    use super::f64::*;
    use std::f64::consts::PI;

    #[test]
    fn v_minus_sin_matches_the_direct_form_where_that_is_safe() {
        for &v in &[1e-8, 1e-3, 0.1, 0.5, 0.999, 1.0, 2.0, 6.0] {
            let ours = v_minus_sin(v);
            // Reference: the series summed in f64 to 30 terms (alternating,
            // decreasing: error below the first omitted term).
            let mut reference = 0.0;
            let mut term = v * v * v / 6.0;
            for k in 2..40 {
                reference += term;
                term *= -v * v / ((2 * k) as f64 * (2 * k + 1) as f64);
            }
            let rel = (ours - reference).abs() / reference;
            assert!(rel < 4.0 * f64::EPSILON, "v = {v}: {ours} vs {reference}");
        }
        assert_eq!(v_minus_sin(0.0), 0.0);
    }

    /// The branch-free form is the branching one to the bit on [0, 1000]
    /// (both precisions), across the switch at v = 1.
    #[test]
    fn branch_free_v_minus_sin_is_the_same_bits() {
        for i in 0..=200_000 {
            let v = i as f64 * 0.005;
            assert_eq!(
                v_minus_sin_branch_free(v).to_bits(),
                v_minus_sin(v).to_bits(),
                "v = {v}"
            );
            let v32 = v as f32;
            assert_eq!(
                super::f32::v_minus_sin_branch_free(v32).to_bits(),
                super::f32::v_minus_sin(v32).to_bits(),
                "f32 v = {v32}"
            );
        }
        for v in [1.0 - f64::EPSILON / 2.0, 1.0, 1.0 + f64::EPSILON, PI] {
            assert_eq!(v_minus_sin_branch_free(v), v_minus_sin(v));
        }
    }
    #[test]
    fn segment_area_is_inverted_to_a_few_ulps() {
        let mut worst: f64 = 0.0;
        for i in 0..=2000 {
            let k = 2.0 * i as f64 / 2000.0;
            let a = segment_area(k);
            let back = segment_height(a);
            // dk/dA = 1/(2√(k(2−k))): relative error of A, a few ε, maps to
            // an error in k of (few ε)·A/(2√(k(2−k))), largest at the ends.
            let scale = a / (2.0 * (k * (2.0 - k)).sqrt()).max(1e-300) + k;
            let err = (back - k).abs() / scale.max(f64::MIN_POSITIVE);
            worst = worst.max(if k == 0.0 { back } else { err });
        }
        assert!(worst < 16.0 * f64::EPSILON, "worst {worst:e}");
        assert_eq!(segment_area(2.0), PI);
        assert!((segment_area(1.0) - PI / 2.0).abs() < 4.0 * f64::EPSILON);
        // Thin segments keep full relative precision: S ≈ (4√2/3) k^{3/2}.
        let k = 1e-20;
        let expected = 4.0 * 2f64.sqrt() / 3.0 * k * k.sqrt();
        assert!((segment_area(k) - expected).abs() < 1e-12 * expected);
        assert!((segment_height(segment_area(k)) - k).abs() < 1e-14 * k);
    }

    #[test]
    fn halley_takes_one_step_from_the_fitted_guess() {
        // The documented count: the guess is within 7.2e-8 of the root, so
        // the first Halley step is below ¼ε^{1/3} φ and is the last, in f64
        // and f32, over areas from 1e-30 to π (log-spaced and uniform).
        let mut worst = (0, 0);
        let areas = (0..=600)
            .map(|i| 1e-30 * (PI / 1e-30).powf(i as f64 / 600.0))
            .chain((1..=1000).map(|i| PI * i as f64 / 1000.0));
        for a in areas {
            worst.0 = worst.0.max(segment_angle_and_steps(a).1);
            worst.1 = worst.1.max(super::f32::segment_angle_and_steps(a as f32).1);
        }
        assert_eq!(worst, (1, 1), "steps (f64, f32)");
        // Area 0 takes none (φ = 0 exactly).
        assert_eq!(segment_angle_and_steps(0.0), (0.0, 0));
    }

    #[test]
    fn cube_root_is_accurate_over_its_range() {
        // Two Halley steps from a guess 3.2 % off: the error constant of
        // Halley's method on y³ = x is 2/3 (relative), so 3.2e-2 → 2.2e-5
        // → 7e-15, plus a few ulps of rounding; the seed it feeds needs
        // 1e-8 only. Bound: 1e-13 (measured worst: 2e-14).
        let mut worst: f64 = 0.0;
        for i in 0..=20_000 {
            let x = f64::MIN_POSITIVE * (1e300 / f64::MIN_POSITIVE).powf(i as f64 / 20_000.0);
            let x = x.min(1e300);
            worst = worst.max((super::cube_root(x) / x.cbrt() - 1.0).abs());
        }
        assert!(worst < 1e-13, "worst {worst:e}");
        // Outside the range, the standard library's values.
        for x in [0.0, 5e-324, 1e-310, 1e301, f64::INFINITY] {
            assert_eq!(super::cube_root(x), x.cbrt(), "x = {x:e}");
        }
        assert!(super::cube_root(f64::NAN).is_nan());
    }

    #[test]
    fn third_of_is_integer_division_by_three() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        let edges = [
            0,
            1,
            2,
            3,
            u32::MAX as u64,
            1 << 32,
            (1 << 32) + 2,
            u64::MAX,
            u64::MAX - 1,
        ];
        for b in edges
            .into_iter()
            .chain((0..100_000).map(|_| rng.random::<u64>()))
        {
            assert_eq!(super::third_of(b), b / 3, "b = {b}");
        }
        // Every remainder pair (H mod 3, L mod 3) at the carry's edge.
        for high in [3u64, 4, 5] {
            for low in [u32::MAX as u64 - 2, u32::MAX as u64 - 1, u32::MAX as u64] {
                let b = (high << 32) + low;
                assert_eq!(super::third_of(b), b / 3, "b = {b}");
            }
        }
    }

    #[test]
    fn branch_free_segment_height_is_the_same_bits() {
        // Wherever it says it answered, the value is `segment_height`'s to
        // the bit; it answers every area but NaN and the subnormal ones
        // (whose cube roots `cube_root` leaves to the standard library).
        fn check<R: Copy + std::fmt::Debug>(
            areas: impl Iterator<Item = R>,
            branch_free: fn(R) -> (R, bool),
            plain: fn(R) -> R,
            bits: fn(R) -> u64,
            expect_answer: fn(R) -> bool,
        ) {
            for a in areas {
                let (k, answered) = branch_free(a);
                assert_eq!(answered, expect_answer(a), "area {a:?}");
                if answered {
                    assert_eq!(bits(k), bits(plain(a)), "area {a:?}");
                }
            }
        }
        let areas = || {
            (0..=600)
                .map(|i| 1e-300 * (PI / 1e-300).powf(i as f64 / 600.0))
                .chain((0..=20_000).map(|i| PI * i as f64 / 20_000.0))
                .chain([
                    -0.0,
                    -1.0,
                    0.5 * PI,
                    PI,
                    4.0,
                    f64::INFINITY,
                    1e-310,
                    f64::NAN,
                ])
        };
        check(
            areas(),
            segment_height_branch_free,
            segment_height,
            f64::to_bits,
            // 1.5 A below the smallest normal number: the library's root.
            |a| !(a.is_nan() || a > 0.0 && 1.5 * a < f64::MIN_POSITIVE),
        );
        // f32 areas reach the cube root in f64: only NaN is left out.
        check(
            areas().map(|a| a as f32),
            super::f32::segment_height_branch_free,
            super::f32::segment_height,
            |k| k.to_bits() as u64,
            |a| !a.is_nan(),
        );
    }

    #[test]
    fn f32_segment_inverse_is_accurate() {
        use super::f32 as s;
        let mut worst: f64 = 0.0;
        for i in 1..2000 {
            let k = 2.0 * i as f32 / 2000.0;
            let back = s::segment_height(s::segment_area(k));
            worst = worst.max(((back - k) / k).abs() as f64);
        }
        assert!(worst < 64.0 * f32::EPSILON as f64, "worst {worst:e}");
    }
}
