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
//! latency per number, and PCG-XSL-RR 128/64, even stepped in lanes,
//! ten 32-bit multiplies per output where a vector set has no 64-bit one.
//! That is what the independent estimator (both precisions) and the batch
//! benches use it for.
//!
//! Each 64-bit output gives two coordinates, its two 32-bit halves scaled
//! to [0, 1). In f64 ([`SplitMix64::fill_2d`]) output i is point i: x from
//! its high half, y from its low half, k·2⁻³². In f32
//! ([`SplitMix64::fill_2d_f32`]) each half's top 24 bits give k·2⁻²⁴ (so
//! no value rounds to 1), and the points come in groups of 16: of the 16
//! outputs from a multiple of 16, the first 8 give the group's x
//! coordinates and the last 8 its y, each output its low half to an even
//! point and its high half to the next,
//!
//! ```text
//! x_i = top24(half_{i mod 2}(out[16⌊i/16⌋ + (i mod 16)/2])) · 2⁻²⁴,
//! y_i = the same of out[16⌊i/16⌋ + 8 + (i mod 16)/2].
//! ```
//!
//! That is the order of the halves in memory (x86 is little-endian), so a
//! vector of eight outputs is, read as sixteen 32-bit lanes, sixteen
//! coordinates in order: a shift, a conversion and a product, where one
//! output per point needs its halves narrowed and separated (the f32 fill
//! took 0.40 ns per point with one output per point and 0.25 grouped,
//! criterion on an AVX-512 host). The layout is part of every f32
//! estimate's values (it changed them once, 2026-12).

use super::splitmix_avx2;
use super::{mix64, GAMMA, MIX_1, MIX_2};
use crate::isa::Isa;

/// Points per group of the f32 fill: the 16 outputs from a multiple of 16
/// give 16 points, the first 8 their x and the last 8 their y (module
/// docs).
const GROUP: usize = 16;

/// The top 24 bits of a 32-bit word times 2⁻²⁴, in [0, 1 − 2⁻²⁴]. The
/// integer is below 2²⁴, so the signed conversion is exact (and one
/// instruction on every vector set), and so is the scaling.
#[inline(always)]
fn word_to_f32(word: u32) -> f32 {
    (word >> 8) as i32 as f32 * (1.0 / 16_777_216.0)
}

/// One group of the f32 fill in scalar code: `state` is output 16t's
/// state; output 16t + j gives x[2j] (low half) and x[2j + 1] (high
/// half), output 16t + 8 + j the same of y.
#[inline(always)]
fn group_f32(state: u64, x: &mut [f32; GROUP], y: &mut [f32; GROUP]) {
    for j in 0..GROUP / 2 {
        let bx = mix64(state.wrapping_add((j as u64).wrapping_mul(GAMMA)));
        let by = mix64(state.wrapping_add((j as u64 + 8).wrapping_mul(GAMMA)));
        x[2 * j] = word_to_f32(bx as u32);
        x[2 * j + 1] = word_to_f32((bx >> 32) as u32);
        y[2 * j] = word_to_f32(by as u32);
        y[2 * j + 1] = word_to_f32((by >> 32) as u32);
    }
}

