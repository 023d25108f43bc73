//! Jittered stratification for a known sample count `N`.
//!
//! Each 2-D request (a dimension pair `(d, d+1)`) stratifies `[0,1)²` into a
//! grid of `nx × ny = N` cells, with `nx` the largest divisor of `N` not above
//! `√N` and `ny = N / nx` (near-square; `N = 12` gives 3 × 4, `N = 1024`
//! gives 32 × 32). Sample `i` of a pass goes to cell `π_d(i)`, column
//! `c` and row `r` of the grid, where
//!
//! * for the first pair (`d = 0`), the cells are visited column by column:
//!   with `p = (i + b) mod N`, column `c = ⌊p / ny⌋·g_x mod nx` and row
//!   `r = p mod ny`, where `b` is a random offset hashed from the pass
//!   (so each sample's cell is uniform through `b`) and `g_x` the integer
//!   coprime to `nx` nearest `0.618·nx`: the columns come in a spread-out
//!   order (Fibonacci hashing; by the three-distance theorem every run of
//!   whole columns is spread over the grid), each from its first row to
//!   its last;
//! * for later pairs, `π_d` is a pseudo-random permutation of the cells
//!   hashed from `(seed, pass, d)`, so that the cells of different pairs
//!   are paired at random (the idea of pbrt-v4's `StratifiedSampler`, §8.5,
//!   which hashes a permutation per dimension): on a grid whose columns
//!   number `nx ≥ 16`, whose rows number at most `nx²/4` and `2¹⁵`, and
//!   whose `N` is not a power of two, five Feistel rounds on the column
//!   and the row (`stratified_shuffle.rs`); otherwise
//!   a keyed bijection of `w`-bit integers walked until it falls in `0..N`
//!   (`stratified_batch.rs`; for a power of two it never walks).
//!
//! Within its cell the point is jittered in the manner of *multi-jittered*
//! sampling (Chiu, Shirley & Wang 1994, "Multi-jittered sampling", Graphics
//! Gems IV): the cell `(c, r)` is split into `ny` columns and `nx` rows, and
//! the point is placed uniformly at random in column `(r·g_y + s_c) mod ny`
//! and row `(c·g_x + t_r) mod nx` of that cell, with `g_y`, `g_x` the
//! integers coprime to `ny`, `nx` nearest `0.618·ny`, `0.618·nx`, and `s_c`
//! and `t_r` uniform random shifts per column and per row. Kensler 2013
//! ("Correlated Multi-Jittered Sampling") shares one permutation between
//! all columns; a shift per column keeps the columns' patterns independent,
//! which removes Kensler's error term of order `N^(-3/4)` on integrands
//! such as `x·y`. The multiplier `g` matters as much: with the plain
//! rotation `(r + s_c) mod ny`, the cells of one column in adjacent rows put
//! their points one sub-column apart, so neighbouring points sit at nearly
//! the same offset in their cells and their errors add up instead of
//! cancelling (measured on a disk light of angular radius 0.01 sampled
//! through the cosine hemisphere, 2²² samples: relative RMSE 6.3·10⁻² with
//! the rotation, 7.6·10⁻³ with the golden multiplier; 1.2·10⁻⁷ against
//! 2.3·10⁻⁸ on the smooth sphere-light integrand at 2²⁰), while `r·g_y`
//! sends adjacent rows about `0.618·ny` sub-columns apart, every run of rows
//! spread evenly (the three-distance theorem). So
//!
//! ```text
//! x = (c · ny + (r·g_y + s_c) mod ny + ξ₀) / N,    y = (r · nx + (c·g_x + t_r) mod nx + ξ₁) / N,
//! ```
//!
//! with `ξ₀, ξ₁` uniform in `[0, 1)` hashed from `(seed, pass, d, i)` (32
//! bits each: a resolution of `2⁻³²/N`, finer than a Sobol point's `2⁻³²`).
//! Hence:
//!
//! * exactly one point per cell of the `nx × ny` grid (jittered stratification);
//! * exactly one point in each of the `N` intervals `[k/N, (k+1)/N)` of each
//!   axis (a Latin hypercube, the "N-rooks" property).
//!
//! The shifts and the jitters are a keyed 32-bit multiply-xorshift hash
//! (Wellons' two-round hash) of the column, the row and the position, which
//! vector units run sixteen lanes at a time; the shifts are reduced to their
//! range by a multiplication (Lemire's). A 1-D request (`next_1d`) jitters
//! with 53 bits of a counter-based SplitMix64 stream. The values are
//! computed as `(k + ξ)·N⁻¹`, so a point within an ulp of a stratum's edge
//! may round across it.
//!
//! **Why the first pair goes column by column**: the lanes of a vector
//! then share their column, whose shift and spread are computed once, and
//! differ in consecutive rows, whose shifts a batch that covers a whole
//! column hashes once per row into a table and reads by contiguous loads
//! (`stratified_batch.rs`). In the golden order the first pair had before
//! (below), the lanes read scattered columns and rows, so each point
//! hashed and reduced both of its shifts: tables of them would have been
//! read by gathers, which cost more there (measured with both tables
//! built once and gathered by sixteen 32-bit lanes, f32 points, `N =
//! 10⁶`: 1.40–1.45 ns a point against 1.07–1.17 hashed).
//!
//! **Prime `N`** (and `N = 2`, 3): the grid is `1 × N`, horizontal strips,
//! which stratifies `y` only; the Latin-hypercube jitter above still
//! stratifies `x` into `N` intervals, so both 1-D projections stay
//! stratified, but there is no 2-D stratification beyond strips. Choose a
//! composite `N` (a power of two or a square) for a square grid.
//!
//! 1-D requests use the same construction in one dimension:
//! `x = (π_d(i) + ξ) / N`, with a 53-bit `ξ`.
//!
//! **Indices `≥ N`**: index `i` belongs to pass `⌊i / N⌋` at position
//! `i mod N`; each pass is an independent stratified set (its offsets,
//! permutations, shifts and jitter are hashed from `(seed, pass)`), so any
//! prefix of whole passes is a union of stratified sets.
//!
//! **Batches**: [`SampleSequence::fill_2d`] computes a dimension pair for
//! many consecutive samples at once (`stratified_batch.rs`): keys hashed
//! once per batch, the first pair's points column run by column run, the
//! points in vector lanes (for a power-of-two `N`, every modulus a mask
//! and every reduction a shift: `stratified_pow2.rs`); the values are the
//! cursor's, to the bit.
//!
//! **Values before 2026-12**: the sequence used to permute every pair's
//! cells by a keyed permutation and every column's and row's sub-strata by
//! keyed permutations too (three cycle-walking permutations per point, about
//! 4.6 walk steps), and cost 3.5× an independent sample; the present
//! definition keeps both stratification properties, has equal or smaller
//! error on the integrands measured above (the old one: 2.0·10⁻² on the
//! disk, 1.2·10⁻⁷ on the sphere light), and costs less (README, "Speed").
//!
//! **The first pair's order before 2026-12-06**: the cells of the first
//! pair were visited in the order `(i·α + b) mod N`, with `α` the integer
//! coprime to `N` nearest `0.618·N`, so that every prefix of a pass, not
//! only runs of whole columns, was spread over the grid. The change only
//! relabels the points: each cell's point has the same formula in `(c, r,
//! s_c, t_r)` and a jitter hashed from its position, so a whole pass is the
//! same set of points in distribution (for random hashes the jitters of
//! different positions are independent, and later pairs' cells are paired
//! with the first pair's through a random permutation either way), and an
//! estimate over whole passes, which is all the estimator and the study
//! take, has the same error. Measured (relative RMSE over 40 seeds, 16
//! replicates, old → new): a disk of angular radius 0.01 seen 30° off the
//! normal, cosine sampling, `N = 10⁶` 5.15·10⁻³ → 5.12·10⁻³ and `N = 2²⁰`
//! 6.53·10⁻³ → 6.62·10⁻³; the sphere light, light sampling, 2.77·10⁻⁹ →
//! 2.77·10⁻⁹ and 1.97·10⁻⁹ → 1.97·10⁻⁹. It halves the cost of an f32
//! point at `N = 10⁶` (README, "Speed"). What a prefix shorter than a
//! column loses is its spread across columns.
//!
//! **The later pairs' order before 2026-12-06**: on every grid, the cycle
//! walk above (the cell `π_d(i)` then split into column and row by a
//! division). The walk takes a random number of steps per point, which
//! vector lanes wait for, and made a later pair's point cost five times
//! the first pair's at `N = 3 125 000`; the rounds cost the same on every
//! lane and give the column and row at once. Like the first pair's new
//! order, the change relabels the points of each pass (which sample gets
//! which cell of the pair), so a whole pass's error keeps its
//! distribution as long as the pairing stays random; measured in README,
//! "Speed".
//!
//! **f32 output** (2-D requests), for `N ≤ 2²⁴`: the coordinate with its
//! jitter cut to the `s = 24 − ⌈log₂ N⌉` bits an f32 near 1 can show,
//! `q/M` with `q = k·2ˢ + ⌊h/2^(32−s)⌋` and `M = N·2ˢ ≤ 2²⁴`, rounded to
//! the nearest f32 (`stratified_f32.rs`, computed in f32 lanes). It never
//! reaches its stratum's upper edge (nor 1); a point within half an f32
//! step above the lower edge `k/N` may round just below it. On a
//! power-of-two grid this is the exact value `(k + ξ)/N` rounded down to
//! 24 bits. For `N > 2²⁴`, where a stratum near 1 is narrower than an f32
//! step, the f64 value rounded down to 24 bits, except on power-of-two
//! grids, whose f32 value stays the exact one rounded down
//! (`stratified_pow2.rs`, computed in integers). 1-D requests round the
//! f64 value down to 24 bits.
//!
//! **f32 values before 2026-12-06**: every grid's f32 coordinate was the f64
//! one rounded down to 24 bits (on power-of-two grids above `2²¹` the
//! exact one rounded down, an earlier change of 2026-12). On the
//! other grids that route ran in f64 lanes and made an f32 point cost
//! more than an f64 one; the present values differ from those by less
//! than `1/M + 2⁻²⁵ < 2⁻²²` and are the same on power-of-two grids up to
//! `2²⁴` (README, "Speed").

