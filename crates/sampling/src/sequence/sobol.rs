//! Owen-scrambled Sobol points, after Burley 2020.
//!
//! **Sobol points** (Sobol 1967, "On the distribution of points in a cube and
//! the approximate evaluation of integrals"): coordinate `j` of point `i` is
//!
//! ```text
//! x_j(i) = ⨁_{k : bit k of i is 1} v_{j,k}      (XOR of direction numbers, 32-bit fixed point)
//! ```
//!
//! in natural index order (not Gray-code order), so any point is computed
//! directly from its index. Dimension 0 is the van der Corput sequence
//! (`v_{0,k} = 2^-(k+1)`, bit reversal of the index); dimensions 1 … 255 use
//! the direction numbers of Joe & Kuo 2008 ("Constructing Sobol sequences
//! with better two-dimensional projections", file `new-joe-kuo-6.21201`),
//! see `sobol_table.rs`. Dimensions 0 and 1 together form a (0,2)-sequence
//! in base 2: every aligned block of `2^m` consecutive points is a
//! (0,m,2)-net — each elementary interval `2^-k × 2^-(m−k)` holds exactly one
//! point. (The Gray-code order used by Joe & Kuo's own generator visits the
//! same point sets per aligned block, in a different order.)
//!
//! **Scrambling** (Owen 1995, "Randomly permuted (t,m,s)-nets and
//! (t,s)-sequences"): nested uniform scrambling flips digit `b` of a
//! coordinate according to a random bit chosen by the `b` digits before it,
//! which randomises the points while keeping every net property. Two
//! implementations, per dimension with a seed hashed from `(seed, dimension)`:
//! * [`Scramble::FastOwen`] (default): the hash-based permutation of Laine &
//!   Karras 2011 ("Stratified sampling for stochastic transparency"), with the
//!   improved constants of Burley 2020 ("Practical Hash-based Owen
//!   Scrambling", JCGT 9(4), listing 2), applied to the bit-reversed value so
//!   that carries propagate from the leading digit down. 5 integer operations.
//! * [`Scramble::Owen`]: a full nested uniform scramble, one hashed bit per
//!   node of the binary tree (the approach of pbrt-v4's `OwenScrambler`,
//!   §8.7); statistically the reference, ~32 hashes per coordinate.
//!
//! **Index shuffling** (Burley 2020 §4, on by default): the index itself is
//! Owen-scrambled (as a 32-bit binary fraction) with a seed per padding block
//! before the Sobol point is computed. Such a scramble maps every aligned
//! block of `2^m` indices onto another aligned block, so every prefix of
//! `2^m` points is still a (0,m,2)-net, while different seeds give
//! statistically independent sequences.
//!
//! **Layouts** ([`SobolLayout`]): `Global` uses Sobol dimensions `d` in
//! order (dimension `d ≥ 256` reuses table dimension `d mod 256` with an
//! independent index shuffle and scramble per block of 256, so there is no
//! limit); `Padded` gives every 2-D request Sobol dimensions (0, 1) and every
//! 1-D request dimension 0, decorrelated by an independent index shuffle per
//! request (Burley 2020 §4's padding, pbrt-v4's `PaddedSobolSampler`), so
//! every pair is a (0,2)-sequence.
//!
//! **Index range**: 32-bit, `2^32` points per seed. Index `i ≥ 2^32` is point
//! `i mod 2^32` of an independently seeded copy (seed hashed with
//! `⌊i / 2^32⌋`); unscrambled and unshuffled, the sequence simply repeats.
//!
//! **Output**: f64 is `x · 2^-32` for the 32-bit value `x`, or, with
//! [`Sobol::with_random_low_bits`], `x · 2^-32` plus 21 hashed bits below it
//! (53 bits in all); f32 is the top 24 bits, `⌊x / 2^8⌋ · 2^-24`. Both are
//! below 1 for every `x`.
//!
//! **Batches**: [`SampleSequence::fill_2d`] computes a dimension pair for
//! many consecutive indices at once, in the bit-reversed domain where the
//! scramble acts directly, with byte-wise tables of the generator matrices
//! (built once per process; read by nibbles from registers where the
//! process runs AVX-512, and in byte planes, 32 indices at a time, where
//! it runs AVX2) and, for dimension 1 (Pascal's matrix), a five-step
//! butterfly (`sobol_batch.rs`); it is inlined into its caller, so
//! it runs in the caller's vector instruction set. The values are the
//! cursor's, to the bit.
//!
//! Why not the `sobol_burley` crate: it returns only f32, and with index
//! shuffling gives at most `2^16` samples per seed (it keeps 16 direction
//! numbers per dimension). This implementation keeps 32 direction numbers,
//! gives f64 and f32, and `2^32` points per seed.