/// Whole groups of the f32 fill with AVX-512, when `isa` is
/// [`Isa::Avx512`] or [`Isa::Avx512Gfni`] and the processor has it; returns whether it filled
/// them. `state` is the first group's output-0 state, `x` and `y` are
/// whole groups.
///
/// Why explicit: each vector of eight 64-bit outputs is, read as sixteen
/// 32-bit lanes, the sixteen halves a group's x (or y) needs in order, so
/// one shift, one conversion and one product turn it into sixteen
/// coordinates. Written as scalar code the compiler does not see that
/// reinterpretation: it vectorised the group loop across groups and
/// shuffled every lane (criterion, `soa/splitmix64 rng only f32`: 407 ns
/// per 1,024 points for the ungrouped layout, 984 for the grouped one in
/// scalar code, 253 with this body; the cosine-hemisphere f32 slice form with
/// its numbers went from 1.11 to 0.99–1.03 µs per 1,024 points).
#[inline(always)]
fn fill_groups_avx512(isa: Isa, state: u64, x: &mut [f32], y: &mut [f32]) -> bool {
    #[cfg(target_arch = "x86_64")]
    if isa >= Isa::Avx512 {
        if let Some(simd) = pulp::x86::V4::try_new() {
            simd.vectorize(
                #[inline(always)]
                || {
                    use core::arch::x86_64::__m512i;
                    let (f, dq) = (simd.avx512f, simd.avx512dq);
                    macro_rules! splat {
                        ($v:expr) => {
                            f._mm512_set1_epi64($v as i64)
                        };
                    }
                    let steps: __m512i = pulp::cast(core::array::from_fn::<u64, 8, _>(|j| {
                        (j as u64).wrapping_mul(GAMMA)
                    }));
                    let mut sx = f._mm512_add_epi64(splat!(state), steps);
                    let mut sy = f._mm512_add_epi64(sx, splat!(8u64.wrapping_mul(GAMMA)));
                    let advance = splat!((GROUP as u64).wrapping_mul(GAMMA));
                    let (c1, c2) = (splat!(MIX_1), splat!(MIX_2));
                    let scale = f._mm512_set1_ps(1.0 / 16_777_216.0);
                    // No closures in here (see `splitmix_avx2::fill_groups_f32`).
                    let (xs, _) = x.as_chunks_mut::<GROUP>();
                    let (ys, _) = y.as_chunks_mut::<GROUP>();
                    for (xg, yg) in xs.iter_mut().zip(ys) {
                        for (out, s) in [xg, yg].into_iter().zip([&mut sx, &mut sy]) {
                            let z = *s;
                            let z = f._mm512_xor_si512(z, f._mm512_srli_epi64::<30>(z));
                            let z = dq._mm512_mullo_epi64(z, c1);
                            let z = f._mm512_xor_si512(z, f._mm512_srli_epi64::<27>(z));
                            let z = dq._mm512_mullo_epi64(z, c2);
                            let bits = f._mm512_xor_si512(z, f._mm512_srli_epi64::<31>(z));
                            let words = f._mm512_srli_epi32::<8>(bits);
                            *out = pulp::cast(f._mm512_mul_ps(f._mm512_cvtepi32_ps(words), scale));
                            *s = f._mm512_add_epi64(*s, advance);
                        }
                    }
                },
            );
            return true;
        }
    }
    let _ = (isa, state, x, y);
    false
}

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
    /// `mix64(state + (k + 1)·γ)`, SplitMix64 as its authors seed it.
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
    /// coordinates, by the grouped layout of the module docs: point i's x
    /// and y are 32-bit halves of outputs 16⌊i/16⌋ + (i mod 16)/2 and that
    /// plus 8, the low half for even i, each half's top 24 bits times 2⁻²⁴
    /// (in [0, 1 − 2⁻²⁴]). Fills the shorter length, with
    /// [`Isa::selected`]; [`fill_2d_f32_in`](Self::fill_2d_f32_in) names
    /// the set.
    #[inline(always)]
    pub fn fill_2d_f32(&self, first: u64, x: &mut [f32], y: &mut [f32]) {
        self.fill_2d_f32_in(Isa::selected(), first, x, y);
    }

    /// [`fill_2d_f32`](Self::fill_2d_f32) with the instruction set `isa`:
    /// with [`Isa::Avx512`] or [`Isa::Avx2Fma`] whole groups of 16 points
    /// take an explicit body (`fill_groups_avx512`: eight outputs per
    /// vector, whose sixteen 32-bit halves convert in place, no narrowing
    /// or shuffles; `splitmix_avx2::fill_groups_f32` the same four at a time); with the
    /// baseline set, and for the points before the first whole group and
    /// after the last, the scalar code.
    /// The same bits either way (integer steps, and conversions of
    /// integers below 2²⁴ and scalings by 2⁻²⁴ that are exact).
    #[inline(always)]
    pub fn fill_2d_f32_in(&self, isa: Isa, first: u64, x: &mut [f32], y: &mut [f32]) {
        let len = x.len().min(y.len());
        let (x, y) = (&mut x[..len], &mut y[..len]);
        // Points up to the next multiple of GROUP, one at a time.
        let head = ((GROUP as u64).wrapping_sub(first % GROUP as u64) % GROUP as u64) as usize;
        let head = head.min(len);
        for k in 0..head {
            (x[k], y[k]) = self.point_f32(first.wrapping_add(k as u64));
        }
        let whole = (len - head) / GROUP * GROUP;
        let body = first.wrapping_add(head as u64);
        let (xb, yb) = (&mut x[head..head + whole], &mut y[head..head + whole]);
        let filled = fill_groups_avx512(isa, self.state_before(body), xb, yb)
            || splitmix_avx2::fill_groups_f32(isa, self.state_before(body), xb, yb);
        if !filled {
            let mut state = self.state_before(body);
            for (xg, yg) in xb
                .as_chunks_mut::<GROUP>()
                .0
                .iter_mut()
                .zip(yb.as_chunks_mut::<GROUP>().0)
            {
                group_f32(state, xg, yg);
                state = state.wrapping_add((GROUP as u64).wrapping_mul(GAMMA));
            }
        }
        for k in head + whole..len {
            (x[k], y[k]) = self.point_f32(first.wrapping_add(k as u64));
        }
    }

    /// Point `index` alone, in f32 (the grouped layout of
    /// [`fill_2d_f32`](Self::fill_2d_f32)).
    #[inline(always)]
    fn point_f32(&self, index: u64) -> (f32, f32) {
        let r = index % GROUP as u64;
        let output = index - r + r / 2;
        let half = |bits: u64| {
            word_to_f32(if r.is_multiple_of(2) {
                bits as u32
            } else {
                (bits >> 32) as u32
            })
        };
        (
            half(self.at(output)),
            half(self.at(output.wrapping_add(GROUP as u64 / 2))),
        )
    }

    /// [`fill_2d_f32`](Self::fill_2d_f32) in f64: the two 32-bit halves of
    /// output `first + k`, times 2⁻³² (in [0, 1 − 2⁻³²]): x from the high
    /// half, y from the low. Fills the shorter length.
    ///
    /// The outputs are computed sixteen at a time, each lane's state
    /// stepped by 16γ, so that the compiler keeps the states in vector
    /// registers (a state stepped by γ after every output is one serial
    /// chain), and each half becomes its coordinate by an exponent trick
    /// instead of a conversion (h·2⁻³² = (1 + h·2⁻³²) − 1, the first
    /// term's bits written directly; exact). On an AVX2 host, 1.12 ns a
    /// point against 1.25 with the state stepped by γ (4096 points,
    /// medians of 9).
    #[inline(always)]
    pub fn fill_2d(&self, first: u64, x: &mut [f64], y: &mut [f64]) {
        let len = x.len().min(y.len());
        let (x, y) = (&mut x[..len], &mut y[..len]);
        let whole = len / LANES * LANES;
        let mut states = [0u64; LANES];
        for (j, s) in states.iter_mut().enumerate() {
            *s = self.state_before(first.wrapping_add(j as u64));
        }
        let step = (LANES as u64).wrapping_mul(GAMMA);
        let (xs, _) = x[..whole].as_chunks_mut::<LANES>();
        let (ys, _) = y[..whole].as_chunks_mut::<LANES>();
        for (xg, yg) in xs.iter_mut().zip(ys) {
            for j in 0..LANES {
                let bits = mix64(states[j]);
                states[j] = states[j].wrapping_add(step);
                (xg[j], yg[j]) = (half_to_f64(bits >> 32), half_to_f64(bits & 0xffff_ffff));
            }
        }
        self.fill_2d_tail(first, whole, x, y);
    }

    /// [`fill_2d`](Self::fill_2d) with the instruction set `isa`: with
    /// [`Isa::Avx2Fma`] whole runs of 16 points take an explicit body
    /// (`splitmix_avx2::fill_points_f64`, whose 64-bit multiplies are two
    /// 32-bit ones where the compiler's form of `fill_2d` takes three: an
    /// f64 point 1.08 → 0.95 ns on the Zen 2 host); with any other set,
    /// `fill_2d` compiled for it (AVX-512 has the 64-bit multiply). The
    /// same bits either way (integer steps and exact conversions).
    ///
    /// ```
    /// use lambert_sampling::isa::Isa;
    /// use lambert_sampling::sequence::SplitMix64;
    /// let rng = SplitMix64::new(3);
    /// let (mut x, mut y) = ([0.0; 40], [0.0; 40]);
    /// let (mut x1, mut y1) = ([0.0; 40], [0.0; 40]);
    /// for isa in Isa::available() {
    ///     isa.run(|| rng.fill_2d_in(isa, 5, &mut x, &mut y));
    ///     rng.fill_2d(5, &mut x1, &mut y1);
    ///     assert_eq!((x, y), (x1, y1));
    /// }
    /// ```
    #[inline(always)]
    pub fn fill_2d_in(&self, isa: Isa, first: u64, x: &mut [f64], y: &mut [f64]) {
        let len = x.len().min(y.len());
        let (x, y) = (&mut x[..len], &mut y[..len]);
        let whole = len / splitmix_avx2::STEP * splitmix_avx2::STEP;
        let state = self.state_before(first);
        if splitmix_avx2::fill_points_f64(isa, state, &mut x[..whole], &mut y[..whole]) {
            self.fill_2d_tail(first, whole, x, y);
        } else {
            self.fill_2d(first, x, y);
        }
    }

    /// Points `first + k` for k from `whole` to the end, one at a time
    /// (the fills' points after their last whole run).
    #[inline(always)]
    fn fill_2d_tail(&self, first: u64, whole: usize, x: &mut [f64], y: &mut [f64]) {
        let mut state = self.state_before(first.wrapping_add(whole as u64));
        for (xk, yk) in x[whole..].iter_mut().zip(&mut y[whole..]) {
            let bits = mix64(state);
            state = state.wrapping_add(GAMMA);
            (*xk, *yk) = (half_to_f64(bits >> 32), half_to_f64(bits & 0xffff_ffff));
        }
    }
}