use super::stratified_batch::{cell_of, fill_pass, stream_bits, Coordinate, Grid, PairKeys, BLOCK};
use super::{assert_split_lengths, hash2, u64_to_f64, SampleSequence};
use crate::SamplingError;
use glam::{DVec2, Vec2};

/// Jittered, per-dimension-permuted stratified samples for a known count `N`.
///
/// ```
/// use lambert_sampling::sequence::{SampleSequence, Stratified};
/// let mut seq = Stratified::new(16, 1).unwrap();
/// assert_eq!(seq.grid(), (4, 4));
/// let mut hit = [false; 16];
/// for i in 0..16 {
///     seq.start_sample(i);
///     let u = seq.next_2d();
///     let cell = (u.y * 4.0) as usize * 4 + (u.x * 4.0) as usize;
///     assert!(!hit[cell]);
///     hit[cell] = true;
/// }
/// ```
#[derive(Clone, Debug)]
pub struct Stratified {
    seed: u64,
    /// The grid and what else `N` fixes.
    grid: Grid,
    /// Seed of the current pass, `hash(seed, ⌊index / N⌋)`.
    pass_seed: u64,
    /// Position within the pass, `index mod N`.
    local: u32,
    dim: u64,
}

impl Stratified {
    /// Stratified samples for `sample_count` samples per pass, determined by
    /// `seed`, positioned at sample 0.
    ///
    /// # Errors
    /// [`SamplingError::OutOfRange`] if `sample_count` is 0.
    pub fn new(sample_count: u32, seed: u64) -> Result<Self, SamplingError> {
        if sample_count == 0 {
            return Err(SamplingError::OutOfRange {
                field: "sample_count",
                value: 0.0,
                range: "[1, 2^32 − 1]",
            });
        }
        let (nx, ny) = near_square_grid(sample_count);
        let mut s = Self {
            seed,
            grid: Grid::new(sample_count, nx, ny),
            pass_seed: 0,
            local: 0,
            dim: 0,
        };
        s.start_sample(0);
        Ok(s)
    }

