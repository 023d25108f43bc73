//! Statistical tests of `lambert study`: CI coverage against a derived
//! binomial band, and the fitted convergence slopes of independent Monte
//! Carlo (−½) and Owen-scrambled Sobol (steeper than −¾) on smooth scenes,
//! each with a negative control that the same check rejects.
//!
//! Deterministic (fixed seeds). Coverage runs over the whole built-in
//! suite; the slopes over the smooth scenes.

use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::strategy::Strategy;
use lambert_study::{
    aggregate, fit_loglog, plan, run_replicates, LogLogFit, ReplicateResult, StudyConfig,
    StudyScene,
};

/// The two-sided binomial acceptance band [lo, hi] for X ~ Bin(k, p) at
/// level alpha: the largest lo with P(X < lo) ≤ α/2 and the smallest hi
/// with P(X > hi) ≤ α/2 (pmf summed exactly in f64).
fn binomial_band(k: u64, p: f64, alpha: f64) -> (u64, u64) {
    let mut pmf = Vec::with_capacity(k as usize + 1);
    // log pmf by recursion from x = 0.
    let mut log = k as f64 * (1.0 - p).ln();
    for x in 0..=k {
        pmf.push(log.exp());
        if x < k {
            log += ((k - x) as f64).ln() - ((x + 1) as f64).ln() + p.ln() - (1.0 - p).ln();
        }
    }
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

/// The quick study's independent-MC rows over the whole built-in suite,
/// N ≥ 2^10, with non-zero variance: each row's truth and replicates.
fn quick_independent_rows() -> Vec<(f64, Vec<ReplicateResult>)> {
    let config = StudyConfig::quick();
    plan(&config)
        .into_iter()
        .filter(|key| key.sequence == SequenceKind::Independent && key.log2_n >= 10)
        .filter_map(|key| {
            let scene = &config.scenes[key.scene];
            let truth = scene.reference.expect("built-in scenes have closed forms");
            let reps = run_replicates(&config, &key).unwrap();
            // Exact (cosine sampling under a sky): nothing to cover.
            (aggregate(Some(truth), &reps).sample_variance > 0.0).then_some((truth, reps))
        })
        .collect()
}

/// (covered, total) of the central-limit intervals and of the others
/// (rare-event and bounded ones, which are conservative), at the truth
/// scaled by `shift`.
fn coverage(rows: &[(f64, Vec<ReplicateResult>)], shift: f64) -> ((u64, u64), (u64, u64)) {
    let mut clt = (0, 0);
    let mut rare = (0, 0);
    for (truth, reps) in rows {
        let truth = truth * shift;
        for r in reps {
            let tally = if r.interval == IntervalKind::CentralLimit {
                &mut clt
            } else {
                &mut rare
            };
            tally.0 += u64::from(r.ci99.0 <= truth && truth <= r.ci99.1);
            tally.1 += 1;
        }
    }
    (clt, rare)
}

#[test]
fn binomial_band_is_right() {
    // Bin(100, 0.5) at α = 0.05: the usual 40…60.
    assert_eq!(binomial_band(100, 0.5, 0.05), (40, 60));
}

/// 99 % intervals cover the truth in 99 % of replicates: the number of
/// misses over K central-limit intervals is Bin(K, 0.01) if they are honest
/// (replicates are independent: every seed hashes its row's key). One test
/// at α = 0.001 two-sided. The other intervals (rare-event bounds, where a
/// part of the estimate had few hits) are conservative: their misses must
/// not exceed the same band's upper end. Negative control: a truth 0.2 %
/// off, which the CLT intervals at large N exclude, must fall outside the
/// band.
#[test]
fn ci99_coverage_within_binomial_band() {
    let rows = quick_independent_rows();
    let ((covered, total), (rare_covered, rare_total)) = coverage(&rows, 1.0);
    let misses = total - covered;
    let (lo, hi) = binomial_band(total, 0.01, 0.001);
    eprintln!(
        "{misses} misses of {total} CLT intervals, band {lo}..={hi}; \
         {} misses of {rare_total} rare-event intervals",
        rare_total - rare_covered
    );
    assert!(total >= 400, "{total} intervals");
    assert!(
        (lo..=hi).contains(&misses),
        "{misses} misses of {total} intervals, band {lo}..={hi}"
    );
    let (_, rare_hi) = binomial_band(rare_total, 0.01, 0.001);
    assert!(
        rare_total - rare_covered <= rare_hi,
        "{} misses of {rare_total} rare-event intervals (at most {rare_hi})",
        rare_total - rare_covered
    );
    let ((covered, total), _) = coverage(&rows, 1.002);
    let misses = total - covered;
    assert!(
        !(lo..=hi).contains(&misses),
        "negative control accepted: {misses} misses of {total}, band {lo}..={hi}"
    );
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
