//! Stratified points of many consecutive samples at once: the kernel behind
//! [`Stratified`](super::Stratified)'s batch fills, the definitions both
//! paths share, and the keyed permutation of the later dimension pairs.
//!
//! A point of a later pair costs, besides its cell:
//!
//! * two column and row shifts `s_c`, `t_r` and the jitters of both axes:
//!   four 32-bit hashes ([`hash_u32`]), which the compiler runs sixteen
//!   lanes to an AVX-512 register;
//! * two range reductions by multiplication ([`reduce_u32`], in 32-bit
//!   lanes when the grid's sides are below 2¹⁶: [`reduce_u32_narrow`]), two
//!   rotations ([`rotate`]) and two multiplications by `1/N` (in f32,
//!   two fused multiply-adds by its two f32 parts: `stratified_f32.rs`);
//! * the spread sub-strata `r·g_y mod ny` and `c·g_x mod nx`, computed in
//!   32-bit lanes with the quotient estimated in f32 ([`Spread`]).
//!
//! The first pair goes column by column ([`Grid::first_pair_cell`]), so
//! its points come in runs of one column ([`fill_first_pair`]): the
//! column's shift, spread and `c·ny` once per run, and per point the
//! jitters, the row's shift (read from a table hashed once per row when
//! the batch covers a whole column, hashed per point otherwise), the row's
//! spread (a table read by contiguous loads, or the run's first spread
//! plus a tabulated step), two rotations and the two coordinates.
//!
//! The cells of later pairs come, on grids of at least 16 columns, at
//! most `nx²/4` and 2¹⁵ rows, whose `N` is not a power of two, from the
//! Feistel rounds of `stratified_shuffle.rs`: one division for a block's
//! first position, then round by round over the block in 16-bit lanes. On the other grids they come
//! from a keyed permutation walked in blocks: one walk step for a whole
//! block (branch-free, structure of arrays), and nothing more when `N` is a
//! power of two (the step is then a permutation of `0..N`). Otherwise the
//! lanes that fell outside `0..N` (fewer than half, since `2^w < 2N`) are
//! stepped again by a whole-block round that keeps the lanes already
//! inside (a select, which vectorises), and the few still outside after
//! it are listed without branches and stepped in rounds, each round
//! listing again those still outside, so that no branch depends on a
//! random walk length; `cell mod nx`
//! and `cell / nx` use a precomputed reciprocal ([`FastDiv`], Lemire, Kaser
//! & Kurz 2019, "Faster remainder by direct computation"). Every value is
//! the point-by-point value to the bit.
//!
//! When `N` is a power of two, [`fill_pass`] hands the pass to the kernel
//! of `stratified_pow2.rs` instead: the same values, with masks and shifts
//! in place of the tables, carries and reciprocals above.

use super::stratified_f32::F32Coordinate;
use super::stratified_pow2::{fixed_sum, PowerOfTwoGrid};
use super::stratified_shuffle::{shuffles, CellShuffle};
use super::{hash2, mix64, TWO_POW_M32};
use lambert_geometry::precision::f64::ONE_MINUS_EPSILON;

/// Samples per block of the structure-of-arrays loops.
pub(super) const BLOCK: usize = 256;

/// `0x2c1b_3c6d`, the fixed odd multiplier of every permutation round.
const ROUND_MULTIPLIER: u32 = 0x2c1b_3c6d;

/// The keys of the two rounds of one permutation of [`Domain::permute`]: per round
/// `[xor key, odd multiplier, addend, combined odd multiplier]`, derived
/// from the 64-bit hashes `mix64(key)` and `mix64(key ⊕ γ)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PermuteKeys([[u32; 4]; 2]);

impl PermuteKeys {
    /// The round keys of the permutation keyed by `key`.
    #[inline]
    pub(super) fn new(key: u64) -> Self {
        let round = |kr: u64| {
            [
                kr as u32,
                (kr >> 32) as u32 | 1,
                (kr >> 40) as u32,
                ROUND_MULTIPLIER.wrapping_mul((kr >> 16) as u32 | 1),
            ]
        };
        PermuteKeys([round(mix64(key)), round(mix64(key ^ 0x9e37_79b9_7f4a_7c15))])
    }
}

/// The domain `0..n` of a permutation: `n`, the mask of `w` bits (`2^w` the
/// smallest power of two `≥ n`) and the shift `⌈w/2⌉`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Domain {
    n: u32,
    mask: u32,
    half: u32,
}

impl Domain {
    /// The domain `0..n`, `n ≥ 1`.
    #[inline]
    pub(super) fn new(n: u32) -> Self {
        debug_assert!(n >= 1);
        let w = 32 - n.saturating_sub(1).leading_zeros();
        let mask = if w == 32 { u32::MAX } else { (1u32 << w) - 1 };
        Domain {
            n,
            mask,
            half: w.div_ceil(2),
        }
    }

    /// Whole-block rounds of [`Domain::permute_block`]'s walk before the
    /// lanes still outside are listed. One: after the first step fewer than
    /// half the lanes are outside and after one more round fewer than a
    /// quarter, so a further whole-block round steps mostly lanes already
    /// inside; listing the few left and stepping only them measured ~4 %
    /// faster per sample than four rounds (stratified MIS on the sphere
    /// light, f32 and f64, 5·10^7 samples), with the same values.
    const VECTOR_ROUNDS: usize = 1;

    /// Whether `n = 2^w`: then the walk's bijection of `0..2^w` is already
    /// a permutation of `0..n`, and no value ever falls outside (every `n`
    /// of a power-of-two sample count, as in the study's rows).
    #[inline(always)]
    fn is_whole(self) -> bool {
        u64::from(self.mask) + 1 == u64::from(self.n)
    }

    /// One step of the cycle walk: two rounds of invertible operations on
    /// `w`-bit integers (a bijection of `0..2^w`).
    #[inline(always)]
    pub(super) fn step(self, mut x: u32, keys: &PermuteKeys) -> u32 {
        for [xor, mul, add, mul2] in keys.0 {
            // (x ⊕ k) & mask = x ⊕ (k & mask) for x < 2^w, and masking
            // commutes with the multiplications modulo 2^32.
            x = (x ^ xor).wrapping_mul(mul) & self.mask;
            x ^= x >> self.half;
            x = x.wrapping_add(add).wrapping_mul(mul2) & self.mask;
            x ^= x >> self.half;
            x ^= x >> 1;
        }
        x
    }

    /// Element `i` of the permutation of `0..n` keyed by `keys`: steps until
    /// the value falls in `0..n` (cycle walking, Black & Rogaway 2002).
    #[inline]
    pub(super) fn permute(self, i: u32, keys: &PermuteKeys) -> u32 {
        debug_assert!(i < self.n);
        if self.n <= 1 {
            return 0;
        }
        self.walk_on(self.step(i, keys), keys)
    }

    /// Continues a cycle walk from `x`, a value after at least one step.
    #[inline]
    fn walk_on(self, mut x: u32, keys: &PermuteKeys) -> u32 {
        while x >= self.n {
            x = self.step(x, keys);
        }
        x
    }

    /// `x[k] ← π(x[k])` for every `k`, with the keys of lane `k` given by
    /// `keys(k)`: one step on every lane, then the walk of the lanes still
    /// outside `0..n`, found without branches.
    #[inline(always)]
    fn permute_block<'k>(self, x: &mut [u32], keys: impl Fn(usize) -> &'k PermuteKeys) {
        if self.n <= 1 {
            x.fill(0);
            return;
        }
        for (k, x) in x.iter_mut().enumerate() {
            *x = self.step(*x, keys(k));
        }
        if self.is_whole() {
            // Every step lands in 0..2^w = 0..n: no lane needs a walk, and
            // listing them (a serial loop of stores at a running index)
            // would cost as much as the step itself.
            return;
        }
        // Rounds over the whole block, stepping only the lanes still
        // outside 0..n (a select, so they vectorise): each round leaves
        // outside a fraction below ½ (`2^w < 2N`) of those it found, so
        // after them few lanes walk on, and sometimes none.
        for _ in 0..Self::VECTOR_ROUNDS {
            for (k, x) in x.iter_mut().enumerate() {
                let stepped = self.step(*x, keys(k));
                *x = if *x >= self.n { stepped } else { *x };
            }
        }
        if !x.iter().fold(false, |out, &v| out | (v >= self.n)) {
            return;
        }
        // The lanes still outside 0..n, listed without branches; each round
        // steps every listed lane once and lists again those still outside,
        // so no branch depends on a lane's value (the walk lengths are
        // random, and a branch on them would be mispredicted often).
        let mut pending = [0u8; BLOCK];
        let mut count = 0;
        for (k, &v) in x.iter().enumerate() {
            pending[count] = k as u8;
            count += usize::from(v >= self.n);
        }
        while count > 0 {
            let mut still = 0;
            for j in 0..count {
                let k = usize::from(pending[j]);
                let v = self.step(x[k], keys(k));
                x[k] = v;
                pending[still] = k as u8;
                still += usize::from(v >= self.n);
            }
            count = still;
        }
    }
}