    /// The number of samples per pass, `N`.
    pub fn sample_count(&self) -> u32 {
        self.grid.n
    }

    /// The 2-D grid `(nx, ny)`, `nx · ny = N`, `nx ≤ ny`.
    pub fn grid(&self) -> (u32, u32) {
        (self.grid.nx, self.grid.ny)
    }

    /// The current position's point in the current dimension pair, made
    /// by `point(grid, keys, column, row, position)`, and the cursor moved
    /// to the next pair.
    fn next_point<T>(&mut self, point: impl Fn(&Grid, &PairKeys, u32, u32, u32) -> T) -> T {
        let keys = self.keys();
        let cell = cell_of(&self.grid, &keys, self.dim, self.local);
        let (c, r) = self.grid.split(cell);
        self.dim += 2;
        point(&self.grid, &keys, c, r, self.local)
    }

    /// The keys of the current pass and dimension.
    #[inline]
    fn keys(&self) -> PairKeys {
        PairKeys::new(&self.grid, self.pass_seed, self.dim)
    }
}

/// `(nx, ny)` with `nx · ny = n`, `nx` the largest divisor of `n` not above `√n`.
fn near_square_grid(n: u32) -> (u32, u32) {
    let n64 = u64::from(n);
    let mut nx = (f64::from(n).sqrt() as u64).max(1);
    while nx * nx > n64 {
        nx -= 1;
    }
    while (nx + 1) * (nx + 1) <= n64 {
        nx += 1;
    }
    while n64 % nx != 0 {
        nx -= 1;
    }
    (nx as u32, (n64 / nx) as u32)
}

