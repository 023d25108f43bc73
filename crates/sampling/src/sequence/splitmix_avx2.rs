//! The AVX2 bodies of the SplitMix64 fills: sixteen outputs per step,
//! four 64-bit lanes to a vector, the same bits as the scalar
//! generator's (`mix64` of states s + kγ).
//!
//! AVX2 has no 64-bit multiply, so each of the mix's two products z·c
//! (mod 2⁶⁴) is formed from 32-bit halves:
//!
//! ```text
//! z·c ≡ lo(z)·lo(c) + (lo(z)·hi(c) + hi(z)·lo(c))·2³²   (mod 2⁶⁴)
//! ```
//!
//! The first term is one 32 × 32 → 64-bit multiply (`vpmuludq`). Of the
//! cross terms only the low 32 bits matter, so one 32-bit multiply
//! (`vpmulld`) of z's two 32-bit lanes by c's halves swapped forms both;
//! the low lane's is added into the high lane (a 64-bit shift by 32 and a
//! 32-bit add) and the low lane cleared by a blend. The compiler's form of
//! the scalar code takes three `vpmuludq` and two more shifts. On the Zen 2
//! host (2-core AMD EPYC, AVX2 only), 4096-point fills, medians of 11:
//! the f32 fill 1.00 → 0.79 ns a point and the f64 fill 1.08 → 0.95.
//! (Intel's `vpmulld` is two micro-operations, the cost of the multiply it
//! replaces.)

use crate::isa::Isa;

use super::{GAMMA, MIX_1, MIX_2};

/// Outputs per step of both bodies: four vectors of four lanes.
pub(super) const STEP: usize = 16;

/// The f32 grouped fill's whole groups with AVX2 (when `isa` is
/// [`Isa::Avx2Fma`]; returns whether it filled them): `state` is the
/// first group's output-0 state, `x` and `y` whole groups of 16 points.
/// Each group's 16 outputs are four vectors: read as eight 32-bit lanes,
/// the first two are the group's 16 x halves in order and the last two
/// its y halves, so a shift, a conversion and a product make each one
/// eight coordinates (see `fill_groups_avx512` in `splitmix`).
#[inline(always)]
pub(super) fn fill_groups_f32(isa: Isa, state: u64, x: &mut [f32], y: &mut [f32]) -> bool {
    #[cfg(target_arch = "x86_64")]
    return with_avx2(
        isa,
        #[inline(always)]
        |simd| {
            let (a2, a) = (simd.avx2, simd.avx);
            let mix = Mix::new(simd);
            let mut states = mix.lane_states(state);
            let scale = a._mm256_set1_ps(1.0 / 16_777_216.0);
            // No closures in here: one the compiler declined to
            // inline is compiled without AVX2, and every intrinsic
            // in it becomes a call (25× slower, measured).
            let (xs, _) = x.as_chunks_mut::<STEP>();
            let (ys, _) = y.as_chunks_mut::<STEP>();
            for (xg, yg) in xs.iter_mut().zip(ys) {
                let mut coordinates = [[0.0f32; 8]; 4];
                for (c, s) in coordinates.iter_mut().zip(states.iter_mut()) {
                    let words = a2._mm256_srli_epi32::<8>(mix.mix64(*s));
                    *c = pulp::cast(a._mm256_mul_ps(a._mm256_cvtepi32_ps(words), scale));
                    *s = mix.advance(*s);
                }
                xg[..8].copy_from_slice(&coordinates[0]);
                xg[8..].copy_from_slice(&coordinates[1]);
                yg[..8].copy_from_slice(&coordinates[2]);
                yg[8..].copy_from_slice(&coordinates[3]);
            }
        },
    );
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = (isa, state, x, y);
        false
    }
}

/// The f64 fill's points with AVX2 (when `isa` is [`Isa::Avx2Fma`];
/// returns whether it filled them): point k is output k of the states
/// `state + kγ`, x its high half and y its low half times 2⁻³², by the
/// exponent trick of `half_to_f64` in `splitmix` (the half's bits placed
/// in the fraction of 1.0, then 1 subtracted; exact). `x` and `y` have
/// the same length, a multiple of [`STEP`].
#[inline(always)]
pub(super) fn fill_points_f64(isa: Isa, state: u64, x: &mut [f64], y: &mut [f64]) -> bool {
    #[cfg(target_arch = "x86_64")]
    return with_avx2(
        isa,
        #[inline(always)]
        |simd| {
            let (a2, a) = (simd.avx2, simd.avx);
            let mix = Mix::new(simd);
            let mut states = mix.lane_states(state);
            let one_bits = a._mm256_set1_epi64x(0x3ff0_0000_0000_0000);
            let fraction = a._mm256_set1_epi64x(0x000f_ffff_fff0_0000);
            let one = a._mm256_set1_pd(1.0);
            // No closures in here (see `fill_groups_f32`).
            let (xs, _) = x.as_chunks_mut::<STEP>();
            let (ys, _) = y.as_chunks_mut::<STEP>();
            for (xg, yg) in xs.iter_mut().zip(ys) {
                let mut highs = [[0.0f64; 4]; 4];
                let mut lows = [[0.0f64; 4]; 4];
                for ((h, l), s) in highs.iter_mut().zip(lows.iter_mut()).zip(states.iter_mut()) {
                    let bits = mix.mix64(*s);
                    // The high half's bits at fraction bits 20..52
                    // (a shift right by 12), the low half's (a
                    // shift left by 20), each under 1.0's exponent.
                    let high = a2._mm256_and_si256(a2._mm256_srli_epi64::<12>(bits), fraction);
                    let low = a2._mm256_and_si256(a2._mm256_slli_epi64::<20>(bits), fraction);
                    *h = pulp::cast(
                        a._mm256_sub_pd(pulp::cast(a2._mm256_or_si256(one_bits, high)), one),
                    );
                    *l = pulp::cast(
                        a._mm256_sub_pd(pulp::cast(a2._mm256_or_si256(one_bits, low)), one),
                    );
                    *s = mix.advance(*s);
                }
                for (v, (h, l)) in highs.iter().zip(&lows).enumerate() {
                    xg[4 * v..4 * v + 4].copy_from_slice(h);
                    yg[4 * v..4 * v + 4].copy_from_slice(l);
                }
            }
        },
    );
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = (isa, state, x, y);
        false
    }
}

