//! Jittered stratification for a known sample count `N`.
//!
//! Each 2-D request (a dimension pair `(d, d+1)`) stratifies `[0,1)²` into a
//! grid of `nx × ny = N` cells, with `nx` the largest divisor of `N` not above
//! `√N` and `ny = N / nx` (near-square; `N = 12` gives 3 × 4, `N = 1024`
//! gives 32 × 32). Sample `i` of a pass goes to cell `π_d(i)`, where `π_d` is
//! a pseudo-random permutation of `0..N` hashed from `(seed, d)`, so that
//! different dimension pairs are decorrelated (the idea of pbrt-v4's
//! `StratifiedSampler`, §8.5, which hashes a permutation per dimension).
//!
//! Within its cell the point is jittered in the manner of *multi-jittered*
//! sampling (Chiu, Shirley & Wang 1994, "Multi-jittered sampling", Graphics
//! Gems IV; in the hashed form of Kensler 2013, "Correlated Multi-Jittered
//! Sampling", Pixar Technical Memo 13-01, but with a permutation per column
//! and per row rather than Kensler's shared one): the cell `(c, r)` is split
//! into `ny` columns and `nx` rows, and the point is placed uniformly at
//! random in column `σ_{d,c}(r)` and row `τ_{d,r}(c)` of that cell (hashed
//! permutations of `0..ny` and `0..nx`), so
//!
//! ```text
//! x = (c · ny + σ_{d,c}(r) + ξ₀) / N,    y = (r · nx + τ_{d,r}(c) + ξ₁) / N,
//! ```
//!
//! with `ξ₀, ξ₁` uniform in `[0, 1)` hashed from `(seed, d, i)`. Hence:
//!
//! * exactly one point per cell of the `nx × ny` grid (jittered stratification);
//! * exactly one point in each of the `N` intervals `[k/N, (k+1)/N)` of each
//!   axis (a Latin hypercube, the "N-rooks" property).
//!
//! **Prime `N`** (and `N = 2`, 3): the grid is `1 × N`, horizontal strips,
//! which stratifies `y` only; the Latin-hypercube jitter above still
//! stratifies `x` into `N` intervals, so both 1-D projections stay
//! stratified, but there is no 2-D stratification beyond strips. Choose a
//! composite `N` (a power of two or a square) for a square grid.
//!
//! 1-D requests use the same construction in one dimension:
//! `x = (π_d(i) + ξ) / N`.
//!
//! **Indices `≥ N`**: index `i` belongs to pass `⌊i / N⌋` at position
//! `i mod N`; each pass is an independent stratified set (its permutations
//! and jitter are hashed from `(seed, pass)`), so any prefix of whole passes
//! is a union of stratified sets.
//!
//! **Batches**: [`SampleSequence::fill_2d`] computes a dimension pair for
//! many consecutive samples at once (`stratified_batch.rs`): keys hashed
//! once per batch, the column and row keys tabulated once per pass and
//! dimension pair, exact division by a precomputed reciprocal; the values
//! are the cursor's, to the bit.
//!
//! f32 output is the f64 value truncated to 24 bits, so a point lying within
//! `2^-24` above a stratum boundary `k/N` may fall just below it in f32.

use std::sync::Arc;

use super::stratified_batch::{
    fill_pass, stratum_to_unit, Domain, KeyCache, PassPlan, PermuteKeys, BLOCK,
};
use super::{f64_to_f32_unit, hash2, hash3, mix64, SampleSequence};
use crate::SamplingError;
use glam::{DVec2, Vec2};