/// Outputs computed side by side by [`SplitMix64::fill_2d`]: two AVX-512
/// vectors, four AVX2 ones (8 and 32 measured slower on the AVX2 host:
/// 1.31 and 1.13 ns a point against 1.12).
const LANES: usize = 16;

/// A 32-bit half h (`h < 2³²`) as h·2⁻³², exactly, without a conversion
/// or a multiply: the double with exponent 0 and fraction bits h·2²⁰ is
/// 1 + h·2⁻³² exactly (h fits the 52 fraction bits), and subtracting 1 is
/// exact (Sterbenz). A shift, an or and a subtraction, where a 64-bit
/// integer conversion has no vector instruction before AVX-512.
#[inline(always)]
fn half_to_f64(h: u64) -> f64 {
    const ONE: u64 = 0x3ff0_0000_0000_0000;
    debug_assert!(h < 1 << 32);
    f64::from_bits(ONE | (h << 20)) - 1.0
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
            let want = serial(state, 400);
            let stream = SplitMix64::from_state(state);
            for (k, &w) in want.iter().enumerate() {
                assert_eq!(stream.at(k as u64), w, "state {state}, output {k}");
            }
            // The grouped layout, from the serial outputs: point i's x is
            // a half of output 16⌊i/16⌋ + (i mod 16)/2 (low for even i),
            // its y the same half of the output 8 later.
            let half = |i: usize, plus: usize| {
                let bits = want[i - i % 16 + (i % 16) / 2 + plus];
                let word = if i.is_multiple_of(2) {
                    bits & 0xffff_ffff
                } else {
                    bits >> 32
                };
                (word >> 8) as f64 / 16_777_216.0
            };
            for first in [0usize, 1, 5, 16, 130] {
                for len in [0usize, 1, 3, 17, 101, 250] {
                    for isa in Isa::available() {
                        let (mut x, mut y) = (vec![0.0f32; len], vec![0.0f32; len]);
                        stream.fill_2d_f32_in(isa, first as u64, &mut x, &mut y);
                        for k in 0..len {
                            let i = first + k;
                            assert_eq!(f64::from(x[k]), half(i, 0), "{isa} {first}+{k}");
                            assert_eq!(f64::from(y[k]), half(i, 8), "{isa} {first}+{k}");
                            assert!(x[k] < 1.0 && y[k] < 1.0);
                        }
                    }
                }
            }
        }
    }

    /// Every instruction set's fill gives the scalar fill's bits, from
    /// offsets in and out of group alignment, across the wrap of the
    /// index, for lengths with and without whole groups. Negative
    /// control: the grouped layout is not the ungrouped one (point i from
    /// output i's halves), so a body that ignored the groups would fail.
    #[test]
    fn every_set_fills_the_same_bits() {
        let rng = SplitMix64::new(5);
        let fill = |isa: Isa, first: u64, len: usize| {
            let (mut x, mut y) = (vec![0.0f32; len], vec![0.0f32; len]);
            isa.run(|| rng.fill_2d_f32_in(isa, first, &mut x, &mut y));
            (x, y)
        };
        for first in [0u64, 3, 16, 1000, u64::MAX - 37] {
            for len in [15usize, 16, 33, 512, 1027] {
                let want = fill(Isa::Baseline, first, len);
                for isa in Isa::available() {
                    assert_eq!(fill(isa, first, len), want, "{isa} from {first}, {len}");
                }
            }
        }
        let (x, _) = fill(Isa::selected(), 0, 64);
        let ungrouped: Vec<f32> = (0..64)
            .map(|i| word_to_f32((rng.at(i) >> 32) as u32))
            .collect();
        assert_ne!(x, ungrouped);
    }

    #[test]
    fn matches_the_reference_sequence() {
        let rng = SplitMix64 { state: 0 };
        assert_eq!(rng.at(0), 0xe220_a839_7b1d_cdaf);
        assert_eq!(rng.at(1), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(rng.at(2), 0x06c4_5d18_8009_454f);
    }

    /// The exponent trick gives h·2⁻³² to the bit (so +0 for h = 0) at
    /// the half's extremes and around every power of two; a negative
    /// control shows the comparison sees an ulp.
    #[test]
    fn a_half_is_its_value_times_two_to_the_minus_32_exactly() {
        let mut halves = vec![0u64, 1, (1 << 32) - 1];
        for e in 1..32 {
            halves.extend([(1u64 << e) - 1, 1 << e, (1 << e) + 1]);
        }
        for h in halves {
            let want = h as f64 / 4_294_967_296.0;
            assert_eq!(half_to_f64(h).to_bits(), want.to_bits(), "half {h:#x}");
        }
        let off_by_an_ulp = f64::from_bits((0.5f64).to_bits() + 1);
        assert_ne!(half_to_f64(1 << 31), off_by_an_ulp);
    }

    /// The f64 fill gives output `first + k`'s halves (high to x, low to
    /// y) from any offset and for any length, with every instruction set
    /// (`fill_2d_in`, whose AVX2 body is its own code) and as `fill_2d`:
    /// lengths below, at and past a multiple of the lanes, offsets that
    /// cross the index wrap. Its values are the serial generator's, so the
    /// lanes never reorder them. Negative control: the points of the next
    /// vector of four (a body that stored its vectors out of order) are
    /// not these.
    #[test]
    fn the_f64_fill_gives_each_output_its_halves() {
        let half = |h: u64| h as f64 / 4_294_967_296.0;
        for state in [0u64, 0xdead_beef] {
            let stream = SplitMix64::from_state(state);
            for first in [0u64, 1, 15, 16, 1000, u64::MAX - 20] {
                for len in [0usize, 1, 15, 16, 17, 100, 4096] {
                    let want_x: Vec<f64> = (0..len)
                        .map(|k| half(stream.at(first.wrapping_add(k as u64)) >> 32))
                        .collect();
                    let want_y: Vec<f64> = (0..len)
                        .map(|k| half(stream.at(first.wrapping_add(k as u64)) & 0xffff_ffff))
                        .collect();
                    let (mut x, mut y) = (vec![0.0; len], vec![0.0; len]);
                    stream.fill_2d(first, &mut x, &mut y);
                    assert_eq!((&x, &y), (&want_x, &want_y), "{state} {first}, {len}");
                    for isa in Isa::available() {
                        let (mut x, mut y) = (vec![0.0; len], vec![0.0; len]);
                        isa.run(|| stream.fill_2d_in(isa, first, &mut x, &mut y));
                        assert_eq!((&x, &y), (&want_x, &want_y), "{isa} {state} {first}, {len}");
                    }
                }
            }
        }
        let stream = SplitMix64::from_state(1);
        let (mut x, mut y) = ([0.0; 16], [0.0; 16]);
        stream.fill_2d_in(Isa::selected(), 0, &mut x, &mut y);
        let next: Vec<f64> = (4..20).map(|k| half(stream.at(k) >> 32)).collect();
        assert_ne!(x.to_vec(), next);
    }

    #[test]
    fn coordinates_stay_in_the_unit_square_across_the_index_wrap() {
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
            let (px, py) = rng.point_f32((u64::MAX - 10).wrapping_add(k as u64));
            assert_eq!((xf[k], yf[k]), (px, py));
            assert!((0.0..1.0).contains(&xf[k]) && (0.0..1.0).contains(&yf[k]));
        }
    }
}