use super::sobol_batch::{self, burley_hash, CoordinateScramble, PairPlan};
use super::sobol_table::{SOBOL_DIMENSIONS, SOBOL_MATRICES};
use super::{
    assert_four_lengths, assert_split_lengths, hash2, hash3, u32_to_f32, u32_to_f64,
    SampleSequence, TWO_POW_M53,
};
use glam::{DVec2, Vec2};

/// Number of Sobol dimensions with their own direction numbers (256).
pub const SOBOL_TABLE_DIMENSIONS: usize = SOBOL_DIMENSIONS;

/// Tags separating the hashed seeds.
const TAG_SHUFFLE: u64 = 0x0073_6875_6666_6c65; // "shuffle"
const TAG_SCRAMBLE: u64 = 0x7363_7261_6d62_6c65; // "scramble"
const TAG_LOW_BITS: u64 = 0x6c6f_775f_6269_7473; // "low_bits"

/// How the Sobol coordinates are randomised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Scramble {
    /// Plain Sobol points (deterministic; the seed still drives index
    /// shuffling and padding if those are on).
    None,
    /// Hash-based Owen scrambling: Laine–Karras permutation with Burley's
    /// 2020 constants ([`laine_karras_permutation`]).
    #[default]
    FastOwen,
    /// Full nested uniform (Owen) scrambling, one hashed bit per tree node
    /// ([`owen_scramble`]).
    Owen,
}

/// Which Sobol dimensions feed successive requests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SobolLayout {
    /// Dimension `d` of the sequence is Sobol dimension `d` (mod 256): the
    /// classic multi-dimensional Sobol sequence.
    #[default]
    Global,
    /// Every 2-D request is Sobol dimensions (0, 1), every 1-D request Sobol
    /// dimension 0, each request with its own index shuffle and scramble, so
    /// every pair is a scrambled (0,2)-sequence (Burley 2020 §4 padding).
    /// Index shuffling is always on in this layout.
    Padded,
}

/// Owen-scrambled Sobol sequence: random access, deterministic per seed,
/// `2^32` points per seed, f64 and f32 output.
///
/// ```
/// use lambert_sampling::sequence::{SampleSequence, Sobol, SobolLayout};
/// let mut seq = Sobol::new(1).with_layout(SobolLayout::Padded);
/// seq.start_sample(5);
/// let u = seq.next_2d();
/// assert!(u.x >= 0.0 && u.x < 1.0 && u.y >= 0.0 && u.y < 1.0);
/// ```
#[derive(Clone, Debug)]
pub struct Sobol {
    seed: u64,
    scramble: Scramble,
    shuffle: bool,
    low_bits: bool,
    layout: SobolLayout,
    /// Seed of the current block of `2^32` indices.
    block_seed: u64,
    /// Index within the block.
    index: u32,
    dim: u64,
    /// The block whose keys are cached below.
    cached_block: Option<u64>,
    /// hash3(block_seed, slot, TAG) for the first [`KEY_CACHE`] slots: the
    /// shuffle keys and the scramble keys, which depend on the block and the
    /// dimension but not on the index, so they are hashed once per block
    /// instead of once per point (4 hashes per 2-D point saved).
    shuffle_keys: [u64; KEY_CACHE],
    scramble_keys: [u64; KEY_CACHE],
}

/// Dimensions (and shuffle slots) whose hash keys [`Sobol`] caches.
const KEY_CACHE: usize = 16;

impl Sobol {
    /// Owen-scrambled ([`Scramble::FastOwen`]), index-shuffled, `Global`
    /// layout, 32-bit f64 output; positioned at sample 0.
    pub fn new(seed: u64) -> Self {
        let mut s = Self {
            seed,
            scramble: Scramble::FastOwen,
            shuffle: true,
            low_bits: false,
            layout: SobolLayout::Global,
            block_seed: 0,
            index: 0,
            dim: 0,
            cached_block: None,
            shuffle_keys: [0; KEY_CACHE],
            scramble_keys: [0; KEY_CACHE],
        };
        s.start_sample(0);
        s
    }

    /// The plain Sobol sequence: no scrambling, no shuffling, `Global`.
    pub fn unscrambled() -> Self {
        Self::new(0)
            .with_scramble(Scramble::None)
            .with_index_shuffle(false)
    }

    /// Sets the scrambling of the coordinates.
    pub fn with_scramble(mut self, scramble: Scramble) -> Self {
        self.scramble = scramble;
        self
    }