/// Tags separating the hashes of one dimension.
const TAG_CELL: u64 = 0x6365_6c6c; // "cell"
const TAG_SIGMA: u64 = 0x0073_6967_6d61; // "sigma"
const TAG_TAU: u64 = 0x0074_6175; // "tau"

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
    n: u32,
    nx: u32,
    ny: u32,
    /// Seed of the current pass, `hash(seed, ⌊index / N⌋)`.
    pass_seed: u64,
    /// Position within the pass, `index mod N`.
    local: u32,
    dim: u64,
    /// Tabulated column and row keys for the batch fills, shared by clones.
    cache: Arc<KeyCache>,
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
            n: sample_count,
            nx,
            ny,
            pass_seed: 0,
            local: 0,
            dim: 0,
            cache: Arc::default(),
        };
        s.start_sample(0);
        Ok(s)
    }

    /// The number of samples per pass, `N`.
    pub fn sample_count(&self) -> u32 {
        self.n
    }

    /// The 2-D grid `(nx, ny)`, `nx · ny = N`, `nx ≤ ny`.
    pub fn grid(&self) -> (u32, u32) {
        (self.nx, self.ny)
    }

    /// Hash key of the current dimension for `tag`.
    #[inline]
    fn key(&self, tag: u64) -> u64 {
        hash3(self.pass_seed, self.dim, tag)
    }

    /// Jitter bits of the current (pass, dimension, sample).
    #[inline]
    fn jitter_bits(&self) -> u64 {
        hash3(self.pass_seed, self.dim, u64::from(self.local))
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

/// Element `i` of a pseudo-random permutation of `0..n` determined by `key`
/// (`i < n`, `n ≥ 1`).
///
/// A bijection of `w`-bit integers (`2^w ≥ n`, the smallest such) built from
/// invertible steps — xor with a key, multiplication by an odd key, addition,
/// xorshift right, all mod `2^w` — applied repeatedly until the value falls
/// below `n` (cycle walking, Black & Rogaway 2002), which restricts the
/// bijection to `0..n`; fewer than 2 rounds on average since `2^w < 2n`.
/// The steps are [`Domain`]'s, shared with the batch kernel.
#[inline]
pub(crate) fn permute(i: u32, n: u32, key: u64) -> u32 {
    Domain::new(n).permute(i, &PermuteKeys::new(key))
}

impl SampleSequence for Stratified {
    fn start_sample(&mut self, index: u64) {
        let n = u64::from(self.n);
        self.pass_seed = hash2(self.seed, index / n);
        self.local = (index % n) as u32;
        self.dim = 0;
    }

    fn next_1d(&mut self) -> f64 {
        let k = permute(self.local, self.n, self.key(TAG_CELL));
        let x = stratum_to_unit(k, self.jitter_bits(), self.n);
        self.dim += 1;
        x
    }

    fn next_2d(&mut self) -> DVec2 {
        let (nx, ny) = (self.nx, self.ny);
        let cell = permute(self.local, self.n, self.key(TAG_CELL));
        let (c, r) = (cell % nx, cell / nx);
        // One permutation per column (x) and per row (y): a permutation shared
        // by all columns (Kensler's "correlated" variant) leaves an error term
        // of order N^(-3/4) on smooth integrands such as x·y.
        let kx = c * ny + permute(r, ny, hash2(self.key(TAG_SIGMA), u64::from(c)));
        let ky = r * nx + permute(c, nx, hash2(self.key(TAG_TAU), u64::from(r)));
        let bits = self.jitter_bits();
        let u = DVec2::new(
            stratum_to_unit(kx, bits, self.n),
            stratum_to_unit(ky, mix64(bits), self.n),
        );
        self.dim += 2;
        u
    }

    fn next_2d_f32(&mut self) -> Vec2 {
        let u = self.next_2d();
        Vec2::new(f64_to_f32_unit(u.x), f64_to_f32_unit(u.y))
    }

    /// The batch kernel of `stratified_batch.rs`: the same values as the
    /// cursor, to the bit. Inlined, so it runs in the caller's instruction
    /// set (the estimator calls it inside `Isa::run`).
    #[inline(always)]
    fn fill_2d(&self, first: u64, request: u64, out: &mut [DVec2]) {
        let n = u64::from(self.n);
        let dim = 2 * request;
        let mut done = 0usize;
        while done < out.len() {
            let index = first.wrapping_add(done as u64);
            let (pass, local) = (index / n, (index % n) as u32);
            // Up to the end of the pass, of the batch, or of the index range
            // (after 2^64 − 1 comes 0, the start of pass 0).
            let room = (n - u64::from(local) - 1)
                .min((out.len() - done - 1) as u64)
                .min(u64::MAX - index)
                + 1;
            let room = room as usize;
            let pass_seed = hash2(self.seed, pass);
            let h = hash2(pass_seed, dim);
            let plan = PassPlan {
                n: self.n,
                nx: self.nx,
                ny: self.ny,
                cell: PermuteKeys::new(hash2(h, TAG_CELL)),
                sigma_key: hash2(h, TAG_SIGMA),
                tau_key: hash2(h, TAG_TAU),
                jitter_seed: h,
            };
            fill_pass(
                &plan,
                &self.cache,
                pass_seed,
                dim,
                local,
                &mut out[done..done + room],
            );
            done += room;
        }
    }

    fn fill_2d_f32(&self, first: u64, request: u64, out: &mut [Vec2]) {
        let mut wide = [DVec2::ZERO; BLOCK];
        for (b, out) in out.chunks_mut(BLOCK).enumerate() {
            let wide = &mut wide[..out.len()];
            self.fill_2d(first.wrapping_add((b * BLOCK) as u64), request, wide);
            for (o, u) in out.iter_mut().zip(wide.iter()) {
                *o = Vec2::new(f64_to_f32_unit(u.x), f64_to_f32_unit(u.y));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn never_one_even_on_adversarial_jitter() {
        // Largest stratum, all-ones jitter: k + ξ rounds up to n in f64.
        let n = u32::MAX;
        let x = stratum_to_unit(n - 1, u64::MAX, n);
        assert!(x < 1.0);
        assert!(f64_to_f32_unit(x) < 1.0);
        for n in [1u32, 2, 3, 1 << 24, (1 << 24) + 1] {
            let x = stratum_to_unit(n - 1, u64::MAX, n);
            assert!(x < 1.0 && f64_to_f32_unit(x) < 1.0, "n {n}");
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
