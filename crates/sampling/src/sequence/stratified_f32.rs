//! The f32 coordinate of a stratified point when `N ≤ 2²⁴`, computed in
//! f32 lanes from the stratum and the jitter bits, without an f64 value.
//!
//! A coordinate is `(k + h·2⁻³²)/N` for a stratum `k < N` and 32 jitter
//! bits `h`. An f32 in `[½, 1)` has steps of `2⁻²⁴`, so of the jitter only
//! the top `s = 24 − L` bits can show, with `L = ⌈log₂ N⌉` (`2^(L−1) < N ≤
//! 2^L`): the coordinate becomes the ratio of two integers below `2²⁴`,
//!
//! ```text
//! x* = q / M,   q = k·2ˢ + ⌊h / 2^(32−s)⌋,   M = N·2ˢ ∈ (2²³, 2²⁴],
//! ```
//!
//! and the stored value is `x*` rounded to the nearest f32, computed as
//! `q·c_hi + q·c_lo` with one fused multiply-add, where `c_hi = ⌊2⁴⁷/M⌋·2⁻⁴⁷`
//! is `1/M` rounded down to 24 bits and `c_lo` the rest rounded to f32.
//! `q` and `c_hi` are exact in f32, `q·c_lo` is below `2⁻²³` and rounds
//! by less than `2⁻⁴⁸`, so the sum is within about `2⁻⁴⁷` of `x*` before
//! its one rounding: the value is `x*` to the nearest f32 except where `x*`
//! lies within that of a midpoint between two f32 values.
//!
//! Hence every coordinate stays below its stratum's upper edge, and below
//! 1: `x* ≤ (k + 1)/N − 1/M` and `1/M ≥ 2⁻²⁴`, while rounding adds at most
//! half an f32 step (`≤ 2⁻²⁵` below 1) and the sum's error `2⁻⁴⁷`. A point
//! whose `x*` lies within half a step above the lower edge `k/N` may round
//! just below it (that edge is seldom an f32 value): about half of the
//! points with jitter bits 0 there, `2^-(s+1)` of all points, one f32 step.
//!
//! On a power-of-two grid `M = 2²⁴`, `c_lo = 0` and the value is `q·2⁻²⁴`
//! exactly: the exact coordinate rounded down to 24 bits, the value of
//! `stratified_pow2.rs`'s integer form. Defined in 2026-12 for the other
//! grids, whose f32 coordinate was the f64 one rounded down to 24 bits,
//! because that route ran in f64 lanes and made f32 points cost more than
//! f64 ones; the two differ by at most one f32 step and in how the jitter
//! is cut (README, "Speed").

use super::stratified_pow2::shr_or_zero;

/// `2⁻⁴⁷`, the step of f32 values in `[2⁻²⁴, 2⁻²³)`, where `1/M` lies.
const TWO_POW_M47: f64 = 1.0 / 140_737_488_355_328.0;

/// What `N ≤ 2²⁴` fixes for its f32 coordinates: the jitter bits kept,
/// `s = 24 − ⌈log₂ N⌉`, and `1/M = 1/(N·2ˢ)` as a sum of two f32 values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct F32Coordinate {
    /// `s`, the top jitter bits a coordinate keeps (0 … 24).
    jitter_bits: u32,
    /// `⌊2⁴⁷/M⌋·2⁻⁴⁷`, `1/M` rounded down to 24 bits (exact in f32).
    scale_high: f32,
    /// `1/M − scale_high` rounded to f32, in `[0, 2⁻⁴⁷)`.
    scale_low: f32,
}

