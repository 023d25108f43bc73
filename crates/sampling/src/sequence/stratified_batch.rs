//! Stratified points of many consecutive samples at once: the kernel behind
//! [`Stratified`](super::Stratified)'s batch fills, and the keyed
//! permutation both paths share.
//!
//! Point by point, a 2-D request hashes eight splitmix64 keys (the cell
//! permutation's, and one per column `c` and per row `r` for the
//! multi-jitter permutations `σ_{d,c}` and `τ_{d,r}`), walks three cycle-
//! walking permutations, divides by `nx` and hashes the jitter. Of this,
//! per batch:
//!
//! * the cell permutation's keys depend on `(pass, dimension)` only: hashed
//!   once per batch ([`PermuteKeys`]);
//! * the column and row keys depend on `(pass, dimension, c)` and
//!   `(pass, dimension, r)`: `nx + ny` of them per dimension pair, against
//!   two hashes of four splitmix64 rounds per sample. They are tabulated
//!   ([`GridKeys`]) once enough samples of the pair have been asked for that
//!   the table costs less than hashing them per sample (the rent-or-buy
//!   rule: build after `(nx + ny)/2` samples, so the total is at most twice
//!   the cheaper of the two), and the table is shared by every clone of the
//!   sequence, on every thread;
//! * `cell mod nx` and `cell / nx` use a precomputed reciprocal
//!   ([`FastDiv`], Lemire, Kaser & Kurz 2019, "Faster remainder by direct
//!   computation"), exact for all 32-bit operands;
//! * the permutation's constant multiplications fold into one per round
//!   (multiplication and masking to `w` bits commute modulo `2^32`).
//!
//! The cycle walk is split: one walk step for a whole block (branch-free,
//! structure of arrays), then the lanes that fell outside `0..n` (fewer
//! than half, since `2^w < 2n`; 25 to 40 % for the grids of an estimate)
//! are listed without branches and stepped in rounds, each round listing
//! again those still outside, so that no branch depends on a random walk
//! length. Every value is the point-by-point value to the bit.
//!
//! What remains is the work the values are defined by: about 4.6
//! permutation steps per point (`1/p` each, `p = n/2^w`: 1.34 for the
//! cells of a 3 125 000-sample pass, 1.64 for its 2500 rows and 1250
//! columns), of two rounds with two 32-bit multiplications each, and three
//! splitmix64 rounds for the jitter.

use std::sync::{Arc, Mutex};

use super::{clamp_unit, hash2, mix64, u64_to_f64};

/// Samples per block of the structure-of-arrays loops.
pub(super) const BLOCK: usize = 256;

/// `0x2c1b_3c6d`, the fixed odd multiplier of every permutation round.
const ROUND_MULTIPLIER: u32 = 0x2c1b_3c6d;

/// The keys of the two rounds of one permutation of [`permute`]: per round
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

    /// One step of the cycle walk: two rounds of invertible operations on
    /// `w`-bit integers (a bijection of `0..2^w`).
    #[inline(always)]
    fn step(self, mut x: u32, keys: &PermuteKeys) -> u32 {
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
            ((u128::from(self.m) * u128::from(x)) >> 64) as u32
        };
        (q, x - q * self.d)
    }
}

/// The multi-jitter permutation keys of every column (`σ_{d,c}`, permuting
/// `0..ny`) and every row (`τ_{d,r}`, permuting `0..nx`) of one pass and
/// dimension pair.
#[derive(Debug)]
pub(super) struct GridKeys {
    sigma: Vec<PermuteKeys>,
    tau: Vec<PermuteKeys>,
}

impl GridKeys {
    /// `σ` keys `hash2(sigma_key, c)` for `c < nx`, `τ` keys
    /// `hash2(tau_key, r)` for `r < ny`.
    fn new(sigma_key: u64, tau_key: u64, nx: u32, ny: u32) -> Self {
        GridKeys {
            sigma: (0..nx)
                .map(|c| PermuteKeys::new(hash2(sigma_key, u64::from(c))))
                .collect(),
            tau: (0..ny)
                .map(|r| PermuteKeys::new(hash2(tau_key, u64::from(r))))
                .collect(),
        }
    }
}

/// Tabulated [`GridKeys`] shared by the clones of a sequence, keyed by
/// `(pass seed, dimension)`, with the count of samples served without a
/// table (the rent-or-buy rule). Only speed depends on it, never a value.
#[derive(Default)]
pub(super) struct KeyCache {
    entries: Mutex<Vec<CacheEntry>>,
}

struct CacheEntry {
    pass_seed: u64,
    dim: u64,
    served: u64,
    keys: Option<Arc<GridKeys>>,
}

/// Pairs whose keys the cache keeps (the oldest is dropped beyond).
const CACHE_ENTRIES: usize = 32;

impl std::fmt::Debug for KeyCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.entries.lock().map(|e| e.len()).unwrap_or(0);
        write!(f, "KeyCache({n} pairs)")
    }
}

