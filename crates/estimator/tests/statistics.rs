//! Streaming statistics: accuracy on adversarial data, exact merges,
//! thread-count independence, and the honesty of the reported standard
//! error (docs/NUMERICS.md; the statistical-test standard in docs/ARCHITECTURE.md).
//!
//! Statistical family (all fixed seeds, so pass/fail is deterministic):
//! CI coverage at α = 1e-3, mean of z at α = 2.7e-3 (3σ), variance of z at
//! α = 2.7e-3: family-wise level 1 − (1 − 1e-3)(1 − 2.7e-3)² ≈ 6.4e-3.
//! Each has negative controls (a standard error mis-scaled by 1.5 either
//! way) that the same check, on the same replicates, must reject.

use lambert_estimator::statistics::{
    run_chunked, run_samples, Estimate, NeumaierSum, StatisticsError, BATCH_CHUNKS,
};
use lambert_sampling::sequence::{Independent, SampleSequence, Sobol};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg32;
use statrs::distribution::{Binomial, ChiSquared, ContinuousCDF, DiscreteCDF};

const EPS: f64 = f64::EPSILON;

// ---------------------------------------------------------------------------
// Accuracy on adversarial data
// ---------------------------------------------------------------------------

/// Samples 1e9 + k·2⁻²⁰ with integer k uniform in [−1024, 1024] (noise of
/// ±1e-3 on an offset of 1e9; every value exactly representable, since
/// 1e9 < 2³⁰ leaves bits down to 2⁻²²). The exact mean and variance follow
/// from integer sums of k and k² in i128:
/// mean = 1e9 + Σk/(n·2²⁰), s² = (n·Σk² − (Σk)²)/(n(n − 1)·2⁴⁰).
struct Adversarial {
    xs: Vec<f64>,
    mean: f64,
    variance: f64,
}

fn adversarial(n: usize, seed: u64) -> Adversarial {
    let mut rng = Pcg32::seed_from_u64(seed);
    let ks: Vec<i64> = (0..n).map(|_| rng.random_range(-1024..=1024)).collect();
    let scale = (-20.0_f64).exp2();
    let xs: Vec<f64> = ks.iter().map(|&k| 1e9 + k as f64 * scale).collect();
    let s1: i128 = ks.iter().map(|&k| k as i128).sum();
    let s2: i128 = ks.iter().map(|&k| (k * k) as i128).sum();
    let nn = n as i128;
    // Both reference values are rounded at most three times: < 4ε relative.
    let mean = 1e9 + (s1 as f64 / n as f64) * scale;
    let variance = (nn * s2 - s1 * s1) as f64 / (nn * (nn - 1)) as f64 * scale * scale;
    Adversarial { xs, mean, variance }
}

/// Naive two-pass: plain-loop mean, then Σ(x − m)²/(n − 1).
fn naive_two_pass(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, v)
}

/// Textbook one-pass (Σx² − n·m²)/(n − 1): the formula Welford replaces.
fn naive_one_pass_variance(xs: &[f64]) -> f64 {
    let n = xs.len() as f64;
    let (s, s2) = xs.iter().fold((0.0, 0.0), |(s, s2), x| (s + x, s2 + x * x));
    (s2 - s * s / n) / (n - 1.0)
}