/// Exact `x / d` and `x mod d` for a fixed 32-bit divisor by one 64 × 64-bit
/// multiplication (Lemire, Kaser & Kurz 2019: with `M = ⌊(2^64 − 1)/d⌋ + 1`,
/// `x / d = ⌊M·x / 2^64⌋` for all 32-bit `x`).
#[derive(Clone, Copy, Debug)]
pub(super) struct FastDiv {
    d: u32,
    m: u64,
}

impl FastDiv {
    /// Division by `d ≥ 1`.
    pub(super) fn new(d: u32) -> Self {
        debug_assert!(d >= 1);
        // d = 1 would need M = 2^64; it is handled apart (m = 0).
        let m = if d == 1 {
            0
        } else {
            u64::MAX / u64::from(d) + 1
        };
        FastDiv { d, m }
    }

    /// `(x / d, x mod d)`.
    #[inline(always)]
    pub(super) fn div_rem(self, x: u32) -> (u32, u32) {
        let q = if self.d == 1 {
            x
        } else {
            // ⌊M·x / 2⁶⁴⌋ with M = 2³²·M_hi + M_lo, from 32 × 32-bit
            // products, which vectorise (a 64 × 64 → 128-bit product does
            // not): ⌊(M_hi·x + ⌊M_lo·x / 2³²⌋) / 2³²⌋, the same value, and
            // M_hi·x + ⌊M_lo·x / 2³²⌋ < (2³² − 1)² + 2³² < 2⁶⁴.
            let x = u64::from(x);
            let (high, low) = (self.m >> 32, self.m & 0xffff_ffff);
            ((high * x + ((low * x) >> 32)) >> 32) as u32
        };
        (q, x - q * self.d)
    }
}

/// SplitMix64's increment γ = 2⁶⁴/φ (odd).
const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// Output `j` of a SplitMix64 stream seeded by `key`: `mix64(key + γ·(j + 1))`
/// (Steele, Lea & Flood 2014). Distinct `j` give distinct outputs (`mix64`
/// is a bijection and `γ` is odd), one multiply-xorshift finaliser each.
#[inline(always)]
pub(super) fn stream_bits(key: u64, j: u64) -> u64 {
    mix64(key.wrapping_add(GAMMA.wrapping_mul(j.wrapping_add(1))))
}

/// `⌊h · m / 2⁶⁴⌋ ∈ 0..m`: a 64-bit hash reduced to `0..m` by a
/// multiplication instead of a division (Lemire 2019, "Fast random integer
/// generation in an interval"). Each value of `0..m` has probability within
/// `m/2⁶⁴ ≤ 2⁻³²` (relative) of `1/m`. Written with 32 × 32-bit products
/// so that it vectorises: `h·m = hi·m·2³² + lo·m`.
#[inline(always)]
pub(super) fn reduce(h: u64, m: u32) -> u32 {
    let m = u64::from(m);
    let low = (h & 0xffff_ffff) * m;
    let high = (h >> 32) * m;
    ((high + (low >> 32)) >> 32) as u32
}

/// Output `j` of the 32-bit hash stream keyed by `key`: `H(j ⊕ k)`, with
/// `k` the low 32 bits of `key` and `H` the two-round multiply-xorshift
/// hash of lowest measured bias in C. Wellons' search ("Prospecting for
/// Hash Functions", 2018; hash-prospector), a bijection of `u32` with full
/// avalanche. It gives the shifts (of column or row `j`) and the jitters
/// (of position `j`, 32 bits per axis).
///
/// Why 32 bits and not SplitMix64 outputs (which [`stream_bits`] still
/// gives the 1-D coordinates): a shift needs `log₂ √N ≤ 16` bits and a
/// jitter 32, while the 64-bit finaliser's multiplications run eight 64-bit
/// lanes per AVX-512 register at three times the cost of a 32-bit multiply,
/// where these run sixteen; shifts and jitter were half a stratified
/// point's cost.
#[inline(always)]
pub(super) fn hash_u32(key: u64, j: u32) -> u32 {
    let x = hash_u32_high(key, j);
    x ^ (x >> 15)
}

/// [`hash_u32`] without its last step, `x ⊕ (x ≫ 15)`, which changes only
/// the low 17 bits of `x`: the top [`HASH_HIGH_EXACT_BITS`] = 15 bits of
/// the two agree (the rest differ). A kernel that reads no more than the top
/// 15 bits of a hash (the power-of-two kernel's shifts, `h ≫ (32 − log₂ m)`
/// for sides `m ≤ 2¹⁵`, and its f32 jitters, `h ≫ (p + 8)` for `N = 2ᵖ ≥
/// 2⁹`) takes these and skips a shift and an exclusive or per hash, the
/// same values to the bit.
#[inline(always)]
pub(super) fn hash_u32_high(key: u64, j: u32) -> u32 {
    let mut x = j ^ key as u32;
    x ^= x >> 16;
    x = x.wrapping_mul(0x21f0_aaad);
    x ^= x >> 15;
    x.wrapping_mul(0x735a_2d97)
}

/// How many top bits [`hash_u32_high`] shares with [`hash_u32`]: 15.
pub(super) const HASH_HIGH_EXACT_BITS: u32 = 15;

/// [`hash_u32_high`] if `SHORT`, else [`hash_u32`]: the hash a kernel
/// takes when it reads no more than the top [`HASH_HIGH_EXACT_BITS`] bits
/// (`SHORT`), the same values either way.
#[inline(always)]
pub(super) fn hash_u32_cut<const SHORT: bool>(key: u64, j: u32) -> u32 {
    if SHORT {
        hash_u32_high(key, j)
    } else {
        hash_u32(key, j)
    }
}

/// `⌊h · m / 2³²⌋ ∈ 0..m`: [`reduce`] for a 32-bit hash (Lemire 2019),
/// each value of `0..m` within `m/2³²` (relative) of probability `1/m`.
#[inline(always)]
pub(super) fn reduce_u32(h: u32, m: u32) -> u32 {
    ((u64::from(h) * u64::from(m)) >> 32) as u32
}

/// [`reduce_u32`] for `m < 2¹⁶` in 32-bit arithmetic, the same value:
/// with `h = 2¹⁶·a + b`, `⌊h·m/2³²⌋ = ⌊(a·m + ⌊b·m/2¹⁶⌋)/2¹⁶⌋`, and
/// `a·m + ⌊b·m/2¹⁶⌋ ≤ (2¹⁶ − 1)² + 2¹⁶ − 1 < 2³²` does not overflow. Vector
/// units multiply 32-bit lanes at a third of the cost of 64-bit ones (and
/// have no 32-bit high-half multiply), so the batch kernel takes this form
/// whenever the grid's sides allow.
#[inline(always)]
pub(super) fn reduce_u32_narrow(h: u32, m: u32) -> u32 {
    debug_assert!(m < 1 << 16);
    ((h >> 16) * m + (((h & 0xffff) * m) >> 16)) >> 16
}

/// `(x + s) mod m` for `x < m` and `s ≤ m`, without overflow and without a
/// division.
#[inline(always)]
pub(super) fn rotate(x: u32, s: u32, m: u32) -> u32 {
    let room = m - x; // ≥ 1
    if s >= room {
        s - room
    } else {
        x + s
    }
}

/// The unit (an integer coprime to `n`) nearest `n·(√5 − 1)/2`: the
/// multiplier of the spreads ([`Spread`]) and of the first pair's column
/// order. Its multiples modulo `n` are spread as evenly as any (the
/// three-distance theorem; Knuth, TAOCP vol. 3, §6.4, on Fibonacci
/// hashing), so every run of them is spread over `0..n`.
pub(super) fn golden_unit(n: u32) -> u32 {
    if n <= 2 {
        return n - 1; // 0 for n = 1, 1 for n = 2
    }
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let target = (f64::from(n) * 0.618_033_988_749_894_9).round() as i64;
    let n = i64::from(n);
    // Terminates: 1 is a unit, at most n away.
    (0..n)
        .flat_map(|d| [target - d, target + d])
        .find(|&a| a >= 1 && a < n && gcd(a as u64, n as u64) == 1)
        .unwrap_or(1) as u32
}

