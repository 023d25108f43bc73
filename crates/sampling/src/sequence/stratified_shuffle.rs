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
//! with `F_k(x) = ⌊⌊H(x ⊕ key_k) / 2¹⁶⌋ · m / 2¹⁶⌋` for the side `m`
//! being changed and `H` the 32-bit hash of the stratified shifts, cut
//! short ([`hash_u32_high`]). Each round is a bijection of `0..nx × 0..ny`
//! whatever its hash (it shifts one side by an amount the other side
//! fixes, and the other side is left as it was), so the five make a
//! permutation, with no cycle walk: the cell is column `a` and row `b`.
//! The construction is the unbalanced Feistel network on a product of
//! two rings (Black & Rogaway 2002, "Ciphers with arbitrary finite
//! domains", method FE2), used here for its statistics, not as a cipher.
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
//! which positions share only in groups of about `ny/nx²`: 0.96, 1.05 and
//! 1.02 (the cycle walk: 0.98 and 1.03 on the first two; the sampling
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
//! (25 × 151: 1.04, 32 × 251: 1.03, each ± 0.022 over 4 000 passes).

use super::mix64;
use super::stratified_batch::{hash_u32_high, rotate, rotate_narrow};

/// The shortest side `nx` for which the later pairs take these rounds
/// instead of the cycle walk (module docs, "Why long sides").
pub(super) const MIN_SIDE: u32 = 16;

/// Whether an `nx × ny` grid of `n = nx·ny` samples, `nx ≤ ny`, takes its
/// later pairs' cells from these rounds: `n` not a power of two, `nx ≥`
/// [`MIN_SIDE`] and `ny ≤ nx²/4` (module docs, "Why long sides, and near
/// each other").
pub(super) fn shuffles(n: u32, nx: u32, ny: u32) -> bool {
    !n.is_power_of_two() && nx >= MIN_SIDE && 4 * u64::from(ny) <= u64::from(nx) * u64::from(nx)
}

/// The five round keys of one dimension pair's cell permutation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CellShuffle([u32; 5]);

impl CellShuffle {
    /// The round keys of the shuffle keyed by `key`: the halves of
    /// `mix64(key)`, `mix64(key ⊕ γ)` and `mix64(key ⊕ 2γ)`.
    #[inline]
    pub(super) fn new(key: u64) -> Self {
        const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;
        let [first, second, third] = [0, GAMMA, GAMMA.wrapping_mul(2)].map(|tag| mix64(key ^ tag));
        CellShuffle([
            first as u32,
            (first >> 32) as u32,
            second as u32,
            (second >> 32) as u32,
            third as u32,
        ])
    }

    /// The cell `[column, row]` of position `(a, b) = (⌊i / ny⌋, i mod
    /// ny)`, `a < nx`, `b < ny`. `WIDE` says whether a side may reach
    /// `2¹⁶` (the round's product then needs 64 bits; the same values).
    #[inline(always)]
    pub(super) fn cell<const WIDE: bool>(
        self,
        [mut a, mut b]: [u32; 2],
        [nx, ny]: [u32; 2],
    ) -> [u32; 2] {
        let [k0, k1, k2, k3, k4] = self.0;
        b = rotate(b, round::<WIDE>(k0, a, ny), ny);
        a = rotate(a, round::<WIDE>(k1, b, nx), nx);
        b = rotate(b, round::<WIDE>(k2, a, ny), ny);
        a = rotate(a, round::<WIDE>(k3, b, nx), nx);
        b = rotate(b, round::<WIDE>(k4, a, ny), ny);
        [a, b]
    }

