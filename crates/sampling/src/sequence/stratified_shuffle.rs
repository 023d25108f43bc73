//! The cell order of a stratified sequence's later dimension pairs on a
//! grid whose sides are long enough and near enough to each other: a
//! keyed permutation of the `nx × ny` cells computed on the grid itself,
//! by five Feistel rounds with addition modulo each side.
//!
//! Position `i` of a pass starts as the pair `(a, b) = (⌊i / ny⌋, i mod
//! ny)`, a column `a ∈ 0..nx` and a row `b ∈ 0..ny`. Each round adds to
//! one side a hash of the other, reduced to its range:
//!
//! ```text
//! b ← (b + F₀(a)) mod ny,   a ← (a + F₁(b)) mod nx,   b ← (b + F₂(a)) mod ny,
//! a ← (a + F₃(b)) mod nx,   b ← (b + F₄(a)) mod ny,
//! ```
//!
//! with `F_k(x) = ⌊H(x ⊕ key_k) · m / 2¹⁶⌋` for the side `m` being
//! changed, `key_k` a 16-bit key and `H` a 16-bit hash ([`round`]). Each
//! round is a bijection of `0..nx × 0..ny` whatever its hash (it shifts
//! one side by an amount the other side fixes, and the other side is left
//! as it was), so the five make a permutation, with no cycle walk: the
//! cell is column `a` and row `b`. The construction is the unbalanced
//! Feistel network on a product of two rings (Black & Rogaway 2002,
//! "Ciphers with arbitrary finite domains", method FE2), used here for
//! its statistics, not as a cipher.
//!
//! **Why it replaces the cycle walk there**: the walk permutes `0..N`
//! inside `0..2^w` and steps again every value that lands at `N` or above,
//! so its lanes take a random number of steps (1.34 on average for `N =
//! 3 125 000`), and its cell must then be split into column and row by a
//! division. The rounds here take the same time on every lane and give
//! the column and row directly (measured in README, "Speed").
//!
//! **Why five rounds**: the first pair visits its cells column by column,
//! so consecutive positions, which share `a` here, are its neighbours.
//! A row's final value is `b` plus the shifts of the rounds on `b`, which
//! depend only on the values `a` took before them; positions that share
//! all those values keep their rows' differences, so the pairing of the
//! two pairs' rows is a shift among them rather than a random match. With
//! four rounds (the last on `a`), the positions of one column that the
//! second round sends to one column share both values: about `ny/nx` of
//! them per group. On a 25 × 125 grid that made the variance of the pass
//! mean of `x₀x₁ + y₀y₁` (first pair times second) 1.50 times that of a
//! random pairing (2 000 passes; 1.13 on 25 × 40, 1.10 on 100 × 100;
//! four rounds starting on `a` measured 1.13, 1.47 and 1.11). The
//! fifth round shifts each row again by a hash of its third column value,
//! which positions share only in groups of about `ny/nx²`: 0.99, 1.00 and
//! 1.01 (the cycle walk: 0.98 and 1.03 on the first two; the sampling
//! spread of these ratios is 0.03), tested in `stratified.rs`.
//!
//! **Why long sides, and near each other**: the same argument with a
//! side of `nx` columns leaves a structured fraction of about `1/nx` to
//! `1/nx²`; a grid of `2 × p` would move whole runs of rows together. So
//! grids with `nx <` [`MIN_SIDE`] keep the cycle walk, as do power-of-two
//! grids, where the walk's first step is already a permutation of `0..N`.
//! The groups of positions that share the three values `a` takes before
//! the rounds on `b` hold about `N / nx³ = ny / nx²` positions each, so
//! a grid much longer than it is wide pairs its rows by shifts again:
//! the variance ratio above measured about `1 + 0.1·ny/nx²` (16 × 521:
//! 1.14, 16 × 1031: 1.32, 16 × 4099: 2.59, 16 × 32 749: 13.3, worse than
//! independent points for an integrand such as `x₀x₁ + y₀y₁`). Grids with
//! `ny > nx²/4` ([`shuffles`]) therefore walk as well, which measured
//! 0.98 on 16 × 32 749; at the bound the ratio is at most about 1.03
//! (25 × 151: 1.04, 32 × 251: 1.06, each ± 0.022 over 4 000 passes).
//!
//! **Why 16-bit lanes**: grids up to [`MAX_SIDE`] = 2¹⁵ on either side
//! (every near-square `N` below 2³⁰) keep every value of a round below
//! 2¹⁶, the sum `x + s < 2m` included, so the rounds run sixteen lanes to
//! an AVX2 register and thirty-two to an AVX-512 one, and the reduction
//! is the high half of a 16 × 16-bit product ([`CellShuffle::cells`]
//! says how the compiler is kept to it). Longer sides walk. (An f32 point
//! of a later pair at `N = 10⁶` took 3.55 ns with the 32-bit rounds this
//! replaced and 2.70–2.75 ns with these, on an AVX2 host; README,
//! "Speed".)

