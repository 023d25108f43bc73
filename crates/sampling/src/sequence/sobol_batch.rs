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
//! bit: every step is an exact identity over `u32`. Where the process
//! runs AVX-512, the tables are nibble-wise instead, `N_k[v] = A_t ·
//! (v << 4k)`: sixteen entries of 32 bits fill one register, so `vpermd`
//! looks up sixteen indices at once ([`nibble_products_avx512`]; the same
//! XOR of the same columns). Where it runs AVX2, whose `vpermd` holds half
//! such a table, the nibble tables are split by output byte instead and 32
//! indices are transposed into four byte planes, so that one `vpshufb`
//! looks up a nibble's contribution to one output byte for all 32
//! ([`byte_plane_products_avx2`]). Elsewhere the byte tables are scalar
//! memory lookups; they were a third of an f32 MIS estimate's time on
//! Sobol points, whose second pair of dimensions takes them.
//!
//! Why not a Gray-code walk over consecutive indices: the index shuffle
//! sends consecutive indices to scattered ones, so consecutive `i'` do not
//! differ in one bit; the byte tables serve any order.

use std::sync::OnceLock;

use super::sobol_table::{SOBOL_DIMENSIONS, SOBOL_MATRICES};

/// Indices per block of the structure-of-arrays loops (1 KiB per `u32`
/// array, so the working set stays in the L1 cache).
pub(super) const BLOCK: usize = 256;

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
#[derive(Clone, Copy)]
enum ReversedMatrix {
    /// `t = 0`: `A_0 = R`.
    Reverse,
    /// `t = 1`: the Pascal matrix, as a subset transform (below).
    Pascal,
    /// Byte-wise tables: `y = T_0[j₀] ⊕ T_1[j₁] ⊕ T_2[j₂] ⊕ T_3[j₃]`,
    /// and the same products by nibbles ([`nibble_products_avx512`]) and
    /// by nibbles in byte planes ([`byte_plane_products_avx2`]).
    Tables(
        &'static [[u32; 256]; 4],
        &'static [[u32; 16]; 8],
        &'static BytePlaneTables,
    ),
}

/// The byte tables of every dimension that has needed them, built on
/// first use (1024 entries, 4 KiB, per dimension) and kept for the life of
/// the process: a batch no longer pays for them (building them per batch
/// cost about 3 % of a Sobol-driven estimate).
static TABLES: [OnceLock<Box<[[u32; 256]; 4]>>; SOBOL_DIMENSIONS] =
    [const { OnceLock::new() }; SOBOL_DIMENSIONS];

/// The byte tables of `A_t` (module docs): column b of `A_t` is
/// `A_t · 2^b = R(S_t · 2^(31−b)) = R(v_{t,31−b})`.
fn tables(dim: usize) -> &'static [[u32; 256]; 4] {
    TABLES[dim].get_or_init(|| {
        let v = &SOBOL_MATRICES[dim];
        let mut tables = Box::new([[0u32; 256]; 4]);
        for (q, table) in tables.iter_mut().enumerate() {
            for byte in 1..256usize {
                let low = byte.trailing_zeros() as usize;
                table[byte] = table[byte & (byte - 1)] ^ v[31 - (8 * q + low)].reverse_bits();
            }
        }
        tables
    })
}

/// The nibble tables of every dimension that has needed them:
/// `N_k[v] = A_t · (v·2^(4k))` for the eight 4-bit fields of `j`, so that
/// `A_t · j = N_0[j mod 16] ⊕ … ⊕ N_7[j >> 28]` ([`nibble_products_avx512`]).
static NIBBLES: [OnceLock<[[u32; 16]; 8]>; SOBOL_DIMENSIONS] =
    [const { OnceLock::new() }; SOBOL_DIMENSIONS];

/// The nibble tables of `A_t`, read off its byte tables: nibble `k` is the
/// low or high half of byte `k/2`.
fn nibbles(dim: usize) -> &'static [[u32; 16]; 8] {
    NIBBLES[dim].get_or_init(|| {
        let bytes = tables(dim);
        core::array::from_fn(|k| core::array::from_fn(|v| bytes[k / 2][v << (4 * (k % 2))]))
    })
}