    /// Turns Burley's index shuffling on or off (ignored by
    /// [`SobolLayout::Padded`], which always shuffles).
    pub fn with_index_shuffle(mut self, shuffle: bool) -> Self {
        self.shuffle = shuffle;
        self
    }

    /// Adds 21 hashed random bits below the 32 Sobol bits of f64 output.
    pub fn with_random_low_bits(mut self, low_bits: bool) -> Self {
        self.low_bits = low_bits;
        self
    }

    /// Sets the dimension layout.
    pub fn with_layout(mut self, layout: SobolLayout) -> Self {
        self.layout = layout;
        self
    }

    /// The seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The 32-bit value of coordinate `dim` of point `index`, scrambled and
    /// shuffled as configured, in the `Global` layout (`x / 2^32` is the f64
    /// output without low bits). Random access without moving the cursor.
    pub fn value_u32(&self, index: u64, dim: u64) -> u32 {
        let block_seed = hash2(self.seed, index >> 32);
        let pad = dim / SOBOL_DIMENSIONS as u64;
        let table_dim = (dim % SOBOL_DIMENSIONS as u64) as usize;
        let shuffle = self.shuffle || pad > 0;
        self.point(block_seed, index as u32, table_dim, pad, dim, shuffle)
    }

    /// Coordinate `table_dim` of the Sobol point of index `i`, with the index
    /// shuffled by the key of `shuffle_slot` (if `shuffle`) and the
    /// coordinate scrambled by the key of `scramble_slot`.
    #[inline]
    fn point(
        &self,
        block_seed: u64,
        i: u32,
        table_dim: usize,
        shuffle_slot: u64,
        scramble_slot: u64,
        shuffle: bool,
    ) -> u32 {
        let cached = self.cached_block == Some(block_seed);
        let shuffle_key = |slot: u64| match (cached, usize::try_from(slot)) {
            (true, Ok(k)) if k < KEY_CACHE => self.shuffle_keys[k],
            _ => hash3(block_seed, slot, TAG_SHUFFLE),
        };
        let scramble_key = |slot: u64| match (cached, usize::try_from(slot)) {
            (true, Ok(k)) if k < KEY_CACHE => self.scramble_keys[k],
            _ => hash3(block_seed, slot, TAG_SCRAMBLE),
        };
        let i = if shuffle {
            laine_karras_permutation(i, shuffle_key(shuffle_slot) as u32)
        } else {
            i
        };
        let x = sobol_u32(i, table_dim);
        match self.scramble {
            Scramble::None => x,
            Scramble::FastOwen => laine_karras_permutation(x, scramble_key(scramble_slot) as u32),
            Scramble::Owen => owen_scramble(x, scramble_key(scramble_slot)),
        }
    }

    /// The 32-bit value at the cursor's dimension `dim`, for a 2-D request
    /// starting at `first` (`Padded` groups the pair under one shuffle).
    #[inline]
    fn current_u32(&self, dim: u64, first: u64) -> u32 {
        match self.layout {
            SobolLayout::Global => {
                let pad = dim / SOBOL_DIMENSIONS as u64;
                let table_dim = (dim % SOBOL_DIMENSIONS as u64) as usize;
                let shuffle = self.shuffle || pad > 0;
                self.point(self.block_seed, self.index, table_dim, pad, dim, shuffle)
            }
            SobolLayout::Padded => {
                let table_dim = (dim - first) as usize;
                self.point(self.block_seed, self.index, table_dim, first, dim, true)
            }
        }
    }

    /// f64 from a 32-bit value, with optional hashed low bits.
    #[inline]
    fn to_f64(&self, x: u32, dim: u64) -> f64 {
        if self.low_bits {
            with_low_bits(x, self.block_seed, dim, self.index)
        } else {
            u32_to_f64(x)
        }
    }

    /// What a batch of 2-D request `request` computes in the block of
    /// `2^32` indices with seed `block_seed`: the same shuffle slot, table
    /// dimensions and scramble slots as
    /// [`current_u32`](Self::current_u32) for dimensions `2·request` and
    /// `2·request + 1`.
    fn pair_plan(&self, block_seed: u64, request: u64) -> PairPlan {
        let d = 2 * request;
        let (shuffle_slot, shuffle, first_table_dim) = match self.layout {
            SobolLayout::Global => {
                // d is even, so d and d + 1 share the padding block.
                let pad = d / SOBOL_DIMENSIONS as u64;
                let table_dim = (d % SOBOL_DIMENSIONS as u64) as usize;
                (pad, self.shuffle || pad > 0, table_dim)
            }
            SobolLayout::Padded => (d, true, 0),
        };
        let scramble = |dim: u64| {
            let key = hash3(block_seed, dim, TAG_SCRAMBLE);
            match self.scramble {
                Scramble::None => CoordinateScramble::None,
                Scramble::FastOwen => CoordinateScramble::FastOwen(key as u32),
                Scramble::Owen => CoordinateScramble::Owen(key),
            }
        };
        PairPlan {
            shuffle: shuffle.then(|| hash3(block_seed, shuffle_slot, TAG_SHUFFLE) as u32),
            dims: [first_table_dim, first_table_dim + 1],
            scramble: [scramble(d), scramble(d + 1)],
        }
    }