/// The bijection `x ↦ x·g mod m` of `0..m`, with `g` = [`golden_unit`]`(m)`:
/// consecutive `x` land far apart (about `0.618·m` apart, every run of
/// them spread evenly by the three-distance theorem).
///
/// Tabulated for `m ≤ 2¹⁶` (`m` entries: a stratified sequence of `N`
/// samples builds `√N`-sized tables, and the study builds thousands of
/// short sequences) for the lookups of one point at a time and the first
/// pair's runs of rows (contiguous loads); computed per point beyond.
/// A block of scattered lookups ([`Spread::get_block`]) computes instead,
/// in f32 lanes ([`Spread::compute_narrow`]).
#[derive(Clone, Debug)]
struct Spread {
    m: u32,
    g: u32,
    /// `1/m`, rounded to f32.
    inv_m: f32,
    table: Option<std::sync::Arc<[u32]>>,
}

impl Spread {
    /// Sides up to this are tabulated.
    const TABULATED: u32 = 1 << 16;

    fn new(m: u32) -> Self {
        let g = golden_unit(m);
        let table =
            (m <= Self::TABULATED).then(|| (0..m).map(|x| Self::compute(x, g, m)).collect());
        Spread {
            m,
            g,
            inv_m: 1.0 / m as f32,
            table,
        }
    }

    /// `x·g mod m`, computed.
    #[inline(always)]
    fn compute(x: u32, g: u32, m: u32) -> u32 {
        ((u64::from(x) * u64::from(g)) % u64::from(m)) as u32
    }

    /// `x·g mod m` for `x, g < m ≤ 2¹⁶`, in 32-bit lanes: the product
    /// `x·g < 2³²` is exact in `u32`, and the quotient is estimated in f32
    /// as `fl(fl(x·g)·fl(1/m))`, three roundings of relative error `2⁻²⁴`
    /// each, so within `3·2⁻²⁴·2¹⁶ < 1/2` of `x·g/m < 2¹⁶`: rounded to an
    /// integer, it is the floor or one above. The remainder by that
    /// estimate is then in `[−m, m)`, and one step brings it into `0..m`. The same
    /// value as [`Spread::compute`]; vector units have no integer division
    /// and, before AVX-512, no gathers worth a table lookup (measured on an
    /// AVX2 host, where a block's lookups ran one lane at a time).
    #[inline(always)]
    fn compute_narrow(x: u32, g: u32, m: u32, inv_m: f32) -> u32 {
        // The quotient rounded to an integer by adding 2²³ (its f32 then
        // has the integer in its low mantissa bits): a bit cast where `as`
        // would check for NaN and saturate lane by lane.
        const ROUND: f32 = 8_388_608.0;
        let product = x.wrapping_mul(g);
        let (x_f, g_f) = (x as i32 as f32, g as i32 as f32); // < 2¹⁶: exact
        let quotient = (x_f * g_f * inv_m + ROUND).to_bits() - ROUND.to_bits();
        let rest = product.wrapping_sub(quotient.wrapping_mul(m)) as i32;
        (if rest < 0 { rest + m as i32 } else { rest }) as u32
    }

    /// `x·g mod m` for `x < m`.
    #[inline(always)]
    fn get(&self, x: u32) -> u32 {
        match &self.table {
            // x < m = the table's length: `unwrap_or` is never taken, and
            // unlike indexing it needs no panic path.
            Some(table) => table.get(x as usize).copied().unwrap_or(0),
            None => Self::compute(x, self.g, self.m),
        }
    }

    /// `out[k] = x[k]·g mod m` for every `k`: one branch for the block, then
    /// a loop in vector lanes.
    #[inline(always)]
    fn get_block(&self, x: &[u32], out: &mut [u32]) {
        let (m, g, inv_m) = (self.m, self.g, self.inv_m);
        if m <= Self::TABULATED {
            for (out, &x) in out.iter_mut().zip(x) {
                *out = Self::compute_narrow(x, g, m, inv_m);
            }
        } else {
            for (out, &x) in out.iter_mut().zip(x) {
                *out = Self::compute(x, g, m);
            }
        }
    }
}

/// What a stratified sequence of `N` samples per pass fixes once: the grid,
/// `1/N`, the divisions by `nx` and `ny`, the spreads and the row steps of
/// a block's lanes.
#[derive(Clone, Debug)]
pub(super) struct Grid {
    /// Samples per pass, `N`.
    pub n: u32,
    /// Columns, `nx ≤ ny`.
    pub nx: u32,
    /// Rows, `ny = N / nx`.
    pub ny: u32,
    /// `1/N`, rounded.
    inv_n: f64,
    /// `2²⁴ · inv_n` (exact).
    #[cfg(test)]
    inv_n_24: f64,
    /// `2⁻³² · inv_n` (exact), [`Grid::unit_of_parts`]'s factor.
    inv_n_m32: f64,
    /// `2⁻⁸ · inv_n` (exact), [`Grid::unit_f32_of_wide_parts`]'s factor.
    inv_n_24_m32: f64,
    /// The f32 coordinates of `N ≤ 2²⁴` (`stratified_f32.rs`).
    f32_coordinate: Option<F32Coordinate>,
    /// `cell mod nx` and `cell / nx`.
    by_nx: FastDiv,
    /// `r·g_y mod ny` for every row `r`, with `g_y` = [`golden_unit`]`(ny)`
    /// (empty if `ny > 2¹⁶`: computed per point instead).
    row_spread: Spread,
    /// `c·g_x mod nx` for every column `c`, likewise.
    column_spread: Spread,
    /// `q·g_y mod ny` for `q < BLOCK`: the row spreads of a run of
    /// consecutive rows, added to the spread of its first row.
    row_steps: std::sync::Arc<[u32; BLOCK]>,
    /// `⌊p / ny⌋` and `p mod ny` of a position `p` of the first pair's order.
    by_ny: FastDiv,
    /// The grid's masks and shifts when `N`, `nx` and `ny` are powers of
    /// two: then the batch kernel is `stratified_pow2.rs`'s.
    power_of_two: Option<PowerOfTwoGrid>,
    /// When the later pairs' cells come from the rounds of
    /// `stratified_shuffle.rs` (as [`shuffles`] says) rather than from the
    /// cycle walk of [`Domain`]: `nx` and `ny` in every 16-bit lane of a
    /// block, the sides the rounds read lane by lane
    /// ([`CellShuffle::cells`]).
    shuffle_sides: Option<std::sync::Arc<[[u16; BLOCK]; 2]>>,
}

impl Grid {
    /// The grid of `n ≥ 1` samples as `nx × ny` cells.
    pub(super) fn new(n: u32, nx: u32, ny: u32) -> Self {
        debug_assert_eq!(u64::from(nx) * u64::from(ny), u64::from(n));
        let by_nx = FastDiv::new(nx);
        let (row_spread, column_spread) = (Spread::new(ny), Spread::new(nx));
        let mut row_steps = std::sync::Arc::new([0u32; BLOCK]);
        for (q, step) in std::sync::Arc::make_mut(&mut row_steps)
            .iter_mut()
            .enumerate()
        {
            *step = Spread::compute(q as u32 % ny, row_spread.g, ny);
        }
        Grid {
            n,
            nx,
            ny,
            inv_n: 1.0 / f64::from(n),
            #[cfg(test)]
            inv_n_24: 16_777_216.0 / f64::from(n),
            inv_n_m32: (1.0 / f64::from(n)) * TWO_POW_M32,
            inv_n_24_m32: (1.0 / f64::from(n)) * (1.0 / 256.0),
            f32_coordinate: F32Coordinate::new(n),
            by_nx,
            row_spread,
            column_spread,
            row_steps,
            by_ny: FastDiv::new(ny),
            power_of_two: PowerOfTwoGrid::new(n, nx, ny),
            shuffle_sides: shuffles(n, nx, ny)
                .then(|| std::sync::Arc::new([[nx as u16; BLOCK], [ny as u16; BLOCK]])),
        }
    }

    /// The power-of-two form of the grid, if it has one.
    #[cfg(test)]
    pub(super) fn power_of_two(&self) -> Option<PowerOfTwoGrid> {
        self.power_of_two
    }