/// `y[k] = A_t · j[k]` by the nibble tables, sixteen indices to an
/// AVX-512 register, for the whole vectors of `j` when the process's set
/// ([`Isa::selected`]) is one of the AVX-512 ones; returns how many it computed (the
/// caller does the rest with the byte tables, to the same bits: both are
/// the XOR of the same columns).
///
/// Why: a 16-entry table of 32-bit words is one register, and one
/// `vpermd` looks up sixteen lanes in it, so a product costs eight
/// shifts, eight lookups and eight XORs per sixteen indices. The byte
/// tables are four memory lookups per index, which the compiler leaves
/// scalar: they were a third of an f32 MIS estimate's time with Sobol
/// points (profile), whose later dimension pairs take this path.
#[inline(always)]
fn nibble_products_avx512(nibbles: &[[u32; 16]; 8], j: &[u32], y: &mut [u32]) -> usize {
    #[cfg(target_arch = "x86_64")]
    if crate::isa::Isa::selected() >= crate::isa::Isa::Avx512 {
        if let Some(simd) = pulp::x86::V4::try_new() {
            let whole = j.len().min(y.len()) / 16 * 16;
            simd.vectorize(
                #[inline(always)]
                || {
                    use core::arch::x86_64::__m512i;
                    let f = simd.avx512f;
                    // No closures in here (see `splitmix_avx2::fill_groups_f32`).
                    let t: [__m512i; 8] = pulp::cast(*nibbles);
                    let (js, _) = j[..whole].as_chunks::<16>();
                    let (ys, _) = y[..whole].as_chunks_mut::<16>();
                    for (jv, yv) in js.iter().zip(ys) {
                        let j: __m512i = pulp::cast(*jv);
                        // vpermd reads the low four bits of each index lane.
                        macro_rules! nibble {
                            ($k:literal, $shift:literal) => {
                                f._mm512_permutexvar_epi32(f._mm512_srli_epi32::<$shift>(j), t[$k])
                            };
                        }
                        let a = f._mm512_xor_si512(nibble!(0, 0), nibble!(1, 4));
                        let b = f._mm512_xor_si512(nibble!(2, 8), nibble!(3, 12));
                        let c = f._mm512_xor_si512(nibble!(4, 16), nibble!(5, 20));
                        let d = f._mm512_xor_si512(nibble!(6, 24), nibble!(7, 28));
                        let product =
                            f._mm512_xor_si512(f._mm512_xor_si512(a, b), f._mm512_xor_si512(c, d));
                        *yv = pulp::cast(product);
                    }
                },
            );
            return whole;
        }
    }
    let _ = (nibbles, j, y);
    0
}

/// The nibble tables of one dimension split into bytes, for
/// [`byte_plane_products_avx2`]: entry `[k][b]` holds byte `b` of
/// `N_k[v]` at position `v` (`v < 16`), twice (one copy per 128-bit half
/// of an AVX2 register, where `vpshufb` looks up).
type BytePlaneTables = [[[u8; 32]; 4]; 8];

/// The byte-plane tables of every dimension that has needed them (1 KiB
/// per dimension).
static BYTE_PLANES: [OnceLock<BytePlaneTables>; SOBOL_DIMENSIONS] =
    [const { OnceLock::new() }; SOBOL_DIMENSIONS];

/// The byte-plane tables of `A_t`, read off its nibble tables.
fn byte_plane_tables(dim: usize) -> &'static BytePlaneTables {
    BYTE_PLANES[dim].get_or_init(|| {
        let nibbles = nibbles(dim);
        core::array::from_fn(|k| {
            core::array::from_fn(|b| {
                core::array::from_fn(|v| (nibbles[k][v % 16] >> (8 * b)) as u8)
            })
        })
    })
}

