//! Value stability: fixed seeds and indices give fixed bits.
//!
//! Every committed study result and every statistical test depends on the
//! exact values of the sequences. These tests pin them — a few values
//! spelled out, and a digest of many — so that an optimisation (a batch
//! kernel, a table, a different instruction set) cannot change a result
//! unnoticed. A deliberate change of values must update the constants here
//! and say why in its commit.

use super::{round_down_24, SampleSequence, Scramble, Sobol, SobolLayout, Stratified};

/// FNV-1a over 64-bit words (Fowler, Noll & Vo): a fixed, dependency-free
/// digest; any changed bit of any word changes it.
fn digest(words: impl IntoIterator<Item = u64>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325_u64;
    for w in words {
        for byte in w.to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// Indices that cover the first points, chunk boundaries (4096), a large
/// replicate (3 125 000 = 5·10⁷ / 16), the end of the first block of `2^32`
/// Sobol indices and the start of the next, and the largest index.
fn indices() -> Vec<u64> {
    let mut v: Vec<u64> = (0..300).collect();
    v.extend([
        4095,
        4096,
        4097,
        65_535,
        (1 << 20) | 12_345,
        3_124_999,
        (1 << 32) - 1,
        1 << 32,
        (1 << 32) + 5,
        (1 << 40) | 777,
        u64::MAX - 1,
        u64::MAX,
    ]);
    v
}

/// The bits of everything a sample reads: two 2-D points, a 1-D value, a
/// 2-D f32 point and a 1-D f32 value (dimensions 0 … 7); for every 16th
/// index also dimensions 8 … 259 in 2-D steps (past the 256 Sobol table
/// dimensions), keeping the last two points.
fn read_bits<S: SampleSequence>(mut seq: S) -> Vec<u64> {
    let mut out = Vec::new();
    for (n, i) in indices().into_iter().enumerate() {
        seq.start_sample(i);
        for u in [seq.next_2d(), seq.next_2d()] {
            out.extend([u.x.to_bits(), u.y.to_bits()]);
        }
        out.push(seq.next_1d().to_bits());
        let v = seq.next_2d_f32();
        out.extend([u64::from(v.x.to_bits()), u64::from(v.y.to_bits())]);
        out.push(u64::from(seq.next_1d_f32().to_bits()));
        if n % 16 == 0 {
            let mut last = [0u64; 4];
            for _ in 0..126 {
                let u = seq.next_2d();
                last = [last[2], last[3], u.x.to_bits(), u.y.to_bits()];
            }
            out.extend(last);
        }
    }
    out
}

/// `(name, sequence)` of every Sobol configuration.
fn sobol_configs() -> Vec<(&'static str, Sobol)> {
    vec![
        ("default seed 1", Sobol::new(1)),
        ("default seed 2^64-1", Sobol::new(u64::MAX)),
        ("unscrambled", Sobol::unscrambled()),
        ("no shuffle", Sobol::new(5).with_index_shuffle(false)),
        ("owen", Sobol::new(6).with_scramble(Scramble::Owen)),
        ("no scramble", Sobol::new(7).with_scramble(Scramble::None)),
        ("low bits", Sobol::new(8).with_random_low_bits(true)),
        ("padded", Sobol::new(9).with_layout(SobolLayout::Padded)),
    ]
}

/// `(n, seed)` of every stratified configuration: a square grid, a grid
/// with passes, a prime (strips), the size of one replicate of a 5·10⁷
/// estimate (1250 × 2500), the largest count.
const STRATIFIED_CONFIGS: [(u32, u64); 5] = [
    (16, 1),
    (1000, 7),
    (13, 3),
    (3_125_000, 0x1234),
    (u32::MAX, 9),
];

#[test]
fn sobol_values_are_pinned() {
    // A few values spelled out: Sobol::new(1), sample i, dimensions (0, 1),
    // as f64 bits.
    let pinned: [(u64, u64, u64); 3] = [
        (0, 0x3fea_aadf_5de0_0000, 0x3feb_8709_3c60_0000),
        (1, 0x3fc4_c379_cb80_0000, 0x3fc9_a33a_0f00_0000),
        (12_345, 0x3fe1_0622_1d80_0000, 0x3fc6_1d45_6300_0000),
    ];
    let mut s = Sobol::new(1);
    for (i, x, y) in pinned {
        s.start_sample(i);
        let u = s.next_2d();
        assert_eq!((u.x.to_bits(), u.y.to_bits()), (x, y), "sample {i}");
    }
    let digests: [u64; 8] = [
        0x51d5_60ec_61ee_6d31,
        0xb975_d5e1_2c3b_95a8,
        0x0f61_cfac_0d37_fa30,
        0x494e_927b_87d9_65bc,
        0x1068_de4f_0eac_95cf,
        0x5fc4_5e50_dc87_4193,
        0x8a8f_06e1_dcf3_7d34,
        0xf6ff_81ac_cb8b_a4fc,
    ];
    for ((name, seq), want) in sobol_configs().into_iter().zip(digests) {
        assert_eq!(digest(read_bits(seq)), want, "sobol {name}");
    }
}

#[test]
fn stratified_values_are_pinned() {
    // N = 3 125 000, seed 0x1234, sample i, dimensions (0, 1), as f64 bits.
    // Re-pinned 2026-12 when the sequence was redefined (the first pair's
    // cells in a golden-ratio order, sub-strata spread by a golden-ratio
    // multiplier and shifted rather than permuted, 32-bit jitters; module
    // docs of `stratified.rs`): a chosen change of values, which keeps both
    // stratification properties (tests in `stratified.rs`), has equal or
    // smaller error on the integrands measured there, and costs under half.
    // Re-pinned again when the shifts s_c, t_r and the jitters became a
    // 32-bit hash (`hash_u32`) instead of SplitMix64 outputs: half of a
    // 2-D point's hashing cost. Relative RMSE did not move beyond its noise
    // (before → after): disk of angular radius 0.01, cosine sampling, 2²²,
    // 80 seeds: 8.6e-3 → 8.8e-3; the same, uniform sampling, 48 seeds:
    // 6.3e-3 → 6.1e-3; sphere light, light sampling, 2²⁰, 24 seeds:
    // 2.3e-8 → 1.8e-8. Re-pinned when the f32 coordinates of grids that
    // are not powers of two (N ≤ 2²⁴) became the nearest f32 to the
    // coordinate with its jitter cut to 24 − ⌈log₂ N⌉ bits instead of the
    // f64 value rounded down (module docs of `stratified.rs`): the f64
    // values and the digests of N = 16 and N = 2³² − 1 did not move; those
    // of N = 1000, 13 and 3 125 000 were 0x2c59_ad66_a503_94fb,
    // 0xc95f_b945_2b07_e009 and 0xf8cc_d395_9d10_d548. Re-pinned when the
    // first pair's cells went column by column instead of in the golden
    // order `(i·α + b) mod N` (module docs of `stratified.rs`): a
    // relabelling of each pass's points, whose whole-pass error did not
    // move (relative RMSE over 40 seeds, old → new: disk 5.15e-3 →
    // 5.12e-3 at N = 10⁶, 6.53e-3 → 6.62e-3 at 2²⁰; sphere light 2.77e-9
    // both, 1.97e-9 both), at half the cost of an f32 point. The pins were
    // samples 0, 1, 2 000 000: (0x3fee_1a23_cc9e_c826, 0x3fe1_79f9_7684_6809),
    // (0x3f9a_458c_2f01_bf5d, 0x3fc5_1362_8126_63e5), (0x3fee_17c7_f8af_d8c3,
    // 0x3f9a_bee5_4d61_113d); the digests 0xf7e7_137e_50ba_c171,
    // 0xb39a_e19d_0778_4006, 0x8287_3b6d_fe1e_bfed, 0x5575_0201_bf8e_6d66,
    // 0x98b3_7d6e_c52c_7bb0. Re-pinned when the later pairs' cells on
    // grids with at least 16 columns (N not a power of two) came from five
    // Feistel rounds on the column and row instead of the cycle walk
    // (`stratified_shuffle.rs`): another relabelling of each pass's points
    // (which sample gets which cell of a later pair; the first pair, N =
    // 16 and N = 13 did not move). The digests of N = 1000, 3 125 000 and
    // 2³² − 1 were 0x84f4_af5c_3972_fcea, 0xf007_a30a_a3ce_7d5b and
    // 0xe359_eab0_03ec_ae66. Re-pinned again when the rounds moved to
    // 16-bit lanes with a 16-bit hash (another relabelling; N = 1000 was
    // 0xd024_6513_cb92_4ede, N = 3 125 000 0x7d08_5c88_7088_33a3) and
    // grids with a side above 2¹⁵ or more than nx²/4 rows went back to the
    // walk: N = 2³² − 1 (65 535 × 65 537) has its walk's digest again
    // (it was 0x3621_4f34_3eed_7030 with the rounds).
    let pinned: [(u64, u64, u64); 3] = [
        (0, 0x3fe7_fc54_83cb_c58a, 0x3fef_0bfc_42e7_828b),
        (1, 0x3fe7_f9d2_c3a1_f9b3, 0x3fef_100b_3923_1932),
        (2_000_000, 0x3fde_0ab5_7176_ee0e, 0x3fef_0a8a_dae1_886e),
    ];
    let mut s = Stratified::new(3_125_000, 0x1234).unwrap();
    for (i, x, y) in pinned {
        s.start_sample(i);
        let u = s.next_2d();
        assert_eq!((u.x.to_bits(), u.y.to_bits()), (x, y), "sample {i}");
    }
    let digests: [u64; 5] = [
        0x81bf_8873_d4b8_6e09,
        0x9e0a_86c2_7a3c_abf1,
        0x0c0f_f050_709d_6bb5,
        0x73d8_111c_1ce8_c1fc,
        0xe359_eab0_03ec_ae66,
    ];
    for ((n, seed), want) in STRATIFIED_CONFIGS.into_iter().zip(digests) {
        let seq = Stratified::new(n, seed).unwrap();
        assert_eq!(digest(read_bits(seq)), want, "stratified N {n} seed {seed}");
    }
}

/// Negative control: the digest sees a change of one bit in one value.
#[test]
fn digest_sees_one_changed_bit() {
    let mut bits = read_bits(Sobol::new(1));
    let before = digest(bits.iter().copied());
    bits[777] ^= 1;
    assert_ne!(digest(bits.iter().copied()), before);
    let mut moved = read_bits(Sobol::new(1));
    moved.swap(3, 4);
    assert_ne!(digest(moved), before);
}

/// What a sequence's split f32 fill (`fill_2d_split_f32`) stores.
#[derive(Clone, Copy)]
enum SplitF32 {
    /// The f64 point rounded down to 24 bits (the trait's default).
    RoundedDown,
    /// The cursor's own f32 point, `next_2d_f32` (stratified).
    CursorF32,
}

/// Batch fills give the cursor's values to the bit: every batch length
/// regime (a single point, below and above the table threshold, several
/// blocks with a partial one), requests in and past the first 256 Sobol
/// dimensions, a batch crossing a block of `2^32` Sobol indices, and one
/// wrapping past `2^64 − 1`. The two-request fills give the one-request
/// fills' values for both requests (request 127 and the next straddle
/// Sobol dimension 256, where the global layout's shuffle key changes).
/// Negative control: a two-request fill's second pair is not its first
/// request's.
fn check_batch_matches_cursor<S: SampleSequence>(seq: &S, name: &str, split_f32: SplitF32) {
    let ranges: [(u64, usize); 7] = [
        (0, 1),
        (5, 63),
        (5, 64),
        (3_120_000, 4096 + 37),
        ((1 << 32) - 300, 700),
        (u64::MAX - 10, 30),
        (12_345, 1000),
    ];
    let mut cursor = seq.clone();
    for (first, len) in ranges {
        for request in [0u64, 1, 2, 127, 128, 130] {
            let mut batch = vec![glam::DVec2::ZERO; len];
            let mut batch_f32 = vec![glam::Vec2::ZERO; len];
            let (mut split_x, mut split_y) = (vec![0.0f32; len], vec![0.0f32; len]);
            seq.fill_2d(first, request, &mut batch);
            seq.fill_2d_f32(first, request, &mut batch_f32);
            seq.fill_2d_split_f32(first, request, &mut split_x, &mut split_y);
            check_two_requests(seq, name, first, request, len);
            for k in 0..len {
                let i = first.wrapping_add(k as u64);
                cursor.start_sample(i);
                for _ in 0..request {
                    cursor.next_2d();
                }
                let mut again = cursor.clone();
                let u = cursor.next_2d();
                let v = again.next_2d_f32();
                assert_eq!(
                    (u.x.to_bits(), u.y.to_bits()),
                    (batch[k].x.to_bits(), batch[k].y.to_bits()),
                    "{name}: index {i} request {request}"
                );
                assert_eq!(
                    (v.x.to_bits(), v.y.to_bits()),
                    (batch_f32[k].x.to_bits(), batch_f32[k].y.to_bits()),
                    "{name} f32: index {i} request {request}"
                );
                // The split f32 fill rounds the f64 point down to 24 bits,
                // or gives the cursor's f32 point (stratified).
                let want = match split_f32 {
                    SplitF32::RoundedDown => (round_down_24(u.x), round_down_24(u.y)),
                    SplitF32::CursorF32 => (v.x, v.y),
                };
                assert_eq!(
                    (want.0.to_bits(), want.1.to_bits()),
                    (split_x[k].to_bits(), split_y[k].to_bits()),
                    "{name} split f32: index {i} request {request}"
                );
            }
        }
    }
}

/// The two-request fills of `request` and `request + 1` against the
/// one-request fills (see [`check_batch_matches_cursor`]).
fn check_two_requests<S: SampleSequence>(
    seq: &S,
    name: &str,
    first: u64,
    request: u64,
    len: usize,
) {
    let one = |r: u64| {
        let (mut x, mut y) = (vec![0.0f64; len], vec![0.0f64; len]);
        seq.fill_2d_split(first, r, &mut x, &mut y);
        let (mut xf, mut yf) = (vec![0.0f32; len], vec![0.0f32; len]);
        seq.fill_2d_split_f32(first, r, &mut xf, &mut yf);
        ((x, y), (xf, yf))
    };
    let (((x0, y0), (xf0, yf0)), ((x1, y1), (xf1, yf1))) = (one(request), one(request + 1));
    let mut two = vec![vec![0.0f64; len]; 4];
    let [a, b, c, d] = &mut two[..] else {
        unreachable!()
    };
    seq.fill_2d_split_two(first, request, [a, b, c, d]);
    assert_eq!(
        two,
        [x0.clone(), y0, x1, y1],
        "{name} two: {first} request {request}"
    );
    let mut two_f32 = vec![vec![0.0f32; len]; 4];
    let [a, b, c, d] = &mut two_f32[..] else {
        unreachable!()
    };
    seq.fill_2d_split_f32_two(first, request, [a, b, c, d]);
    assert_eq!(
        two_f32,
        [xf0, yf0, xf1, yf1],
        "{name} two f32: {first} request {request}"
    );
    if len > 1 {
        assert_ne!(two[2], x0, "{name}: the second pair is the first's");
    }
}

#[test]
fn sobol_batches_match_the_cursor() {
    for (name, seq) in sobol_configs() {
        check_batch_matches_cursor(&seq, name, SplitF32::RoundedDown);
    }
}

#[test]
fn stratified_batches_match_the_cursor() {
    for (n, seed) in STRATIFIED_CONFIGS {
        let seq = Stratified::new(n, seed).unwrap();
        let name = format!("stratified N {n}");
        check_batch_matches_cursor(&seq, &name, SplitF32::CursorF32);
    }
}

#[test]
fn independent_batches_match_the_cursor() {
    let independent = super::Independent::new(4);
    check_batch_matches_cursor(&independent, "independent", SplitF32::RoundedDown);
}