    /// The grid without its power-of-two form, so that the general kernel
    /// runs on it (the reference the power-of-two kernel is tested against).
    #[cfg(test)]
    pub(super) fn without_power_of_two(mut self) -> Self {
        self.power_of_two = None;
        self
    }

    /// `(cell mod nx, cell / nx)`: the column and row of a cell.
    #[inline(always)]
    pub(super) fn split(&self, cell: u32) -> (u32, u32) {
        let (r, c) = self.by_nx.div_rem(cell);
        (c, r)
    }

    /// The first pair's column and row of position `i` of a pass:
    /// with `p = (i + b) mod N`, column `⌊p / ny⌋·g_x mod nx` and row
    /// `p mod ny` (column by column, the columns in the golden order).
    #[inline]
    pub(super) fn first_pair_cell(&self, i: u32, offset: u32) -> (u32, u32) {
        let p = ((u64::from(i) + u64::from(offset)) % u64::from(self.n)) as u32;
        let (j, r) = self.by_ny.div_rem(p);
        (self.column_spread.get(j), r)
    }

    /// `(k + ξ)·N⁻¹` from the sum `k + ξ` of a stratum `k < N` and a jitter
    /// `ξ ∈ [0, 1)`, clamped below 1. A multiplication by the rounded
    /// reciprocal, not a division (which costs as much as the rest of the
    /// point on vector units): a point within an ulp of a stratum's edge
    /// may land on the other side of it.
    #[inline(always)]
    pub(super) fn unit(&self, sum: f64) -> f64 {
        // k + ξ ≥ 0, so only the upper end of a clamp to [0, 1) can act.
        (sum * self.inv_n).min(ONE_MINUS_EPSILON)
    }

    /// [`super::round_down_24`]`(`[`Grid::unit`]`(sum))` to the bit, without the f64
    /// value: `min(⌊sum · 2²⁴N⁻¹⌋, 2²⁴ − 1) · 2⁻²⁴`. Scaling by 2²⁴ commutes
    /// with rounding (no subnormals arise), so `sum · (2²⁴ · N⁻¹)` rounds to
    /// `2²⁴` times the f64 product, and the clamp below 1 becomes the `min`.
    #[cfg(test)]
    pub(super) fn unit_f32(&self, sum: f64) -> f32 {
        const TOP: f64 = 16_777_215.0;
        ((sum * self.inv_n_24).floor().min(TOP) * (1.0 / 16_777_216.0)) as f32
    }

    /// [`Grid::unit`]`(k + h·2⁻³²)` to the bit, from the
    /// fixed-point sum `X = k·2³² + h` ([`fixed_sum`]) times `2⁻³²·N⁻¹`.
    /// `X` is the sum times `2³²` and both are rounded once to f64, so
    /// `fl(X) = 2³²·fl(k + h·2⁻³²)`; the product by the reciprocal scaled
    /// by `2⁻³²` (exact) then rounds to the same f64 as the sum's product
    /// by `N⁻¹`. One 64-bit conversion replaces two 32-bit ones, a
    /// multiply and an add.
    #[inline(always)]
    pub(super) fn unit_of_parts(&self, k: u32, h: u32) -> f64 {
        (fixed_sum(k, h) * self.inv_n_m32).min(ONE_MINUS_EPSILON)
    }

    /// The f32 coordinate of stratum `k` with jitter bits `h`: for `N ≤
    /// 2²⁴` the nearest f32 to the coordinate with its jitter cut to
    /// `24 − ⌈log₂ N⌉` bits (`stratified_f32.rs`), and above
    /// [`Grid::unit_f32_of_wide_parts`].
    #[inline(always)]
    pub(super) fn unit_f32_of_parts(&self, k: u32, h: u32) -> f32 {
        match self.f32_coordinate {
            Some(f32_coordinate) => f32_coordinate.unit((k, h)),
            None => self.unit_f32_of_wide_parts(k, h),
        }
    }

    /// For `N > 2²⁴`, where a stratum is narrower than an f32 step near 1:
    /// [`super::round_down_24`]`(`[`Grid::unit_of_parts`]`(k, h))` to the
    /// bit: `min(⌊X · 2⁻³²·2²⁴N⁻¹⌋, 2²⁴ − 1) · 2⁻²⁴`, the product rounded
    /// as in [`Grid::unit_of_parts`] and scaled by 2²⁴ (which commutes
    /// with rounding: no subnormals arise). The floor is an integer of at
    /// most 2²⁴ (`k + h·2⁻³² < N`), exact in f32, so the clamp and the
    /// scale by 2⁻²⁴ run in f32 lanes, sixteen to an AVX-512 register
    /// where the f64 ones run eight.
    #[inline(always)]
    pub(super) fn unit_f32_of_wide_parts(&self, k: u32, h: u32) -> f32 {
        const TOP: f32 = 16_777_215.0;
        let floor = (fixed_sum(k, h) * self.inv_n_24_m32).floor() as f32;
        floor.min(TOP) * (1.0 / 16_777_216.0)
    }

    /// The 2-D point of position `i` of a pass in cell `(c, r)`: column
    /// stratum `c·ny + (r·g_y + s_c) mod ny` and row stratum
    /// `r·nx + (c·g_x + t_r) mod nx`, jittered.
    #[inline(always)]
    pub(super) fn point(&self, keys: &PairKeys, c: u32, r: u32, i: u32) -> glam::DVec2 {
        let [x, y] = self.point_parts(keys, c, r, i);
        glam::DVec2::new(f64::from_parts(self, x), f64::from_parts(self, y))
    }

    /// [`Grid::point`] as f32 coordinates ([`Coordinate`] for f32).
    #[inline]
    pub(super) fn point_f32(&self, keys: &PairKeys, c: u32, r: u32, i: u32) -> glam::Vec2 {
        let [x, y] = self.point_parts(keys, c, r, i);
        let coordinate = |parts| match self.power_of_two {
            Some(power_of_two) => power_of_two.unit_f32(parts),
            None => f32::from_parts(self, parts),
        };
        glam::Vec2::new(coordinate(x), coordinate(y))
    }

    /// The strata and jitter bits `(k, h)` of [`Grid::point`]'s two
    /// coordinates.
    #[inline(always)]
    pub(super) fn point_parts(&self, keys: &PairKeys, c: u32, r: u32, i: u32) -> [(u32, u32); 2] {
        let spread = [self.column_spread.get(c), self.row_spread.get(r)];
        self.spread_parts(keys, [c, r], spread, i, reduce_u32, hash_u32)
    }

    /// The strata `k` and jitter bits `h` (the coordinate is
    /// `(k + h·2⁻³²)/N`) of [`Grid::point`]'s two coordinates, given the
    /// spread column and row, `c·g_x mod nx` and `r·g_y mod ny`. The
    /// jitters are hashed by `jitter_hash`: [`hash_u32`], or
    /// [`hash_u32_high`] where the caller reads no more than its top
    /// [`HASH_HIGH_EXACT_BITS`] bits.
    #[inline(always)]
    fn spread_parts(
        &self,
        keys: &PairKeys,
        [c, r]: [u32; 2],
        [column_spread, row_spread]: [u32; 2],
        i: u32,
        reduce: impl Fn(u32, u32) -> u32,
        jitter_hash: impl Fn(u64, u32) -> u32,
    ) -> [(u32, u32); 2] {
        let [kx, ky] = self.spread_strata(keys, [c, r], [column_spread, row_spread], reduce);
        // 32 hashed bits per axis, the two halves of the jitter key: a
        // resolution of 2⁻³²/N, finer than the 2⁻³² of a Sobol point.
        let (high, low) = (
            jitter_hash(keys.jitter, i),
            jitter_hash(keys.jitter >> 32, i),
        );
        [(kx, high), (ky, low)]
    }
}

impl Grid {
    /// The strata `[k_x, k_y]` of [`Grid::spread_parts`]: the column's and
    /// the row's shifts, hashed and reduced by `reduce`, applied to the
    /// spread row and column.
    #[inline(always)]
    fn spread_strata(
        &self,
        keys: &PairKeys,
        [c, r]: [u32; 2],
        [column_spread, row_spread]: [u32; 2],
        reduce: impl Fn(u32, u32) -> u32,
    ) -> [u32; 2] {
        let column = ColumnParts::new(self, keys, c, column_spread, &reduce);
        let t = reduce(hash_u32(keys.tau, r), self.nx);
        column.strata(self, r, t, row_spread)
    }
}

