//! Scrambled Sobol coordinates of many consecutive indices at once: the
//! kernel behind [`Sobol`](super::Sobol)'s batch fills.
//!
//! Point by point, coordinate `t` of index `i` is
//!
//! ```text
//! i' = LK(i, k_shuffle)            (Burley 2020 §4 index shuffle)
//! x  = S_t · i'                    (Sobol generator matrix, natural order)
//! out = LK(x, k_t)                 (Laine–Karras / Burley nested scramble)
//! ```
//!
//! with `LK(x, k) = R(C(R(x), k))`, `R` the reversal of the 32 bits and `C`
//! the hash of Burley 2020 (listing 2), whose carries run from the low bits
//! to the high ones. Read naively, that is four bit reversals and a loop over
//! the set bits of `i'` per coordinate. Written in the bit-reversed domain,
//! where `C` acts directly, the same value is
//!
//! ```text
//! j   = C(R(i), k_shuffle)         (so i' = R(j))
//! y_t = A_t · j,  A_t = R·S_t·R    (the generator matrix in reversed coordinates)
//! out = R(C(y_t, k_t))
//! ```
//!
//! `A_t` is a 32 × 32 matrix over GF(2), so `A_t · j` is the XOR of four
//! lookups in byte-wise tables, `T_q[b] = A_t · (b << 8q)` (the table method
//! of e.g. Bratley & Fox 1988 for a linear map, here with bytes of the
//! reversed index). For dimension 0 (van der Corput, `S_0 = R`), `A_0 = R`
//! and `y_0 = R(j)`. That leaves, per 2-D point, three bit reversals and
//! three hashes, all plain 32-bit arithmetic on arrays — structure of arrays
//! over blocks of [`BLOCK`] indices, which the compiler vectorises — and two
//! table lookups. The values are those of the point-by-point path to the
//! bit: every step is an exact identity over `u32`.
//!
//! Why not a Gray-code walk over consecutive indices: the index shuffle
//! sends consecutive indices to scattered ones, so consecutive `i'` do not
//! differ in one bit; the byte tables serve any order.

use super::sobol_table::SOBOL_MATRICES;

/// Indices per block of the structure-of-arrays loops (1 KiB per `u32`
/// array, so the working set stays in the L1 cache).
pub(super) const BLOCK: usize = 256;

/// Batches shorter than this compute `A_t · j` bit by bit instead of
/// building the 4 KiB of byte tables (which costs about 1000 table entries).
const TABLE_MIN_LEN: usize = 64;

/// The hash `C` of Burley 2020 (listing 2; Laine & Karras 2011 with
/// Burley's constants), acting on a bit-reversed 32-bit value: output bit
/// `b` depends on input bits `0 … b` only, so in the reversed domain it is a
/// nested (Owen) scramble.
#[inline(always)]
pub(super) fn burley_hash(mut v: u32, seed: u32) -> u32 {
    v ^= v.wrapping_mul(0x3d20_adea);
    v = v.wrapping_add(seed);
    v = v.wrapping_mul((seed >> 16) | 1);
    v ^= v.wrapping_mul(0x0552_6c56);
    v ^= v.wrapping_mul(0x53a2_2864);
    v
}

/// How one coordinate of a batch is scrambled.
#[derive(Clone, Copy, Debug)]
pub(super) enum CoordinateScramble {
    /// Plain Sobol coordinate.
    None,
    /// Laine–Karras / Burley hash with this 32-bit key.
    FastOwen(u32),
    /// Full nested uniform scramble with this 64-bit seed.
    Owen(u64),
}

/// What a batch computes for a dimension pair: the index shuffle key (if
/// any), the two Sobol table dimensions and their scrambles.
#[derive(Clone, Copy, Debug)]
pub(super) struct PairPlan {
    /// Key of the index shuffle, or `None` for natural order.
    pub shuffle: Option<u32>,
    /// Sobol table dimensions of the two coordinates (`< 256`).
    pub dims: [usize; 2],
    /// Scramble of each coordinate.
    pub scramble: [CoordinateScramble; 2],
}

/// `y = A_t · j` for one table dimension `t`, `A_t = R·S_t·R`.
enum ReversedMatrix {
    /// `t = 0`: `A_0 = R`.
    Reverse,
    /// Byte-wise tables: `y = T_0[j₀] ⊕ T_1[j₁] ⊕ T_2[j₂] ⊕ T_3[j₃]`.
    Tables(Box<[[u32; 256]; 4]>),
    /// Bit by bit (short batches): the point-by-point formula.
    Direct(usize),
}

