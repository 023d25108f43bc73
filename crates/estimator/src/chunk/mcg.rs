//! The independent-sample estimator's random stream, read in blocks and
//! lanes: the same numbers as `rand_pcg`'s `Pcg64Mcg`, without its serial
//! dependency.
//!
//! `Pcg64Mcg` (PCG-XSL-RR 128/64 on a multiplicative congruential
//! generator; O'Neill 2014, "PCG: A family of simple fast space-efficient
//! statistically good algorithms for random number generation",
//! HMC-CS-2014-0905) steps its 128-bit state by sₖ = sₖ₋₁·M mod 2¹²⁸ and
//! outputs xₖ = rotr(hi(sₖ) ⊕ lo(sₖ), sₖ ≫ 122). Drawn one by one, every
//! output waits for the previous 128-bit multiply (three 64-bit multiplies
//! and their carries in a chain). But sₖ = s₀·Mᵏ, so output k can start
//! from any earlier state by a multiply with a power of M (Brown 1994,
//! "Random number generation with arbitrary stride", the jump `rand_pcg`'s
//! own `advance` uses for its LCGs): [`McgStream::fill_2d`] keeps
//! [`LANES`] states s_{a+j}, j < LANES, steps each by M^LANES, and so has
//! that many independent multiplies in flight; it also starts a block at
//! any offset, so a chunk can be evaluated in cache-sized blocks and still
//! read exactly the numbers it always read.

/// `rand_pcg`'s multiplier of `Mcg128Xsl64`.
const MULTIPLIER: u128 = 0x2360_ED05_1FC6_5DA4_4385_DF64_9FCC_F645;

/// Independent states stepped side by side: 16, two 512-bit vectors per
/// 64-bit half. Each step is a chain of dependent multiplies, shifts and
/// adds, so one vector of 8 states waited on that chain's latency; two
/// independent vectors fill it. Criterion medians of 4096 outputs as f64
/// coordinates (bench `sequences`, rows `mcg stream`), 8 → 16 lanes,
/// alternated: AVX-512 2.78–2.87 → 1.89–2.22 µs, baseline 12.4 → 8.9 µs;
/// AVX2 within its noise (5.3–5.6 → 5.0–6.6 µs; an interleaved probe gave
/// 1.39 → 1.24 ns/output). The numbers do not depend on it (each lane is
/// s₀·M^(first+1+j), stepped by M^LANES).
pub const LANES: usize = 16;

/// A `Pcg64Mcg` stream, addressed by output index (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct McgStream {
    /// The state s₀ before output 0.
    state: u128,
}

/// `a`ᵉ mod 2¹²⁸ by squaring.
#[inline]
fn power(mut a: u128, mut e: u64) -> u128 {
    let mut acc: u128 = 1;
    while e > 0 {
        if e & 1 == 1 {
            acc = acc.wrapping_mul(a);
        }
        a = a.wrapping_mul(a);
        e >>= 1;
    }
    acc
}

/// The PCG-XSL-RR output of a state.
#[inline(always)]
fn output(state: u128) -> u64 {
    let rot = (state >> 122) as u32;
    (((state >> 64) as u64) ^ (state as u64)).rotate_right(rot)
}

impl McgStream {
    /// The stream `rand_pcg::Pcg64Mcg::seed_from_u64(seed)` produces:
    /// `rand_core`'s default seeding (four PCG32 outputs of the seed as the
    /// little-endian bytes of the 128-bit state), with the low bit set.
    pub fn seed_from_u64(mut seed: u64) -> Self {
        const MUL: u64 = 6_364_136_223_846_793_005;
        const INC: u64 = 11_634_580_027_462_260_723;
        let mut state: u128 = 0;
        for word in 0..4 {
            seed = seed.wrapping_mul(MUL).wrapping_add(INC);
            let xorshifted = (((seed >> 18) ^ seed) >> 27) as u32;
            let x = xorshifted.rotate_right((seed >> 59) as u32);
            state |= u128::from(x) << (32 * word);
        }
        McgStream { state: state | 1 }
    }

    /// Output number `index` (the `index + 1`-th `next_u64`).
    pub fn at(&self, index: u64) -> u64 {
        output(self.state.wrapping_mul(power(MULTIPLIER, index + 1)))
    }

