//! Stratified points when `N` is a power of two: the same values as the
//! general kernel of `stratified_batch.rs`, to the bit, with every modulus
//! a mask and every range reduction a shift.
//!
//! With `N = 2^p`, the near-square grid is `nx = 2^⌊p/2⌋` by
//! `ny = 2^⌈p/2⌉`, and each step of the general kernel has a form without
//! tables, carries or divisions:
//!
//! * the first pair's position `(i + b) mod N` is the low `p` bits of the
//!   wrapping 32-bit `i + b` (`2^p` divides `2^32`); its row is the low
//!   `log₂ ny` bits of that and its column the bits above times `g_x`,
//!   masked. Consecutive points then run down a column, so for `ny` at
//!   least a span (256) the column's terms (its spread and the hash of its
//!   shift) are computed once per run and each lane computes only its
//!   row's: three 32-bit multiplies a point instead of seven, and one
//!   hash instead of two (below `ny = 256` each lane computes its own
//!   cell);
//! * `cell mod nx` and `⌊cell / nx⌋` are a mask and a shift;
//! * the spreads `x·g mod m` (`m = nx` or `ny`) are the low bits of the
//!   wrapping product: no table, no gather;
//! * the shift reduction `⌊h·m / 2³²⌋` is `h ≫ (32 − log₂ m)`, and the
//!   rotation `(x + s) mod m` with `x, s < m` is `(x + s) & (m − 1)`;
//! * a later pair's keyed permutation is one walk step (it is a bijection
//!   of `0..2^p` already).
//!
//! Every lane is independent and the block needs no intermediate arrays,
//! so the compiler runs sixteen 32-bit lanes per AVX-512 register end to
//! end. The study's sample counts are powers of two, as are most users'.
//!
//! **The f32 coordinate** is the exact value `(k + h·2⁻³²)/N` rounded down
//! to 24 bits, by integer arithmetic: the top 24 bits of the fixed-point
//! number `k·2³² + h` below `2^(p+32)`, `((k ≫ (p − 24)⁺) ≪ (24 − p)⁺) |
//! (h ≫ (p + 8))`, converted exactly. For `N ≤ 2²⁴` it is the general
//! kernel's f32 coordinate (`stratified_f32.rs`, whose `M` is `2²⁴` here),
//! to the bit; above, the general kernel would round the f64 coordinate
//! down. That rounded-down f64 coordinate agrees with this one for `N ≤
//! 2²¹`: `k + h·2⁻³²` (`k < 2²¹`, 32 jitter bits) fits the 53 bits of an
//! f64 and the product by `2⁻ᵖ` is exact. Above `2²¹` the f64 sum rounds `h` to
//! fewer bits; where that rounding carries across a 24-bit step (`k ≥ 2²¹`
//! and the jitter's bits below the step all ones, about one coordinate in
//! `2³⁰`) the f32 coordinate here is one step below the rounded-down f64
//! one. The exact form was chosen because it costs a third of the f64
//! route in vector lanes (measured: light sampling of a sphere light in
//! f32, 2²⁶ stratified samples in 16 replicates of `N = 2²²`: 1.83 → 1.22
//! ns per sample) and, for `N ≤ 2²⁴` (a stratum at least one f32 step
//! wide), never leaves its stratum.

use super::stratified_batch::{golden_unit, hash_u32_cut, Domain, PairKeys, HASH_HIGH_EXACT_BITS};

/// `x ≫ s`, and 0 for `s ≥ 32` (Rust's `>>` wraps the count). One
/// instruction in vector lanes: x86's variable shifts (`vpsrlvd`) give 0
/// for counts past the width, and the compiler folds the select into
/// them, where the former form, two shifts `(x ≫ 1) ≫ (s − 1)`, was two.
#[inline(always)]
pub(super) fn shr_or_zero(x: u32, s: u32) -> u32 {
    x.checked_shr(s).unwrap_or(0)
}

/// `x ≪ s`, and 0 for `s ≥ 32` ([`shr_or_zero`]'s mirror, `vpsllvd`).
#[inline(always)]
fn shl_or_zero(x: u32, s: u32) -> u32 {
    x.checked_shl(s).unwrap_or(0)
}

