//! Sample sequences: where the canonical `u ∈ [0, 1)^d` fed to the warps
//! comes from.
//!
//! Every sequence implements [`SampleSequence`]: position it at a sample
//! index with [`start_sample`](SampleSequence::start_sample) (random access,
//! so a chunk of samples computed on any thread is the same, to the bit,
//! whatever the chunking), then draw that sample's coordinates one or two
//! dimensions at a time. Every sequence is fully determined by its seed.
//!
//! | type | what | follows |
//! |------|------|---------|
//! | [`Independent`] | i.i.d. uniform numbers from PCG32, one stream per sample index | O'Neill 2014 |
//! | [`Stratified`] | jittered, multi-jittered (Latin hypercube) strata for a known sample count | Chiu, Shirley & Wang 1994; Kensler 2013; pbrt-v4 §8.5 |
//! | [`Sobol`] | Owen-scrambled Sobol (0,2)-sequence, 256 dimensions | Sobol 1967; Joe & Kuo 2008; Owen 1995; Laine & Karras 2011; Burley 2020 |
//! | [`SplitMix64`] | i.i.d. 2-D points for whole batches, one counter-based output per point (vectorisable) | Steele, Lea & Flood 2014 |
//!
//! Dimensions are consumed in order: [`next_1d`](SampleSequence::next_1d)
//! takes one, [`next_2d`](SampleSequence::next_2d) and
//! [`next_2d_f32`](SampleSequence::next_2d_f32) take two (the pair `(d, d+1)`).
//!
//! **Batches**: [`fill_2d`](SampleSequence::fill_2d) fills one dimension
//! pair for a run of consecutive samples (a chunk of an estimate) with the
//! values the cursor would give, to the bit. [`Sobol`] and [`Stratified`]
//! implement it with kernels that do per batch what is per batch (keys,
//! tables) and compute the points in blocks of arrays, at a fraction of the
//! cost of reading them one by one (`benches/benches/sequences.rs`).
//!
//! ```
//! use lambert_sampling::sequence::{SampleSequence, Sobol};
//! use lambert_sampling::f64::UniformCone;
//! // Mean of cos θ over a cone of half-angle 60° (uniform in solid angle):
//! // (1 + cos θmax) / 2 = 3/4.
//! let cone = UniformCone::from_cos_theta_max(0.5).unwrap();
//! let mut seq = Sobol::new(7);
//! let mut sum_cos = 0.0_f64;
//! for i in 0..1024 {
//!     seq.start_sample(i);
//!     sum_cos += cone.sample(seq.next_2d()).z;
//! }
//! assert!((sum_cos / 1024.0 - 0.75).abs() < 1e-3);
//! ```

pub mod independent;
pub mod sobol;
mod sobol_batch;
mod sobol_table;
mod splitmix;
mod splitmix_avx2;
pub mod stratified;
mod stratified_batch;
mod stratified_f32;
mod stratified_pow2;
mod stratified_shuffle;
#[cfg(test)]
mod value_stability;

pub use independent::Independent;
pub use sobol::{Scramble, Sobol, SobolLayout};
pub use splitmix::SplitMix64;
pub use stratified::Stratified;

use glam::{DVec2, Vec2};

/// A deterministic, randomly accessible source of points in `[0, 1)^d`.
///
/// A sequence is a cursor `(sample index, dimension)`. After
/// [`start_sample(i)`](SampleSequence::start_sample) the cursor is at
/// dimension 0 of sample `i`; each `next_*` call returns the next one or two
/// coordinates of that sample and advances the dimension. Reading sample `i`
/// gives the same numbers whatever was read before, so samples can be
/// computed in any order, on any thread.
///
/// Values are always in `[0, 1)`: never negative, never 1, never NaN, in both
/// precisions. The f32 values are built from 24 bits (`k · 2^-24`,
/// `k < 2^24`), so they never round up to 1.
pub trait SampleSequence: Clone + Send + Sync {
    /// Moves the cursor to dimension 0 of sample `index`.
    fn start_sample(&mut self, index: u64);