impl Stratified {
    /// Request `request` of samples `first..first + x.len()`, pass by
    /// pass, as f64 or f32 coordinates written to `x` and `y`: the batch
    /// kernel of `stratified_batch.rs`.
    #[inline(always)]
    fn fill_points<T: Coordinate>(&self, first: u64, request: u64, x: &mut [T], y: &mut [T]) {
        let n = u64::from(self.grid.n);
        let dim = 2 * request;
        let len = x.len();
        let mut done = 0usize;
        while done < len {
            let index = first.wrapping_add(done as u64);
            let (pass, local) = (index / n, (index % n) as u32);
            // Up to the end of the pass, of the batch, or of the index range
            // (after 2^64 − 1 comes 0, the start of pass 0).
            let room = (n - u64::from(local) - 1)
                .min((len - done - 1) as u64)
                .min(u64::MAX - index)
                + 1;
            let room = room as usize;
            let keys = PairKeys::new(&self.grid, hash2(self.seed, pass), dim);
            let (x, y) = (&mut x[done..done + room], &mut y[done..done + room]);
            fill_pass(&self.grid, &keys, dim, local, x, y);
            done += room;
        }
    }

    /// Request `request` of samples `first..first + out.len()` from the
    /// batch kernel in coordinates of type `C`, block by block, each point
    /// made by `make(x, y)`.
    #[inline(always)]
    fn fill_made<C: Coordinate + Copy + Default, T>(
        &self,
        first: u64,
        request: u64,
        out: &mut [T],
        make: impl Fn(C, C) -> T,
    ) {
        let (mut x, mut y) = ([C::default(); BLOCK], [C::default(); BLOCK]);
        for (b, out) in out.chunks_mut(BLOCK).enumerate() {
            let (x, y) = (&mut x[..out.len()], &mut y[..out.len()]);
            self.fill_points(first.wrapping_add((b * BLOCK) as u64), request, x, y);
            for (o, (&x, &y)) in out.iter_mut().zip(x.iter().zip(&*y)) {
                *o = make(x, y);
            }
        }
    }
}

impl SampleSequence for Stratified {
    fn start_sample(&mut self, index: u64) {
        let n = u64::from(self.grid.n);
        self.pass_seed = hash2(self.seed, index / n);
        self.local = (index % n) as u32;
        self.dim = 0;
    }