    /// The f64 values of one axis, dimension `dim`, of a block of samples
    /// `local, local + 1, …` of the block seeded `block_seed`, from their
    /// 32-bit values: the cursor's values, to the bit.
    #[inline(always)]
    fn axis_f64(&self, bits: &[u32], block_seed: u64, dim: u64, local: u32, out: &mut [f64]) {
        if self.low_bits {
            for (k, (o, &x)) in out.iter_mut().zip(bits).enumerate() {
                *o = with_low_bits(x, block_seed, dim, local + k as u32);
            }
        } else {
            for (o, &x) in out.iter_mut().zip(bits) {
                *o = u32_to_f64(x);
            }
        }
    }

    /// The 32-bit values of 2-D request `request` of samples `first …
    /// first + len − 1`, computed by the batch kernel and handed to
    /// `sink(offset, block_seed, first_local, xs, ys)` block by block
    /// (`offset` counts from `first`; `first_local` is the index, within its
    /// block of `2^32`, of `xs[0]`).
    #[inline(always)]
    fn fill_pair_u32<F>(&self, first: u64, request: u64, len: usize, mut sink: F)
    where
        F: FnMut(usize, u64, u32, &[u32], &[u32]),
    {
        self.fill_pairs_u32(
            first,
            [request],
            len,
            #[inline(always)]
            |offset, block_seed, local, [(xs, ys)]| sink(offset, block_seed, local, xs, ys),
        );
    }

    /// [`fill_pair_u32`](Self::fill_pair_u32) for `R` requests of the same
    /// samples at once (`sobol_batch::fill_pairs`, which shares their
    /// index shuffle where their plans have one key).
    #[inline(always)]
    fn fill_pairs_u32<const R: usize, F>(
        &self,
        first: u64,
        requests: [u64; R],
        len: usize,
        mut sink: F,
    ) where
        F: FnMut(usize, u64, u32, [(&[u32], &[u32]); R]),
    {
        let mut done = 0usize;
        while done < len {
            let index = first.wrapping_add(done as u64);
            let block_seed = hash2(self.seed, index >> 32);
            let local = index as u32;
            // Up to the end of this block of 2^32 indices.
            let room = ((1u64 << 32) - u64::from(local)).min((len - done) as u64) as usize;
            let plans = requests.map(|request| self.pair_plan(block_seed, request));
            // Inlined, so the sink runs in the caller's instruction set.
            sobol_batch::fill_pairs(
                plans.each_ref(),
                local,
                room,
                #[inline(always)]
                |offset, blocks| sink(done + offset, block_seed, local + offset as u32, blocks),
            );
            done += room;
        }
    }

    /// The two 32-bit values of the next 2-D request; advances the cursor.
    #[inline]
    fn next_pair_u32(&mut self) -> (u32, u32, u64) {
        let d = self.dim;
        let a = self.current_u32(d, d);
        let b = self.current_u32(d + 1, d);
        self.dim += 2;
        (a, b, d)
    }
}

impl SampleSequence for Sobol {
    #[inline]
    fn start_sample(&mut self, index: u64) {
        self.block_seed = hash2(self.seed, index >> 32);
        self.index = index as u32;
        self.dim = 0;
        if self.cached_block != Some(self.block_seed) {
            for k in 0..KEY_CACHE {
                self.shuffle_keys[k] = hash3(self.block_seed, k as u64, TAG_SHUFFLE);
                self.scramble_keys[k] = hash3(self.block_seed, k as u64, TAG_SCRAMBLE);
            }
            self.cached_block = Some(self.block_seed);
        }
    }

    #[inline]
    fn next_1d(&mut self) -> f64 {
        let d = self.dim;
        let x = self.current_u32(d, d);
        self.dim += 1;
        self.to_f64(x, d)
    }

    #[inline]
    fn next_2d(&mut self) -> DVec2 {
        let (a, b, d) = self.next_pair_u32();
        DVec2::new(self.to_f64(a, d), self.to_f64(b, d + 1))
    }