    /// The next coordinate, in `[0, 1)`.
    fn next_1d(&mut self) -> f64;

    /// The next two coordinates, in `[0, 1)²`: the `u` of a 2-D warp.
    fn next_2d(&mut self) -> DVec2;

    /// The next two coordinates in f32, in `[0, 1)²`, each `k · 2^-24` with
    /// `k < 2^24`. Same dimensions, same stratification as
    /// [`next_2d`](SampleSequence::next_2d).
    fn next_2d_f32(&mut self) -> Vec2;

    /// The next coordinate in f32, `k · 2^-24` with `k < 2^24`.
    ///
    /// The default truncates [`next_1d`](SampleSequence::next_1d) to 24 bits.
    fn next_1d_f32(&mut self) -> f32 {
        round_down_24(self.next_1d())
    }

    /// Fills `out[k]` with 2-D request number `request` of sample
    /// `first + k` (indices wrap modulo `2^64`): the value
    /// [`next_2d`](SampleSequence::next_2d) returns after
    /// [`start_sample(first + k)`](SampleSequence::start_sample) and
    /// `request` earlier `next_2d` calls — dimensions
    /// `(2·request, 2·request + 1)` — to the bit. The cursor does not move.
    ///
    /// The default reads the samples one by one; [`Sobol`] and
    /// [`Stratified`] override it with batch kernels that hoist the per-batch
    /// work (hash keys, tables) out of the loop and compute the points in
    /// structure-of-arrays blocks.
    ///
    /// ```
    /// use glam::DVec2;
    /// use lambert_sampling::sequence::{SampleSequence, Sobol};
    /// let seq = Sobol::new(3);
    /// let mut batch = [DVec2::ZERO; 100];
    /// seq.fill_2d(1000, 1, &mut batch);
    /// let mut one = seq.clone();
    /// one.start_sample(1042);
    /// one.next_2d();
    /// assert_eq!(batch[42], one.next_2d());
    /// ```
    fn fill_2d(&self, first: u64, request: u64, out: &mut [DVec2]) {
        let mut s = self.clone();
        for (k, o) in out.iter_mut().enumerate() {
            s.start_sample(first.wrapping_add(k as u64));
            for _ in 0..request {
                s.next_2d();
            }
            *o = s.next_2d();
        }
    }

    /// [`fill_2d`](SampleSequence::fill_2d) into two coordinate arrays,
    /// the structure of arrays the estimator's block kernels read: `x[k]`
    /// and `y[k]` are `out[k].x` and `out[k].y`, to the bit.
    ///
    /// The default goes through [`fill_2d`](SampleSequence::fill_2d) in
    /// blocks of 256; [`Sobol`] and [`Stratified`] write the arrays
    /// directly.
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use glam::DVec2;
    /// use lambert_sampling::sequence::{SampleSequence, Stratified};
    /// let seq = Stratified::new(64, 3).unwrap();
    /// let (mut x, mut y) = ([0.0; 64], [0.0; 64]);
    /// seq.fill_2d_split(0, 1, &mut x, &mut y);
    /// let mut points = [DVec2::ZERO; 64];
    /// seq.fill_2d(0, 1, &mut points);
    /// assert!(points.iter().enumerate().all(|(k, p)| (p.x, p.y) == (x[k], y[k])));
    /// ```
    fn fill_2d_split(&self, first: u64, request: u64, x: &mut [f64], y: &mut [f64]) {
        assert_split_lengths("fill_2d_split", x.len(), y.len());
        let mut block = [DVec2::ZERO; 256];
        for (b, (x, y)) in x.chunks_mut(256).zip(y.chunks_mut(256)).enumerate() {
            let block = &mut block[..x.len()];
            self.fill_2d(first.wrapping_add((b * 256) as u64), request, block);
            for ((p, xk), yk) in block.iter().zip(x).zip(y) {
                (*xk, *yk) = (p.x, p.y);
            }
        }
    }