/// Tags separating the keys of one pass and dimension.
const TAG_CELL: u64 = 0x6365_6c6c; // "cell"
const TAG_SIGMA: u64 = 0x0073_6967_6d61; // "sigma"
const TAG_TAU: u64 = 0x0074_6175; // "tau"
const TAG_JITTER: u64 = 0x6a69_7474_6572; // "jitter"

/// The keys of one pass and dimension `d`, all hashed from
/// `h = hash2(pass seed, d)`.
#[derive(Clone, Copy, Debug)]
pub(super) struct PairKeys {
    /// The cell permutation of dimensions `d > 0`, keyed by `hash2(h, "cell")`.
    pub cell: PermuteKeys,
    /// The cell order of dimensions `d > 0` on the grids that shuffle
    /// (`stratified_shuffle.rs`), keyed by the same hash.
    pub shuffle: CellShuffle,
    /// The first pair's offset `b = reduce(hash2(h, "cell"), N)`.
    pub offset: u32,
    /// Column shifts `s_c`: [`hash_u32`] of `c` keyed `hash2(h, "sigma")`.
    pub sigma: u64,
    /// Row shifts `t_r`: [`hash_u32`] of `r` keyed `hash2(h, "tau")`.
    pub tau: u64,
    /// Jitter of position `i`: [`hash_u32`] of `i` keyed by the low (x) and
    /// high (y) halves of `hash2(h, "jitter")`; 1-D coordinates take output
    /// `i` of the SplitMix64 stream [`stream_bits`] keyed by all of it.
    pub jitter: u64,
}

impl PairKeys {
    /// The keys of dimension `dim` of the pass seeded `pass_seed`.
    #[inline]
    pub(super) fn new(grid: &Grid, pass_seed: u64, dim: u64) -> Self {
        let h = hash2(pass_seed, dim);
        let cell = hash2(h, TAG_CELL);
        PairKeys {
            cell: PermuteKeys::new(cell),
            shuffle: CellShuffle::new(cell),
            offset: reduce(cell, grid.n),
            sigma: hash2(h, TAG_SIGMA),
            tau: hash2(h, TAG_TAU),
            jitter: hash2(h, TAG_JITTER),
        }
    }
}

/// The cell of position `i` of a pass in dimension `dim`: the ordered cell
/// for `dim = 0`, otherwise the shuffled one (`stratified_shuffle.rs`) or
/// the keyed permutation's, as the grid says. The point-by-point
/// definition the batch kernel reproduces.
#[inline]
pub(super) fn cell_of(grid: &Grid, keys: &PairKeys, dim: u64, i: u32) -> u32 {
    if dim == 0 {
        let (c, r) = grid.first_pair_cell(i, keys.offset);
        r * grid.nx + c
    } else if grid.shuffle_sides.is_some() {
        let (a, b) = grid.by_ny.div_rem(i);
        let [c, r] = keys.shuffle.cell([a, b], [grid.nx, grid.ny]);
        r * grid.nx + c
    } else {
        Domain::new(grid.n).permute(i, &keys.cell)
    }
}

/// A coordinate the batch kernel stores, from its stratum `k` and jitter
/// bits `h`: f64, `(k + h·2⁻³²)·N⁻¹` ([`Grid::unit`]); or f32, for `N ≤
/// 2²⁴` the nearest f32 to that value with its jitter cut to what an f32
/// shows (`stratified_f32.rs`), above it the f64 value rounded down to 24
/// bits ([`Grid::unit_f32_of_wide_parts`]), except on power-of-two grids,
/// whose f32 coordinate is the exact one rounded down
/// (`stratified_pow2.rs`: the same as `stratified_f32.rs`'s for `N ≤
/// 2²⁴`).
pub(super) trait Coordinate: Sized {
    /// The coordinate on a grid that is not a power of two.
    fn from_parts(grid: &Grid, parts: (u32, u32)) -> Self;

    /// The coordinate on a power-of-two grid.
    fn from_power_of_two(grid: &Grid, power_of_two: PowerOfTwoGrid, parts: (u32, u32)) -> Self;

    /// How many top bits of the jitter `h` [`Coordinate::from_power_of_two`]
    /// reads (the power-of-two kernel hashes no more of them than it must).
    fn power_of_two_jitter_bits(power_of_two: PowerOfTwoGrid) -> u32;

    /// [`fill_pass`] on a grid that is not a power of two: the general
    /// kernel, [`fill_general`], with the coordinate's form chosen once
    /// for the pass (a choice per point keeps the loop from vectorising).
    fn fill_general(
        grid: &Grid,
        keys: &PairKeys,
        dim: u64,
        first: u32,
        x: &mut [Self],
        y: &mut [Self],
    );
}

impl Coordinate for f64 {
    #[inline(always)]
    fn from_parts(grid: &Grid, (k, h): (u32, u32)) -> f64 {
        grid.unit_of_parts(k, h)
    }

    #[inline(always)]
    fn from_power_of_two(grid: &Grid, _: PowerOfTwoGrid, parts: (u32, u32)) -> f64 {
        f64::from_parts(grid, parts)
    }

    /// All 32: the f64 sum `k·2³² + h` keeps every jitter bit for `N ≤ 2²¹`.
    #[inline(always)]
    fn power_of_two_jitter_bits(_: PowerOfTwoGrid) -> u32 {
        32
    }

    #[inline(always)]
    fn fill_general(
        grid: &Grid,
        keys: &PairKeys,
        dim: u64,
        first: u32,
        x: &mut [f64],
        y: &mut [f64],
    ) {
        fill_general(grid, keys, dim, first, x, y, 32, |(k, h)| {
            grid.unit_of_parts(k, h)
        });
    }
}

impl Coordinate for f32 {
    #[inline(always)]
    fn from_parts(grid: &Grid, (k, h): (u32, u32)) -> f32 {
        grid.unit_f32_of_parts(k, h)
    }

    #[inline(always)]
    fn from_power_of_two(_: &Grid, power_of_two: PowerOfTwoGrid, parts: (u32, u32)) -> f32 {
        power_of_two.unit_f32(parts)
    }

    #[inline(always)]
    fn power_of_two_jitter_bits(power_of_two: PowerOfTwoGrid) -> u32 {
        power_of_two.f32_jitter_bits()
    }

    #[inline(always)]
    fn fill_general(
        grid: &Grid,
        keys: &PairKeys,
        dim: u64,
        first: u32,
        x: &mut [f32],
        y: &mut [f32],
    ) {
        match grid.f32_coordinate {
            Some(f32_coordinate) => {
                let bits = f32_coordinate.jitter_bits();
                fill_general(grid, keys, dim, first, x, y, bits, |parts| {
                    f32_coordinate.unit(parts)
                });
            }
            None => fill_general(grid, keys, dim, first, x, y, 32, |(k, h)| {
                grid.unit_f32_of_wide_parts(k, h)
            }),
        }
    }
}

/// The 2-D points of positions `first … first + len − 1` of one pass (all
/// `< N`) in dimensions `(dim, dim + 1)`, each coordinate made from its
/// stratum and jitter bits by [`Coordinate`] and written to `x[k]`, `y[k]`
/// for `k < len = x.len()`; power-of-two grids take the kernel of
/// `stratified_pow2.rs`. Inlined into the caller's instruction set.
#[inline(always)]
pub(super) fn fill_pass<T: Coordinate>(
    grid: &Grid,
    keys: &PairKeys,
    dim: u64,
    first: u32,
    x: &mut [T],
    y: &mut [T],
) {
    if let Some(power_of_two) = grid.power_of_two {
        let jitter_bits = T::power_of_two_jitter_bits(power_of_two);
        power_of_two.fill_pass(keys, dim, first, x, y, jitter_bits, |parts| {
            T::from_power_of_two(grid, power_of_two, parts)
        });
        return;
    }
    T::fill_general(grid, keys, dim, first, x, y);
}

/// [`fill_pass`]'s general kernel (any `N`), each coordinate stored as
/// `store((k, h))`, which reads no more than the top `jitter_bits` bits of
/// `h`: where those are at most [`HASH_HIGH_EXACT_BITS`], the jitters'
/// hashes skip their last step ([`hash_u32_high`]), the same values.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fill_general<T>(
    grid: &Grid,
    keys: &PairKeys,
    dim: u64,
    first: u32,
    x: &mut [T],
    y: &mut [T],
    jitter_bits: u32,
    store: impl Fn((u32, u32)) -> T + Copy,
) {
    if jitter_bits <= HASH_HIGH_EXACT_BITS {
        fill_general_with::<T, true>(grid, keys, dim, first, x, y, store);
    } else {
        fill_general_with::<T, false>(grid, keys, dim, first, x, y, store);
    }
}