/// `y[k] = A_t · j[k]` by the nibble tables split into bytes, thirty-two
/// indices at a time, for the whole groups of 32 of `j` when the process's
/// set ([`Isa::selected`]) is AVX2; returns how many it computed (the
/// caller does the rest with the byte tables, to the same bits).
///
/// Why: AVX2's `vpermd` indexes eight 32-bit entries, half a nibble table,
/// and the byte tables' four memory lookups per index stay scalar (1.15 ns
/// an index on the AVX2 host, measured). Byte `b` of `A_t · j` is the XOR,
/// over the eight nibbles `j_k` of `j`, of byte `b` of `N_k[j_k]`: a
/// 16-entry table of bytes, which is what one `vpshufb` looks up, for 32
/// bytes at once. So 32 indices are first transposed into four byte
/// planes (plane `q` holds byte `q` of every index: a byte transpose in
/// each 128-bit half, then a 4 × 4 transpose of 32-bit words across the
/// four registers), each output plane is eight lookups and seven XORs,
/// and the same two transposes, both their own inverses, applied in the
/// other order, return the four output planes to indices in place (the
/// lane order inside the planes is the same for every plane, so it
/// cancels). 32 `vpshufb` per 32 indices: 0.37 ns an index, measured
/// against the byte tables' 1.15 in one run.
#[inline(always)]
fn byte_plane_products_avx2(planes: &BytePlaneTables, j: &[u32], y: &mut [u32]) -> usize {
    #[cfg(target_arch = "x86_64")]
    if crate::isa::Isa::selected() == crate::isa::Isa::Avx2Fma {
        if let Some(simd) = pulp::x86::V3::try_new() {
            let whole = j.len().min(y.len()) / 32 * 32;
            simd.vectorize(
                #[inline(always)]
                || {
                    use core::arch::x86_64::__m256i;
                    let a2 = simd.avx2;
                    // No closures in here (see `splitmix_avx2::fill_groups_f32`).
                    // Byte m of word w to byte w of word m, in each 128-bit
                    // half: the byte transpose of a 4 × 4 block.
                    let byte_transpose: __m256i =
                        pulp::cast([[0u8, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15]; 2]);
                    let low_nibbles: __m256i = pulp::cast([0x0fu8; 32]);
                    // The 4 × 4 transpose of 32-bit words across four
                    // registers, in each 128-bit half.
                    macro_rules! word_transpose {
                        ($r:expr) => {{
                            let r: [__m256i; 4] = $r;
                            let t0 = a2._mm256_unpacklo_epi32(r[0], r[1]);
                            let t1 = a2._mm256_unpackhi_epi32(r[0], r[1]);
                            let t2 = a2._mm256_unpacklo_epi32(r[2], r[3]);
                            let t3 = a2._mm256_unpackhi_epi32(r[2], r[3]);
                            [
                                a2._mm256_unpacklo_epi64(t0, t2),
                                a2._mm256_unpackhi_epi64(t0, t2),
                                a2._mm256_unpacklo_epi64(t1, t3),
                                a2._mm256_unpackhi_epi64(t1, t3),
                            ]
                        }};
                    }
                    let (js, _) = j[..whole].as_chunks::<32>();
                    let (ys, _) = y[..whole].as_chunks_mut::<32>();
                    for (jv, yv) in js.iter().zip(ys) {
                        let words: [__m256i; 4] = pulp::cast(*jv);
                        let [p0, p1, p2, p3] = word_transpose!([
                            a2._mm256_shuffle_epi8(words[0], byte_transpose),
                            a2._mm256_shuffle_epi8(words[1], byte_transpose),
                            a2._mm256_shuffle_epi8(words[2], byte_transpose),
                            a2._mm256_shuffle_epi8(words[3], byte_transpose),
                        ]);
                        // Nibble k of every index: the low and high halves
                        // of plane k / 2.
                        let nibble: [__m256i; 8] = [
                            a2._mm256_and_si256(p0, low_nibbles),
                            a2._mm256_and_si256(a2._mm256_srli_epi16::<4>(p0), low_nibbles),
                            a2._mm256_and_si256(p1, low_nibbles),
                            a2._mm256_and_si256(a2._mm256_srli_epi16::<4>(p1), low_nibbles),
                            a2._mm256_and_si256(p2, low_nibbles),
                            a2._mm256_and_si256(a2._mm256_srli_epi16::<4>(p2), low_nibbles),
                            a2._mm256_and_si256(p3, low_nibbles),
                            a2._mm256_and_si256(a2._mm256_srli_epi16::<4>(p3), low_nibbles),
                        ];
                        let mut out = [nibble[0]; 4];
                        for (b, out) in out.iter_mut().enumerate() {
                            let mut sum =
                                a2._mm256_shuffle_epi8(pulp::cast(planes[0][b]), nibble[0]);
                            for k in 1..8 {
                                sum = a2._mm256_xor_si256(
                                    sum,
                                    a2._mm256_shuffle_epi8(pulp::cast(planes[k][b]), nibble[k]),
                                );
                            }
                            *out = sum;
                        }
                        let words = word_transpose!(out);
                        *yv = pulp::cast([
                            a2._mm256_shuffle_epi8(words[0], byte_transpose),
                            a2._mm256_shuffle_epi8(words[1], byte_transpose),
                            a2._mm256_shuffle_epi8(words[2], byte_transpose),
                            a2._mm256_shuffle_epi8(words[3], byte_transpose),
                        ]);
                    }
                },
            );
            return whole;
        }
    }
    let _ = (planes, j, y);
    0
}

