//! Uniform numbers for whole batches: the SplitMix64 generator, evaluated
//! as a counter so that every lane of a vector computes its own output.
//!
//! SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom
//! number generators", OOPSLA; the generator of Java's `SplittableRandom`)
//! walks a 64-bit state by the odd constant γ = 0x9e3779b97f4a7c15 (the
//! golden ratio times 2⁶⁴) and outputs a bijective mix of it:
//!
//! ```text
//! sᵢ = s₀ + (i + 1)·γ  (mod 2⁶⁴),     xᵢ = mix64(sᵢ)
//! ```
//!
//! with `mix64` the finaliser z ← (z ⊕ z≫30)·0xbf58476d1ce4e5b9,
//! z ← (z ⊕ z≫27)·0x94d049bb133111eb, z ⊕ z≫31 (Stafford's "Mix13"). Its
//! period is 2⁶⁴ and it passes BigCrush (Steele et al. §5). Because sᵢ is a
//! closed form in i, output i costs the same whatever came before: a batch
//! fills its lanes independently (two 64-bit multiplies and a few shifts
//! per number, which AVX-512 does eight at a time), where a generator whose
//! next state needs the last one (PCG's 128-bit multiply) costs a multiply
//! latency per number. That is what the f32 estimator path and the batch
//! benches use it for; the f64 estimator keeps its PCG stream, whose
//! values it has always had.
//!
//! One 64-bit output gives one 2-D point: its high and low 32-bit halves,
//! each scaled to [0, 1): k·2⁻²⁴ from the top 24 bits in f32 (so no value
//! rounds to 1), k·2⁻³² in f64.

use super::mix64;

/// The golden-ratio increment γ of SplitMix64.
const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// A SplitMix64 stream read in batches (module docs).
///
/// ```
/// use lambert_sampling::sequence::SplitMix64;
/// let rng = SplitMix64::new(7);
/// let (mut x, mut y) = ([0.0f32; 8], [0.0f32; 8]);
/// rng.fill_2d_f32(100, &mut x, &mut y);
/// // Random access: point 103 alone is the same as the batch's fourth.
/// let (mut x1, mut y1) = ([0.0f32; 1], [0.0f32; 1]);
/// rng.fill_2d_f32(103, &mut x1, &mut y1);
/// assert_eq!((x[3], y[3]), (x1[0], y1[0]));
/// assert!(x.iter().chain(&y).all(|&v| (0.0..1.0).contains(&v)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The stream whose state before output 0 is `mix64(seed)` (a
    /// scrambled seed, so that nearby seeds start far apart).
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: mix64(seed) }
    }

    /// The stream whose state before output 0 is `state` itself, without
    /// [`SplitMix64::new`]'s scrambling: output k is
    /// `mix64(state + (k + 1)·γ)`, SplitMix64 as its authors seed it (the
    /// f32 estimator's chunk streams start from their chunk seeds so).
    pub fn from_state(state: u64) -> Self {
        SplitMix64 { state }
    }

    /// Output number `index` (64 bits).
    #[inline(always)]
    pub fn at(&self, index: u64) -> u64 {
        mix64(self.state_before(index))
    }

    /// The state s₀ + (index + 1)·γ whose mix is output `index`; output
    /// `index + k` mixes this plus k·γ. The fills step a state by γ per
    /// output rather than multiply k·γ: the compiler keeps the stepped
    /// states in vector registers and adds 16γ per vector, where the
    /// product k·γ cost a 64-bit vector multiply per 8 outputs, a third of
    /// the generator's multiplies (criterion, `soa` group on an AVX-512
    /// host: the cosine- and uniform-hemisphere f32 slice forms with their
    /// numbers took 7 % less time once the fills stepped the state).
    #[inline(always)]
    fn state_before(&self, index: u64) -> u64 {
        self.state
            .wrapping_add(index.wrapping_add(1).wrapping_mul(GAMMA))
    }

    /// Points `first + k` of the stream in f32, as two arrays of
    /// coordinates: `x[k]`, `y[k]` are the top 24 bits of the high and low
    /// halves of output `first + k`, times 2⁻²⁴ (in [0, 1 − 2⁻²⁴]). Fills
    /// the shorter length.
    #[inline(always)]
    pub fn fill_2d_f32(&self, first: u64, x: &mut [f32], y: &mut [f32]) {
        const SCALE: f32 = 1.0 / 16_777_216.0;
        let mut state = self.state_before(first);
        for (xk, yk) in x.iter_mut().zip(y.iter_mut()) {
            let bits = mix64(state);
            state = state.wrapping_add(GAMMA);
            // Both values are below 2^24: the signed conversion is exact
            // and is one instruction on every vector set.
            *xk = (bits >> 40) as i32 as f32 * SCALE;
            *yk = ((bits >> 8) & 0x00ff_ffff) as i32 as f32 * SCALE;
        }
    }

    /// [`fill_2d_f32`](Self::fill_2d_f32) in f64: the two 32-bit halves of
    /// output `first + k`, times 2⁻³² (in [0, 1 − 2⁻³²]).
    #[inline(always)]
    pub fn fill_2d(&self, first: u64, x: &mut [f64], y: &mut [f64]) {
        const SCALE: f64 = 1.0 / 4_294_967_296.0;
        let mut state = self.state_before(first);
        for (xk, yk) in x.iter_mut().zip(y.iter_mut()) {
            let bits = mix64(state);
            state = state.wrapping_add(GAMMA);
            *xk = u32_to_f64_exact(bits >> 32) * SCALE;
            *yk = u32_to_f64_exact(bits & 0xffff_ffff) * SCALE;
        }
    }
}