/// [`fill_general`] with the jitters' hashes cut short or whole, as
/// `SHORT_JITTER` says.
#[inline(always)]
fn fill_general_with<T, const SHORT_JITTER: bool>(
    grid: &Grid,
    keys: &PairKeys,
    dim: u64,
    first: u32,
    x: &mut [T],
    y: &mut [T],
    store: impl Fn((u32, u32)) -> T + Copy,
) {
    let len = x.len();
    debug_assert_eq!(len, y.len());
    let (n, nx, ny) = (grid.n, grid.nx, grid.ny);
    debug_assert!(u64::from(first) + len as u64 <= u64::from(n));
    if dim == 0 {
        let jitter_hash = hash_u32_cut::<SHORT_JITTER>;
        if nx < 1 << 16 && ny < 1 << 16 {
            fill_first_pair(
                grid,
                keys,
                first,
                x,
                y,
                reduce_u32_narrow,
                jitter_hash,
                store,
            );
        } else {
            fill_first_pair(grid, keys, first, x, y, reduce_u32, jitter_hash, store);
        }
        return;
    }
    let cells = Domain::new(n);
    let mut c = [0u32; BLOCK];
    let mut r = [0u32; BLOCK];
    let mut spread_c = [0u32; BLOCK];
    let mut spread_r = [0u32; BLOCK];
    let mut column16 = [0u16; BLOCK];
    let mut row16 = [0u16; BLOCK];
    for start in (0..len).step_by(BLOCK) {
        let m = BLOCK.min(len - start);
        let base = first + start as u32;
        if let Some(sides) = grid.shuffle_sides.as_deref() {
            // Sides of at most 2¹⁵: the rounds run in 16-bit lanes.
            let (a, b) = (&mut column16[..m], &mut row16[..m]);
            if ny as usize >= BLOCK {
                // Consecutive positions: one division for the block, and
                // at most one step to the next column in it.
                let (a0, b0) = grid.by_ny.div_rem(base);
                for k in 0..m {
                    let row = b0 + k as u32;
                    let next = row >= ny;
                    a[k] = (a0 + u32::from(next)) as u16;
                    b[k] = if next { row - ny } else { row } as u16;
                }
            } else {
                for k in 0..m {
                    let (column, row) = grid.by_ny.div_rem(base + k as u32);
                    (a[k], b[k]) = (column as u16, row as u16);
                }
            }
            let [nx_lanes, ny_lanes] = sides;
            keys.shuffle.cells(a, b, [&nx_lanes[..m], &ny_lanes[..m]]);
            for k in 0..m {
                (c[k], r[k]) = (u32::from(a[k]), u32::from(b[k]));
            }
        } else {
            let cell = &mut c[..m];
            for (k, x) in cell.iter_mut().enumerate() {
                *x = base + k as u32;
            }
            cells.permute_block(cell, |_| &keys.cell);
            for k in 0..m {
                (c[k], r[k]) = grid.split(c[k]);
            }
        }
        grid.column_spread.get_block(&c[..m], &mut spread_c[..m]);
        grid.row_spread.get_block(&r[..m], &mut spread_r[..m]);
        let (x, y) = (&mut x[start..start + m], &mut y[start..start + m]);
        let cells = [&mut c[..m], &mut r[..m]];
        let spreads = [&mut spread_c[..m], &mut spread_r[..m]];
        // The same shifts either way (`reduce_u32_narrow`); the narrow form
        // vectorises better.
        let forms = (hash_u32_cut::<SHORT_JITTER>, store);
        if nx < 1 << 16 && ny < 1 << 16 {
            block_points(
                grid,
                keys,
                cells,
                spreads,
                base,
                x,
                y,
                reduce_u32_narrow,
                forms,
            );
        } else {
            block_points(grid, keys, cells, spreads, base, x, y, reduce_u32, forms);
        }
    }
}

/// The most rows whose shifts [`fill_first_pair`] tabulates per call.
const ROW_SHIFT_TABLE: usize = 4096;

/// What one column `c` fixes for the points in it: `c·ny`, the column's
/// shift `s_c` and its spread `c·g_x mod nx`.
#[derive(Clone, Copy)]
struct ColumnParts {
    start: u32,
    shift: u32,
    spread: u32,
}

impl ColumnParts {
    /// Column `c`'s parts, given its spread, its shift reduced by `reduce`.
    #[inline(always)]
    fn new(
        grid: &Grid,
        keys: &PairKeys,
        c: u32,
        spread: u32,
        reduce: impl Fn(u32, u32) -> u32,
    ) -> Self {
        ColumnParts {
            start: c * grid.ny,
            shift: reduce(hash_u32(keys.sigma, c), grid.ny),
            spread,
        }
    }

    /// The strata `(k_x, k_y)` of the point in row `r` of this column,
    /// given the row's shift `t_r` and spread `r·g_y mod ny`: column
    /// stratum `c·ny + (r·g_y + s_c) mod ny`, row stratum `r·nx + (c·g_x +
    /// t_r) mod nx`.
    #[inline(always)]
    fn strata(self, grid: &Grid, r: u32, t: u32, spread_r: u32) -> [u32; 2] {
        [
            self.start + rotate(spread_r, self.shift, grid.ny),
            r * grid.nx + rotate(self.spread, t, grid.nx),
        ]
    }
}

/// The first pair's points of positions `first … first + len − 1` of a
/// pass: column by column ([`Grid::first_pair_cell`]), so that within a
/// run of one column `c·ny`, `s_c` and `c·g_x mod nx` are computed once
/// and the lanes differ only in the row, `r₀ + q`. When the batch covers
/// at least a whole column (`ny ≤ len`, up to [`ROW_SHIFT_TABLE`] rows),
/// the row shifts `t_r` are hashed once per row into a table and read,
/// with the rows' spreads, by contiguous loads; otherwise each lane
/// hashes its row's shift and adds a tabulated step to the run's first
/// spread.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn fill_first_pair<T>(
    grid: &Grid,
    keys: &PairKeys,
    first: u32,
    x: &mut [T],
    y: &mut [T],
    reduce: impl Fn(u32, u32) -> u32 + Copy,
    jitter_hash: impl Fn(u64, u32) -> u32 + Copy,
    store: impl Fn((u32, u32)) -> T + Copy,
) {
    let (nx, ny) = (grid.nx, grid.ny);
    let forms = (reduce, jitter_hash, store);
    match &grid.row_spread.table {
        // The table is zeroed per call, so short batches (as many short
        // passes give) hash per lane instead.
        Some(spreads)
            if ny as usize <= x.len().min(ROW_SHIFT_TABLE) && x.len() >= ROW_SHIFT_TABLE / 4 =>
        {
            let mut shifts = [0u32; ROW_SHIFT_TABLE];
            let shifts = &mut shifts[..ny as usize];
            for (r, t) in shifts.iter_mut().enumerate() {
                *t = reduce(hash_u32(keys.tau, r as u32), nx);
            }
            first_pair_runs(grid, keys, first, x, y, Some((shifts, spreads)), forms);
        }
        _ => first_pair_runs(grid, keys, first, x, y, None, forms),
    }
}

