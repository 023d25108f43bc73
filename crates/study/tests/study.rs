//! Statistical tests of `lambert study`: the honesty of every estimator's
//! 99 % intervals (the spread of z per scene × strategy × sequence, and
//! coverage per strategy × sequence, randomized QMC included), and the
//! fitted convergence slopes of independent Monte Carlo (−½) and
//! Owen-scrambled Sobol (steeper than −¾) on smooth scenes, each with a
//! negative control that the same check rejects.
//!
//! Deterministic (fixed seeds). Intervals over the whole built-in suite;
//! slopes over the smooth scenes.

use lambert_estimator::clt::{clt_applies, normal_score};
use lambert_estimator::estimation::{prepare, SequenceKind, RQMC_REPLICATES};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::strategy::{PreparedEmitter, Strategy};
use lambert_estimator::ConfidenceInterval;
use lambert_study::{
    aggregate, fit_loglog, plan, run_replicates, LogLogFit, StudyConfig, StudyScene,
};
use lambert_validate::{critical_value, sidak_level};
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal, StudentsT};
use std::collections::BTreeMap;

/// The two-sided binomial acceptance band [lo, hi] for X ~ Bin(k, p) at
/// level alpha: the largest lo with P(X < lo) ≤ α/2 and the smallest hi
/// with P(X > hi) ≤ α/2 (pmf summed exactly in f64).
fn binomial_band(k: u64, p: f64, alpha: f64) -> (u64, u64) {
    let pmf = binomial_pmf(k, p);
    let mut lo = 0;
    let mut below = 0.0;
    while below + pmf[lo as usize] <= alpha / 2.0 {
        below += pmf[lo as usize];
        lo += 1;
    }
    let mut hi = k;
    let mut above = 0.0;
    while above + pmf[hi as usize] <= alpha / 2.0 {
        above += pmf[hi as usize];
        hi -= 1;
    }
    (lo, hi)
}

/// P(X = x), x = 0 … k, for X ~ Bin(k, p) (log pmf by recursion from 0).
fn binomial_pmf(k: u64, p: f64) -> Vec<f64> {
    let mut pmf = Vec::with_capacity(k as usize + 1);
    let mut log = k as f64 * (1.0 - p).ln();
    for x in 0..=k {
        pmf.push(log.exp());
        if x < k {
            log += ((k - x) as f64).ln() - ((x + 1) as f64).ln() + p.ln() - (1.0 - p).ln();
        }
    }
    pmf
}

#[test]
fn binomial_band_is_right() {
    // Bin(100, 0.5) at α = 0.05: the usual 40…60.
    assert_eq!(binomial_band(100, 0.5, 0.05), (40, 60));
}

/// Family-wise level of each family of interval tests.
const FAMILY_ALPHA: f64 = 0.01;
/// The least power a negative control must have at its test's level.
const CONTROL_POWER: f64 = 0.999;

/// The interval tests' study: every built-in scene × the six strategies ×
/// the three sequences, each estimator at one N ([`MIN_EFFECTIVE_SAMPLES`])
/// with 144 replicates, so K = 144 intervals per estimator: what a single
/// estimator at 90 % coverage needs to be caught with power ≥ 0.999 at the
/// family's level (120 give 0.9986).
fn interval_config() -> StudyConfig {
    StudyConfig {
        name: "intervals".into(),
        n_min_log2: 10,
        n_max_log2: 13,
        replicates: 144,
        seed: 99,
        ..StudyConfig::builtin()
    }
}