impl F32Coordinate {
    /// The f32 coordinates of a grid of `n` samples, if `1 ≤ n ≤ 2²⁴`.
    pub(super) fn new(n: u32) -> Option<Self> {
        if !(1..=1 << 24).contains(&n) {
            return None;
        }
        let log_n = 32 - (n - 1).leading_zeros(); // ⌈log₂ n⌉, 0 for n = 1
        let jitter_bits = 24 - log_n;
        let m = u64::from(n) << jitter_bits; // (2²³, 2²⁴]
        let high = (1u64 << 47) / m; // [2²³, 2²⁴): exact in f32 and f64
        let scale_high = high as f64 * TWO_POW_M47;
        // 1/M − ⌊2⁴⁷/M⌋·2⁻⁴⁷ = (2⁴⁷ mod M)/M · 2⁻⁴⁷, both factors exact in
        // f64 (integers below 2²⁴ and a power of two): one rounding, then
        // one to f32.
        let remainder = ((1u64 << 47) % m) as f64;
        let scale_low = (remainder / m as f64 * TWO_POW_M47) as f32;
        Some(F32Coordinate {
            jitter_bits,
            scale_high: scale_high as f32,
            scale_low,
        })
    }

    /// How many top bits of the jitter `h` [`F32Coordinate::unit`] reads.
    #[inline(always)]
    pub(super) fn jitter_bits(self) -> u32 {
        self.jitter_bits
    }