    fn next_1d(&mut self) -> f64 {
        let keys = self.keys();
        let k = cell_of(&self.grid, &keys, self.dim, self.local);
        let jitter = u64_to_f64(stream_bits(keys.jitter, u64::from(self.local)));
        let x = self.grid.unit(f64::from(k) + jitter);
        self.dim += 1;
        x
    }

    fn next_2d(&mut self) -> DVec2 {
        self.next_point(Grid::point)
    }

    /// The point's f32 coordinates (module docs): for `N ≤ 2²⁴` the
    /// nearest f32 to the coordinate with its jitter cut to `24 − ⌈log₂
    /// N⌉` bits; above, the f64 point rounded down to 24 bits (on a
    /// power-of-two grid the exact point rounded down).
    fn next_2d_f32(&mut self) -> Vec2 {
        self.next_point(Grid::point_f32)
    }

    /// The batch kernel of `stratified_batch.rs`: the same values as the
    /// cursor, to the bit. Inlined, so it runs in the caller's instruction
    /// set (the estimator calls it inside `Isa::run`).
    #[inline(always)]
    fn fill_2d(&self, first: u64, request: u64, out: &mut [DVec2]) {
        self.fill_made(first, request, out, DVec2::new);
    }

    /// The batch kernel of [`fill_2d`](SampleSequence::fill_2d), written
    /// to two arrays.
    #[inline(always)]
    fn fill_2d_split(&self, first: u64, request: u64, x: &mut [f64], y: &mut [f64]) {
        assert_split_lengths("fill_2d_split", x.len(), y.len());
        self.fill_points(first, request, x, y);
    }

    /// The batch kernel, storing [`next_2d_f32`](SampleSequence::next_2d_f32)'s
    /// coordinates, computed in f32 lanes: no f64 arrays in between.
    #[inline(always)]
    fn fill_2d_split_f32(&self, first: u64, request: u64, x: &mut [f32], y: &mut [f32]) {
        assert_split_lengths("fill_2d_split_f32", x.len(), y.len());
        self.fill_points(first, request, x, y);
    }

    /// The batch kernel in f32: the cursor's
    /// [`next_2d_f32`](SampleSequence::next_2d_f32) values, to the bit.
    fn fill_2d_f32(&self, first: u64, request: u64, out: &mut [Vec2]) {
        self.fill_made(first, request, out, Vec2::new);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sequence::round_down_24;

    #[test]
    fn grids_are_near_square() {
        assert_eq!(near_square_grid(1), (1, 1));
        assert_eq!(near_square_grid(2), (1, 2));
        assert_eq!(near_square_grid(12), (3, 4));
        assert_eq!(near_square_grid(13), (1, 13));
        assert_eq!(near_square_grid(16), (4, 4));
        assert_eq!(near_square_grid(1000), (25, 40));
        assert_eq!(near_square_grid(1024), (32, 32));
        assert_eq!(near_square_grid(u32::MAX), (65535, 65537));
    }

    /// Element `i` of the keyed permutation of `0..n` that orders the cells
    /// of the later dimension pairs: a bijection of `w`-bit integers
    /// (`2^w ≥ n`, the smallest such) built from invertible steps — xor with a
    /// key, multiplication by an odd key, addition, xorshift right, all mod
    /// `2^w` — applied until the value falls below `n` (cycle walking, Black &
    /// Rogaway 2002).
    fn permute(i: u32, n: u32, key: u64) -> u32 {
        use crate::sequence::stratified_batch::{Domain, PermuteKeys};
        Domain::new(n).permute(i, &PermuteKeys::new(key))
    }

    #[test]
    fn permute_is_a_permutation() {
        for n in [1u32, 2, 3, 5, 16, 17, 100, 1000, 4096] {
            for key in 0..4u64 {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let p = permute(i, n, key) as usize;
                    assert!(!seen[p]);
                    seen[p] = true;
                }
            }
        }
        // Different keys give different permutations.
        let a: Vec<u32> = (0..64).map(|i| permute(i, 64, 1)).collect();
        let b: Vec<u32> = (0..64).map(|i| permute(i, 64, 2)).collect();
        assert_ne!(a, b);
        // Large domains work (w = 32).
        let n = u32::MAX;
        assert!(permute(n - 1, n, 9) < n);
    }