/// `x < 2³²` as an f64, exactly: the bits of 2⁵² + x minus 2⁵². One
/// integer or and one subtraction, where a 64-bit integer conversion has
/// no vector instruction before AVX-512.
#[inline(always)]
pub(crate) fn u32_to_f64_exact(x: u64) -> f64 {
    const TWO_52: f64 = 4_503_599_627_370_496.0;
    debug_assert!(x < 1 << 32);
    f64::from_bits(TWO_52.to_bits() | x) - TWO_52
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The published SplitMix64 sequence for state 0 (the reference
    /// implementation's first outputs, as quoted by Vigna's xoshiro page
    /// for seeding): 0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f.
    /// SplitMix64 as its authors step it, one output after the other.
    fn serial(state: u64, count: usize) -> Vec<u64> {
        let mut state = state;
        (0..count)
            .map(|_| {
                state = state.wrapping_add(GAMMA);
                mix64(state)
            })
            .collect()
    }

    /// Random access and the batch fills give the serial generator's
    /// numbers from any offset and for any length, and the f32 points are
    /// the top 24 bits of each half.
    #[test]
    fn same_numbers_as_the_serial_generator_from_any_offset() {
        for state in [0u64, 1, 0xdead_beef, u64::MAX] {
            let want = serial(state, 300);
            let stream = SplitMix64::from_state(state);
            for (k, &w) in want.iter().enumerate() {
                assert_eq!(stream.at(k as u64), w, "state {state}, output {k}");
            }
            for first in [0usize, 1, 5, 130] {
                for len in [0usize, 1, 3, 17, 101] {
                    let (mut x, mut y) = (vec![0.0f32; len], vec![0.0f32; len]);
                    stream.fill_2d_f32(first as u64, &mut x, &mut y);
                    for k in 0..len {
                        let bits = want[first + k];
                        assert_eq!(f64::from(x[k]), (bits >> 40) as f64 / 16_777_216.0);
                        let lo = ((bits & 0xffff_ffff) >> 8) as f64 / 16_777_216.0;
                        assert_eq!(f64::from(y[k]), lo);
                        assert!(x[k] < 1.0 && y[k] < 1.0);
                    }
                }
            }
        }
    }

    #[test]
    fn matches_the_reference_sequence() {
        let rng = SplitMix64 { state: 0 };
        assert_eq!(rng.at(0), 0xe220_a839_7b1d_cdaf);
        assert_eq!(rng.at(1), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(rng.at(2), 0x06c4_5d18_8009_454f);
    }

    #[test]
    fn exact_conversion_of_32_bit_words() {
        for x in [0u64, 1, 12345, (1 << 31) + 7, (1 << 32) - 1] {
            assert_eq!(u32_to_f64_exact(x), x as f64);
        }
    }

    #[test]
    fn coordinates_stay_in_the_unit_square_and_are_halves_of_one_output() {
        let rng = SplitMix64::new(1);
        let (mut x, mut y) = ([0.0f64; 64], [0.0f64; 64]);
        rng.fill_2d(u64::MAX - 10, &mut x, &mut y); // indices wrap
        for k in 0..64 {
            let bits = rng.at((u64::MAX - 10).wrapping_add(k as u64));
            assert_eq!(x[k], (bits >> 32) as f64 / 4_294_967_296.0);
            assert!((0.0..1.0).contains(&x[k]) && (0.0..1.0).contains(&y[k]));
        }
        let (mut xf, mut yf) = ([0.0f32; 64], [0.0f32; 64]);
        rng.fill_2d_f32(u64::MAX - 10, &mut xf, &mut yf);
        for k in 0..64 {
            // The f32 coordinate is the f64 one truncated to 24 bits.
            assert_eq!(xf[k] as f64, (x[k] * 16_777_216.0).floor() / 16_777_216.0);
            assert!(yf[k] < 1.0);
        }
    }
}