/// [`fill_first_pair`] with the rows' shifts and spreads tabulated
/// (`tables`) or not.
#[inline(always)]
#[allow(clippy::type_complexity)]
fn first_pair_runs<T>(
    grid: &Grid,
    keys: &PairKeys,
    first: u32,
    x: &mut [T],
    y: &mut [T],
    tables: Option<(&[u32], &[u32])>,
    (reduce, jitter_hash, store): (
        impl Fn(u32, u32) -> u32 + Copy,
        impl Fn(u64, u32) -> u32 + Copy,
        impl Fn((u32, u32)) -> T + Copy,
    ),
) {
    let (n, nx, ny) = (grid.n, grid.nx, grid.ny);
    let len = x.len();
    let (jitter_x, jitter_y) = (keys.jitter, keys.jitter >> 32);
    let mut p = ((u64::from(first) + u64::from(keys.offset)) % u64::from(n)) as u32;
    let mut done = 0usize;
    while done < len {
        let (j, r0) = grid.by_ny.div_rem(p);
        let c = grid.column_spread.get(j);
        let column = ColumnParts::new(grid, keys, c, grid.column_spread.get(c), reduce);
        let i0 = first + done as u32;
        // Up to the column's end or the batch's (without tables, at most
        // a block: the steps' table is that long).
        let mut run = ((ny - r0) as usize).min(len - done);
        if tables.is_none() {
            run = run.min(BLOCK);
        }
        if core::mem::size_of::<T>() <= 4 {
            // f32 coordinates: one loop, whose vectors hold as many lanes
            // as the 32-bit work's (staged as below, an f32 first-pair
            // point took 1.28 ns against 0.99 on an AVX2 host).
            let (xs, ys) = (&mut x[done..done + run], &mut y[done..done + run]);
            let points = xs.iter_mut().zip(ys.iter_mut());
            let point = |q: usize, [kx, ky]: [u32; 2]| {
                let i = i0 + q as u32;
                [
                    store((kx, jitter_hash(jitter_x, i))),
                    store((ky, jitter_hash(jitter_y, i))),
                ]
            };
            match tables {
                Some((shifts, spreads)) => {
                    let rows = r0 as usize..r0 as usize + run;
                    let rows = shifts[rows.clone()].iter().zip(&spreads[rows]);
                    for (q, ((x, y), (&t, &spread_r))) in points.zip(rows).enumerate() {
                        let r = r0 + q as u32;
                        [*x, *y] = point(q, column.strata(grid, r, t, spread_r));
                    }
                }
                None => {
                    let spread_r0 = grid.row_spread.get(r0);
                    for (q, ((x, y), &step)) in points.zip(&grid.row_steps[..run]).enumerate() {
                        let r = r0 + q as u32;
                        let t = reduce(hash_u32(keys.tau, r), nx);
                        let spread_r = rotate(spread_r0, step, ny);
                        [*x, *y] = point(q, column.strata(grid, r, t, spread_r));
                    }
                }
            }
        } else {
            // In stages of [`BLOCK`] points: the strata and jitter bits first,
            // in 32-bit arrays, then the coordinates. In one loop the compiler
            // ran the 32-bit work at the coordinates' width, four lanes to an
            // AVX2 register in f64 (the power-of-two kernel's reason too).
            let mut stage = 0;
            while stage < run {
                let m = BLOCK.min(run - stage);
                let mut parts = [[0u32; BLOCK]; 4];
                let [kx, ky, hx, hy] = &mut parts;
                let (kx, ky) = (&mut kx[..m], &mut ky[..m]);
                let r1 = r0 + stage as u32;
                match tables {
                    Some((shifts, spreads)) => {
                        let rows = r1 as usize..r1 as usize + m;
                        let rows = shifts[rows.clone()].iter().zip(&spreads[rows]);
                        for (q, ((kx, ky), (&t, &spread_r))) in
                            kx.iter_mut().zip(ky.iter_mut()).zip(rows).enumerate()
                        {
                            let r = r1 + q as u32;
                            [*kx, *ky] = column.strata(grid, r, t, spread_r);
                        }
                    }
                    None => {
                        let spread_r0 = grid.row_spread.get(r0);
                        let steps = &grid.row_steps[stage..stage + m];
                        for (q, ((kx, ky), &step)) in
                            kx.iter_mut().zip(ky.iter_mut()).zip(steps).enumerate()
                        {
                            let r = r1 + q as u32;
                            let t = reduce(hash_u32(keys.tau, r), nx);
                            let spread_r = rotate(spread_r0, step, ny);
                            [*kx, *ky] = column.strata(grid, r, t, spread_r);
                        }
                    }
                }
                let i1 = i0 + stage as u32;
                for (q, (hx, hy)) in hx[..m].iter_mut().zip(hy[..m].iter_mut()).enumerate() {
                    let i = i1 + q as u32;
                    (*hx, *hy) = (jitter_hash(jitter_x, i), jitter_hash(jitter_y, i));
                }
                let [kx, ky, hx, hy] = &parts;
                let xs = x[done + stage..done + stage + m].iter_mut();
                let ys = y[done + stage..done + stage + m].iter_mut();
                for (q, (x, y)) in xs.zip(ys).enumerate() {
                    (*x, *y) = (store((kx[q], hx[q])), store((ky[q], hy[q])));
                }
                stage += m;
            }
        }
        done += run;
        p += run as u32;
        if p == n {
            p = 0;
        }
    }
}