    /// [`fill_2d_split`](SampleSequence::fill_2d_split) rounded down to 24
    /// bits: `x[k]` is [`round_down_24`] of the f64 `x[k]`, to the bit, so
    /// the f32 points keep the f64 points' strata down to cells of `2^-24`
    /// (the points the estimator's f32 path reads). For [`Sobol`] these
    /// are also the values of [`next_2d_f32`](SampleSequence::next_2d_f32);
    /// [`Independent`]'s `next_2d_f32` draws its f32 values from 32-bit
    /// words instead. [`Stratified`] stores its own f32 coordinates, those
    /// of its `next_2d_f32`, computed in f32 lanes: within `2⁻²²` of the
    /// f64 ones and never beyond their strata's upper edges (module
    /// `stratified`).
    ///
    /// The default rounds [`fill_2d_split`](SampleSequence::fill_2d_split)'s
    /// values in blocks of 256; [`Sobol`] rounds as it stores and
    /// [`Stratified`] computes its f32 values directly, with no f64 arrays
    /// in between.
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use lambert_sampling::sequence::{round_down_24, SampleSequence, Sobol};
    /// let seq = Sobol::new(5);
    /// let (mut x, mut y) = ([0.0; 64], [0.0; 64]);
    /// seq.fill_2d_split(100, 2, &mut x, &mut y);
    /// let (mut x32, mut y32) = ([0.0f32; 64], [0.0f32; 64]);
    /// seq.fill_2d_split_f32(100, 2, &mut x32, &mut y32);
    /// assert!((0..64).all(|k| x32[k] == round_down_24(x[k]) && y32[k] == round_down_24(y[k])));
    /// ```
    fn fill_2d_split_f32(&self, first: u64, request: u64, x: &mut [f32], y: &mut [f32]) {
        assert_split_lengths("fill_2d_split_f32", x.len(), y.len());
        let (mut bx, mut by) = ([0.0; 256], [0.0; 256]);
        for (b, (x, y)) in x.chunks_mut(256).zip(y.chunks_mut(256)).enumerate() {
            let (bx, by) = (&mut bx[..x.len()], &mut by[..x.len()]);
            self.fill_2d_split(first.wrapping_add((b * 256) as u64), request, bx, by);
            for ((xk, yk), (&px, &py)) in x.iter_mut().zip(y).zip(bx.iter().zip(&*by)) {
                (*xk, *yk) = (round_down_24(px), round_down_24(py));
            }
        }
    }

    /// Requests `request` and `request + 1` of samples `first + k` (a
    /// multiple-importance sample's two points) into four arrays:
    /// `[x0, y0]` as [`fill_2d_split`](SampleSequence::fill_2d_split) of
    /// `request` gives them and `[x1, y1]` as it gives `request + 1`, to
    /// the bit.
    ///
    /// The default makes the two calls; [`Sobol`] overrides it to compute
    /// the work the two pairs share once. Inlined, as the fills it calls,
    /// so that they run in the caller's instruction set (see
    /// [`crate::isa::Isa::run`]).
    ///
    /// # Panics
    /// If the four arrays differ in length.
    ///
    /// ```
    /// use lambert_sampling::sequence::{SampleSequence, Sobol};
    /// let seq = Sobol::new(3);
    /// let mut two = [[0.0; 300]; 4];
    /// let [a, b, c, d] = &mut two;
    /// seq.fill_2d_split_two(7, 0, [a, b, c, d]);
    /// let (mut x, mut y) = ([0.0; 300], [0.0; 300]);
    /// seq.fill_2d_split(7, 1, &mut x, &mut y);
    /// assert_eq!((two[2], two[3]), (x, y));
    /// ```
    #[inline(always)]
    fn fill_2d_split_two(&self, first: u64, request: u64, [x0, y0, x1, y1]: [&mut [f64]; 4]) {
        assert_four_lengths(
            "fill_2d_split_two",
            [x0.len(), y0.len(), x1.len(), y1.len()],
        );
        self.fill_2d_split(first, request, x0, y0);
        self.fill_2d_split(first, request + 1, x1, y1);
    }