/// Estimate against the exact values and against the naive computations.
///
/// Tolerances: the mean to 1 ulp of 1e9 (|Δ| ≤ ε·m; the compensated mean is
/// the exact mean rounded once, and the reference rounded at most twice).
/// The variance to 1e-13 relative: each Welford term (x − m_{k−1})(x − m_k)
/// is formed with the double-length mean, so carries a few ε of relative
/// error, and the compensated M₂ adds them with no growth in n; the bound
/// is ~10ε ≈ 2e-15, the tolerance 45× that. The naive two-pass mean (plain
/// loop over 1e5 values near 1e9: error ~√n·ulp(1e14)/n ≈ 1e-5) feeds a
/// bias of (Δm)² into its variance; the textbook one-pass formula cancels
/// 1e18-sized terms to get 8e-8 and is wrong by orders of magnitude.
#[test]
fn welford_and_neumaier_on_large_offset_with_small_noise() {
    for seed in [1u64, 2, 3] {
        let data = adversarial(100_000, seed);
        let e: Estimate = data.xs.iter().copied().collect();
        let m = e.mean().unwrap();
        let v = e.variance().unwrap();
        let (nm, nv) = naive_two_pass(&data.xs);
        let one_pass = naive_one_pass_variance(&data.xs);
        let rel_v = (v - data.variance).abs() / data.variance;
        let rel_nv = (nv - data.variance).abs() / data.variance;
        eprintln!(
            "seed {seed}: mean err {:e} (naive {:e}); var rel err {rel_v:e} (naive two-pass {rel_nv:e}, one-pass {:e})",
            m - data.mean,
            nm - data.mean,
            (one_pass - data.variance).abs() / data.variance,
        );
        assert!(
            (m - data.mean).abs() <= EPS * data.mean,
            "mean {m} vs {}",
            data.mean
        );
        assert!(rel_v <= 1e-13, "variance rel err {rel_v:e}");
        // At least as good as the naive two-pass, which is itself far off.
        assert!((m - data.mean).abs() <= (nm - data.mean).abs());
        assert!(rel_v <= rel_nv);
        assert!((one_pass - data.variance).abs() > 0.1 * data.variance);
    }
}

/// Chunked over 8 threads, the same data gives the same tolerances.
#[test]
fn adversarial_data_through_the_parallel_runner() {
    let data = adversarial(100_000, 4);
    let xs = &data.xs;
    let e = run_chunked(xs.len() as u64, 777, 8, |_, r| {
        xs[r.start as usize..r.end as usize]
            .iter()
            .copied()
            .collect()
    })
    .unwrap();
    assert!((e.mean().unwrap() - data.mean).abs() <= EPS * data.mean);
    assert!((e.variance().unwrap() - data.variance).abs() <= 1e-13 * data.variance);
}

// ---------------------------------------------------------------------------
// Constant integrand, 1e8 and 1e9 samples
// ---------------------------------------------------------------------------

/// 0.1 is not representable; the exact mean of n copies of the f64 0.1 is
/// that f64 itself. A plain running sum drifts (~1e-9 relative at 1e8).
const TENTH: f64 = 0.1;

fn constant_one_by_one(total: u64) -> Estimate {
    run_chunked(total, 1 << 22, 2, |_, r| {
        let mut e = Estimate::new();
        for _ in r {
            e.push(std::hint::black_box(TENTH));
        }
        e
    })
    .unwrap()
}

fn assert_exact_constant_mean(e: &Estimate, total: u64) {
    assert_eq!(e.n(), total);
    let rel = (e.mean().unwrap() - TENTH).abs() / TENTH;
    assert!(rel <= 1e-15, "relative error {rel:e}");
    assert!(e.variance().unwrap() <= (EPS * TENTH).powi(2));
}

/// 1e8 samples pushed one by one (24 chunks on 2 threads; ~0.3 s at
/// opt-level 3): relative error of the mean ≤ 1e-15 (it is 0).
#[test]
fn constant_integrand_1e8_one_by_one_mean_is_exact() {
    let total = 100_000_000;
    let e = constant_one_by_one(total);
    assert_exact_constant_mean(&e, total);
    assert_eq!(e.mean(), Some(TENTH));
    // The plain loop is measurably off (the reason for compensation).
    let mut plain = 0.0;
    for _ in 0..total {
        plain += std::hint::black_box(TENTH);
    }
    assert!((plain / total as f64 - TENTH).abs() / TENTH > 1e-12);
}

/// 1e9 samples through the runner with the bulk path (`push_n` per chunk,
/// 1000 chunks of 1e6 merged in order): relative error ≤ 1e-15. Runs by
/// default (milliseconds).
#[test]
fn constant_integrand_1e9_bulk_through_runner_mean_is_exact() {
    let total = 1_000_000_000;
    let e = run_chunked(total, 1_000_000, 2, |_, r| {
        let mut e = Estimate::new();
        e.push_n(TENTH, r.end - r.start);
        e
    })
    .unwrap();
    assert_exact_constant_mean(&e, total);
    let mut single = Estimate::new();
    single.push_n(TENTH, total);
    assert_exact_constant_mean(&single, total);
}