use super::mix64;

/// The shortest side `nx` for which the later pairs take these rounds
/// instead of the cycle walk (module docs, "Why long sides").
pub(super) const MIN_SIDE: u32 = 16;

/// The longest side for which they do (module docs, "Why 16-bit lanes").
pub(super) const MAX_SIDE: u32 = 1 << 15;

/// Whether an `nx × ny` grid of `n = nx·ny` samples, `nx ≤ ny`, takes its
/// later pairs' cells from these rounds: `n` not a power of two, `nx ≥`
/// [`MIN_SIDE`], `ny ≤` [`MAX_SIDE`] and `ny ≤ nx²/4` (module docs, "Why
/// long sides, and near each other").
pub(super) fn shuffles(n: u32, nx: u32, ny: u32) -> bool {
    !n.is_power_of_two()
        && nx >= MIN_SIDE
        && ny <= MAX_SIDE
        && 4 * u64::from(ny) <= u64::from(nx) * u64::from(nx)
}

/// The five round keys of one dimension pair's cell permutation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CellShuffle([u16; 5]);

impl CellShuffle {
    /// The round keys of the shuffle keyed by `key`: the four 16-bit
    /// quarters of `mix64(key)` and the low quarter of `mix64(key ⊕ γ)`.
    #[inline]
    pub(super) fn new(key: u64) -> Self {
        const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;
        let (first, second) = (mix64(key), mix64(key ^ GAMMA));
        CellShuffle([
            first as u16,
            (first >> 16) as u16,
            (first >> 32) as u16,
            (first >> 48) as u16,
            second as u16,
        ])
    }

    /// The cell `[column, row]` of position `(a, b) = (⌊i / ny⌋, i mod
    /// ny)`, `a < nx ≤` [`MAX_SIDE`], `b < ny ≤` [`MAX_SIDE`].
    #[inline(always)]
    pub(super) fn cell(self, [a, b]: [u32; 2], [nx, ny]: [u32; 2]) -> [u32; 2] {
        debug_assert!(nx <= MAX_SIDE && ny <= MAX_SIDE && a < nx && b < ny);
        let [k0, k1, k2, k3, k4] = self.0;
        let (mut a, mut b, nx, ny) = (a as u16, b as u16, nx as u16, ny as u16);
        b = rotate(b, round(k0, a, ny), ny);
        a = rotate(a, round(k1, b, nx), nx);
        b = rotate(b, round(k2, a, ny), ny);
        a = rotate(a, round(k3, b, nx), nx);
        b = rotate(b, round(k4, a, ny), ny);
        [u32::from(a), u32::from(b)]
    }