impl KeyCache {
    /// The keys of `(pass_seed, dim)` for a batch of `len` samples: the
    /// cached table, or a new one once the samples asked for reach
    /// `(nx + ny)/2`, or `None` (hash per sample) before.
    fn grid_keys(
        &self,
        plan: &PassPlan,
        pass_seed: u64,
        dim: u64,
        len: usize,
    ) -> Option<Arc<GridKeys>> {
        // A poisoned lock only means another thread panicked while holding
        // it; the entries are still valid (each is written whole).
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        let at = match entries
            .iter()
            .position(|e| e.pass_seed == pass_seed && e.dim == dim)
        {
            Some(at) => at,
            None => {
                if entries.len() >= CACHE_ENTRIES {
                    entries.remove(0);
                }
                entries.push(CacheEntry {
                    pass_seed,
                    dim,
                    served: 0,
                    keys: None,
                });
                entries.len() - 1
            }
        };
        let entry = &mut entries[at];
        if entry.keys.is_none() {
            entry.served += len as u64;
            if 2 * entry.served >= u64::from(plan.nx) + u64::from(plan.ny) {
                let keys = GridKeys::new(plan.sigma_key, plan.tau_key, plan.nx, plan.ny);
                entry.keys = Some(Arc::new(keys));
            }
        }
        entry.keys.clone()
    }
}

/// Everything a batch of one pass and dimension pair needs.
pub(super) struct PassPlan {
    /// Samples per pass, `N`.
    pub n: u32,
    /// Columns of the grid.
    pub nx: u32,
    /// Rows of the grid.
    pub ny: u32,
    /// Keys of the cell permutation.
    pub cell: PermuteKeys,
    /// `hash3(pass seed, d, "sigma")`: `σ_{d,c}` is keyed by `hash2(this, c)`.
    pub sigma_key: u64,
    /// `hash3(pass seed, d, "tau")`: `τ_{d,r}` is keyed by `hash2(this, r)`.
    pub tau_key: u64,
    /// `hash2(pass seed, d)`: the jitter of sample `i` is `hash2(this, i)`.
    pub jitter_seed: u64,
}

/// The 2-D points of positions `first … first + out.len() − 1` of one pass
/// (all `< n`), written to `out`. Inlined into the caller's instruction set.
#[inline(always)]
pub(super) fn fill_pass(
    plan: &PassPlan,
    cache: &KeyCache,
    pass_seed: u64,
    dim: u64,
    first: u32,
    out: &mut [glam::DVec2],
) {
    let (n, nx, ny) = (plan.n, plan.nx, plan.ny);
    debug_assert!(u64::from(first) + out.len() as u64 <= u64::from(n));
    let grid = cache.grid_keys(plan, pass_seed, dim, out.len());
    let (cells, columns, rows) = (Domain::new(n), Domain::new(ny), Domain::new(nx));
    let div = FastDiv::new(nx);
    let mut cell = [0u32; BLOCK];
    let mut c = [0u32; BLOCK];
    let mut r = [0u32; BLOCK];
    let mut sx = [0u32; BLOCK];
    let mut sy = [0u32; BLOCK];
    for (b, out) in out.chunks_mut(BLOCK).enumerate() {
        let m = out.len();
        let base = first + (b * BLOCK) as u32;
        let cell = &mut cell[..m];
        for (k, x) in cell.iter_mut().enumerate() {
            *x = base + k as u32;
        }
        cells.permute_block(cell, |_| &plan.cell);
        for k in 0..m {
            // (c, r) = (cell mod nx, cell / nx).
            let (q, rem) = div.div_rem(cell[k]);
            (c[k], r[k]) = (rem, q);
        }
        sx[..m].copy_from_slice(&r[..m]);
        sy[..m].copy_from_slice(&c[..m]);
        match &grid {
            Some(g) => {
                columns.permute_block(&mut sx[..m], |k| &g.sigma[c[k] as usize]);
                rows.permute_block(&mut sy[..m], |k| &g.tau[r[k] as usize]);
            }
            None => {
                let hashed: Vec<[PermuteKeys; 2]> = (0..m)
                    .map(|k| {
                        [
                            PermuteKeys::new(hash2(plan.sigma_key, u64::from(c[k]))),
                            PermuteKeys::new(hash2(plan.tau_key, u64::from(r[k]))),
                        ]
                    })
                    .collect();
                columns.permute_block(&mut sx[..m], |k| &hashed[k][0]);
                rows.permute_block(&mut sy[..m], |k| &hashed[k][1]);
            }
        }
        for k in 0..m {
            let kx = c[k] * ny + sx[k];
            let ky = r[k] * nx + sy[k];
            let bits = hash2(plan.jitter_seed, u64::from(base + k as u32));
            out[k] = glam::DVec2::new(
                stratum_to_unit(kx, bits, n),
                stratum_to_unit(ky, mix64(bits), n),
            );
        }
    }
}

/// `(k + ξ) / n` for stratum `k < n` and jitter bits `bits` (ξ = top 53 bits
/// · 2^-53), clamped below 1 (the sum `k + ξ` may round up to `k + 1`).
#[inline(always)]
pub(super) fn stratum_to_unit(k: u32, bits: u64, n: u32) -> f64 {
    clamp_unit((f64::from(k) + u64_to_f64(bits)) / f64::from(n))
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

    /// The column and row keys are hashed per sample until the rent-or-buy
    /// threshold, then tabulated: batches of 7 samples, which cross the
    /// threshold part-way, give the cursor's values throughout.
    #[test]
    fn tabulating_the_keys_mid_pass_changes_no_value() {
        let seq = Stratified::new(10_000, 3).unwrap(); // 100 × 100: threshold 100 samples
        let mut cursor = seq.clone();
        let mut batch = [glam::DVec2::ZERO; 7];
        for start in (0..700u64).step_by(7) {
            seq.fill_2d(start, 0, &mut batch);
            for (k, u) in batch.iter().enumerate() {
                cursor.start_sample(start + k as u64);
                assert_eq!(*u, cursor.next_2d(), "sample {}", start + k as u64);
            }
        }
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