/// 1e9 samples pushed one by one, through the parallel runner in 239
/// chunks of 2²² on 2 threads: 2.8 s measured at opt-level 3 (the test
/// profile) on this machine class, so it runs by default. Relative error of
/// the mean ≤ 1e-15 (it is 0).
#[test]
fn constant_integrand_1e9_one_by_one_mean_is_exact() {
    let total = 1_000_000_000;
    let e = constant_one_by_one(total);
    assert_exact_constant_mean(&e, total);
    assert_eq!(e.mean(), Some(TENTH));
}

// ---------------------------------------------------------------------------
// Merge against one pass
// ---------------------------------------------------------------------------

fn bits(e: &Estimate) -> [u64; 4] {
    [
        e.n(),
        e.sum().unwrap().to_bits(),
        e.mean().unwrap().to_bits(),
        e.variance().unwrap().to_bits(),
    ]
}

/// Integer data (partial sums exact): the merged sum and mean equal the
/// one-pass ones to the bit, for any split; the variance to 1e-14 relative
/// (Welford and Chan round differently; both are within ~10ε of exact).
#[test]
fn merge_equals_one_pass_to_the_bit_for_integer_data() {
    let mut rng = Pcg32::seed_from_u64(10);
    let xs: Vec<f64> = (0..100_000)
        .map(|_| rng.random_range(0..1000) as f64)
        .collect();
    let whole: Estimate = xs.iter().copied().collect();
    for split in [1, 17, 50_000, 99_999] {
        let a: Estimate = xs[..split].iter().copied().collect();
        let b: Estimate = xs[split..].iter().copied().collect();
        let m = a.merged(&b);
        assert_eq!(m.n(), whole.n());
        assert_eq!(m.sum().unwrap().to_bits(), whole.sum().unwrap().to_bits());
        assert_eq!(m.mean().unwrap().to_bits(), whole.mean().unwrap().to_bits());
        let (vm, vw) = (m.variance().unwrap(), whole.variance().unwrap());
        assert!((vm - vw).abs() <= 1e-14 * vw, "split {split}: {vm} {vw}");
    }
}

/// Real-valued data U(0,1)²: merging 2 or 100 pieces in order agrees with
/// one pass to one rounding of the mean (|Δ| ≤ ε·m: both are the exact mean
/// rounded once, up to O(n ε²)) and 1e-14 relative on the variance.
#[test]
fn merge_equals_one_pass_within_rounding_for_real_data() {
    let mut rng = Pcg32::seed_from_u64(11);
    let xs: Vec<f64> = (0..200_000).map(|_| rng.random::<f64>().powi(2)).collect();
    let whole: Estimate = xs.iter().copied().collect();
    for pieces in [2usize, 100] {
        let size = xs.len().div_ceil(pieces);
        let merged = xs
            .chunks(size)
            .map(|c| c.iter().copied().collect::<Estimate>())
            .fold(Estimate::new(), |acc, e| acc.merged(&e));
        let (mm, mw) = (merged.mean().unwrap(), whole.mean().unwrap());
        let (vm, vw) = (merged.variance().unwrap(), whole.variance().unwrap());
        eprintln!(
            "{pieces} pieces: mean Δ {:e} ulp-rel, var rel Δ {:e}",
            (mm - mw) / (EPS * mw),
            (vm - vw) / vw
        );
        assert!((mm - mw).abs() <= EPS * mw);
        assert!((vm - vw).abs() <= 1e-14 * vw);
    }
    // The compensated sum agrees with an exactly rounded reference (the sum
    // of squares of 53-bit numbers, accumulated as integers of 2⁻¹⁰⁶).
    let neumaier: NeumaierSum = xs.iter().copied().sum();
    let exact: u128 = xs
        .iter()
        .map(|&x| (x * (106.0_f64).exp2()) as u128) // x < 1, multiples of 2⁻¹⁰⁶
        .sum();
    let exact = exact as f64 * (-106.0_f64).exp2();
    assert!((neumaier.sum() - exact).abs() <= EPS * exact);
}