    /// [`CellShuffle::cell`] of every `(a[k], b[k])`, in place: round by
    /// round over the whole block, so that a loop's chain of dependent
    /// operations is one round long and the processor overlaps many lanes'
    /// rounds (a loop of all the rounds per lane waited on their latency:
    /// on an AVX2 host, with four rounds, f32 points of a later pair at `N
    /// = 10⁶` took 4.66 ns each that way and 3.82 ns this way).
    #[inline(always)]
    pub(super) fn cells<const WIDE: bool>(self, a: &mut [u32], b: &mut [u32], [nx, ny]: [u32; 2]) {
        let [k0, k1, k2, k3, k4] = self.0;
        let round_on = |key: u32, side: &mut [u32], other: &[u32], m: u32| {
            for (x, &y) in side.iter_mut().zip(other) {
                let shift = round::<WIDE>(key, y, m);
                *x = if WIDE {
                    rotate(*x, shift, m)
                } else {
                    rotate_narrow(*x, shift, m)
                };
            }
        };
        round_on(k0, b, a, ny);
        round_on(k1, a, b, nx);
        round_on(k2, b, a, ny);
        round_on(k3, a, b, nx);
        round_on(k4, b, a, ny);
    }
}

/// A round's shift of a side of `m` cells, from the other side's value
/// `x`: `⌊⌊H(x ⊕ key) / 2¹⁶⌋ · m / 2¹⁶⌋ ∈ 0..m`, with `H` the hash of
/// [`hash_u32_high`]. Its top 16 bits scaled to the side (Lemire's
/// reduction, in 32-bit lanes for `m < 2¹⁶`: one multiplication); a
/// shift a few per cent more likely than another would do no harm, since
/// every shift gives a bijection.
#[inline(always)]
fn round<const WIDE: bool>(key: u32, x: u32, m: u32) -> u32 {
    let top = hash_u32_high(u64::from(key), x) >> 16;
    if WIDE {
        ((u64::from(top) * u64::from(m)) >> 16) as u32
    } else {
        (top * m) >> 16
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every key gives a permutation of the cells, on grids with sides
    /// short, long, equal, unequal and odd; different keys give different
    /// permutations (negative control for a shuffle that does nothing).
    #[test]
    fn every_key_permutes_the_cells() {
        for [nx, ny] in [[16u32, 16], [16, 17], [25, 40], [31, 37], [100, 125]] {
            let mut orders = Vec::new();
            for key in 0..4u64 {
                let shuffle = CellShuffle::new(key);
                let mut seen = vec![false; (nx * ny) as usize];
                let order: Vec<u32> = (0..nx * ny)
                    .map(|i| {
                        let [c, r] = shuffle.cell::<false>([i / ny, i % ny], [nx, ny]);
                        assert_eq!([c, r], shuffle.cell::<true>([i / ny, i % ny], [nx, ny]));
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
            let (mut a, mut b): (Vec<u32>, Vec<u32>) =
                (0..nx * ny).map(|i| (i / ny, i % ny)).unzip();
            shuffle.cells::<false>(&mut a, &mut b, [nx, ny]);
            for (i, (&c, &r)) in a.iter().zip(&b).enumerate() {
                let i = i as u32;
                assert_eq!([c, r], shuffle.cell::<false>([i / ny, i % ny], [nx, ny]));
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
                let [c0, _] = shuffle.cell::<false>([a, b], [nx, ny]);
                let [c1, _] = shuffle.cell::<false>([a, b + 1], [nx, ny]);
                same += u32::from(c0 == c1);
            }
        }
        // 8·2499 neighbour pairs at p = 1/1250: mean 16, sd 4; 60 is 11 sd
        // above the mean (far beyond any significance level that matters)
        // and far below the 19 992 of an order that keeps runs together.
        assert!(same < 60, "{same} neighbours share a column");
        let first_round_only =
            |[a, b]: [u32; 2]| [a, rotate(b, round::<false>(0x85a3_08d3, a, ny), ny)];
        let kept = (0..ny - 1)
            .filter(|&b| first_round_only([0, b])[0] == first_round_only([0, b + 1])[0])
            .count();
        assert_eq!(kept as u32, ny - 1);
    }
}