    /// For each dimension pair of a pass: one point per grid cell, and one
    /// point per `1/N` interval on each axis; 1-D dimensions one per interval.
    #[test]
    fn one_point_per_stratum_in_every_dimension_pair() {
        for n in [1u32, 2, 7, 12, 13, 16, 64, 97, 1000] {
            for seed in [0u64, 1, 0xdead_beef] {
                let mut seq = Stratified::new(n, seed).unwrap();
                let (nx, ny) = seq.grid();
                // Pass 0 and pass 2 (indices 2N..3N).
                for pass in [0u64, 2] {
                    let mut cells = vec![vec![0u32; n as usize]; 3];
                    let mut xs = vec![vec![0u32; n as usize]; 3];
                    let mut ys = vec![vec![0u32; n as usize]; 3];
                    let mut one_d = vec![0u32; n as usize];
                    for i in 0..u64::from(n) {
                        seq.start_sample(pass * u64::from(n) + i);
                        for p in 0..3 {
                            let u = seq.next_2d();
                            let (cx, cy) = ((u.x * nx as f64) as u32, (u.y * ny as f64) as u32);
                            cells[p][(cy * nx + cx) as usize] += 1;
                            xs[p][(u.x * n as f64) as usize] += 1;
                            ys[p][(u.y * n as f64) as usize] += 1;
                        }
                        one_d[(seq.next_1d() * n as f64) as usize] += 1;
                    }
                    for p in 0..3 {
                        assert!(cells[p].iter().all(|&c| c == 1), "n {n} pair {p}");
                        assert!(xs[p].iter().all(|&c| c == 1), "n {n} pair {p} x");
                        assert!(ys[p].iter().all(|&c| c == 1), "n {n} pair {p} y");
                    }
                    assert!(one_d.iter().all(|&c| c == 1), "n {n} 1-D");
                }
            }
        }
    }

    /// The variance, over passes, of the pass mean of `x·x' + y·y'`, with
    /// `(x, y)` from pair `p` of sequence `a` and `(x', y')` from pair `q`
    /// of sequence `b`, as a multiple of what a uniformly random pairing
    /// of two stratified sets gives: `2·(1/12)²/(N − 1)` (each product's
    /// mean over a random matching of two sets of variance `1/12` has
    /// variance `(1/12)²/(N − 1)`; the means sit within `O(N⁻²)` of ½).
    fn pairing_variance_ratio(
        a: &Stratified,
        b: &Stratified,
        [p, q]: [u64; 2],
        passes: u64,
    ) -> f64 {
        let n = a.sample_count();
        let (mut u, mut v) = (vec![DVec2::ZERO; n as usize], vec![DVec2::ZERO; n as usize]);
        let mut sum = 0.0;
        for pass in 0..passes {
            let first = pass * u64::from(n);
            a.fill_2d(first, p, &mut u);
            b.fill_2d(first, q, &mut v);
            let products = u.iter().zip(&v).map(|(u, v)| u.x * v.x + u.y * v.y);
            let mean = products.sum::<f64>() / f64::from(n);
            sum += (mean - 0.5) * (mean - 0.5);
        }
        let random = 2.0 / 144.0 / (f64::from(n) - 1.0);
        sum / passes as f64 / random
    }