    #[inline]
    fn next_2d_f32(&mut self) -> Vec2 {
        let (a, b, _) = self.next_pair_u32();
        Vec2::new(u32_to_f32(a), u32_to_f32(b))
    }

    #[inline]
    fn next_1d_f32(&mut self) -> f32 {
        let d = self.dim;
        let x = self.current_u32(d, d);
        self.dim += 1;
        u32_to_f32(x)
    }

    /// The batch kernel of `sobol_batch.rs`: the same values as the cursor,
    /// to the bit. Inlined, so it runs in the caller's instruction set.
    #[inline(always)]
    fn fill_2d(&self, first: u64, request: u64, out: &mut [DVec2]) {
        let d = 2 * request;
        self.fill_pair_u32(
            first,
            request,
            out.len(),
            |offset, block_seed, local, xs, ys| {
                let out = &mut out[offset..offset + xs.len()];
                if self.low_bits {
                    for (k, (o, (&x, &y))) in out.iter_mut().zip(xs.iter().zip(ys)).enumerate() {
                        let index = local + k as u32;
                        *o = DVec2::new(
                            with_low_bits(x, block_seed, d, index),
                            with_low_bits(y, block_seed, d + 1, index),
                        );
                    }
                } else {
                    for (o, (&x, &y)) in out.iter_mut().zip(xs.iter().zip(ys)) {
                        *o = DVec2::new(u32_to_f64(x), u32_to_f64(y));
                    }
                }
            },
        );
    }

    /// The batch kernel of [`fill_2d`](SampleSequence::fill_2d), written
    /// to two arrays.
    #[inline(always)]
    fn fill_2d_split(&self, first: u64, request: u64, x: &mut [f64], y: &mut [f64]) {
        assert_split_lengths("fill_2d_split", x.len(), y.len());
        let d = 2 * request;
        self.fill_pair_u32(
            first,
            request,
            x.len(),
            #[inline(always)]
            |offset, block_seed, local, xs, ys| {
                let len = xs.len();
                self.axis_f64(xs, block_seed, d, local, &mut x[offset..offset + len]);
                self.axis_f64(ys, block_seed, d + 1, local, &mut y[offset..offset + len]);
            },
        );
    }

    /// Both requests in one pass of the batch kernel, which computes the
    /// shuffled indices once where the two share their shuffle (the
    /// global layout below dimension 256; the padded layout shuffles each
    /// pair by its own key).
    #[inline(always)]
    fn fill_2d_split_two(&self, first: u64, request: u64, [x0, y0, x1, y1]: [&mut [f64]; 4]) {
        assert_four_lengths(
            "fill_2d_split_two",
            [x0.len(), y0.len(), x1.len(), y1.len()],
        );
        let d = 2 * request;
        self.fill_pairs_u32(
            first,
            [request, request + 1],
            x0.len(),
            #[inline(always)]
            |offset, block_seed, local, [(xs0, ys0), (xs1, ys1)]| {
                let len = xs0.len();
                let range = offset..offset + len;
                self.axis_f64(xs0, block_seed, d, local, &mut x0[range.clone()]);
                self.axis_f64(ys0, block_seed, d + 1, local, &mut y0[range.clone()]);
                self.axis_f64(xs1, block_seed, d + 2, local, &mut x1[range.clone()]);
                self.axis_f64(ys1, block_seed, d + 3, local, &mut y1[range]);
            },
        );
    }

    /// [`fill_2d_split_two`](SampleSequence::fill_2d_split_two) in f32,
    /// as [`fill_2d_split_f32`](SampleSequence::fill_2d_split_f32) makes
    /// its values.
    #[inline(always)]
    fn fill_2d_split_f32_two(&self, first: u64, request: u64, [x0, y0, x1, y1]: [&mut [f32]; 4]) {
        assert_four_lengths(
            "fill_2d_split_f32_two",
            [x0.len(), y0.len(), x1.len(), y1.len()],
        );
        self.fill_pairs_u32(
            first,
            [request, request + 1],
            x0.len(),
            #[inline(always)]
            |offset, _, _, blocks| {
                let len = blocks[0].0.len();
                let outputs = [&mut *x0, &mut *y0, &mut *x1, &mut *y1];
                let inputs = [blocks[0].0, blocks[0].1, blocks[1].0, blocks[1].1];
                for (out, input) in outputs.into_iter().zip(inputs) {
                    for (o, &v) in out[offset..offset + len].iter_mut().zip(input) {
                        *o = u32_to_f32(v);
                    }
                }
            },
        );
    }