/// What `N = 2^p` fixes: the logarithms of `N`, `nx` and `ny`, and the
/// multipliers of the cell order and the spreads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PowerOfTwoGrid {
    /// `p = log₂ N`.
    log_n: u32,
    /// `log₂ nx`.
    log_nx: u32,
    /// `log₂ ny`.
    log_ny: u32,
    /// The column spread's multiplier `g_x` (`golden_unit(nx)`).
    column_unit: u32,
    /// The row spread's multiplier `g_y` (`golden_unit(ny)`).
    row_unit: u32,
}

impl PowerOfTwoGrid {
    /// The grid of `n` samples as `nx × ny` cells, if all three are powers
    /// of two.
    pub(super) fn new(n: u32, nx: u32, ny: u32) -> Option<Self> {
        if !(n.is_power_of_two() && nx.is_power_of_two() && ny.is_power_of_two()) {
            return None;
        }
        let log_n = n.trailing_zeros();
        Some(PowerOfTwoGrid {
            log_n,
            log_nx: nx.trailing_zeros(),
            log_ny: ny.trailing_zeros(),
            column_unit: golden_unit(nx),
            row_unit: golden_unit(ny),
        })
    }

    /// `N − 1`, `nx − 1`, `ny − 1`.
    #[inline(always)]
    fn masks(self) -> (u32, u32, u32) {
        let mask = |log: u32| ((1u64 << log) - 1) as u32;
        (mask(self.log_n), mask(self.log_nx), mask(self.log_ny))
    }

    /// The f32 coordinate of stratum `k < N` with jitter bits `h`:
    /// `⌊(k·2³² + h) / 2^(p+8)⌋ · 2⁻²⁴`, exactly (module docs).
    #[inline(always)]
    pub(super) fn unit_f32(self, (k, h): (u32, u32)) -> f32 {
        // k·2^(32−p) puts the stratum's p bits at the top of a word (k < 2ᵖ);
        // dropping 8 bits leaves k·2^(24−p) for p ≤ 24 and ⌊k / 2^(p−24)⌋
        // above. The jitter's share, h ≫ (p + 8), vanishes for p ≥ 24.
        let top = (shl_or_zero(k, 32 - self.log_n) >> 8) | shr_or_zero(h, self.log_n + 8);
        // top < 2²⁴: exact through i32, one instruction before AVX-512.
        top as i32 as f32 * (1.0 / 16_777_216.0)
    }

    /// How many top jitter bits [`PowerOfTwoGrid::unit_f32`] reads:
    /// `(24 − p)⁺`, the bits of `h ≫ (p + 8)`.
    #[inline(always)]
    pub(super) fn f32_jitter_bits(self) -> u32 {
        24u32.saturating_sub(self.log_n)
    }

