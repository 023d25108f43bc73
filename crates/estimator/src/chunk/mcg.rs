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

/// Independent states stepped side by side.
pub const LANES: usize = 4;

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
        const SCALE: f64 = 1.0 / 4_294_967_296.0;
        self.fill_with(first, x, y, |bits| {
            (
                f64::from((bits >> 32) as u32) * SCALE,
                f64::from(bits as u32) * SCALE,
            )
        });
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
    /// The outputs are drawn [`SPAN`] at a time into a small buffer of
    /// integers, then converted in a separate loop: the 128-bit multiplies
    /// are scalar work, but the conversion then runs in vector registers
    /// (it was a quarter of the stream's cost done one output at a time).
    #[inline(always)]
    fn fill_with<T>(&self, first: u64, x: &mut [T], y: &mut [T], point: impl Fn(u64) -> (T, T)) {
        let n = x.len().min(y.len());
        let (x, y) = (&mut x[..n], &mut y[..n]);
        let mut lanes = [0u128; LANES];
        let mut s = self.state.wrapping_mul(power(MULTIPLIER, first + 1));
        for lane in lanes.iter_mut() {
            *lane = s;
            s = s.wrapping_mul(MULTIPLIER);
        }
        let step = power(MULTIPLIER, LANES as u64);
        let mut bits = [0u64; SPAN];
        for (xs, ys) in x.chunks_mut(SPAN).zip(y.chunks_mut(SPAN)) {
            let m = xs.len();
            let full = m / LANES * LANES;
            for group in bits[..full].chunks_exact_mut(LANES) {
                for (b, lane) in group.iter_mut().zip(lanes.iter_mut()) {
                    *b = output(*lane);
                    *lane = lane.wrapping_mul(step);
                }
            }
            // Only the last span can end inside a group of lanes.
            for (b, &lane) in bits[full..m].iter_mut().zip(lanes.iter()) {
                *b = output(lane);
            }
            for ((xk, yk), &b) in xs.iter_mut().zip(ys.iter_mut()).zip(&bits[..m]) {
                (*xk, *yk) = point(b);
            }
        }
    }
}

/// Outputs drawn between two conversions (a multiple of [`LANES`]).
const SPAN: usize = 64;

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{RngCore, SeedableRng};

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