    /// The batch kernel's 32-bit values straight to f32 (their top 24
    /// bits): the hashed low bits of
    /// [`with_random_low_bits`](Sobol::with_random_low_bits) lie below
    /// `2^-32`, so rounding the f64 values down to 24 bits gives the same.
    #[inline(always)]
    fn fill_2d_split_f32(&self, first: u64, request: u64, x: &mut [f32], y: &mut [f32]) {
        assert_split_lengths("fill_2d_split_f32", x.len(), y.len());
        self.fill_pair_u32(
            first,
            request,
            x.len(),
            #[inline(always)]
            |offset, _, _, xs, ys| {
                let len = xs.len();
                for (o, &v) in x[offset..offset + len].iter_mut().zip(xs) {
                    *o = u32_to_f32(v);
                }
                for (o, &v) in y[offset..offset + len].iter_mut().zip(ys) {
                    *o = u32_to_f32(v);
                }
            },
        );
    }

    fn fill_2d_f32(&self, first: u64, request: u64, out: &mut [Vec2]) {
        self.fill_pair_u32(first, request, out.len(), |offset, _, _, xs, ys| {
            let out = &mut out[offset..offset + xs.len()];
            for (o, (&x, &y)) in out.iter_mut().zip(xs.iter().zip(ys)) {
                *o = Vec2::new(u32_to_f32(x), u32_to_f32(y));
            }
        });
    }
}

/// `x · 2^-32` plus 21 hashed bits below it (53 bits in all), the hash
/// drawn from `(block seed, dimension, index within the block)`.
#[inline]
fn with_low_bits(x: u32, block_seed: u64, dim: u64, index: u32) -> f64 {
    let r = hash3(block_seed ^ TAG_LOW_BITS, dim, u64::from(index));
    ((u64::from(x) << 21) | (r >> 43)) as f64 * TWO_POW_M53
}

/// Coordinate `dim` of the unscrambled Sobol point of index `index`, as a
/// 32-bit binary fraction (`0x8000_0000` is 1/2), natural index order.
///
/// # Panics
/// If `dim ≥ 256` ([`SOBOL_TABLE_DIMENSIONS`]).
#[inline]
pub fn sobol_u32(index: u32, dim: usize) -> u32 {
    let v = &SOBOL_MATRICES[dim];
    let mut x = 0;
    let mut i = index;
    while i != 0 {
        x ^= v[i.trailing_zeros() as usize];
        i &= i - 1;
    }
    x
}

/// Hash-based nested scramble of a 32-bit binary fraction `x` (bit 31 is the
/// leading digit): Laine & Karras 2011, constants of Burley 2020 (listing 2),
/// applied to the bit-reversed value so that each digit is permuted
/// according to the digits before it only.
///
/// A bijection of `u32` for every `seed`; it maps every aligned interval of
/// `2^k` values onto an aligned interval of `2^k` values, so it preserves
/// every (t,m,s)-net property, and is used both to scramble coordinates and
/// to shuffle indices.
#[inline]
pub fn laine_karras_permutation(x: u32, seed: u32) -> u32 {
    burley_hash(x.reverse_bits(), seed).reverse_bits()
}