    /// Positions `first … first + len − 1` of one pass in dimensions
    /// `(dim, dim + 1)`: `x[k]`, `y[k]` = `store((k_x, h_x))`,
    /// `store((k_y, h_y))`, the stratum and the 32 jitter bits of each axis
    /// (`stratified_batch::fill_pass`, whose values these are), of which
    /// `store` reads no more than the top `jitter_bits`.
    ///
    /// The shifts read the top `log₂ nx` and `log₂ ny` bits of their hashes;
    /// where those and `jitter_bits` are at most
    /// [`HASH_HIGH_EXACT_BITS`], the hashes skip their last step
    /// ([`hash_u32_cut`]), the same values to the bit (every `N` from 2⁹
    /// to 2³⁰ in f32; the shifts alone for `N ≤ 2³⁰` in f64). Measured on
    /// `N = 2²⁰` in f32: 0.74 → 0.65 ns per point.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fill_pass<T>(
        self,
        keys: &PairKeys,
        dim: u64,
        first: u32,
        x: &mut [T],
        y: &mut [T],
        jitter_bits: u32,
        store: impl Fn((u32, u32)) -> T,
    ) {
        let short_shifts = self.log_nx.max(self.log_ny) <= HASH_HIGH_EXACT_BITS;
        let jitter = if jitter_bits == 0 {
            Jitter::NONE
        } else if jitter_bits <= HASH_HIGH_EXACT_BITS {
            Jitter::SHORT
        } else {
            Jitter::WHOLE
        };
        // The pair and the hashes' forms are fixed for the pass: each
        // combination is its own loop, with no test of them per point
        // (with `dim` a run-time value the compiler kept a branch on it in
        // the loop and spilled constants of both arms).
        macro_rules! fill {
            ($first:expr, $short:expr, $jitter:expr) => {
                self.fill::<T, $first, $short, { $jitter }>(keys, first, x, y, store)
            };
        }
        match (dim == 0, short_shifts, jitter) {
            (true, true, Jitter::NONE) => fill!(true, true, Jitter::NONE),
            (true, true, Jitter::SHORT) => fill!(true, true, Jitter::SHORT),
            (true, true, _) => fill!(true, true, Jitter::WHOLE),
            (false, true, Jitter::NONE) => fill!(false, true, Jitter::NONE),
            (false, true, Jitter::SHORT) => fill!(false, true, Jitter::SHORT),
            (false, true, _) => fill!(false, true, Jitter::WHOLE),
            // Sides above 2¹⁵ (N > 2³⁰): every hash whole.
            (true, false, _) => fill!(true, false, Jitter::WHOLE),
            (false, false, _) => fill!(false, false, Jitter::WHOLE),
        }
    }

    /// Point `i`'s position on the grid before the spreads: for the first
    /// request pair (`FIRST`) `(i + b) mod N`, read column by column; for
    /// a later one its cell permuted over `domain`, read row by row
    /// ([`PowerOfTwoGrid::parts`] splits it).
    #[inline(always)]
    fn position<const FIRST: bool>(self, keys: &PairKeys, domain: Domain, i: u32) -> u32 {
        let (n_mask, _, _) = self.masks();
        if FIRST {
            i.wrapping_add(keys.offset) & n_mask
        } else {
            domain.step(i, &keys.cell) & n_mask
        }
    }

    /// Point `i`'s strata and jitter bits, `((kx, hx), (ky, hy))`, from its
    /// [`position`](PowerOfTwoGrid::position) in the first request pair
    /// (`FIRST`: column ⌊p / ny⌋·g_x, row p mod ny) or a later one
    /// (column and row of the cell), with the shifts' hashes cut short
    /// ([`hash_u32_cut`]) or whole, as `SHORT_SHIFTS` says, and the
    /// jitters' as `JITTER` says ([`Jitter`]; 0 for [`Jitter::NONE`]).
    #[inline(always)]
    fn parts<const FIRST: bool, const SHORT_SHIFTS: bool, const JITTER: u8>(
        self,
        keys: &PairKeys,
        position: u32,
        i: u32,
    ) -> ((u32, u32), (u32, u32)) {
        let (_, nx_mask, ny_mask) = self.masks();
        let (c, r) = if FIRST {
            (self.first_column(position), position & ny_mask)
        } else {
            (position & nx_mask, position >> self.log_nx)
        };
        self.row_parts::<SHORT_SHIFTS, JITTER>(
            keys,
            self.column_terms::<SHORT_SHIFTS>(keys, c),
            r,
            i,
        )
    }

    /// The column `c` of position `p` in the first request pair:
    /// ⌊p / ny⌋·g_x mod nx.
    #[inline(always)]
    fn first_column(self, position: u32) -> u32 {
        let (_, nx_mask, _) = self.masks();
        (position >> self.log_ny).wrapping_mul(self.column_unit) & nx_mask
    }

    /// What column `c` fixes of its points' parts: its strata's top bits
    /// `c·ny`, its spread `c·g_x mod nx` and its shift
    /// `s = ⌊σ(c)·ny / 2³²⌋`.
    #[inline(always)]
    fn column_terms<const SHORT_SHIFTS: bool>(self, keys: &PairKeys, c: u32) -> ColumnTerms {
        let (_, nx_mask, _) = self.masks();
        ColumnTerms {
            top: c << self.log_ny,
            spread: c.wrapping_mul(self.column_unit) & nx_mask,
            // ⌊h·m/2³²⌋ for m = 2^log: h ≫ (32 − log), 0 for log = 0.
            shift: shr_or_zero(
                hash_u32_cut::<SHORT_SHIFTS>(keys.sigma, c),
                32 - self.log_ny,
            ),
        }
    }

    /// Point `i`'s parts ([`PowerOfTwoGrid::parts`]) from its column's
    /// terms and its row `r`.
    #[inline(always)]
    fn row_parts<const SHORT_SHIFTS: bool, const JITTER: u8>(
        self,
        keys: &PairKeys,
        column: ColumnTerms,
        r: u32,
        i: u32,
    ) -> ((u32, u32), (u32, u32)) {
        let (_, nx_mask, ny_mask) = self.masks();
        let row_spread = r.wrapping_mul(self.row_unit) & ny_mask;
        let t = shr_or_zero(hash_u32_cut::<SHORT_SHIFTS>(keys.tau, r), 32 - self.log_nx);
        let kx = column.top | ((row_spread + column.shift) & ny_mask);
        let ky = (r << self.log_nx) | ((column.spread + t) & nx_mask);
        (
            (kx, Jitter::bits::<JITTER>(keys.jitter, i)),
            (ky, Jitter::bits::<JITTER>(keys.jitter >> 32, i)),
        )
    }

    /// [`PowerOfTwoGrid::fill_pass`] for the first pair or a later one,
    /// with the hashes cut short, whole or (the jitters) skipped, as the
    /// flags say ([`PowerOfTwoGrid::parts`]).
    #[inline(always)]
    fn fill<T, const FIRST: bool, const SHORT_SHIFTS: bool, const JITTER: u8>(
        self,
        keys: &PairKeys,
        first: u32,
        x: &mut [T],
        y: &mut [T],
        store: impl Fn((u32, u32)) -> T,
    ) {
        let (n_mask, _, _) = self.masks();
        let domain = Domain::new(n_mask.wrapping_add(1).max(1));
        // Spans in two stages: the integers of SPAN points, then their
        // coordinates. In one loop the compiler ran the 32-bit integer
        // work as many lanes as an f64 vector has (four on AVX2), half a
        // vector of them.
        let (mut kx, mut hx) = ([0u32; SPAN], [0u32; SPAN]);
        let (mut ky, mut hy) = ([0u32; SPAN], [0u32; SPAN]);
        for (s, (xs, ys)) in x.chunks_mut(SPAN).zip(y.chunks_mut(SPAN)).enumerate() {
            let m = xs.len().min(ys.len());
            let base = first.wrapping_add((s * SPAN) as u32);
            let (kx, hx, ky, hy) = (&mut kx[..m], &mut hx[..m], &mut ky[..m], &mut hy[..m]);
            if FIRST && self.log_ny >= SPAN.ilog2() {
                // Consecutive points of the first pair run down a column
                // (position p + 1 follows p in the same column until p
                // reaches a multiple of ny): each column's terms once per
                // run, at most two runs a span (ny ≥ SPAN).
                let position = self.position::<true>(keys, domain, base);
                let (_, _, ny_mask) = self.masks();
                let left = ((ny_mask - (position & ny_mask)) as usize + 1).min(m);
                let (n_mask, _, _) = self.masks();
                for (start, run, position) in [
                    (0, left, position),
                    (left, m - left, position.wrapping_add(left as u32) & n_mask),
                ] {
                    let column = self.first_column(position);
                    let terms = self.column_terms::<SHORT_SHIFTS>(keys, column);
                    let r0 = position & ny_mask;
                    for j in start..start + run {
                        ((kx[j], hx[j]), (ky[j], hy[j])) = self.row_parts::<SHORT_SHIFTS, JITTER>(
                            keys,
                            terms,
                            r0 + (j - start) as u32,
                            base.wrapping_add(j as u32),
                        );
                    }
                }
            } else {
                // The positions first, in kx (a later pair's permutation
                // step is a long chain of dependent operations; in a loop
                // of its own more points' chains overlap).
                for (j, k) in kx.iter_mut().enumerate() {
                    *k = self.position::<FIRST>(keys, domain, base.wrapping_add(j as u32));
                }
                for j in 0..m {
                    ((kx[j], hx[j]), (ky[j], hy[j])) = self.parts::<FIRST, SHORT_SHIFTS, JITTER>(
                        keys,
                        kx[j],
                        base.wrapping_add(j as u32),
                    );
                }
            }
            let (xs, ys) = (&mut xs[..m], &mut ys[..m]);
            for j in 0..m {
                xs[j] = store((kx[j], hx[j]));
                ys[j] = store((ky[j], hy[j]));
            }
        }
    }
}