    /// Outputs `first + k` as 2-D points: `x[k]`, `y[k]` are the high and
    /// low 32-bit halves times 2⁻³² (the estimator's coordinates, exact).
    /// Fills the shorter length.
    #[inline(always)]
    pub fn fill_2d(&self, first: u64, x: &mut [f64], y: &mut [f64]) {
        self.fill_with(first, x, y, unit_pair);
    }

    /// The f32 path's coordinates of outputs `first + k`: the top 24 bits
    /// of each 32-bit half times 2⁻²⁴ — [`fill_2d`](Self::fill_2d)'s
    /// coordinates rounded down to the 24 bits an f32 in [0, 1) holds
    /// exactly (so never 1). Fills the shorter length.
    #[inline(always)]
    pub fn fill_2d_f32(&self, first: u64, x: &mut [f32], y: &mut [f32]) {
        const SCALE: f32 = 1.0 / 16_777_216.0;
        self.fill_with(first, x, y, |bits| {
            (
                (bits >> 40) as f32 * SCALE,
                ((bits >> 8) & 0xff_ffff) as f32 * SCALE,
            )
        });
    }

    /// `(x[k], y[k]) = point(output(first + k))`, [`LANES`] states stepped
    /// side by side.
    ///
    /// The states are held as their 64-bit halves, one array each, and the
    /// 128-bit step is written in 64- and 32-bit multiplies ([`Lanes`]), so
    /// that the compiler steps all lanes in vector registers (a `u128`
    /// multiply stays scalar: three dependent 64-bit multiplies per
    /// output). The outputs are drawn [`SPAN`] at a time into a small
    /// buffer of integers, then converted in a separate loop.
    #[inline(always)]
    fn fill_with<T>(&self, first: u64, x: &mut [T], y: &mut [T], point: impl Fn(u64) -> (T, T)) {
        let n = x.len().min(y.len());
        let (x, y) = (&mut x[..n], &mut y[..n]);
        let mut lanes = Lanes::starting_at(self.state.wrapping_mul(power(MULTIPLIER, first + 1)));
        let step = power(MULTIPLIER, LANES as u64);
        let step = ((step >> 64) as u64, step as u64);
        let mut bits = [0u64; SPAN];
        for (xs, ys) in x.chunks_mut(SPAN).zip(y.chunks_mut(SPAN)) {
            let m = xs.len();
            let full = m / LANES * LANES;
            for group in bits[..full].as_chunks_mut::<LANES>().0 {
                lanes.output(group);
                lanes.step(step);
            }
            // Only the last span can end inside a group of lanes. Tested,
            // not done unconditionally: an empty copy still called
            // `memcpy` once per span, and the call spilled the lanes.
            if full < m {
                let mut last = [0u64; LANES];
                lanes.output(&mut last);
                bits[full..m].copy_from_slice(&last[..m - full]);
            }
            for ((xk, yk), &b) in xs.iter_mut().zip(ys.iter_mut()).zip(&bits[..m]) {
                (*xk, *yk) = point(b);
            }
        }
    }
}

/// [`LANES`] consecutive states s_{a+j}, as high and low 64-bit halves.
struct Lanes {
    hi: [u64; LANES],
    lo: [u64; LANES],
}

impl Lanes {
    /// The states `s·M^j`, j < [`LANES`].
    #[inline(always)]
    fn starting_at(mut s: u128) -> Self {
        let (mut hi, mut lo) = ([0u64; LANES], [0u64; LANES]);
        for j in 0..LANES {
            (hi[j], lo[j]) = ((s >> 64) as u64, s as u64);
            s = s.wrapping_mul(MULTIPLIER);
        }
        Lanes { hi, lo }
    }

    /// Every lane's PCG-XSL-RR output, as [`output`] gives it.
    #[inline(always)]
    fn output(&self, out: &mut [u64; LANES]) {
        for ((o, &hi), &lo) in out.iter_mut().zip(&self.hi).zip(&self.lo) {
            *o = (hi ^ lo).rotate_right((hi >> 58) as u32);
        }
    }