/// Each estimator is tested at the smallest N = 2^10 … 2^13 at which its
/// normal (or t) interval can be expected to be honest, judged from an
/// independent-sample pilot at N = 2^10 (the same scene and strategy): with
/// V the variance of one sample's estimate and E the truth, N·E²/V is the
/// effective sample count (a light seen by a fraction p of the samples
/// gives N·E²/V ≈ Np hits), and the interval's error is that of the central
/// limit theorem, of the order of the estimate's skewness ≈ 1/√(N·E²/V).
///
/// * Independent samples: N·E²/V ≥ 100 (skewness ≤ 0.1). Measured:
///   uniform-hemisphere sampling of the overhead sphere (5 hits at 2^10)
///   and of the grazing rectangle fail the test at 2^10 (Σz² 232 and 228
///   against a band ending at 223).
/// * Randomized QMC: (N/16)·E²/V ≥ 20, i.e. about 20 hits in each of the 16
///   randomizations. With fewer, stratified and Sobol points make each
///   randomization's hit count nearly fixed (⌊Np/16⌋ or ⌈Np/16⌉), the 16
///   means nearly agree, and the t interval can be far too narrow. Measured
///   for uniform-hemisphere sampling of the overhead sphere over 200 seeds:
///   mean z² 0.97 at N = 2^10 (0.3 hits per randomization), 5400 at 2^12
///   and 75 000 at 2^14 (z down to −1100 when all 16 randomizations hit it
///   once), 0.98 at 2^16 (20 hits each).
///
/// An estimator that needs more than 2^13 is not tested here (the cost of
/// 144 replicates); only the rare-hit hemisphere strategies may (asserted).
const MIN_EFFECTIVE_SAMPLES: f64 = 100.0;

/// Hits per randomization the randomized-QMC intervals need (see
/// [`MIN_EFFECTIVE_SAMPLES`]).
const MIN_HITS_PER_RANDOMIZATION: f64 = 20.0;

/// Estimators whose randomized-QMC t interval this test finds dishonest:
/// found by it, not fixed here. The test asserts that each still fails, so
/// that a fix shows up as a failure asking to shorten this list. None today.
const KNOWN_DISHONEST: [(&str, Strategy, SequenceKind); 0] = [];

/// Estimators this test once found dishonest, which now say so themselves:
/// their intervals are rare-event ones, judged by coverage, not Σz² (the
/// test asserts it).
///
/// * Uniform-hemisphere sampling of the large coaxial disk: the disk's rim
///   is the line u₀ = cos 1.2 of the sample square (z = u₀), parallel to the
///   strata, so stratified and Sobol points fix each randomization's hit
///   count up to the one point in the straddling interval; the 16
///   randomization means then often nearly agree and the t interval was far
///   too narrow, the more so as N grows (over 300 seeds, mean z² 1.5 at
///   N = 2^8, 5 at 2^10, 54 at 2^14, 126 at 2^16, for both sequences). The
///   estimator now sees the fixed count and adds one hit's worth (warning
///   `FixedCount`). Cosine sampling of the same disk (a circular rim in the
///   square) passes as a CLT estimator.
/// * Balance-heuristic MIS of the tilted sphere, stratified: the rare
///   cosine hits of the small sphere carry weight (as for the small disk of
///   `clt_applies`), a few per randomization; that part now has fewer than
///   30 hits and its rare-event bound.
const FORMERLY_DISHONEST: [(&str, Strategy, SequenceKind); 3] = [
    (
        "disk-coaxial-large",
        Strategy::UniformHemisphere,
        SequenceKind::Stratified,
    ),
    (
        "disk-coaxial-large",
        Strategy::UniformHemisphere,
        SequenceKind::Sobol,
    ),
    (
        "sphere-tilted-30",
        Strategy::Mis(lambert_estimator::strategy::Heuristic::Balance),
        SequenceKind::Stratified,
    ),
];

/// One estimator's 99 % intervals: its z = (estimate − truth)/se per
/// replicate and row, and how many intervals covered the truth.
struct Intervals {
    scene: String,
    strategy: Strategy,
    sequence: SequenceKind,
    /// log₂ N of its rows.
    log2_n: u32,
    /// (estimate − truth), and the interval's half-width, per interval.
    errors: Vec<(f64, f64)>,
    /// Whether every interval is the CLT one. Σz² judges only those; the
    /// rare-event and bounded intervals (a part with < 30 hits, a count
    /// fixed by stratification, a heavy tail) are judged by coverage.
    clt: bool,
}