/// `A_1 · j` for the second Sobol dimension, whose generator matrix is
/// Pascal's triangle mod 2 (its primitive polynomial is x + 1 and every
/// direction number m_k = 1, so v_k = v_{k−1} ⊕ (v_{k−1} ≫ 1); Joe & Kuo
/// 2008). By Lucas' theorem binomial(a, c) is odd iff the bits of c are a
/// subset of those of a. Index bit a contributes to digit c of `S_1 · i`
/// iff c ⊆ a; in reversed coordinates (a 5-bit position p ↔ 31 − p, which
/// complements it) bit b of `j` contributes to bit c of `y = A_1 · j` iff
/// b ∧ c = 0. That matrix is the Kronecker product, over the five bits of a
/// position, of the 2 × 2 matrix [[1, 1], [1, 0]]: one butterfly per bit
/// level l, (y_lo, y_hi) ← (y_lo ⊕ y_hi, y_lo) for the position pairs that
/// differ in bit l only (the fast transform of a Kronecker product, as in
/// Yates 1937). Five shift-and-mask steps: no table, no gather, and
/// exactly the table's value (tested on every basis vector).
#[inline(always)]
const fn pascal_reversed(mut y: u32) -> u32 {
    let levels = [
        (1, 0x5555_5555u32),
        (2, 0x3333_3333),
        (4, 0x0f0f_0f0f),
        (8, 0x00ff_00ff),
        (16, 0x0000_ffff),
    ];
    let mut l = 0;
    while l < levels.len() {
        let (shift, low) = levels[l];
        y = ((y ^ (y >> shift)) & low) | ((y << shift) & !low);
        l += 1;
    }
    y
}

/// The sixteen bytes `M(v)` and `M(v·2⁴)`, `v < 16`, of the 8 × 8 block
/// `M` of [`pascal_reversed`] inside a byte (bit b to bit c iff b ∧ c = 0,
/// for 3-bit positions): `M(byte) = LOW[byte mod 16] ⊕ HIGH[byte >> 4]`,
/// `M` being linear.
const PASCAL_NIBBLES: [[u8; 16]; 2] = {
    let mut tables = [[0u8; 16]; 2];
    let mut v = 0;
    while v < 16 {
        // A byte's own block, read off the whole transform: byte 0 reaches
        // byte 0 (0 ∧ 0 = 0) through `M`.
        tables[0][v] = pascal_reversed(v as u32) as u8;
        tables[1][v] = pascal_reversed((v as u32) << 4) as u8;
        v += 1;
    }
    tables
};