    /// [`CellShuffle::cell`] of every `(a[k], b[k])`, in place, in 16-bit
    /// lanes: round by round over the whole block, so that a loop's chain
    /// of dependent operations is one round long and the processor
    /// overlaps many lanes' rounds (a loop of all the rounds per lane
    /// waited on their latency: on an AVX2 host, with four rounds, f32
    /// points of a later pair at `N = 10⁶` took 4.66 ns each that way and
    /// 3.82 ns this way).
    ///
    /// The sides come lane by lane, `nx[k] = nx` and `ny[k] = ny` for every
    /// `k < a.len()`, read from memory: with a side held in a register the
    /// compiler hoists its widening to 32 bits out of the loop, no longer
    /// sees a 16 × 16-bit product's high half, and widens, multiplies and
    /// packs back every vector (five shuffles more), where a side read per
    /// lane keeps one `vpmulhuw`. On an AVX2 host a later pair's point at
    /// `N = 10⁶` took 3.38 ns (f32) and 4.22 ns (f64) that way, 2.70–2.75
    /// and 3.53 this way.
    #[inline(always)]
    pub(super) fn cells(self, a: &mut [u16], b: &mut [u16], [nx, ny]: [&[u16]; 2]) {
        debug_assert!(nx.len() >= a.len() && ny.len() >= a.len() && a.len() == b.len());
        let [k0, k1, k2, k3, k4] = self.0;
        let round_on = |key: u16, side: &mut [u16], other: &[u16], m: &[u16]| {
            for ((x, &y), &m) in side.iter_mut().zip(other).zip(m) {
                *x = rotate(*x, round(key, y, m), m);
            }
        };
        round_on(k0, b, a, ny);
        round_on(k1, a, b, nx);
        round_on(k2, b, a, ny);
        round_on(k3, a, b, nx);
        round_on(k4, b, a, ny);
    }
}

/// The first multiplier of [`round`]'s hash.
const ROUND_MULTIPLIER_1: u16 = 0x1c4d;

/// The second multiplier of [`round`]'s hash.
const ROUND_MULTIPLIER_2: u16 = 0xd735;

/// A round's shift of a side of `m ≤ 2¹⁵` cells, from the other side's
/// value `x`: `⌊H(x ⊕ key) · m / 2¹⁶⌋ ∈ 0..m`, with `H` the 16-bit hash
/// `h ← h ⊕ (h ≫ 8); h ← h·0x1c4d; h ← h ⊕ (h ≫ 7); h ← h·0xd735` (mod
/// 2¹⁶), a xorshift–multiply hash of the kind Wellons's "hash prospector"
/// searches for (nullprogram.com, 2018), with multipliers and shifts we
/// chose by the same avalanche measure on its top ten bits, the ones the
/// reduction reads: over every input and every flipped input bit, each of
/// them flips with probability 0.5 within 0.006 (root mean square). The
/// reduction is Lemire's, the high half of a 16 × 16-bit product (one
/// instruction for sixteen lanes). A shift a few per cent more likely than
/// another would do no harm, since every shift gives a bijection.
#[inline(always)]
fn round(key: u16, x: u16, m: u16) -> u16 {
    let mut h = x ^ key;
    h ^= h >> 8;
    h = h.wrapping_mul(ROUND_MULTIPLIER_1);
    h ^= h >> 7;
    h = h.wrapping_mul(ROUND_MULTIPLIER_2);
    ((u32::from(h) * u32::from(m)) >> 16) as u16
}