// ---------------------------------------------------------------------------
// Thread-count independence
// ---------------------------------------------------------------------------

fn x_squared<S: SampleSequence>(s: &mut S) -> f64 {
    s.next_1d().powi(2)
}

/// ∫₀¹ x² dx over 1 000 003 Independent samples in chunks of 4096 (245
/// chunks, the last one short): identical bits on 1, 2 and 8 threads and
/// across two runs; a single chunk equals a plain sequential loop.
#[test]
fn bit_identical_for_1_2_and_8_threads_and_across_runs() {
    let seq = Independent::new(2024);
    let total = 1_000_003;
    let reference = run_samples(&seq, total, 4096, 1, x_squared).unwrap();
    for threads in [1, 2, 8] {
        for _run in 0..2 {
            let e = run_samples(&seq, total, 4096, threads, x_squared).unwrap();
            assert_eq!(e, reference, "{threads} threads");
            assert_eq!(bits(&e), bits(&reference), "{threads} threads");
        }
    }
    assert!(reference.z(1.0 / 3.0).unwrap().abs() < 4.0);
    // Sobol (random access too): same property.
    let sobol = Sobol::new(5);
    let a = run_samples(&sobol, 1 << 18, 1000, 1, x_squared).unwrap();
    let b = run_samples(&sobol, 1 << 18, 1000, 8, x_squared).unwrap();
    assert_eq!(bits(&a), bits(&b));
    // One chunk = the sequential loop.
    let one = run_samples(&seq, 10_000, 10_000, 2, x_squared).unwrap();
    let mut s = seq.clone();
    let mut seq_e = Estimate::new();
    for i in 0..10_000 {
        s.start_sample(i);
        seq_e.push(x_squared(&mut s));
    }
    assert_eq!(bits(&one), bits(&seq_e));
}

/// Across the runner's batch boundaries (chunks are folded [`BATCH_CHUNKS`]
/// at a time): 2.5 batches of one-sample chunks, each chunk's value a
/// different real number, give on 1, 2 and 3 threads the bits of folding
/// the chunk estimates one by one in chunk order on this thread.
#[test]
fn bit_identical_across_batches_of_chunks() {
    let total = BATCH_CHUNKS * 5 / 2 + 7;
    let value = |k: u64| ((k as f64) * 0.618_033_988_749_895).fract().powi(3);
    let chunk = |k: u64, r: std::ops::Range<u64>| r.map(|_| value(k)).collect::<Estimate>();
    let mut folded = Estimate::new();
    for k in 0..total {
        folded.merge(&chunk(k, k..k + 1));
    }
    for threads in [1, 2, 3] {
        let e = run_chunked(total, 1, threads, chunk).unwrap();
        assert_eq!(e.n(), total);
        assert_eq!(bits(&e), bits(&folded), "{threads} threads");
    }
    // Negative control: a fold that lost the first chunk of the second
    // batch (an off-by-one at a boundary) shows in the bits.
    let mut lost = Estimate::new();
    for k in (0..total).filter(|&k| k != BATCH_CHUNKS) {
        lost.merge(&chunk(k, k..k + 1));
    }
    assert_ne!(bits(&lost), bits(&folded));
}

#[test]
fn runner_rejects_bad_parameters_and_handles_zero_samples() {
    let f = |_: u64, _: std::ops::Range<u64>| Estimate::new();
    assert_eq!(
        run_chunked(10, 0, 1, f),
        Err(StatisticsError::ZeroChunkSize)
    );
    assert_eq!(run_chunked(10, 1, 0, f), Err(StatisticsError::ZeroThreads));
    assert_eq!(run_chunked(0, 5, 2, f), Ok(Estimate::new()));
    // Chunk ranges tile 0..total in order.
    let ranges = std::sync::Mutex::new(Vec::new());
    run_chunked(10_001, 1000, 2, |k, r| {
        ranges.lock().unwrap().push((k, r));
        Estimate::new()
    })
    .unwrap();
    let mut ranges = ranges.into_inner().unwrap();
    ranges.sort_by_key(|(k, _)| *k);
    assert_eq!(ranges.len(), 11);
    for (k, r) in &ranges {
        assert_eq!(r.start, k * 1000);
        assert_eq!(r.end, ((k + 1) * 1000).min(10_001));
    }
}