/// The loop of [`pascal_avx512`] and [`pascal_avx2`] over the whole
/// vectors of `j` (the first `$whole`), `$lanes` indices to a `$vector`:
/// the in-byte block `M` by two `vpshufb` lookups, then the butterflies
/// between bytes and between 16-bit halves. `$ops` and `$shuffles` are the
/// pulp handles whose methods, named by the remaining arguments, do the
/// bitwise operations and the byte shuffle. No closures in here (see
/// `splitmix_avx2::fill_groups_f32`).
macro_rules! pascal_vectors {
    (
        $j:ident, $y:ident, $whole:ident, $lanes:literal, $vector:ty, $ops:ident, $shuffles:ident,
        $and:ident, $andnot:ident, $or:ident, $xor:ident, $srli:ident, $slli:ident,
        $shuffle:ident
    ) => {{
        let low: $vector = pulp::cast([PASCAL_NIBBLES[0]; $lanes / 4]);
        let high: $vector = pulp::cast([PASCAL_NIBBLES[1]; $lanes / 4]);
        let nibble: $vector = pulp::cast([0x0f0f_0f0fu32; $lanes]);
        let even_bytes: $vector = pulp::cast([0x00ff_00ffu32; $lanes]);
        let even_halves: $vector = pulp::cast([0x0000_ffffu32; $lanes]);
        let (js, _) = $j[..$whole].as_chunks::<$lanes>();
        let (ys, _) = $y[..$whole].as_chunks_mut::<$lanes>();
        for (jv, yv) in js.iter().zip(ys) {
            let j: $vector = pulp::cast(*jv);
            let lo = $ops.$and(j, nibble);
            let hi = $ops.$and($ops.$srli::<4>(j), nibble);
            let v = $ops.$xor($shuffles.$shuffle(low, lo), $shuffles.$shuffle(high, hi));
            // (y_lo, y_hi) ← (y_lo ⊕ y_hi, y_lo) between bytes, then
            // between 16-bit halves.
            let v = $ops.$or(
                $ops.$and($ops.$xor(v, $ops.$srli::<8>(v)), even_bytes),
                $ops.$andnot(even_bytes, $ops.$slli::<8>(v)),
            );
            let v = $ops.$or(
                $ops.$and($ops.$xor(v, $ops.$srli::<16>(v)), even_halves),
                $ops.$andnot(even_halves, $ops.$slli::<16>(v)),
            );
            *yv = pulp::cast(v);
        }
    }};
}

/// [`pascal_reversed`] of the whole vectors of `j`, sixteen to an AVX-512
/// register, when the process's set ([`Isa::selected`]) is one of the
/// AVX-512 ones; returns how many it computed (the caller does the rest
/// one by one, to the same bits).
///
/// Why: the transform is a Kronecker product over the five bits of a bit
/// position, so it splits into the three levels inside each byte (the same
/// 8 × 8 block `M` for every byte) and the two levels between bytes. `M` of
/// a byte is two `vpshufb` lookups in 16-byte tables ([`PASCAL_NIBBLES`])
/// and an XOR, where its three butterfly levels were twelve instructions;
/// the two byte levels stay butterflies. The scalar form's five levels were
/// the largest single line of an f32 light estimate on Sobol points
/// (11.6 % of its profile); measured A/B, that estimate's time did not
/// move (other work hides the butterflies there), and an f32 MIS estimate
/// on Sobol points, which draws two pairs, took 0.92× the time.
#[inline(always)]
fn pascal_avx512(j: &[u32], y: &mut [u32]) -> usize {
    #[cfg(target_arch = "x86_64")]
    if crate::isa::Isa::selected() >= crate::isa::Isa::Avx512 {
        if let Some(simd) = pulp::x86::V4::try_new() {
            let whole = j.len().min(y.len()) / 16 * 16;
            simd.vectorize(
                #[inline(always)]
                || {
                    use core::arch::x86_64::__m512i;
                    let (f, bw) = (simd.avx512f, simd.avx512bw);
                    pascal_vectors!(
                        j,
                        y,
                        whole,
                        16,
                        __m512i,
                        f,
                        bw,
                        _mm512_and_si512,
                        _mm512_andnot_si512,
                        _mm512_or_si512,
                        _mm512_xor_si512,
                        _mm512_srli_epi32,
                        _mm512_slli_epi32,
                        _mm512_shuffle_epi8
                    );
                },
            );
            return whole;
        }
    }
    let _ = (j, y);
    0
}

/// [`pascal_reversed`] of the whole vectors of `j`, eight to an AVX2
/// register, when the process's set ([`Isa::selected`]) is AVX2; returns
/// how many it computed. The method of [`pascal_avx512`] (lookups of the
/// in-byte block, butterflies between bytes), in 256-bit registers.
#[inline(always)]
fn pascal_avx2(j: &[u32], y: &mut [u32]) -> usize {
    #[cfg(target_arch = "x86_64")]
    if crate::isa::Isa::selected() == crate::isa::Isa::Avx2Fma {
        if let Some(simd) = pulp::x86::V3::try_new() {
            let whole = j.len().min(y.len()) / 8 * 8;
            simd.vectorize(
                #[inline(always)]
                || {
                    use core::arch::x86_64::__m256i;
                    let a2 = simd.avx2;
                    pascal_vectors!(
                        j,
                        y,
                        whole,
                        8,
                        __m256i,
                        a2,
                        a2,
                        _mm256_and_si256,
                        _mm256_andnot_si256,
                        _mm256_or_si256,
                        _mm256_xor_si256,
                        _mm256_srli_epi32,
                        _mm256_slli_epi32,
                        _mm256_shuffle_epi8
                    );
                },
            );
            return whole;
        }
    }
    let _ = (j, y);
    0
}