    /// The f32 coordinate of stratum `k < N` with jitter bits `h`: `q/M`
    /// to the nearest f32 (module docs).
    #[inline(always)]
    pub(super) fn unit(self, (k, h): (u32, u32)) -> f32 {
        let s = self.jitter_bits;
        // k < N, so k·2ˢ < M ≤ 2²⁴; the jitter fills the s bits below.
        // q < 2²⁴ converts exactly through i32: one instruction where an
        // unsigned conversion takes several before AVX-512.
        let q = ((k << s) | shr_or_zero(h, 32 - s)) as i32 as f32;
        q.mul_add(self.scale_high, q * self.scale_low)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x·M` in f64, exact: a 24-bit significand times `M ≤ 2²⁴`.
    fn times(x: f32, m: u64) -> f64 {
        f64::from(x) * m as f64
    }

    /// The f32 values next below and above `x`.
    fn neighbours(x: f32) -> (f32, f32) {
        (x.next_down(), x.next_up())
    }

    /// Sample counts of every kind up to `2²⁴`: 1, 2, 3, primes, powers
    /// of two and their neighbours, the study's and the README's counts.
    const COUNTS: [u32; 16] = [
        1,
        2,
        3,
        7,
        13,
        1000,
        1023,
        1024,
        1025,
        1_000_000,
        1 << 20,
        (1 << 21) + 1,
        3_125_000,
        (1 << 23) + 1,
        (1 << 24) - 1,
        1 << 24,
    ];

    /// Jitter bits at the ends, at the seams a cut can fall on, and spread.
    fn jitters() -> impl Iterator<Item = u32> {
        let spread = (0..97u32).map(|j| j.wrapping_mul(0x9e37_79b9));
        spread.chain([0, 1, 0xff, 0x100, 0xffff, 1 << 31, u32::MAX - 1, u32::MAX])
    }

    /// The coordinate is `q/M` rounded to the nearest f32: neither f32
    /// neighbour of it is nearer to `q/M` (checked in exact arithmetic),
    /// on every kind of count, at the first, middle and last strata.
    #[test]
    fn the_coordinate_is_the_ratio_rounded_to_nearest() {
        for n in COUNTS {
            let f = F32Coordinate::new(n).unwrap();
            let s = f.jitter_bits();
            let m = u64::from(n) << s;
            assert!(m > 1 << 23 && m <= 1 << 24, "n {n}: M {m}");
            for k in [0, 1.min(n - 1), n / 3, n / 2, n - 1] {
                for h in jitters() {
                    let q = (u64::from(k) << s) | (u64::from(h) >> (32 - s));
                    let x = f.unit((k, h));
                    // |x − q/M| ≤ |y − q/M| for both neighbours y, times
                    // M: |x·M − q| against |y·M − q|, exact in f64.
                    let off = |y: f32| (times(y, m) - q as f64).abs();
                    let (below, above) = neighbours(x);
                    let what = format!("n {n} k {k} h {h:#x}");
                    assert!(off(x) <= off(below) && off(x) <= off(above), "{what}");
                }
            }
        }
    }

    /// Every coordinate lies below its stratum's upper edge `(k + 1)/N`
    /// (so below 1), and at most one f32 step below its lower edge `k/N`,
    /// checked in exact arithmetic with the jitters at their extremes.
    #[test]
    fn coordinates_stay_in_their_strata_within_one_step_below() {
        for n in COUNTS {
            let f = F32Coordinate::new(n).unwrap();
            let s = f.jitter_bits();
            for k in [0, 1.min(n - 1), n / 2, n - 2.min(n), n - 1] {
                for h in jitters() {
                    let x = f.unit((k, h));
                    let what = format!("n {n} k {k} h {h:#x}");
                    // x < (k + 1)/N ⇔ x·M < (k + 1)·2ˢ, and the next f32
                    // up is at or above k/N ⇔ next_up(x)·M ≥ k·2ˢ.
                    let m = u64::from(n) << s;
                    let (upper, lower) = (u64::from(k + 1) << s, u64::from(k) << s);
                    assert!(times(x, m) < upper as f64, "{what}");
                    assert!(x < 1.0, "{what}");
                    assert!(times(neighbours(x).1, m) >= lower as f64, "{what}");
                }
            }
        }
    }

    /// On a power-of-two grid the value is `q·2⁻²⁴` exactly, the exact
    /// coordinate rounded down to 24 bits: `⌊(k·2³² + h)/2^(p+8)⌋·2⁻²⁴`.
    #[test]
    fn powers_of_two_take_the_exact_value_rounded_down() {
        for p in 0..=24u32 {
            let n = 1u32 << p;
            let f = F32Coordinate::new(n).unwrap();
            assert_eq!(f.scale_low, 0.0, "p {p}");
            for k in [0, 1.min(n - 1), n / 2, n - 1] {
                for h in jitters() {
                    let top = ((u64::from(k) << 32) | u64::from(h)) >> (p + 8);
                    let want = top as f32 / 16_777_216.0;
                    assert_eq!(f.unit((k, h)).to_bits(), want.to_bits(), "p {p} k {k}");
                }
            }
        }
    }

    /// Only counts from 1 to `2²⁴` have this form; the coordinate reads
    /// `24 − ⌈log₂ N⌉` jitter bits.
    #[test]
    fn counts_above_two_to_the_24_have_no_f32_form() {
        assert!(F32Coordinate::new(0).is_none());
        assert!(F32Coordinate::new((1 << 24) + 1).is_none());
        assert!(F32Coordinate::new(u32::MAX).is_none());
        let bits = |n| F32Coordinate::new(n).unwrap().jitter_bits();
        assert_eq!(
            [bits(1), bits(2), bits(3), bits(1000), bits(1 << 24)],
            [24, 23, 22, 14, 0]
        );
    }

    /// Negative control for the rounding test: the coordinate rounded
    /// down by `1/M`'s high part alone (no low part) is not always the
    /// nearest f32 on a grid that is not a power of two, so the test can
    /// tell a value that is off by a step.
    #[test]
    fn the_high_part_alone_is_sometimes_a_step_off() {
        let n = 1_000_000;
        let f = F32Coordinate::new(n).unwrap();
        let s = f.jitter_bits();
        let m = u64::from(n) << s;
        let mut off_by_a_step = 0;
        for k in (0..n).step_by(997) {
            for h in jitters() {
                let q = (u64::from(k) << s) | (u64::from(h) >> (32 - s));
                let high_only = q as f32 * f.scale_high;
                let off = |y: f32| (times(y, m) - q as f64).abs();
                let (below, above) = neighbours(high_only);
                off_by_a_step +=
                    usize::from(off(below) < off(high_only) || off(above) < off(high_only));
            }
        }
        assert!(off_by_a_step > 0);
    }
}