    /// The later pairs are paired with the first pair and with each other
    /// as at random: on the grids that shuffle (25 × 40, 25 × 125, 100 ×
    /// 100; `stratified_shuffle.rs`) and two that walk (N = 2 × 499, and
    /// 16 × 1031, too long for its width), the variance ratio of
    /// [`pairing_variance_ratio`] is 1 within its sampling error. Over `K =
    /// 2000` passes the pass means are normal (sums of `N` terms), so the
    /// ratio is `χ²_K/K`, of standard deviation `√(2/K) = 0.032`; ten
    /// ratios at a family level of 0.001, Šidák-corrected to 10⁻⁴ each,
    /// two-sided: |ratio − 1| ≤ 3.89·0.032 = 0.12. A shuffle of four
    /// rounds, whose rows kept their differences in groups, measured 1.50
    /// on 25 × 125, and five rounds on 16 × 1031 measured 1.32; the
    /// negative control, the first pairs of two seeds (both column by
    /// column, so matched by a shift), measures hundreds.
    #[test]
    fn later_pairs_are_paired_at_random() {
        const PASSES: u64 = 2000;
        const TOLERANCE: f64 = 3.89 * 0.0316;
        for n in [1000u32, 3125, 10_000, 998, 16 * 1031] {
            let seq = Stratified::new(n, 11).unwrap();
            for pairs in [[0, 1], [1, 2]] {
                let ratio = pairing_variance_ratio(&seq, &seq, pairs, PASSES);
                assert!(
                    (ratio - 1.0).abs() <= TOLERANCE,
                    "N {n} pairs {pairs:?}: {ratio}"
                );
            }
        }
        let other = Stratified::new(3125, 12).unwrap();
        let first = Stratified::new(3125, 11).unwrap();
        let ratio = pairing_variance_ratio(&first, &other, [0, 0], PASSES);
        assert!(ratio > 1.0 + TOLERANCE, "control: {ratio}");
    }