/// The quantile q of the study's 99 % intervals (half-width q·se): normal
/// for independent samples (N ≥ 30), Student-t with 15 degrees of freedom
/// for the 16 randomizations of randomized QMC.
fn quantile(sequence: SequenceKind) -> f64 {
    let n = match sequence {
        SequenceKind::Independent => 1 << 10,
        _ => RQMC_REPLICATES,
    };
    ConfidenceInterval::new(0.0, 1.0, n, 0.99).quantile
}

impl Intervals {
    /// Σ (normal score)² with every standard error divided by `shrink`
    /// (1 for the estimator as it is), and the number of intervals.
    fn sum_of_squares(&self, shrink: f64) -> (f64, usize) {
        let q = quantile(self.sequence);
        let s = self
            .errors
            .iter()
            .map(|&(e, h)| normal_score(e / (h / q) * shrink, self.sequence).powi(2))
            .sum();
        (s, self.errors.len())
    }

    /// Intervals whose half-width, times `scale`, covers the truth.
    fn covered(&self, scale: f64) -> usize {
        self.errors
            .iter()
            .filter(|&&(e, h)| e.abs() <= h * scale)
            .count()
    }
}

/// The interval study: the estimators tested ([`Intervals`]) and those
/// left out because they need N > 2^13 (scene, strategy, sequence, N).
struct IntervalStudy {
    tested: Vec<Intervals>,
    untested: Vec<(String, Strategy, SequenceKind, f64)>,
}

/// The interval study, run once for the tests that read it.
fn intervals() -> &'static IntervalStudy {
    static STUDY: std::sync::OnceLock<IntervalStudy> = std::sync::OnceLock::new();
    STUDY.get_or_init(run_intervals)
}

/// Runs the interval study: per scene and strategy an independent pilot
/// at N = 2^10 (also that estimator's test rows if it needs no more), then
/// every sequence at its N ([`MIN_EFFECTIVE_SAMPLES`]). Estimators with
/// no variance (cosine sampling under a sky, delta lights) have nothing to
/// cover and are left out, as are those the central limit theorem does not
/// describe at any N here ([`clt_applies`]).
fn run_intervals() -> IntervalStudy {
    let config = interval_config();
    let mut study = IntervalStudy {
        tested: Vec::new(),
        untested: Vec::new(),
    };
    let mut index = 0;
    for (scene_index, scene) in config.scenes.iter().enumerate() {
        let truth = scene.reference.expect("built-in scenes have closed forms");
        for &strategy in &config.strategies {
            if !clt_applies(&scene.name, strategy) {
                continue;
            }
            let mut key = |sequence, log2_n| {
                index += 1;
                lambert_study::RowKey {
                    index,
                    scene: scene_index,
                    strategy,
                    sequence,
                    precision: lambert_estimator::precision::Precision::F64,
                    log2_n,
                }
            };
            let systematic: f64 = prepare(&scene.scene, strategy)
                .0
                .iter()
                .map(PreparedEmitter::systematic_error)
                .sum();
            let pilot_key = key(SequenceKind::Independent, config.n_min_log2);
            let pilot = run_replicates(&config, &pilot_key).unwrap();
            let v = pilot.iter().map(|r| r.sample_variance).sum::<f64>() / pilot.len() as f64;
            let relative_variance = v / (truth * truth);
            for &sequence in &config.sequences {
                let needed = match sequence {
                    SequenceKind::Independent => MIN_EFFECTIVE_SAMPLES * relative_variance,
                    _ => MIN_HITS_PER_RANDOMIZATION * RQMC_REPLICATES as f64 * relative_variance,
                };
                let log2_n = config.n_min_log2.max(needed.log2().ceil() as u32);
                if log2_n > config.n_max_log2 {
                    study
                        .untested
                        .push((scene.name.clone(), strategy, sequence, needed));
                    continue;
                }
                let reps = if sequence == SequenceKind::Independent && log2_n == config.n_min_log2 {
                    pilot.clone()
                } else {
                    run_replicates(&config, &key(sequence, log2_n)).unwrap()
                };
                let errors: Vec<(f64, f64)> = reps
                    .iter()
                    .map(|r| (r.mean - truth, 0.5 * (r.ci99.1 - r.ci99.0)))
                    .collect();
                // Exact estimators (cosine sampling under a sky, a delta
                // light, projected sampling of a uniform light) report the
                // rounding floor (21u + 4(N + 2)u²)·(m + |δ|) ≤ 2.4e-15·m at
                // N ≤ 2^13, plus the projected samplers' bound on their Ω⊥
                // error, not a sampling σ: any σ ≤ 3e-15·|m| + that bound
                // is that floor, and such an estimator has nothing to cover.
                let sampled = reps
                    .iter()
                    .any(|r| r.std_error > 3e-15 * r.mean.abs() + systematic);
                if sampled {
                    study.tested.push(Intervals {
                        scene: scene.name.clone(),
                        strategy,
                        sequence,
                        log2_n,
                        errors,
                        clt: reps
                            .iter()
                            .all(|r| r.interval == IntervalKind::CentralLimit),
                    });
                }
            }
        }
    }
    study
}