    /// [`fill_2d_split_two`](SampleSequence::fill_2d_split_two) in f32:
    /// the values of [`fill_2d_split_f32`](SampleSequence::fill_2d_split_f32)
    /// for the two requests, to the bit.
    ///
    /// # Panics
    /// If the four arrays differ in length.
    #[inline(always)]
    fn fill_2d_split_f32_two(&self, first: u64, request: u64, [x0, y0, x1, y1]: [&mut [f32]; 4]) {
        assert_four_lengths(
            "fill_2d_split_f32_two",
            [x0.len(), y0.len(), x1.len(), y1.len()],
        );
        self.fill_2d_split_f32(first, request, x0, y0);
        self.fill_2d_split_f32(first, request + 1, x1, y1);
    }

    /// [`fill_2d`](SampleSequence::fill_2d) in f32: `out[k]` is the value
    /// [`next_2d_f32`](SampleSequence::next_2d_f32) returns for request
    /// `request` of sample `first + k`, to the bit.
    fn fill_2d_f32(&self, first: u64, request: u64, out: &mut [Vec2]) {
        let mut s = self.clone();
        for (k, o) in out.iter_mut().enumerate() {
            s.start_sample(first.wrapping_add(k as u64));
            for _ in 0..request {
                s.next_2d();
            }
            *o = s.next_2d_f32();
        }
    }
}

/// The check every split fill makes: `x` and `y` must have one length.
///
/// # Panics
/// If they differ, naming `method`.
#[inline(always)]
pub(crate) fn assert_split_lengths(method: &str, x: usize, y: usize) {
    assert_eq!(x, y, "{method}: x and y differ in length");
}

/// The panic of the two-request fills when their four arrays differ in
/// length.
pub(crate) fn assert_four_lengths(method: &str, lengths: [usize; 4]) {
    assert!(
        lengths.iter().all(|&l| l == lengths[0]),
        "{method}: the four arrays differ in length ({lengths:?})"
    );
}

/// `2^-32`.
pub(super) const TWO_POW_M32: f64 = 1.0 / 4_294_967_296.0;
/// `2^-53`.
const TWO_POW_M53: f64 = 1.0 / 9_007_199_254_740_992.0;
/// `2^-24`.
const TWO_POW_M24_F32: f32 = 1.0 / 16_777_216.0;

/// `x · 2^-32`: exact, in `[0, 1 − 2^-32]`.
#[inline]
pub(crate) fn u32_to_f64(x: u32) -> f64 {
    f64::from(x) * TWO_POW_M32
}

/// The top 53 bits of `x` times `2^-53`: exact, in `[0, 1 − 2^-53]`.
#[inline]
pub(crate) fn u64_to_f64(x: u64) -> f64 {
    (x >> 11) as f64 * TWO_POW_M53
}

/// The top 24 bits of `x` times `2^-24`: exact, in `[0, 1 − 2^-24]`.
#[inline]
pub(crate) fn u32_to_f32(x: u32) -> f32 {
    (x >> 8) as f32 * TWO_POW_M24_F32
}

/// `x ∈ [0, 1)` rounded down to 24 bits, `⌊x · 2^24⌋ · 2^-24`: exact, and
/// never 1 (rounding to nearest, `x as f32`, gives 1 for `x > 1 − 2^-25`).
/// Inputs outside `[0, 1)` are clamped to `[0, 1 − 2^-24]`.
///
/// Written with `floor` and clamps in f64 rather than a conversion to an
/// integer: Rust's saturating float-to-integer cast has no vector
/// instruction, so a loop of those stays scalar (it was a quarter of an
/// f32 stratified estimate), while this one vectorises. Every step is
/// exact: scaling by a power of two, `floor`, and the final cast of
/// `k · 2^-24` with `k < 2^24`, which f32 represents.
///
/// ```
/// use lambert_sampling::sequence::round_down_24;
/// assert_eq!(round_down_24(0.5), 0.5);
/// assert_eq!(round_down_24(1.0 - 1e-12), 1.0 - 1.0 / 16_777_216.0);
/// assert_eq!(round_down_24(1.5e-8), 0.0);
/// ```
#[inline(always)]
pub fn round_down_24(x: f64) -> f32 {
    const SCALE: f64 = 16_777_216.0;
    ((x * SCALE).floor().clamp(0.0, SCALE - 1.0) * (1.0 / SCALE)) as f32
}