impl ReversedMatrix {
    fn new(dim: usize) -> Self {
        match dim {
            0 => ReversedMatrix::Reverse,
            1 => ReversedMatrix::Pascal,
            _ => ReversedMatrix::Tables(tables(dim), nibbles(dim), byte_plane_tables(dim)),
        }
    }

    /// `y[k] = A_t · j[k]`.
    #[inline(always)]
    fn apply(&self, j: &[u32], y: &mut [u32]) {
        match self {
            ReversedMatrix::Reverse => {
                for (y, &j) in y.iter_mut().zip(j) {
                    *y = j.reverse_bits();
                }
            }
            ReversedMatrix::Pascal => {
                let mut done = pascal_avx512(j, y);
                if done == 0 {
                    done = pascal_avx2(j, y);
                }
                for (y, &j) in y[done..].iter_mut().zip(&j[done..]) {
                    *y = pascal_reversed(j);
                }
            }
            ReversedMatrix::Tables(t, n, planes) => {
                let mut done = nibble_products_avx512(n, j, y);
                if done == 0 {
                    done = byte_plane_products_avx2(planes, j, y);
                }
                for (y, &j) in y[done..].iter_mut().zip(&j[done..]) {
                    let b = j.to_le_bytes();
                    *y = t[0][usize::from(b[0])]
                        ^ t[1][usize::from(b[1])]
                        ^ t[2][usize::from(b[2])]
                        ^ t[3][usize::from(b[3])];
                }
            }
        }
    }
}

/// Scrambles reversed coordinates `y` in place and returns them to natural
/// bit order: `y ← R(C(y, k))` (or the full Owen scramble of `R(y)`).
#[inline(always)]
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

/// The bit reversals R(k) of the indices k < 256, for [`reversed_indices`].
static REVERSED_BYTES: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut k = 0;
    while k < 256 {
        table[k] = (k as u32).reverse_bits();
        k += 1;
    }
    table
};

/// `j[k] = R(base + k)` for a block of at most 256 indices, without
/// reversing each. Within one window of 256 indices (same bits above the
/// lowest eight) base + k = w + (base + k − w), two disjoint bit fields,
/// so R(base + k) = R(w) ⊕ R(base + k − w): one reversal per window and a
/// table of the 256 low ones. A block spans at most two windows. x86 has
/// no vector bit reversal (it takes a dozen instructions per lane), and
/// the index was one of three reversals per point.
///
/// With a `shuffle` key each is then hashed, `j[k] = C(R(base + k), key)`,
/// in the same loop (the index shuffle).
#[inline(always)]
fn reversed_indices(base: u32, j: &mut [u32], shuffle: Option<u32>) {
    const { assert!(BLOCK <= 256) };
    let low = (base & 0xff) as usize;
    let window = base & !0xff;
    let in_first = (256 - low).min(j.len());
    let (first, second) = j.split_at_mut(in_first);
    let windows = [
        (first, &REVERSED_BYTES[low..], window.reverse_bits()),
        (
            second,
            &REVERSED_BYTES[..],
            window.wrapping_add(256).reverse_bits(),
        ),
    ];
    for (j, table, r) in windows {
        match shuffle {
            Some(key) => {
                for (j, &t) in j.iter_mut().zip(table) {
                    *j = burley_hash(r ^ t, key);
                }
            }
            None => {
                for (j, &t) in j.iter_mut().zip(table) {
                    *j = r ^ t;
                }
            }
        }
    }
}