/// The two-sided acceptance band of Σ z² over K intervals at level α:
/// the χ²(K) points α/2 and 1 − α/2.
fn chi_square_band(k: usize, alpha: f64) -> (f64, f64) {
    let kf = k as f64;
    (
        ChiSquared::new(kf)
            .unwrap()
            .inverse_cdf(alpha / 2.0)
            .max(0.0),
        critical_value(kf, alpha / 2.0),
    )
}

/// The interval half-width factor κ that makes a 99 % interval a 90 % one
/// (z₀.₉₅/z₀.₉₉₅ for normal z, the t(15) quantiles' ratio for randomized
/// QMC): an estimator reporting its standard error κ times too small.
fn ninety_percent(sequence: SequenceKind) -> f64 {
    let q90 = match sequence {
        SequenceKind::Independent => Normal::standard().inverse_cdf(0.95),
        _ => StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64)
            .unwrap()
            .inverse_cdf(0.95),
    };
    quantile(sequence) / q90
}

/// The power of the spread test against a randomized-QMC estimator made
/// to cover 90 %: its scores s = Φ⁻¹(F_t(κT)), T ~ t(15), κ the t
/// quantiles' ratio; E[s²] and Var[s²] by Simpson's rule over T ∈ [−60, 60]
/// (the t(15) density is ~1e-24 beyond), and Σ s² over K intervals taken as
/// a·χ²(b) with the same two moments (Satterthwaite 1946).
fn rqmc_control_power(k: usize, lo: f64, hi: f64) -> f64 {
    let nu = (RQMC_REPLICATES - 1) as f64;
    let t = StudentsT::new(0.0, 1.0, nu).unwrap();
    let kappa = ninety_percent(SequenceKind::Sobol);
    let steps = 120_000;
    let h = 120.0 / steps as f64;
    let (mut m1, mut m2) = (0.0, 0.0);
    for i in 0..=steps {
        let x = -60.0 + h * i as f64;
        let weight = if i == 0 || i == steps {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let density = statrs::distribution::Continuous::pdf(&t, x);
        let s2 = normal_score(kappa * x, SequenceKind::Sobol).powi(2);
        m1 += weight * density * s2;
        m2 += weight * density * s2 * s2;
    }
    let (m1, m2) = (m1 * h / 3.0, m2 * h / 3.0);
    let variance = m2 - m1 * m1;
    let (a, b) = (variance / (2.0 * m1), 2.0 * k as f64 * m1 * m1 / variance);
    let chi = ChiSquared::new(b).unwrap();
    chi.sf(hi / a) + chi.cdf(lo / a)
}

/// The spread of z, estimator by estimator: for honest 99 % intervals the
/// normal scores of z are N(0, 1) and Σ z² over an estimator's K = 120
/// intervals is χ²(K) (K = 144); too large (intervals too narrow, or a bias) is as
/// wrong as too small (too wide). One two-sided test per estimator
/// (scene × strategy × sequence: 12 × 6 × 3 less the 9 rare-event ones, the
/// exact ones and those needing N > 2^13), Šidák-corrected over all of
/// them; the [`KNOWN_DISHONEST`] ones must fail it.
///
/// Negative control, the one the pooled coverage test of old could not
/// see: each estimator in turn made to report a standard error κ times too
/// small (κ = z₀.₉₉₅/z₀.₉₅ = 1.57, so that its 99 % intervals cover 90 %)
/// must be rejected by its test. Its power, for independent samples
/// exactly P(κ²χ²(144) outside the band), is stated and required ≥ 0.999;
/// for randomized QMC (scores of a t(15) scaled by the t quantiles' ratio
/// 1.68) it is at least as high (stated, from the scores' moments).
#[test]
fn the_spread_of_z_is_honest_for_every_estimator_and_one_miscalibrated_estimator_is_caught() {
    let study = intervals();
    for (scene, strategy, sequence, needed) in &study.untested {
        eprintln!("not tested: {scene} {strategy} {sequence} (needs N ≈ {needed:.0} > 2^13)");
        assert!(
            matches!(
                strategy,
                Strategy::UniformHemisphere | Strategy::CosineHemisphere
            ),
            "only the rare-hit hemisphere strategies may need N > 2^13: {scene} {strategy} {sequence}"
        );
    }
    for (scene, strategy, sequence) in FORMERLY_DISHONEST {
        let found = study
            .tested
            .iter()
            .find(|i| i.scene == scene && i.strategy == strategy && i.sequence == sequence)
            .unwrap_or_else(|| panic!("{scene} {strategy} {sequence} is no longer tested"));
        assert!(
            !found.clt,
            "{scene} {strategy} {sequence} is back to CLT intervals (move it to KNOWN_DISHONEST \
             if Σz² rejects it)"
        );
    }
    let all: Vec<&Intervals> = study.tested.iter().filter(|i| i.clt).collect();
    let alpha = sidak_level(FAMILY_ALPHA, all.len());
    let k = all[0].errors.len();
    assert!(all.iter().all(|i| i.errors.len() == k));
    let (lo, hi) = chi_square_band(k, alpha);
    let kappa = ninety_percent(SequenceKind::Independent);
    let chi = ChiSquared::new(k as f64).unwrap();
    let power = chi.sf(hi / (kappa * kappa)) + chi.cdf(lo / (kappa * kappa));
    let rqmc_power = rqmc_control_power(k, lo, hi);
    eprintln!(
        "{} estimators × {k} intervals, Σz² band [{lo:.1}, {hi:.1}] at α₁ = {alpha:.2e}; \
         control power (κ = {kappa:.3}) {power:.6} independent, {rqmc_power:.6} randomized QMC",
        all.len()
    );
    assert!(rqmc_power >= CONTROL_POWER, "power {rqmc_power}");
    let mut failures = Vec::new();
    let mut missed = Vec::new();
    for i in all {
        let (s, _) = i.sum_of_squares(1.0);
        let (control, _) = i.sum_of_squares(ninety_percent(i.sequence));
        eprintln!(
            "{:>20} {:>18} {:>11} 2^{:<2}: Σz² = {s:7.1}  (control {control:7.1})",
            i.scene, i.strategy, i.sequence, i.log2_n
        );
        let known = KNOWN_DISHONEST.contains(&(i.scene.as_str(), i.strategy, i.sequence));
        if (lo..=hi).contains(&s) == known {
            failures.push(format!(
                "{} {} {}: Σz² = {s:.1} {} [{lo:.1}, {hi:.1}]",
                i.scene,
                i.strategy,
                i.sequence,
                if known {
                    "inside (update KNOWN_DISHONEST)"
                } else {
                    "outside"
                }
            ));
        }
        if (lo..=hi).contains(&control) {
            missed.push(format!(
                "{} {} {}: {control:.1}",
                i.scene, i.strategy, i.sequence
            ));
        }
    }
    assert!(power >= CONTROL_POWER, "power {power}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(
        missed.is_empty(),
        "a 90 %-covering estimator passed:\n{}",
        missed.join("\n")
    );
}

/// Coverage per strategy × sequence: the misses of the 99 % intervals of
/// every estimator of a strategy and sequence (all scenes, each at its
/// three N of [`interval_config`])
/// are Bin(K, 0.01) if the intervals are honest; one two-sided exact
/// binomial band per (strategy, sequence), Šidák-corrected over the 18.
/// The coverage figures are printed. Negative control: the same intervals
/// narrowed to 90 % ones (half-width × z₀.₉₅/z₀.₉₉₅, or the t(15)
/// quantiles' ratio) must fall outside the band of every strategy ×
/// sequence; its power P(Bin(K, 0.10) outside the band) is stated. (The
/// control narrowed to 95 % until the stratified points' 32-bit hashes of
/// 2026-12: where the intervals are conservative, mis-balance × stratified
/// at 99 % covered 0.9954, its 95 % intervals missed only 25 of 1728,
/// inside the band 5..=33, and mis-balance × Sobol 34, at its edge. The
/// narrower control keeps the power without depending on exact
/// calibration, as the Σz² test's 90 % control does.)
/// A strategy with too few sampled estimators for that power in some
/// sequence (`projected`, exact on every light but disks, where it samples
/// by solid angle like `light`) is judged with its sequences pooled: each
/// interval misses with probability 0.01 whatever its sequence.
#[test]
fn coverage_per_strategy_and_sequence_is_within_its_binomial_band() {
    let all = &intervals().tested;
    let mut cells: BTreeMap<(String, String), (usize, usize, usize)> = BTreeMap::new();
    for i in all {
        let q90 = match i.sequence {
            SequenceKind::Independent => Normal::standard().inverse_cdf(0.95),
            _ => StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64)
                .unwrap()
                .inverse_cdf(0.95),
        };
        let cell = cells
            .entry((i.strategy.to_string(), i.sequence.to_string()))
            .or_default();
        cell.0 += i.covered(1.0);
        cell.1 += i.covered(q90 / quantile(i.sequence));
        cell.2 += i.errors.len();
    }
    // Judged at the Šidák level over the unpooled cells: pooling only
    // leaves fewer cells, a wider per-cell level and a narrower band.
    let unpooled_alpha = sidak_level(FAMILY_ALPHA, cells.len());
    let weak: Vec<String> = cells
        .iter()
        .filter(|(_, &(_, _, total))| {
            let (lo, hi) = binomial_band(total as u64, 0.01, unpooled_alpha);
            let power: f64 = binomial_pmf(total as u64, 0.10)
                .iter()
                .enumerate()
                .filter(|(x, _)| !(lo..=hi).contains(&(*x as u64)))
                .map(|(_, p)| p)
                .sum();
            power < CONTROL_POWER
        })
        .map(|((strategy, _), _)| strategy.clone())
        .collect();
    let cells: BTreeMap<(String, String), (usize, usize, usize)> =
        cells
            .into_iter()
            .fold(BTreeMap::new(), |mut pooled, ((strategy, sequence), c)| {
                let sequence = if weak.contains(&strategy) {
                    "pooled".to_string()
                } else {
                    sequence
                };
                let cell = pooled.entry((strategy, sequence)).or_default();
                *cell = (cell.0 + c.0, cell.1 + c.1, cell.2 + c.2);
                pooled
            });
    let alpha = sidak_level(FAMILY_ALPHA, cells.len());
    let mut failures = Vec::new();
    for ((strategy, sequence), (covered, covered90, total)) in &cells {
        let total = *total as u64;
        let (lo, hi) = binomial_band(total, 0.01, alpha);
        let misses = total - *covered as u64;
        let control = total - *covered90 as u64;
        let pmf = binomial_pmf(total, 0.10);
        let power: f64 = pmf
            .iter()
            .enumerate()
            .filter(|(x, _)| !(lo..=hi).contains(&(*x as u64)))
            .map(|(_, p)| p)
            .sum();
        eprintln!(
            "{strategy:>18} × {sequence:<11}: coverage {:.4} ({misses} misses of {total}, band {lo}..={hi}); \
             control 90 %: {control} misses, power {power:.6}",
            *covered as f64 / total as f64
        );
        assert!(
            power >= CONTROL_POWER,
            "{strategy} {sequence}: power {power}"
        );
        if !(lo..=hi).contains(&misses) {
            failures.push(format!(
                "{strategy} × {sequence}: {misses} misses of {total}"
            ));
        }
        assert!(
            !(lo..=hi).contains(&control),
            "{strategy} × {sequence}: 90 % intervals passed ({control} misses)"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A study of one scene, strategy and sequence with many replicates.
fn slope(scene: &str, strategy: Strategy, sequence: SequenceKind) -> f64 {
    let base = StudyConfig::builtin();
    let s: StudyScene = base.scenes.into_iter().find(|s| s.name == scene).unwrap();
    let config = StudyConfig {
        name: "slope".into(),
        scenes: vec![s],
        strategies: vec![strategy],
        sequences: vec![sequence],
        precisions: vec![lambert_estimator::precision::Precision::F64],
        n_min_log2: 5,
        n_max_log2: 16,
        replicates: 96,
        seed: 17,
    };
    let truth = config.scenes[0].reference.unwrap();
    let points: Vec<(f64, f64)> = plan(&config)
        .iter()
        .map(|key| {
            let reps = run_replicates(&config, key).unwrap();
            (key.n() as f64, aggregate(Some(truth), &reps).rmse.unwrap())
        })
        .collect();
    match fit_loglog(&points) {
        LogLogFit::Line { slope, .. } => slope,
        other => panic!("{scene}: {other:?}"),
    }
}

/// Independent MC: RMSE ∝ N^-½. With 96 replicates per N the standard error
/// of the fitted slope is about 0.01, so ±0.05 is a 5σ band. Negative
/// control: Sobol on the same scene is rejected by the same check.
#[test]
fn independent_slope_is_minus_half() {
    for (scene, strategy) in [
        ("uniform-sky", Strategy::UniformHemisphere),
        ("directional-and-sky", Strategy::Light),
    ] {
        let b = slope(scene, strategy, SequenceKind::Independent);
        assert!((b + 0.5).abs() < 0.05, "{scene} {strategy}: slope {b}");
        let control = slope(scene, strategy, SequenceKind::Sobol);
        assert!(
            (control + 0.5).abs() >= 0.05,
            "negative control: Sobol slope {control} passed as −½"
        );
    }
}

/// Owen-scrambled Sobol on smooth integrands: RMSE ∝ N^-3/2 in theory;
/// require < −0.75. Negative control: independent MC fails the same check.
#[test]
fn sobol_slope_is_steeper() {
    for (scene, strategy) in [
        ("uniform-sky", Strategy::UniformHemisphere),
        ("directional-and-sky", Strategy::Light),
    ] {
        let b = slope(scene, strategy, SequenceKind::Sobol);
        assert!(b < -0.75, "{scene} {strategy}: slope {b}");
        let control = slope(scene, strategy, SequenceKind::Independent);
        assert!(control >= -0.75, "negative control: slope {control}");
    }
}