/// Full nested uniform scramble (Owen 1995) of a 32-bit binary fraction:
/// digit `b` (bit `31 − b`) is flipped iff a hash of `(seed, b, the first b
/// digits of x)` is odd — an independent random flip for every node of the
/// binary tree.
#[inline]
pub fn owen_scramble(x: u32, seed: u64) -> u32 {
    let mut out = x;
    for b in 0..32u32 {
        // The node: the first b digits, tagged by a leading 1 so that
        // prefixes of different lengths differ.
        let prefix = if b == 0 { 0 } else { u64::from(x >> (32 - b)) };
        let node = (1u64 << b) | prefix;
        out ^= ((hash2(seed, node) >> 63) as u32) << (31 - b);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts, for every elementary interval shape `2^-k × 2^-(m−k)`, the
    /// points of `pts` (2^m of them) per interval; true iff each holds one.
    fn is_02_net(pts: &[(u32, u32)], m: u32) -> bool {
        assert_eq!(pts.len(), 1 << m);
        for k in 0..=m {
            let mut count = vec![0u32; 1 << m];
            for &(x, y) in pts {
                let cx = (u64::from(x) >> (32 - k)) as usize;
                let cy = (u64::from(y) >> (32 - (m - k))) as usize;
                count[(cx << (m - k)) | cy] += 1;
            }
            if count.iter().any(|&c| c != 1) {
                return false;
            }
        }
        true
    }

    #[test]
    fn direction_numbers_are_triangular_with_unit_diagonal() {
        // Column k is m_k · 2^(32−k−1) with m_k odd, m_k < 2^(k+1): its lowest
        // set bit is bit 31 − k, so the top-left m × m block of every matrix is
        // triangular with a unit diagonal and every dimension is a (0,1)-sequence.
        for (j, v) in SOBOL_MATRICES.iter().enumerate() {
            for (k, &vk) in v.iter().enumerate() {
                assert_eq!(vk.trailing_zeros() as usize, 31 - k, "dim {j} col {k}");
            }
        }
    }

    #[test]
    fn first_points_match_known_values() {
        let f = |i: u32, d: usize| u32_to_f64(sobol_u32(i, d));
        // Natural order: dimension 0 is van der Corput.
        let d0: Vec<f64> = (0..8).map(|i| f(i, 0)).collect();
        assert_eq!(d0, [0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875]);
        let d1: Vec<f64> = (0..4).map(|i| f(i, 1)).collect();
        assert_eq!(d1, [0.0, 0.5, 0.75, 0.25]);
        // Gray-code order (Joe & Kuo's generator, SciPy): the published values.
        let g = |i: u32, d: usize| f(i ^ (i >> 1), d);
        let gray: Vec<[f64; 3]> = (0..8).map(|i| [g(i, 0), g(i, 1), g(i, 2)]).collect();
        assert_eq!(
            gray,
            [
                [0.0, 0.0, 0.0],
                [0.5, 0.5, 0.5],
                [0.75, 0.25, 0.25],
                [0.25, 0.75, 0.75],
                [0.375, 0.375, 0.625],
                [0.875, 0.875, 0.125],
                [0.625, 0.125, 0.875],
                [0.125, 0.625, 0.375],
            ]
        );
        // The sequence's cursor reads the same values.
        let mut s = Sobol::unscrambled();
        s.start_sample(3);
        assert_eq!(s.next_2d(), DVec2::new(0.75, 0.25));
        assert_eq!(s.next_1d(), f(3, 2));
    }

    fn net_points(seq: &Sobol, start: u64, m: u32, d0: u64, d1: u64) -> Vec<(u32, u32)> {
        (start..start + (1 << m))
            .map(|i| (seq.value_u32(i, d0), seq.value_u32(i, d1)))
            .collect()
    }

    #[test]
    fn first_two_dimensions_are_02_nets_unscrambled_and_scrambled() {
        let mut seqs = vec![Sobol::unscrambled()];
        for seed in [0u64, 1, 0x1234_5678_9abc, u64::MAX] {
            for scramble in [Scramble::FastOwen, Scramble::Owen, Scramble::None] {
                for shuffle in [false, true] {
                    seqs.push(
                        Sobol::new(seed)
                            .with_scramble(scramble)
                            .with_index_shuffle(shuffle),
                    );
                }
            }
        }
        for seq in &seqs {
            for m in 0..=12 {
                let first = net_points(seq, 0, m, 0, 1);
                assert!(is_02_net(&first, m), "{seq:?} m {m} first block");
                let second = net_points(seq, 1 << m, m, 0, 1);
                assert!(is_02_net(&second, m), "{seq:?} m {m} second block");
            }
        }
    }

    #[test]
    fn net_test_rejects_a_non_net() {
        // Negative control: dimensions (0, 0) are not a (0,2)-net for m ≥ 1,
        // and nor are Independent-like hashed points.
        let seq = Sobol::unscrambled();
        assert!(!is_02_net(&net_points(&seq, 0, 4, 0, 0), 4));
        let pts: Vec<(u32, u32)> = (0..16u64)
            .map(|i| (hash2(1, i) as u32, hash2(2, i) as u32))
            .collect();
        assert!(!is_02_net(&pts, 4));
    }

    #[test]
    fn every_dimension_is_a_01_sequence_scrambled() {
        let seq = Sobol::new(99);
        for dim in [0u64, 1, 2, 3, 17, 100, 255, 256, 300] {
            for m in [1u32, 5, 10] {
                let mut count = vec![0u32; 1 << m];
                for i in 0..(1u64 << m) {
                    count[(seq.value_u32(i, dim) >> (32 - m)) as usize] += 1;
                }
                assert!(count.iter().all(|&c| c == 1), "dim {dim} m {m}");
            }
        }
    }

    #[test]
    fn padded_layout_makes_every_pair_a_02_net() {
        let mut seq = Sobol::new(4).with_layout(SobolLayout::Padded);
        for m in [4u32, 8, 10] {
            let mut pairs = vec![Vec::new(); 4];
            for i in 0..(1u64 << m) {
                seq.start_sample(i);
                for p in pairs.iter_mut() {
                    let d = seq.dim;
                    p.push((seq.current_u32(d, d), seq.current_u32(d + 1, d)));
                    seq.next_2d();
                }
            }
            for p in &pairs {
                assert!(is_02_net(p, m));
            }
            assert_ne!(pairs[0], pairs[1]);
        }
    }

    #[test]
    fn same_seed_same_points_different_seed_different() {
        for layout in [SobolLayout::Global, SobolLayout::Padded] {
            let read = |seed: u64| {
                let mut s = Sobol::new(seed).with_layout(layout);
                (0..256u64)
                    .map(|i| {
                        s.start_sample(i);
                        (s.next_2d(), s.next_1d(), s.next_2d_f32())
                    })
                    .collect::<Vec<_>>()
            };
            assert_eq!(read(10), read(10));
            let (a, b) = (read(10), read(11));
            let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
            assert!(differ > 250);
        }
    }

    #[test]
    fn random_access_and_value_u32_agree_with_the_cursor() {
        let mut s = Sobol::new(3).with_random_low_bits(true);
        let plain = Sobol::new(3);
        for i in [0u64, 1, 1000, (1 << 32) - 1, 1 << 32, u64::MAX] {
            s.start_sample(i);
            let u = s.next_2d();
            let v = s.next_1d();
            for (d, x) in [(0u64, u.x), (1, u.y), (2, v)] {
                let hi = plain.value_u32(i, d);
                // Low bits add less than 2^-32.
                assert!(x >= u32_to_f64(hi) && x < u32_to_f64(hi) + 1.0 / 4_294_967_296.0);
            }
        }
        // Blocks of 2^32 indices are independent copies when scrambled.
        assert_ne!(plain.value_u32(5, 0), plain.value_u32(5 + (1 << 32), 0));
        // ... and repeat when not.
        let u = Sobol::unscrambled();
        assert_eq!(u.value_u32(5, 0), u.value_u32(5 + (1 << 32), 0));
    }

    #[test]
    fn scrambles_are_bijections_preserving_aligned_blocks() {
        for seed in [0u32, 1, 0xffff_ffff, 0x8765_4321] {
            // Every 2^4-aligned block of inputs maps into one aligned block.
            for block in 0..64u32 {
                let base = block.wrapping_mul(0x0123_4567) & !0xf;
                let outs: Vec<u32> = (0..16)
                    .map(|j| laine_karras_permutation(base + j, seed))
                    .collect();
                let hi = outs[0] >> 4;
                assert!(outs.iter().all(|&o| o >> 4 == hi));
                let mut low: Vec<u32> = outs.iter().map(|o| o & 0xf).collect();
                low.sort_unstable();
                assert_eq!(low, (0..16).collect::<Vec<_>>());
                let outs: Vec<u32> = (0..16)
                    .map(|j| owen_scramble(base + j, u64::from(seed)))
                    .collect();
                let hi = outs[0] >> 4;
                assert!(outs.iter().all(|&o| o >> 4 == hi));
            }
        }
    }

    #[test]
    fn f32_and_f64_never_reach_one() {
        // Adversarial: the all-ones value.
        assert!(u32_to_f32(u32::MAX) < 1.0);
        assert!(u32_to_f64(u32::MAX) < 1.0);
        let mut s = Sobol::new(0).with_random_low_bits(true);
        for i in 0..(1u64 << 16) {
            s.start_sample(i);
            let u = s.next_2d();
            let w = s.next_1d_f32();
            s.start_sample(i);
            let v = s.next_2d_f32();
            assert!(u.x < 1.0 && u.y < 1.0 && v.x < 1.0 && v.y < 1.0 && w < 1.0);
        }
        // Unscrambled point with the all-ones index: value has all bits set
        // in dimension 0 (van der Corput of 2^32 − 1).
        let mut u = Sobol::unscrambled();
        u.start_sample(u64::from(u32::MAX));
        assert_eq!(u.value_u32(u64::from(u32::MAX), 0), u32::MAX);
        let v = u.next_2d_f32();
        assert!(v.x < 1.0 && v.y < 1.0);
        u.start_sample(u64::from(u32::MAX));
        assert!(u.next_1d() < 1.0);
        assert!(u.next_1d_f32() < 1.0);
    }

    #[test]
    fn scrambled_mean_converges_fast() {
        // Integrating x·y over [0,1)² with 4096 scrambled points: error far
        // below the Monte Carlo σ ≈ 0.22/64 ≈ 3.4e-3.
        let mut s = Sobol::new(77);
        let mut sum = 0.0;
        for i in 0..4096 {
            s.start_sample(i);
            let u = s.next_2d();
            sum += u.x * u.y;
        }
        assert!((sum / 4096.0 - 0.25).abs() < 2e-4);
    }
}