// ---------------------------------------------------------------------------
// Honest standard errors: CI coverage and the spread of z
// ---------------------------------------------------------------------------

/// Replicate r: ∫₀¹ x² dx = 1/3 with 4096 Independent samples of stream
/// `split(r)`. Per sample, x² has skewness ≈ 0.64, so the mean of 4096 is
/// normal to ~1 % in its skewness (0.64/√4096): the coverage error of a 99 %
/// interval is O(1/n), far inside the binomial band below.
const SAMPLES_PER_REPLICATE: u64 = 4096;
const TRUE_MEAN: f64 = 1.0 / 3.0;

fn replicates(count: u64, seed: u64) -> Vec<Estimate> {
    let parent = Independent::new(seed);
    (0..count)
        .map(|r| {
            let mut seq = parent.split(r);
            let mut e = Estimate::new();
            for i in 0..SAMPLES_PER_REPLICATE {
                seq.start_sample(i);
                e.push(x_squared(&mut seq));
            }
            e
        })
        .collect()
}

/// The two-sided acceptance band [lo, hi] for K ~ Binomial(n, p) at level
/// α: the largest lo with P(K < lo) ≤ α/2 and the smallest hi with
/// P(K > hi) ≤ α/2.
fn binomial_band(n: u64, p: f64, alpha: f64) -> (u64, u64) {
    let b = Binomial::new(p, n).unwrap();
    let lo = (0..=n)
        .take_while(|&k| k == 0 || b.cdf(k - 1) <= alpha / 2.0)
        .last()
        .unwrap();
    let hi = (0..=n).find(|&k| b.sf(k) <= alpha / 2.0).unwrap();
    (lo, hi)
}

const CI_REPLICATES: u64 = 2000;
const CI_LEVEL: f64 = 0.99;
/// Level of the coverage test.
const CI_ALPHA: f64 = 1e-3;

/// Counts replicates whose interval, with its half-width scaled by `scale`,
/// covers the true mean.
fn coverage(reps: &[Estimate], scale: f64) -> u64 {
    reps.iter()
        .filter(|e| {
            let ci = e.confidence_interval(CI_LEVEL).unwrap();
            (ci.mean - TRUE_MEAN).abs() <= scale * ci.half_width
        })
        .count() as u64
}

/// 2000 replicate 99 % intervals: the number covering 1/3 is
/// Binomial(2000, 0.99) (mean 1980, sd 4.45) if the intervals are honest.
/// Accepted in the exact binomial band at α = 1e-3 ([1964, 1993]); the
/// negative controls (half-widths 1.5× too small: coverage ≈ 91 %; 1.5× too
/// large: ≈ 99.99 %) must fall outside the same band.
#[test]
fn ci_coverage_99_percent_within_binomial_band_with_negative_controls() {
    let reps = replicates(CI_REPLICATES, 77);
    let (lo, hi) = binomial_band(CI_REPLICATES, CI_LEVEL, CI_ALPHA);
    let honest = coverage(&reps, 1.0);
    let narrow = coverage(&reps, 1.0 / 1.5);
    let wide = coverage(&reps, 1.5);
    eprintln!("band [{lo}, {hi}]; covered {honest}, narrow {narrow}, wide {wide}");
    assert!(
        (lo..=hi).contains(&honest),
        "coverage {honest} outside [{lo}, {hi}]"
    );
    assert!(
        !(lo..=hi).contains(&narrow),
        "narrow control {narrow} accepted"
    );
    assert!(!(lo..=hi).contains(&wide), "wide control {wide} accepted");
}

const Z_SEEDS: u64 = 200;
/// Level of each of the two z checks (3σ two-sided).
const Z_ALPHA: f64 = 2.699_796_063_260_2e-3;

/// Mean and sample variance of z values.
fn mean_and_variance(zs: &[f64]) -> (f64, f64) {
    let e: Estimate = zs.iter().copied().collect();
    (e.mean().unwrap(), e.variance().unwrap())
}