/// `(x + s) mod m` for `x, s < m ≤ 2¹⁵`: `t = x + s < 2m` fits in 16
/// bits, and the unsigned minimum of `t` and `t − m` (which wraps above
/// `t` when `t < m`) is `t mod m`.
#[inline(always)]
fn rotate(x: u16, s: u16, m: u16) -> u16 {
    debug_assert!(u32::from(m) <= MAX_SIDE && x < m && s < m);
    let t = x + s;
    t.min(t.wrapping_sub(m))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every key gives a permutation of the cells, on grids with sides
    /// short, long, equal, unequal and odd; different keys give different
    /// permutations (negative control for a shuffle that does nothing).
    #[test]
    fn every_key_permutes_the_cells() {
        for [nx, ny] in [
            [16u32, 16],
            [16, 17],
            [25, 40],
            [31, 37],
            [100, 125],
            [16, 32_749],
            [16, MAX_SIDE],
        ] {
            let mut orders = Vec::new();
            for key in 0..4u64 {
                let shuffle = CellShuffle::new(key);
                let mut seen = vec![false; (nx * ny) as usize];
                let order: Vec<u32> = (0..nx * ny)
                    .map(|i| {
                        let [c, r] = shuffle.cell([i / ny, i % ny], [nx, ny]);
                        assert!(c < nx && r < ny, "{nx} × {ny}: ({c}, {r})");
                        let cell = r * nx + c;
                        assert!(!seen[cell as usize], "{nx} × {ny}: cell {cell} twice");
                        seen[cell as usize] = true;
                        cell
                    })
                    .collect();
                orders.push(order);
            }
            assert!(orders.windows(2).all(|w| w[0] != w[1]), "{nx} × {ny}");
            // The block form, round by round, gives the same cells.
            let shuffle = CellShuffle::new(3);
            let (mut a, mut b): (Vec<u16>, Vec<u16>) = (0..nx * ny)
                .map(|i| ((i / ny) as u16, (i % ny) as u16))
                .unzip();
            let lanes = [vec![nx as u16; a.len()], vec![ny as u16; a.len()]];
            shuffle.cells(&mut a, &mut b, [&lanes[0], &lanes[1]]);
            for (i, (&c, &r)) in a.iter().zip(&b).enumerate() {
                let i = i as u32;
                let cell = [u32::from(c), u32::from(r)];
                assert_eq!(cell, shuffle.cell([i / ny, i % ny], [nx, ny]));
            }
        }
    }

    /// The 16-bit rotation is `(x + s) mod m` on every side up to 2¹⁵,
    /// at the ends of its range and between.
    #[test]
    fn rotation_is_exact_up_to_the_longest_side() {
        for m in [1u16, 2, 3, 17, 1000, 32_749, 1 << 15] {
            let values = [0, 1 % m, m / 2, m.saturating_sub(2), m - 1];
            for x in values {
                for s in values {
                    let want = ((u32::from(x) + u32::from(s)) % u32::from(m)) as u16;
                    assert_eq!(rotate(x, s, m), want, "x {x} s {s} m {m}");
                }
            }
        }
    }

    /// Positions of one column, which the first pair's order puts in one
    /// run, land in different columns: of the `ny − 1` neighbours in a
    /// column's run, the number sharing the next one's column is binomial
    /// with `p = 1/nx` (rounds on `a` with hashes of different rows), far
    /// from the `ny − 1` an order without the rounds on `a` would give
    /// (negative control: the first round alone keeps every run whole).
    #[test]
    fn runs_of_one_column_are_scattered() {
        let (nx, ny) = (1250u32, 2500u32);
        let shuffle = CellShuffle::new(0x243f_6a88_85a3_08d3);
        let mut same = 0;
        for a in 0..8 {
            for b in 0..ny - 1 {
                let [c0, _] = shuffle.cell([a, b], [nx, ny]);
                let [c1, _] = shuffle.cell([a, b + 1], [nx, ny]);
                same += u32::from(c0 == c1);
            }
        }
        // 8·2499 neighbour pairs at p = 1/1250: mean 16, sd 4; 60 is 11 sd
        // above the mean (far beyond any significance level that matters)
        // and far below the 19 992 of an order that keeps runs together.
        assert!(same < 60, "{same} neighbours share a column");
        let first_round_only =
            |[a, b]: [u16; 2]| [a, rotate(b, round(0x08d3, a, ny as u16), ny as u16)];
        let kept = (0..ny - 1)
            .filter(|&b| {
                first_round_only([0, b as u16])[0] == first_round_only([0, b as u16 + 1])[0]
            })
            .count();
        assert_eq!(kept as u32, ny - 1);
    }
}