/// What a column of the grid fixes of its points' strata
/// ([`PowerOfTwoGrid::column_terms`]).
#[derive(Clone, Copy)]
struct ColumnTerms {
    /// The x strata's top bits, `c·ny`.
    top: u32,
    /// The column's spread, `c·g_x mod nx`.
    spread: u32,
    /// The column's shift of its rows, `⌊σ(c)·ny / 2³²⌋`.
    shift: u32,
}

/// How a pass forms its jitter bits (the `JITTER` parameter of
/// [`PowerOfTwoGrid::fill`]).
struct Jitter;

impl Jitter {
    /// The coordinates read none (an f32 coordinate for `N ≥ 2²⁴`, whose
    /// stratum alone fills its 24 bits): no hash, `h = 0`, the same
    /// values, since the store reads no bit of `h`.
    const NONE: u8 = 0;
    /// At most [`HASH_HIGH_EXACT_BITS`]: the hash cut short.
    const SHORT: u8 = 1;
    /// More: the whole hash.
    const WHOLE: u8 = 2;

    /// Point `i`'s jitter bits under `key`, formed as `JITTER` says.
    #[inline(always)]
    fn bits<const JITTER: u8>(key: u64, i: u32) -> u32 {
        match JITTER {
            Jitter::NONE => 0,
            Jitter::SHORT => hash_u32_cut::<true>(key, i),
            _ => hash_u32_cut::<false>(key, i),
        }
    }
}