    /// s ← s·m mod 2¹²⁸ on every lane, m = (high, low) halves:
    /// lo' = lo·m_lo mod 2⁶⁴, hi' = ⌊lo·m_lo / 2⁶⁴⌋ + lo·m_hi + hi·m_lo
    /// (mod 2⁶⁴), the high product from four 32 × 32-bit products.
    #[inline(always)]
    fn step(&mut self, (m_hi, m_lo): (u64, u64)) {
        const LOW: u64 = 0xffff_ffff;
        let (b1, b0) = (m_lo >> 32, m_lo & LOW);
        for j in 0..LANES {
            let (hi, lo) = (self.hi[j], self.lo[j]);
            let (a1, a0) = (lo >> 32, lo & LOW);
            let (p00, p01, p10, p11) = (a0 * b0, a0 * b1, a1 * b0, a1 * b1);
            // < 3·2³², no overflow.
            let mid = (p00 >> 32) + (p01 & LOW) + (p10 & LOW);
            let carry_hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
            self.lo[j] = (mid << 32) | (p00 & LOW);
            self.hi[j] = carry_hi
                .wrapping_add(lo.wrapping_mul(m_hi))
                .wrapping_add(hi.wrapping_mul(m_lo));
        }
    }
}

/// The high and low 32-bit halves h of `bits` as h·2⁻³², exactly.
///
/// Without a conversion or a multiply: the double with exponent 0 and
/// fraction bits h·2²⁰ is 1 + h·2⁻³² exactly (h fits the 52 fraction bits),
/// and subtracting 1 is exact (the difference is representable): a shift,
/// a mask, an or and a subtraction in place of a conversion and a multiply
/// (measured within noise of that form on AVX-512).
#[inline(always)]
fn unit_pair(bits: u64) -> (f64, f64) {
    const ONE: u64 = 0x3ff0_0000_0000_0000;
    const HIGH_HALF: u64 = 0xffff_ffff_0000_0000;
    (
        f64::from_bits(ONE | ((bits & HIGH_HALF) >> 12)) - 1.0,
        f64::from_bits(ONE | ((bits << 32) >> 12)) - 1.0,
    )
}

/// Outputs drawn between two conversions (a multiple of [`LANES`]).
const SPAN: usize = 64;

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{RngCore, SeedableRng};

    /// The exponent trick gives h·2⁻³² to the bit (so +0 for h = 0) at
    /// the halves' extremes and around every power of two; a negative
    /// control shows the comparison sees an ulp.
    #[test]
    fn unit_pair_is_the_exact_scaled_half() {
        let scaled = |h: u64| (h as f64 / 4_294_967_296.0).to_bits();
        let mut halves = vec![0u64, 1, 2, 3, 0xffff_fffe, 0xffff_ffff];
        for k in 1..32 {
            halves.extend([(1u64 << k) - 1, 1 << k, (1 << k) + 1]);
        }
        for &hi in &halves {
            for &lo in &halves {
                let (x, y) = unit_pair(hi << 32 | lo);
                assert_eq!(
                    (x.to_bits(), y.to_bits()),
                    (scaled(hi), scaled(lo)),
                    "{hi:#x} {lo:#x}"
                );
            }
        }
        assert_ne!(unit_pair(5 << 32).0.to_bits(), scaled(5) + 1);
    }

    #[test]
    fn same_numbers_as_rand_pcg_from_any_offset() {
        for seed in [0u64, 1, 0xdead_beef, u64::MAX] {
            let mut reference = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
            let want: Vec<u64> = (0..300).map(|_| reference.next_u64()).collect();
            let stream = McgStream::seed_from_u64(seed);
            for (k, &w) in want.iter().enumerate().step_by(37) {
                assert_eq!(stream.at(k as u64), w, "seed {seed}, output {k}");
            }
            for first in [0usize, 1, 5, 130] {
                for len in [0usize, 1, 3, 4, 9, 101] {
                    let (mut x, mut y) = (vec![0.0; len], vec![0.0; len]);
                    stream.fill_2d(first as u64, &mut x, &mut y);
                    for k in 0..len {
                        let bits = want[first + k];
                        assert_eq!(x[k], (bits >> 32) as f64 / 4_294_967_296.0);
                        assert_eq!(y[k], (bits & 0xffff_ffff) as f64 / 4_294_967_296.0);
                    }
                    // f32: the same coordinates rounded down to 24 bits.
                    let (mut x32, mut y32) = (vec![0.0f32; len], vec![0.0f32; len]);
                    stream.fill_2d_f32(first as u64, &mut x32, &mut y32);
                    for k in 0..len {
                        assert_eq!(
                            f64::from(x32[k]),
                            (x[k] * 16_777_216.0).floor() / 16_777_216.0
                        );
                        assert_eq!(
                            f64::from(y32[k]),
                            (y[k] * 16_777_216.0).floor() / 16_777_216.0
                        );
                        assert!(x32[k] < 1.0 && y32[k] < 1.0);
                    }
                }
            }
        }
    }
}