/// The two scrambled coordinates of `R` pairs for the `len` indices from
/// `first` (the last must not pass `2^32 − 1`), handed to
/// `sink(offset, [(xs, ys); R])` in blocks of at most [`BLOCK`], `offset`
/// counting from `first`. Inlined into its caller, so that it runs in
/// the caller's instruction set (the estimator calls it inside
/// [`crate::isa::Isa::run`]).
///
/// Where the plans share their index shuffle (the global layout's pairs
/// in one run of 256 dimensions do), each block's shuffled indices are
/// computed once for all of them: a third of a pair's hashes (a later
/// pair's f32 point took 1.76 ns without the shuffle against 2.03 with
/// it on the Zen 2 host; two requests' f32 points together 3.55 → 3.38
/// ns once shared).
#[inline(always)]
pub(super) fn fill_pairs<const R: usize, F>(
    plans: [&PairPlan; R],
    first: u32,
    len: usize,
    mut sink: F,
) where
    F: FnMut(usize, [(&[u32], &[u32]); R]),
{
    debug_assert!(len == 0 || u64::from(first) + (len as u64 - 1) <= u64::from(u32::MAX));
    let matrices = plans.map(|plan| plan.dims.map(ReversedMatrix::new));
    let shared = plans.iter().all(|plan| plan.shuffle == plans[0].shuffle);
    let mut j = [0u32; BLOCK];
    let mut xs = [[0u32; BLOCK]; R];
    let mut ys = [[0u32; BLOCK]; R];
    let mut offset = 0;
    while offset < len {
        let m = BLOCK.min(len - offset);
        let base = first.wrapping_add(offset as u32);
        let j = &mut j[..m];
        for (r, ((plan, matrices), (xs, ys))) in plans
            .iter()
            .zip(&matrices)
            .zip(xs.iter_mut().zip(ys.iter_mut()))
            .enumerate()
        {
            // j = C(R(i), k) (or R(i) unshuffled): the shuffled index,
            // reversed; the previous pair's if they share the shuffle.
            if r == 0 || !shared {
                reversed_indices(base, j, plan.shuffle);
            }
            for ((matrix, scramble), out) in matrices
                .iter()
                .zip(plan.scramble)
                .zip([&mut xs[..m], &mut ys[..m]])
            {
                match (matrix, scramble) {
                    // The first dimension's whole chain, R(C(R(j))), in one
                    // loop: a reversal, a hash and a reversal, where the two
                    // loops stored and reloaded the block between them.
                    (ReversedMatrix::Reverse, CoordinateScramble::FastOwen(key)) => {
                        for (y, &j) in out.iter_mut().zip(j.iter()) {
                            *y = burley_hash(j.reverse_bits(), key).reverse_bits();
                        }
                    }
                    _ => {
                        matrix.apply(j, out);
                        finish(scramble, out);
                    }
                }
            }
        }
        let blocks: [(&[u32], &[u32]); R] = core::array::from_fn(|r| (&xs[r][..m], &ys[r][..m]));
        sink(offset, blocks);
        offset += m;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The windowed reversal equals reversing each index: blocks inside
    /// one window, across two, of every length up to 256, and at the top
    /// of the index range.
    #[test]
    fn reversed_indices_reverse_every_index() {
        for base in [
            0u32,
            1,
            255,
            256,
            300,
            0x1234_5678,
            u32::MAX - 255,
            u32::MAX - 300,
        ] {
            for len in [0usize, 1, 7, 200, 255, 256] {
                if u64::from(base) + len as u64 > 1 << 32 {
                    continue;
                }
                let mut j = vec![0u32; len];
                reversed_indices(base, &mut j, None);
                for (k, &got) in j.iter().enumerate() {
                    assert_eq!(
                        got,
                        base.wrapping_add(k as u32).reverse_bits(),
                        "{base} + {k}"
                    );
                }
            }
        }
    }

    /// The nibble products equal the byte tables' for dimensions across
    /// the table, on arbitrary indices, for lengths with and without a
    /// partial vector (whole vectors by nibbles where the process runs
    /// AVX-512, whole groups of 32 by byte planes where it runs AVX2, the
    /// rest by bytes). Negative control: another dimension's nibble or
    /// byte-plane tables give other products.
    #[test]
    fn nibble_products_are_the_byte_tables_products() {
        let mut x = 0x9e37_79b9u32;
        let j: Vec<u32> = (0..77)
            .map(|_| {
                x = x.wrapping_mul(0x2c1b_3c6d).wrapping_add(0x297a_2d39);
                x
            })
            .collect();
        for dim in [2, 3, 7, 100, SOBOL_DIMENSIONS - 1] {
            let matrix = ReversedMatrix::new(dim);
            let t = tables(dim);
            for len in [0, 5, 16, 32, 77] {
                let mut y = vec![0u32; len];
                matrix.apply(&j[..len], &mut y);
                for (k, (&y, &j)) in y.iter().zip(&j).enumerate() {
                    let b = j.to_le_bytes();
                    let want = t[0][usize::from(b[0])]
                        ^ t[1][usize::from(b[1])]
                        ^ t[2][usize::from(b[2])]
                        ^ t[3][usize::from(b[3])];
                    assert_eq!(y, want, "dim {dim} len {len} k {k}");
                }
            }
            let mut wrong = vec![0u32; 16];
            let done = nibble_products_avx512(nibbles(dim - 1), &j[..16], &mut wrong);
            if done == 16 {
                let mut right = vec![0u32; 16];
                nibble_products_avx512(nibbles(dim), &j[..16], &mut right);
                assert_ne!(wrong, right, "dim {dim}");
            }
            let mut wrong = vec![0u32; 32];
            let done = byte_plane_products_avx2(byte_plane_tables(dim - 1), &j[..32], &mut wrong);
            if done == 32 {
                let mut right = vec![0u32; 32];
                byte_plane_products_avx2(byte_plane_tables(dim), &j[..32], &mut right);
                assert_ne!(wrong, right, "dim {dim}");
            }
        }
    }

    /// `A_1 · j` by the subset transform equals the generator matrix's
    /// value on every basis vector (column b of `A_1` is `R(v_{1,31−b})`),
    /// hence everywhere, the map being linear over GF(2); and the byte
    /// tables of dimension 1 agree on arbitrary values.
    #[test]
    fn pascal_transform_is_the_second_dimension() {
        let v = &SOBOL_MATRICES[1];
        for b in 0..32 {
            assert_eq!(pascal_reversed(1 << b), v[31 - b].reverse_bits(), "bit {b}");
        }
        let t = tables(1);
        let mut x = 0x9e37_79b9u32;
        for _ in 0..1000 {
            x = x.wrapping_mul(0x2c1b_3c6d).wrapping_add(0x297a_2d39);
            let b = x.to_le_bytes();
            let want = t[0][usize::from(b[0])]
                ^ t[1][usize::from(b[1])]
                ^ t[2][usize::from(b[2])]
                ^ t[3][usize::from(b[3])];
            assert_eq!(pascal_reversed(x), want);
        }
    }

    /// The vector form of the Pascal transform (byte lookups and two byte
    /// levels, where the process runs AVX-512 or AVX2) equals the scalar one on
    /// arbitrary values and every basis vector, for lengths with and
    /// without a partial vector. Negative control: the in-byte block `M`
    /// alone, which the lookups give before the byte levels, differs.
    #[test]
    fn pascal_vectors_are_the_scalar_transform() {
        let mut x = 0x2545_f491u32;
        let mut j: Vec<u32> = (0..77)
            .map(|_| {
                x = x.wrapping_mul(0x2c1b_3c6d).wrapping_add(0x297a_2d39);
                x
            })
            .collect();
        j.extend((0..32).map(|b| 1u32 << b));
        for len in [0, 5, 16, 77, j.len()] {
            let mut y = vec![0u32; len];
            ReversedMatrix::Pascal.apply(&j[..len], &mut y);
            for (k, (&y, &j)) in y.iter().zip(&j).enumerate() {
                assert_eq!(y, pascal_reversed(j), "len {len} k {k}");
            }
        }
        let in_bytes = |v: u32| {
            u32::from_le_bytes(v.to_le_bytes().map(|b| {
                PASCAL_NIBBLES[0][usize::from(b & 15)] ^ PASCAL_NIBBLES[1][usize::from(b >> 4)]
            }))
        };
        let mut y = vec![0u32; 16];
        ReversedMatrix::Pascal.apply(&j[..16], &mut y);
        assert!(y.iter().zip(&j).any(|(&y, &j)| y != in_bytes(j)));
    }
}