/// Points whose integers [`PowerOfTwoGrid::fill`] computes before their
/// coordinates (4 KiB of integers, in the first-level cache).
const SPAN: usize = 256;

/// The sum `k + h·2⁻³²` of stratum `k` and jitter bits `h`, rounded to
/// f64 (exact while `k < 2²¹`): the reference the kernels' coordinates
/// are tested against.
#[cfg(test)]
pub(super) fn jittered_sum(k: u32, h: u32) -> f64 {
    f64::from(k) + f64::from(h) * super::TWO_POW_M32
}

/// The fixed-point sum `k·2³² + h` of stratum `k` and jitter bits `h`,
/// rounded to f64 (exact while `k < 2²¹`): `2³²` times the sum
/// `k + h·2⁻³²` rounded to f64, to the bit, since scaling by a power of
/// two commutes with the one rounding of each.
#[inline(always)]
pub(super) fn fixed_sum(k: u32, h: u32) -> f64 {
    ((u64::from(k) << 32) | u64::from(h)) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sequence::round_down_24;
    use crate::sequence::stratified_batch::{cell_of, fill_pass, Coordinate, Grid};

    /// The near-square grid of `2^p` samples.
    fn grid_of(p: u32) -> Grid {
        let (nx, ny) = (1u32 << (p / 2), 1u32 << p.div_ceil(2));
        Grid::new(1 << p, nx, ny)
    }

    /// Every power-of-two grid (`N = 1 … 2³¹`), both kinds of cell order
    /// (`dim` 0 and 2), starts at both ends of a pass and in its middle:
    /// the power-of-two kernel gives the general kernel's f64 values to the
    /// bit, and its f32 values too where they agree by definition
    /// (`N ≤ 2²⁴`); everywhere its f32 values are [`exact_f32`] of the
    /// general kernel's strata and jitters.
    #[test]
    fn power_of_two_kernel_gives_the_general_values() {
        for p in 0..=31u32 {
            let grid = grid_of(p);
            let pow2 = grid.power_of_two().unwrap();
            let general = grid.clone().without_power_of_two();
            let n = 1u64 << p;
            for dim in [0u64, 2] {
                let keys = PairKeys::new(&grid, 0x5eed ^ u64::from(p), dim);
                for first in [0, n / 2, n.saturating_sub(300)] {
                    let len = (n - first).min(300) as usize;
                    let first = first as u32;
                    let what = format!("p {p} dim {dim} first {first}");
                    let wide = fill::<f64>(&grid, &keys, dim, first, len);
                    assert_eq!(
                        wide,
                        fill::<f64>(&general, &keys, dim, first, len),
                        "{what}"
                    );
                    let (xf, yf) = fill::<f32>(&grid, &keys, dim, first, len);
                    if p <= 24 {
                        let want = fill::<f32>(&general, &keys, dim, first, len);
                        assert_eq!((&xf, &yf), (&want.0, &want.1), "{what}");
                    }
                    for k in 0..len {
                        let [px, py] = parts(&general, &keys, dim, first + k as u32);
                        let want = (exact_f32(p, px), exact_f32(p, py));
                        assert_eq!((xf[k], yf[k]), want, "{what} k {k}");
                        assert_eq!(pow2.unit_f32(px), want.0, "{what} k {k}");
                    }
                }
            }
        }
    }

    /// The first pair's column runs (`ny ≥ SPAN`) end where a column
    /// does and where the pass wraps from position `N − 1` to 0: spans
    /// that start a few points before either, or on it, give the general
    /// kernel's values (f64, and f32 where they agree by definition) and
    /// the exact f32 ones. Negative control: the same positions read one
    /// point later differ from the kernel's at every point.
    #[test]
    fn first_pair_runs_cross_columns_and_the_pass_end() {
        for p in [16u32, 17, 20, 24, 25, 31] {
            let grid = grid_of(p);
            let general = grid.clone().without_power_of_two();
            let (n_mask, ny, len) = (((1u64 << p) - 1) as u32, grid.ny, 2 * SPAN + 40);
            for before in [0u32, 1, 37, SPAN as u32 - 1, SPAN as u32 + 5] {
                // Positions from the wrap, and from the end of a middle column.
                for target in [0u32, 3 * ny] {
                    let position = target.wrapping_sub(before) & n_mask;
                    // The first pass index reaching `position`, under the
                    // first seed that leaves the points (and one more) in
                    // the pass.
                    let (keys, first) = (0u64..)
                        .map(|seed| {
                            let keys = PairKeys::new(&grid, seed ^ u64::from(p), 0);
                            let first = position.wrapping_sub(keys.offset) & n_mask;
                            (keys, first)
                        })
                        .find(|&(_, first)| u64::from(first) + (len as u64) < 1u64 << p)
                        .unwrap();
                    let what = format!("p {p} before {before} target {target}");
                    let wide = fill::<f64>(&grid, &keys, 0, first, len);
                    assert_eq!(wide, fill::<f64>(&general, &keys, 0, first, len), "{what}");
                    let (xf, yf) = fill::<f32>(&grid, &keys, 0, first, len);
                    for k in 0..len {
                        let [px, py] = parts(&general, &keys, 0, first.wrapping_add(k as u32));
                        assert_eq!(
                            (xf[k], yf[k]),
                            (exact_f32(p, px), exact_f32(p, py)),
                            "{what} k {k}"
                        );
                    }
                    let shifted = fill::<f64>(&grid, &keys, 0, first.wrapping_add(1), len);
                    assert!(wide.0.iter().zip(&shifted.0).all(|(a, b)| a != b), "{what}");
                }
            }
        }
    }

    /// `⌊(k·2³² + h)/2^(p+8)⌋·2⁻²⁴`, in 64-bit integers.
    fn exact_f32(p: u32, (k, h): (u32, u32)) -> f32 {
        let top = ((u64::from(k) << 32) | u64::from(h)) >> (p + 8);
        top as f32 / 16_777_216.0
    }

    /// The strata and jitter bits of position `i` by the cursor's route.
    fn parts(grid: &Grid, keys: &PairKeys, dim: u64, i: u32) -> [(u32, u32); 2] {
        let (c, r) = grid.split(cell_of(grid, keys, dim, i));
        grid.point_parts(keys, c, r, i)
    }

    /// The `(x, y)` coordinates of `len` positions from `first` in
    /// dimension pair `dim`, by the grid's own kernel. (Compared with `==`:
    /// they lie in [0, 1) and are never NaN or −0, so equal values are
    /// equal bits.)
    fn fill<T: Coordinate + Copy + Default>(
        grid: &Grid,
        keys: &PairKeys,
        dim: u64,
        first: u32,
        len: usize,
    ) -> (Vec<T>, Vec<T>) {
        let (mut x, mut y) = (vec![T::default(); len], vec![T::default(); len]);
        fill_pass(grid, keys, dim, first, &mut x, &mut y);
        (x, y)
    }

    /// Where the f64 sum's rounding carries across a 24-bit step (N = 2²²,
    /// a stratum above 2²¹, all-ones jitter), the f32 coordinate is the
    /// exact one, one step below the rounded-down f64 value, as the module
    /// docs say.
    #[test]
    fn the_documented_carry_case_takes_the_exact_value() {
        let grid = grid_of(22);
        let pow2 = grid.power_of_two().unwrap();
        let (k, h) = ((1u32 << 21) + 5, u32::MAX);
        let exact = pow2.unit_f32((k, h));
        let via_f64 = round_down_24(grid.unit(jittered_sum(k, h)));
        assert_eq!(exact.to_bits(), exact_f32(22, (k, h)).to_bits());
        assert_eq!(f64::from(via_f64) - f64::from(exact), 1.0 / 16_777_216.0);
    }

    /// The cursor's f32 points are the batch kernel's on a power-of-two
    /// grid above 2²¹, where the exact form is not the rounded-down f64 one.
    #[test]
    fn the_cursor_gives_the_kernel_f32_points() {
        use crate::sequence::{SampleSequence, Stratified};
        let mut seq = Stratified::new(1 << 23, 4).unwrap();
        let (mut x, mut y) = (vec![0.0f32; 500], vec![0.0f32; 500]);
        let first = (1u64 << 23) - 250; // across the end of pass 0
        for request in [0u64, 1] {
            seq.fill_2d_split_f32(first, request, &mut x, &mut y);
            for k in 0..500 {
                seq.start_sample(first + k as u64);
                for _ in 0..request {
                    seq.next_2d_f32();
                }
                let v = seq.next_2d_f32();
                let want = (x[k].to_bits(), y[k].to_bits());
                assert_eq!(
                    (v.x.to_bits(), v.y.to_bits()),
                    want,
                    "request {request} k {k}"
                );
            }
        }
    }

    /// Negative control for the tests above: the kernels of two different
    /// passes (other keys) do not agree.
    #[test]
    fn other_keys_give_other_points() {
        let grid = grid_of(10);
        let (a, b) = (PairKeys::new(&grid, 1, 0), PairKeys::new(&grid, 2, 0));
        let (pa, pb) = (
            fill::<f64>(&grid, &a, 0, 0, 64),
            fill::<f64>(&grid, &b, 0, 0, 64),
        );
        assert!(pa.0.iter().zip(&pb.0).all(|(a, b)| a != b));
    }

    /// The integer f32 coordinate is the f64 one rounded down, to the bit,
    /// for every `N = 2^p ≤ 2²¹`, at strata 0, 1, the middle and the last,
    /// with jitters at the ends, at the 8-bit seam the formula cuts at, and
    /// spread between.
    #[test]
    fn exact_f32_is_the_f64_coordinate_rounded_down_up_to_2_21() {
        let jitters = (0..64u32).map(|j| j.wrapping_mul(0x9e37_79b9));
        let jitters: Vec<u32> = jitters
            .chain([0, 1, 0xff, 0x100, 0x8000_0000, u32::MAX - 1, u32::MAX])
            .collect();
        for p in 0..=21u32 {
            let grid = grid_of(p);
            let pow2 = grid.power_of_two().unwrap();
            let n = 1u32 << p;
            for k in [0, 1.min(n - 1), n / 2, n - 1] {
                for &h in &jitters {
                    let want = round_down_24(grid.unit(jittered_sum(k, h)));
                    let got = pow2.unit_f32((k, h));
                    assert_eq!(got.to_bits(), want.to_bits(), "p {p} k {k} h {h:#x}");
                }
            }
        }
    }

    /// Only grids whose three sides are powers of two take this kernel.
    #[test]
    fn other_grids_take_the_general_kernel() {
        assert!(PowerOfTwoGrid::new(12, 3, 4).is_none());
        assert!(PowerOfTwoGrid::new(32, 4, 8).is_some());
        assert!(PowerOfTwoGrid::new(u32::MAX, 65_535, 65_537).is_none());
    }
}