/// Bounds of the z checks over `k` values: |z̄| ≤ 3/√k (z̄ ~ N(0, 1/k)),
/// and s_z² in [χ²_{α/2}, χ²_{1−α/2}]/(k − 1) with k − 1 degrees of freedom
/// ((k − 1)s²/σ² ~ χ²(k − 1) for normal z, σ² = 1).
fn z_bounds(k: u64) -> (f64, f64, f64) {
    let chi = ChiSquared::new((k - 1) as f64).unwrap();
    let dof = (k - 1) as f64;
    (
        3.0 / (k as f64).sqrt(),
        chi.inverse_cdf(Z_ALPHA / 2.0) / dof,
        chi.inverse_cdf(1.0 - Z_ALPHA / 2.0) / dof,
    )
}

/// z = (m − 1/3)/(s/√n) over 200 seeds is ~N(0, 1) if the standard error
/// is honest (with s estimated from 4096 samples z is t-distributed, of
/// variance 4095/4093 = 1.0005: negligible against the band). Checks, each
/// at α = 2.7e-3: |z̄| ≤ 3/√200 = 0.212, and the sample variance of z in
/// the χ²(199) band [0.726, 1.328]. Negative controls on the same
/// replicates: a standard error 1.5× too large (variance of z ≈ 0.44) and
/// 1.5× too small (≈ 2.25) are both rejected by the variance check.
#[test]
fn z_over_200_seeds_is_standard_normal_and_miscaled_errors_are_rejected() {
    let reps = replicates(Z_SEEDS, 4242);
    let zs: Vec<f64> = reps.iter().map(|e| e.z(TRUE_MEAN).unwrap()).collect();
    let (mean_bound, var_lo, var_hi) = z_bounds(Z_SEEDS);
    let (zm, zv) = mean_and_variance(&zs);
    eprintln!("z: mean {zm:.4} (±{mean_bound:.4}), variance {zv:.4} in [{var_lo:.4}, {var_hi:.4}]");
    assert!(zm.abs() <= mean_bound, "mean of z {zm}");
    assert!((var_lo..=var_hi).contains(&zv), "variance of z {zv}");
    for scale in [1.5, 1.0 / 1.5] {
        // A standard error `scale` times the honest one divides z by `scale`.
        let bad: Vec<f64> = zs.iter().map(|z| z / scale).collect();
        let (_, bv) = mean_and_variance(&bad);
        eprintln!("control: standard error × {scale:.3}: variance of z {bv:.4}");
        assert!(
            !(var_lo..=var_hi).contains(&bv),
            "scale {scale}: variance {bv} accepted"
        );
    }
}

/// `from_values` (two passes over a buffer) agrees with one-by-one pushes:
/// same n, mean to the bit on integer-valued data (both sums are exact),
/// variance to 270u relative (u = 2⁻⁵³): `from_values` sums M₂'s
/// non-negative terms plainly, at most 256 per lane and window, within
/// (255 + 3 + 2)u of the exact M₂ (each term within about 3u, 2u for the
/// compensated totals), and the pushes' compensated M₂ is within a few u
/// (Welford's terms with double-length means, Neumaier's sum); 270u
/// covers both.
#[test]
fn from_values_matches_pushes() {
    use lambert_estimator::Estimate;
    let values: Vec<f64> = (0..10_000).map(|i| ((i * 7919) % 1000) as f64).collect();
    let a = Estimate::from_values(&values);
    let b: Estimate = values.iter().copied().collect();
    assert_eq!(a.n(), b.n());
    assert_eq!(a.mean(), b.mean());
    let (va, vb) = (a.variance().unwrap(), b.variance().unwrap());
    let tolerance = 270.0 * (f64::EPSILON / 2.0);
    assert!((va - vb).abs() <= tolerance * vb, "{va} vs {vb}");
    let with_nan = Estimate::from_values(&[1.0, f64::NAN, 3.0]);
    assert_eq!(with_nan.non_finite(), 1);
    assert_eq!(Estimate::from_values(&[]).n(), 0);
}