/// The first multiplier of [`mix64`].
pub(crate) const MIX_1: u64 = 0xbf58_476d_1ce4_e5b9;
/// The second multiplier of [`mix64`].
pub(crate) const MIX_2: u64 = 0x94d0_49bb_1331_11eb;
/// The golden-ratio increment γ = ⌊2⁶⁴/φ⌋ (odd) by which SplitMix64
/// steps its state.
pub(crate) const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// The splitmix64 finaliser (Steele, Lea & Flood 2014; constants of
/// Stafford's "Mix13"): a bijection of `u64` with full avalanche.
#[inline]
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(MIX_1);
    z = (z ^ (z >> 27)).wrapping_mul(MIX_2);
    z ^ (z >> 31)
}

/// Hashes two words: `mix64(a + γ·mix64(b + γ))`, γ the golden-ratio increment
/// of splitmix64. Distinct `(a, b)` give unrelated outputs.
#[inline]
pub(crate) fn hash2(a: u64, b: u64) -> u64 {
    mix64(a.wrapping_add(GAMMA.wrapping_mul(mix64(b.wrapping_add(GAMMA)) | 1)))
}

/// Hashes three words.
#[inline]
pub(crate) fn hash3(a: u64, b: u64, c: u64) -> u64 {
    hash2(hash2(a, b), c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_geometry::precision::f64::ONE_MINUS_EPSILON;

    #[test]
    fn conversions_stay_below_one_on_all_ones() {
        assert!(u32_to_f64(u32::MAX) < 1.0);
        assert!(u64_to_f64(u64::MAX) < 1.0);
        assert!(u32_to_f32(u32::MAX) < 1.0);
        assert_eq!(u32_to_f32(u32::MAX), 1.0 - f32::EPSILON / 2.0);
        assert!(round_down_24(ONE_MINUS_EPSILON) < 1.0);
        assert!(round_down_24(1.0) < 1.0);
        // Plain rounding would give 1.0 here: the reason for truncation.
        assert_eq!(ONE_MINUS_EPSILON as f32, 1.0);
        assert_eq!(u32_to_f64(0), 0.0);
        assert_eq!(u32_to_f32(0), 0.0);
        assert_eq!(round_down_24(0.0), 0.0);
        assert_eq!(u32_to_f64(0x8000_0000), 0.5);
    }

    /// The floor form gives the 24-bit truncation `⌊2²⁴x⌋·2⁻²⁴` that an
    /// integer cast gives, on every 32-bit fraction's neighbourhood (each
    /// `u32_to_f64` value and the f64 values one ulp either side, where a
    /// wrong rounding would show) over a stride through `u32`, and on the
    /// ends; and clamps what lies outside `[0, 1)`.
    #[test]
    fn round_down_24_truncates_exactly() {
        let by_cast = |x: f64| ((x * 16_777_216.0) as u32).min((1 << 24) - 1) as f32 / 16_777_216.0;
        for k in (0..=u32::MAX)
            .step_by(9_973)
            .chain([u32::MAX, 255, 256, 257])
        {
            let x = u32_to_f64(k);
            for x in [x, x.next_up(), x.next_down().max(0.0)] {
                assert_eq!(
                    round_down_24(x).to_bits(),
                    by_cast(x).to_bits(),
                    "x = {x:e}"
                );
            }
        }
        assert_eq!(round_down_24(-0.25), 0.0);
        assert_eq!(round_down_24(7.0), 1.0 - 1.0 / 16_777_216.0);
    }

    #[test]
    fn hashes_differ_on_swapped_arguments() {
        assert_ne!(hash2(1, 2), hash2(2, 1));
        assert_ne!(hash3(0, 0, 1), hash3(0, 1, 0));
        assert_ne!(mix64(0), mix64(1));
    }
}