/// Runs `body` with AVX2 and FMA enabled when `isa` is [`Isa::Avx2Fma`]
/// and the processor has them; returns whether it ran. `body` is passed
/// `#[inline(always)]`, so that its intrinsics compile inline in the
/// enabled context.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn with_avx2(isa: Isa, body: impl FnOnce(pulp::x86::V3)) -> bool {
    if isa == Isa::Avx2Fma {
        if let Some(simd) = pulp::x86::V3::try_new() {
            simd.vectorize(
                #[inline(always)]
                || body(simd),
            );
            return true;
        }
    }
    false
}

/// SplitMix64's mix on four 64-bit lanes, with its constants split for
/// the 32-bit multiplies (module docs).
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
struct Mix {
    simd: pulp::x86::V3,
    /// Each constant's low half in every 64-bit lane.
    low_1: core::arch::x86_64::__m256i,
    low_2: core::arch::x86_64::__m256i,
    /// Each constant with its 32-bit halves swapped.
    swapped_1: core::arch::x86_64::__m256i,
    swapped_2: core::arch::x86_64::__m256i,
    zero: core::arch::x86_64::__m256i,
    /// 16γ, a lane's step from one body step to the next.
    advance: core::arch::x86_64::__m256i,
}

#[cfg(target_arch = "x86_64")]
impl Mix {
    #[inline(always)]
    fn new(simd: pulp::x86::V3) -> Self {
        // A macro, not a closure (see `fill_groups_f32`).
        macro_rules! splat {
            ($c:expr) => {
                simd.avx._mm256_set1_epi64x($c as i64)
            };
        }
        Mix {
            simd,
            low_1: splat!(MIX_1 & 0xffff_ffff),
            low_2: splat!(MIX_2 & 0xffff_ffff),
            swapped_1: splat!(MIX_1.rotate_left(32)),
            swapped_2: splat!(MIX_2.rotate_left(32)),
            zero: splat!(0),
            advance: splat!((STEP as u64).wrapping_mul(GAMMA)),
        }
    }

    /// The four vectors of states `state + kγ`, k = 0 … 15, lane j of
    /// vector v holding k = 4v + j.
    #[inline(always)]
    fn lane_states(self, state: u64) -> [core::arch::x86_64::__m256i; 4] {
        let steps: [[u64; 4]; 4] = core::array::from_fn(|v| {
            core::array::from_fn(|j| ((4 * v + j) as u64).wrapping_mul(GAMMA))
        });
        let start = self.simd.avx._mm256_set1_epi64x(state as i64);
        let mut states = [start; 4];
        for (s, step) in states.iter_mut().zip(steps) {
            *s = self.simd.avx2._mm256_add_epi64(start, pulp::cast(step));
        }
        states
    }

    /// A vector of states one body step (16γ) on.
    #[inline(always)]
    fn advance(self, s: core::arch::x86_64::__m256i) -> core::arch::x86_64::__m256i {
        self.simd.avx2._mm256_add_epi64(s, self.advance)
    }

    /// z·c mod 2⁶⁴, for c given by its low half and its swapped halves
    /// (module docs).
    #[inline(always)]
    fn times(
        self,
        z: core::arch::x86_64::__m256i,
        low: core::arch::x86_64::__m256i,
        swapped: core::arch::x86_64::__m256i,
    ) -> core::arch::x86_64::__m256i {
        let a2 = self.simd.avx2;
        let cross = a2._mm256_mullo_epi32(z, swapped);
        let cross = a2._mm256_add_epi32(cross, a2._mm256_slli_epi64::<32>(cross));
        let cross = a2._mm256_blend_epi32::<0b1010_1010>(self.zero, cross);
        a2._mm256_add_epi64(a2._mm256_mul_epu32(z, low), cross)
    }

    /// `mix64` of each lane.
    #[inline(always)]
    fn mix64(self, z: core::arch::x86_64::__m256i) -> core::arch::x86_64::__m256i {
        let a2 = self.simd.avx2;
        let z = self.times(
            a2._mm256_xor_si256(z, a2._mm256_srli_epi64::<30>(z)),
            self.low_1,
            self.swapped_1,
        );
        let z = self.times(
            a2._mm256_xor_si256(z, a2._mm256_srli_epi64::<27>(z)),
            self.low_2,
            self.swapped_2,
        );
        a2._mm256_xor_si256(z, a2._mm256_srli_epi64::<31>(z))
    }
}