    #[test]
    fn deterministic_and_seed_dependent() {
        let read = |seed: u64| {
            let mut s = Stratified::new(64, seed).unwrap();
            (0..64u64)
                .map(|i| {
                    s.start_sample(i);
                    (s.next_2d(), s.next_1d(), s.next_2d())
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(read(5), read(5));
        assert_ne!(read(5), read(6));
        // Random access: out of order reads give the same points.
        let all = read(5);
        let mut s = Stratified::new(64, 5).unwrap();
        for i in (0..64u64).rev() {
            s.start_sample(i);
            assert_eq!((s.next_2d(), s.next_1d(), s.next_2d()), all[i as usize]);
        }
    }

    #[test]
    fn dimension_pairs_are_decorrelated() {
        // The cell of sample i differs between pairs (0,1) and (2,3).
        let mut s = Stratified::new(256, 3).unwrap();
        let mut same = 0;
        for i in 0..256u64 {
            s.start_sample(i);
            let a = s.next_2d();
            let b = s.next_2d();
            if ((a * 16.0).floor()) == ((b * 16.0).floor()) {
                same += 1;
            }
        }
        assert!(same < 8, "{same} of 256 samples share a cell");
    }

    #[test]
    fn rejects_zero_count() {
        assert!(matches!(
            Stratified::new(0, 1),
            Err(SamplingError::OutOfRange {
                field: "sample_count",
                ..
            })
        ));
    }

    /// The f32 coordinate computed without the f64 one (`Grid::unit_f32`)
    /// is the f64 one rounded down to 24 bits, to the bit: on every grid
    /// size class (1, primes, powers of two, N above 2²⁴ where a stratum
    /// is finer than an f32 step, the largest N) and on strata at the ends
    /// and the middle with jitters 0, ½, the largest and a spread of others.
    #[test]
    fn f32_coordinates_are_the_f64_ones_rounded_down() {
        for n in [
            1u32,
            2,
            3,
            7,
            1 << 10,
            1 << 24,
            (1 << 24) + 1,
            3_125_000,
            u32::MAX,
        ] {
            let (nx, ny) = near_square_grid(n);
            let grid = Grid::new(n, nx, ny);
            let jitters = (0..64u64).map(|j| j.wrapping_mul(0x9e37_79b9_7f4a_7c15));
            let jitters = jitters.chain([0, 1 << 63, u64::MAX, u64::MAX >> 1]);
            for bits in jitters {
                for k in [0, 1, n / 2, n / 3, n.saturating_sub(2), n - 1] {
                    let sum = f64::from(k) + u64_to_f64(bits);
                    let want = round_down_24(grid.unit(sum));
                    assert_eq!(grid.unit_f32(sum).to_bits(), want.to_bits(), "n {n} k {k}");
                }
            }
        }
    }

    /// The batch kernels' coordinates, made from a stratum `k` and 32
    /// jitter bits `h` through the fixed-point sum `k·2³² + h`
    /// (`Grid::unit_of_parts`, `Grid::unit_f32_of_wide_parts`), are those
    /// of the f64 sum `k + h·2⁻³²`, to the bit, in both precisions: on
    /// grids below and above 2²¹ (where that sum starts to round) and
    /// 2²⁴, at the strata's ends and middle, with the jitter's extreme
    /// bits and a spread of hashed ones. The f32 coordinate
    /// (`Grid::unit_f32_of_parts`) is `stratified_f32.rs`'s up to `N =
    /// 2²⁴` and the wide form above, and lies within `2⁻²²` of the f64
    /// one (module docs: `1/M + 2⁻²⁵`).
    #[test]
    fn coordinates_of_parts_are_those_of_the_rounded_sum() {
        use super::super::stratified_batch::hash_u32;
        use super::super::stratified_f32::F32Coordinate;
        use super::super::stratified_pow2::jittered_sum;
        for n in [
            1u32,
            2,
            3,
            7,
            1000,
            1 << 20,
            1_000_000,
            (1 << 21) + 1,
            3_125_000,
            (1 << 24) + 1,
            u32::MAX,
        ] {
            let (nx, ny) = near_square_grid(n);
            let grid = Grid::new(n, nx, ny);
            let hashed = (0..256u32).map(|j| hash_u32(0x243f_6a88_85a3_08d3, j));
            let jitters = hashed.chain([0, 1, 1 << 31, u32::MAX - 1, u32::MAX]);
            for h in jitters {
                for k in [0, 1, n / 3, n / 2, n.saturating_sub(2), n - 1] {
                    let x = grid.unit(jittered_sum(k, h));
                    let got = grid.unit_of_parts(k, h);
                    assert_eq!(got.to_bits(), x.to_bits(), "n {n} k {k} h {h}");
                    let wide = grid.unit_f32_of_wide_parts(k, h);
                    let want = round_down_24(x);
                    assert_eq!(wide.to_bits(), want.to_bits(), "n {n} k {k} h {h}");
                    if k >= n {
                        continue; // k = 1 for n = 1: no such stratum
                    }
                    let got = grid.unit_f32_of_parts(k, h);
                    let form = F32Coordinate::new(n).map_or(wide, |f| f.unit((k, h)));
                    assert_eq!(got.to_bits(), form.to_bits(), "n {n} k {k} h {h}");
                    // (The subtraction's rounding is far below the bound.)
                    let off = (f64::from(got) - x).abs();
                    assert!(off < 1.0 / 4_194_304.0, "n {n} k {k} h {h}: {off:e}");
                }
            }
        }
    }

    #[test]
    fn never_one_even_on_adversarial_jitter() {
        // Largest stratum, all-ones jitter: k + ξ rounds up to n in f64.
        let n = u32::MAX;
        let unit = |k: u32, bits: u64, n: u32| {
            let (nx, ny) = near_square_grid(n);
            let grid = Grid::new(n, nx, ny);
            let sum = f64::from(k) + u64_to_f64(bits);
            let x = grid.unit(sum);
            assert_eq!(grid.unit_f32(sum), round_down_24(x), "n {n} k {k}");
            x
        };
        let x = unit(n - 1, u64::MAX, n);
        assert!(x < 1.0);
        assert!(round_down_24(x) < 1.0);
        for n in [1u32, 2, 3, 1 << 24, (1 << 24) + 1] {
            let x = unit(n - 1, u64::MAX, n);
            assert!(x < 1.0 && round_down_24(x) < 1.0, "n {n}");
        }
        let mut s = Stratified::new(u32::MAX, 8).unwrap();
        for i in [0u64, 1, u64::from(u32::MAX) - 1, u64::MAX] {
            s.start_sample(i);
            let v = s.next_2d_f32();
            let u = s.next_2d();
            assert!(v.x < 1.0 && v.y < 1.0 && u.x < 1.0 && u.y < 1.0);
            assert!(s.next_1d_f32() < 1.0);
        }
    }
}