/// The points of one block of [`fill_pass`] from their cells and spreads
/// (both overwritten),
/// with the shifts reduced by `reduce`, the jitters hashed by
/// `jitter_hash` and the coordinates made by `store` (one instantiation
/// per form). The spreads are overwritten by the strata, rather than two
/// more arrays zeroed per block: 2 KiB of `memset` every 256 points, the
/// largest part of the 2–4 % that zeroing took in the profile of an f32
/// MIS estimate on stratified points (a later pair's f32 point at `N =
/// 10⁶` 3.43 → 3.39 ns on an AVX2 host).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn block_points<T>(
    grid: &Grid,
    keys: &PairKeys,
    [c, r]: [&mut [u32]; 2],
    [spread_c, spread_r]: [&mut [u32]; 2],
    base: u32,
    x: &mut [T],
    y: &mut [T],
    reduce: impl Fn(u32, u32) -> u32 + Copy,
    (jitter_hash, store): (impl Fn(u64, u32) -> u32 + Copy, impl Fn((u32, u32)) -> T),
) {
    // Two loops, strata then jitters and coordinates, each a short chain
    // of dependent operations per lane that the processor overlaps across
    // lanes (one loop of both waited on their latency on an AVX2 host);
    // the values are [`Grid::spread_parts`]'s.
    let m = x.len();
    for k in 0..m {
        let cell = [c[k], r[k]];
        let spread = [spread_c[k], spread_r[k]];
        [spread_c[k], spread_r[k]] = grid.spread_strata(keys, cell, spread, reduce);
    }
    let (strata_x, strata_y) = (spread_c, spread_r);
    let (jitter_x, jitter_y) = (keys.jitter, keys.jitter >> 32);
    if core::mem::size_of::<T>() <= 4 {
        for k in 0..m {
            let i = base + k as u32;
            x[k] = store((strata_x[k], jitter_hash(jitter_x, i)));
            y[k] = store((strata_y[k], jitter_hash(jitter_y, i)));
        }
    } else {
        // f64 coordinates: the jitters first, into the cells' arrays (read
        // no more), so that their 32-bit hashes run eight lanes to an AVX2
        // register instead of the four an f64 vector holds (as the first
        // pair's kernel does; a later pair's f64 point at N = 1.6·10⁷
        // 3.54 → 2.99 ns on the Zen 2 host).
        for (k, (hx, hy)) in c.iter_mut().zip(r.iter_mut()).enumerate() {
            let i = base + k as u32;
            (*hx, *hy) = (jitter_hash(jitter_x, i), jitter_hash(jitter_y, i));
        }
        for k in 0..m {
            x[k] = store((strata_x[k], c[k]));
            y[k] = store((strata_y[k], r[k]));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sequence::{SampleSequence, Stratified};

    /// Exact against `/` and `%` on the divisors of the grids that matter
    /// (1, primes, squares, the estimate's 1250, the extremes) and on
    /// dividends at and around multiples of them and at the ends of `u32`.
    #[test]
    fn fast_division_is_exact() {
        let divisors = [
            1u32,
            2,
            3,
            7,
            13,
            100,
            1250,
            2500,
            65_535,
            65_537,
            (1 << 31) - 1,
            1 << 31,
            u32::MAX - 1,
            u32::MAX,
        ];
        for d in divisors {
            let f = FastDiv::new(d);
            let mut xs = vec![0u32, 1, 2, u32::MAX, u32::MAX - 1, 1 << 31];
            for q in [1u64, 2, 3, 1000, 123_457] {
                let at = q * u64::from(d);
                for x in [at.saturating_sub(1), at, at + 1] {
                    if let Ok(x) = u32::try_from(x) {
                        xs.push(x);
                    }
                }
            }
            let mut h = 0x1234_5678_u64;
            for _ in 0..10_000 {
                h = crate::sequence::mix64(h);
                xs.push(h as u32);
            }
            for x in xs {
                assert_eq!(f.div_rem(x), (x / d, x % d), "{x} / {d}");
            }
        }
    }

    /// The spreads computed in f32 lanes are `x·g mod m`, on every `x` of
    /// sides short and long, odd and even, prime, just below and at `2¹⁶`
    /// (where `x·g` nears `2³²` and the f32 quotient is least precise).
    #[test]
    fn narrow_spreads_are_exact() {
        for m in [
            1u32, 2, 3, 25, 40, 1000, 1250, 2500, 4099, 65_521, 65_535, 65_536,
        ] {
            let spread = Spread::new(m);
            let (g, inv_m) = (spread.g, spread.inv_m);
            for x in 0..m {
                let want = Spread::compute(x, g, m);
                assert_eq!(
                    Spread::compute_narrow(x, g, m, inv_m),
                    want,
                    "{x}·{g} mod {m}"
                );
            }
        }
    }

    /// Batches that start anywhere in a pass and cross block boundaries
    /// give the cursor's values, on both kinds of cell order (the first
    /// pair's and the keyed permutation's).
    /// N = 10 000 (100 × 100) shuffles its later pairs' cells
    /// (`stratified_shuffle.rs`); N = 16·65 537 (a side above 2¹⁵, far
    /// longer than wide) and N = 12 (3 × 4, too few columns to shuffle)
    /// walk their permutation; N = 2¹⁴ (a whole power
    /// of two) never walks, and skips the listing of walking lanes. For N = 10 000
    /// (100 rows) the batches of 4 096 and of a whole pass take the first
    /// pair's tabulated row shifts, the shorter ones hash them per point;
    /// the whole pass crosses the point where its column order wraps.
    #[test]
    fn batches_give_the_cursor_values_from_any_start() {
        for n in [10_000u32, 16 * 65_537, 12, 1 << 14] {
            batches_match_the_cursor(n);
        }
    }

    fn batches_match_the_cursor(n: u32) {
        let seq = Stratified::new(n, 3).unwrap();
        let mut cursor = seq.clone();
        let n = u64::from(n);
        for request in [0u64, 1, 2] {
            let whole = n as usize;
            for (start, len) in [
                (0u64, 7usize),
                (250, 300),
                (n.saturating_sub(10), 10),
                (n.saturating_sub(1_000), 1_000),
                (1_234, 4_096),
                (0, whole),
            ] {
                let mut batch = vec![glam::DVec2::ZERO; len];
                seq.fill_2d(start, request, &mut batch);
                for (k, u) in batch.iter().enumerate() {
                    cursor.start_sample(start + k as u64);
                    for _ in 0..request {
                        cursor.next_2d();
                    }
                    assert_eq!(
                        *u,
                        cursor.next_2d(),
                        "request {request} sample {}",
                        start + k as u64
                    );
                }
            }
        }
    }

    /// Exactly the powers of two are whole domains (`0..2^w` with no value
    /// outside `0..n`), and a whole domain's permutation stays inside it
    /// after one step.
    #[test]
    fn whole_domains_are_the_powers_of_two() {
        for n in [1u32, 2, 3, 4, 5, 1 << 14, (1 << 14) + 1, 1 << 31, u32::MAX] {
            assert_eq!(Domain::new(n).is_whole(), n.is_power_of_two(), "n {n}");
        }
        let domain = Domain::new(1 << 10);
        let keys = PermuteKeys::new(42);
        let mut seen = vec![false; 1 << 10];
        for x in 0..1u32 << 10 {
            let y = domain.step(x, &keys);
            assert!(y < 1 << 10, "step({x}) = {y}");
            seen[y as usize] = true;
        }
        assert!(seen.iter().all(|&s| s), "one step is a bijection of 0..n");
    }

    /// The first pair's multiplier is a unit near `0.618 N`, so its order
    /// is a permutation; the lane steps are `k·α mod N` split by `nx`.
    #[test]
    fn golden_units_are_coprime_and_near_the_golden_section() {
        let gcd = |mut a: u64, mut b: u64| {
            while b != 0 {
                (a, b) = (b, a % b);
            }
            a
        };
        for n in [1u32, 2, 3, 4, 6, 12, 16, 30, 1024, 3_125_000, u32::MAX] {
            let a = golden_unit(n);
            assert_eq!(gcd(u64::from(a), u64::from(n)), 1, "n {n}");
            let off = (f64::from(a) - 0.618_033_988_749_894_9 * f64::from(n)).abs();
            // Units are dense: within a few steps of the target for these n.
            assert!(n <= 2 || off <= 4.0, "n {n}: α = {a}");
        }
        // The row steps of a 3 × 4 grid: q·g_y mod 4 for every lane.
        let grid = Grid::new(12, 3, 4);
        for (q, &step) in grid.row_steps.iter().enumerate() {
            assert_eq!(step, (q as u32 * golden_unit(4)) % 4, "lane {q}");
        }
    }

    #[test]
    fn reduce_and_rotate_are_exact() {
        for m in [1u32, 2, 3, 1000, 1 << 31, u32::MAX] {
            for h in [0u64, 1, u64::MAX, 1 << 63, 0x1234_5678_9abc_def0] {
                let want = ((u128::from(h) * u128::from(m)) >> 64) as u32;
                assert_eq!(reduce(h, m), want, "h {h:#x} m {m}");
            }
            for x in [0u32, m / 2, m - 1] {
                for s in [0u32, 1.min(m), m / 2, m - 1, m] {
                    let want = ((u64::from(x) + u64::from(s)) % u64::from(m)) as u32;
                    assert_eq!(rotate(x, s, m), want, "x {x} s {s} m {m}");
                }
            }
        }
    }

    /// The 32-bit reductions against 128-bit arithmetic: `reduce_u32` for
    /// any `m`, and its narrow form, the same value, on every `m < 2¹⁶`
    /// (with hashes at both ends, at the 16-bit seams and spread between).
    #[test]
    fn reductions_of_32_bit_hashes_are_exact() {
        let want = |h: u32, m: u32| ((u64::from(h) * u64::from(m)) >> 32) as u32;
        for m in [1u32, 2, 3, 1000, 65_535, 65_536, 1 << 31, u32::MAX] {
            for h in [0u32, 1, 0xffff, 0x1_0000, u32::MAX, 0x9e37_79b9] {
                assert_eq!(reduce_u32(h, m), want(h, m), "h {h:#x} m {m}");
            }
        }
        let hashes: Vec<u32> = (0..64u32)
            .map(|k| hash_u32(7, k))
            .chain([0, 1, 0xffff, 0x1_0000, 0xffff_0000, 0xfffe_ffff, u32::MAX])
            .collect();
        for m in 1..1u32 << 16 {
            for &h in &hashes {
                assert_eq!(reduce_u32_narrow(h, m), want(h, m), "h {h:#x} m {m}");
            }
        }
    }

    /// The hash cut short shares its top [`HASH_HIGH_EXACT_BITS`] bits with
    /// the whole hash, on keys and positions spread over `u32` and at its
    /// ends; and (negative control) not one bit more: the 16th bit from the
    /// top differs for about half of them, so a kernel that read 16 bits of
    /// the short hash would change values.
    #[test]
    fn a_hash_cut_short_keeps_its_top_15_bits() {
        let top = |x: u32, bits: u32| x >> (32 - bits);
        let mut differ_at_16 = 0;
        let mut count = 0;
        for key in [0u64, 7, 0x243f_6a88_85a3_08d3, u64::MAX] {
            let positions = (0..4096u32).chain([u32::MAX, u32::MAX - 1, 1 << 31]);
            for j in positions.map(|j| j.wrapping_mul(0x9e37_79b9)) {
                let (whole, short) = (hash_u32(key, j), hash_u32_high(key, j));
                let bits = HASH_HIGH_EXACT_BITS;
                assert_eq!(top(whole, bits), top(short, bits), "key {key:#x} j {j}");
                differ_at_16 += usize::from(top(whole, bits + 1) != top(short, bits + 1));
                count += 1;
            }
        }
        // The 16th bit from the top is x's 16th xor its top bit: different for about
        // half; a third is far below that, and far above none.
        assert!(differ_at_16 > count / 3, "{differ_at_16} of {count}");
    }

    /// Negative control for the test above: a batch of another request (other
    /// dimensions) differs from the cursor's first request.
    #[test]
    fn a_different_request_gives_different_points() {
        let seq = Stratified::new(10_000, 3).unwrap();
        let mut a = [glam::DVec2::ZERO; 64];
        let mut b = [glam::DVec2::ZERO; 64];
        seq.fill_2d(0, 0, &mut a);
        seq.fill_2d(0, 1, &mut b);
        assert!(a.iter().zip(&b).all(|(x, y)| x != y));
    }
}