impl ReversedMatrix {
    fn new(dim: usize, len: usize) -> Self {
        if dim == 0 {
            return ReversedMatrix::Reverse;
        }
        if len < TABLE_MIN_LEN {
            return ReversedMatrix::Direct(dim);
        }
        // Column b of A_t: A_t · 2^b = R(S_t · 2^(31−b)) = R(v_{t,31−b}).
        let v = &SOBOL_MATRICES[dim];
        let mut tables = Box::new([[0u32; 256]; 4]);
        for (q, table) in tables.iter_mut().enumerate() {
            for byte in 1..256usize {
                let low = byte.trailing_zeros() as usize;
                table[byte] = table[byte & (byte - 1)] ^ v[31 - (8 * q + low)].reverse_bits();
            }
        }
        ReversedMatrix::Tables(tables)
    }

    /// `y[k] = A_t · j[k]`.
    fn apply(&self, j: &[u32], y: &mut [u32]) {
        match self {
            ReversedMatrix::Reverse => {
                for (y, &j) in y.iter_mut().zip(j) {
                    *y = j.reverse_bits();
                }
            }
            ReversedMatrix::Tables(t) => {
                for (y, &j) in y.iter_mut().zip(j) {
                    let b = j.to_le_bytes();
                    *y = t[0][usize::from(b[0])]
                        ^ t[1][usize::from(b[1])]
                        ^ t[2][usize::from(b[2])]
                        ^ t[3][usize::from(b[3])];
                }
            }
            ReversedMatrix::Direct(dim) => {
                for (y, &j) in y.iter_mut().zip(j) {
                    *y = super::sobol::sobol_u32(j.reverse_bits(), *dim).reverse_bits();
                }
            }
        }
    }
}

/// Scrambles reversed coordinates `y` in place and returns them to natural
/// bit order: `y ← R(C(y, k))` (or the full Owen scramble of `R(y)`).
fn finish(scramble: CoordinateScramble, y: &mut [u32]) {
    match scramble {
        CoordinateScramble::None => {
            for y in y.iter_mut() {
                *y = y.reverse_bits();
            }
        }
        CoordinateScramble::FastOwen(key) => {
            for y in y.iter_mut() {
                *y = burley_hash(*y, key).reverse_bits();
            }
        }
        CoordinateScramble::Owen(seed) => {
            for y in y.iter_mut() {
                *y = super::sobol::owen_scramble(y.reverse_bits(), seed);
            }
        }
    }
}

/// The two scrambled coordinates of indices `first … first + len − 1`
/// (which must not pass `2^32 − 1`), handed to `sink(offset, xs, ys)` in
/// blocks of at most [`BLOCK`], `offset` counting from `first`.
pub(super) fn fill_pair<F>(plan: &PairPlan, first: u32, len: usize, mut sink: F)
where
    F: FnMut(usize, &[u32], &[u32]),
{
    debug_assert!(len == 0 || u64::from(first) + (len as u64 - 1) <= u64::from(u32::MAX));
    let matrices = plan.dims.map(|d| ReversedMatrix::new(d, len));
    let mut j = [0u32; BLOCK];
    let mut xs = [0u32; BLOCK];
    let mut ys = [0u32; BLOCK];
    let mut offset = 0;
    while offset < len {
        let m = BLOCK.min(len - offset);
        let base = first.wrapping_add(offset as u32);
        let j = &mut j[..m];
        // j = C(R(i), k) (or R(i) unshuffled): the shuffled index, reversed.
        for (k, j) in j.iter_mut().enumerate() {
            *j = base.wrapping_add(k as u32).reverse_bits();
        }
        if let Some(key) = plan.shuffle {
            for j in j.iter_mut() {
                *j = burley_hash(*j, key);
            }
        }
        for ((matrix, scramble), out) in matrices
            .iter()
            .zip(plan.scramble)
            .zip([&mut xs[..m], &mut ys[..m]])
        {
            matrix.apply(j, out);
            finish(scramble, out);
        }
        sink(offset, &xs[..m], &ys[..m]);
        offset += m;
    }
}
