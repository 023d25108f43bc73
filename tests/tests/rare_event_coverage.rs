//! Coverage of the rare-event intervals, measured over many seeds.
//!
//! A disk of angular radius 0.1 rad overhead is seen by a cosine-sampled
//! direction with probability p = sin²(0.1) ≈ 0.01 and by a uniform one
//! with p = 1 − cos 0.1 ≈ 0.005. At N = 50 … 2000 samples the expected hits
//! λ = N·p run from 0.25 to 20: no hit, a handful, never the 30 the central
//! limit theorem needs, so every estimate's 99 % interval comes from the
//! rare-event bounds (`interval` ≠ clt). Over 300 seeds per (strategy,
//! sequence, N), those intervals must miss the truth in at most 1 % of the
//! estimates: K estimates per sequence, misses ≤ the upper (1 − α/2)
//! quantile of Bin(K, 0.01), α = 0.001 Šidák-corrected over the three
//! sequences (one-sided: the bounds are conservative by design).
//!
//! Negative control: on the same estimates, the interval that ignores the
//! hit count, `m ± q·s/√N` (with no hit, [0, 0]), must fail the same test.

use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind, RQMC_REPLICATES};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::statistics::ConfidenceInterval;
use lambert_estimator::strategy::{Heuristic, Strategy};
use lambert_light::emitter::{DiskLight, Emitter};
use lambert_light::receiver::Receiver;
use lambert_light::Scene;
use lambert_validate::sidak_level;
use statrs::distribution::{Binomial, DiscreteCDF};

const SEEDS: u64 = 300;
const SAMPLE_COUNTS: [u64; 5] = [50, 200, 500, 1000, 2000];

/// The smallest m with P(Bin(k, p) ≤ m) ≥ 1 − alpha.
fn binomial_upper(k: u64, p: f64, alpha: f64) -> u64 {
    let b = Binomial::new(p, k).expect("a valid binomial");
    (0..=k)
        .find(|&m| b.cdf(m) >= 1.0 - alpha)
        .expect("the cdf reaches 1")
}

/// (misses of the honest intervals, misses of the naive ones, estimates)
/// over every strategy, N and seed, for one sequence.
fn misses(scene: &Scene, truth: f64, sequence: SequenceKind) -> (u64, u64, u64) {
    let (mut honest, mut naive, mut total) = (0, 0, 0);
    for strategy in [
        Strategy::CosineHemisphere,
        Strategy::UniformHemisphere,
        Strategy::Mis(Heuristic::Balance),
    ] {
        for n in SAMPLE_COUNTS {
            for seed in 0..SEEDS {
                let config = EstimateConfig {
                    strategy,
                    sequence,
                    samples: n,
                    seed: 7919 * seed + n,
                    threads: 1,
                    precision: lambert_estimator::precision::Precision::F64,
                };
                let r = estimate(scene, &config).unwrap();
                if r.interval == IntervalKind::CentralLimit {
                    continue;
                }
                let raw_se = (r.sample_variance / n as f64).sqrt();
                let dof = match sequence {
                    SequenceKind::Independent => n,
                    _ => RQMC_REPLICATES,
                };
                let plain = ConfidenceInterval::new(r.mean, raw_se, dof, 0.99);
                honest += u64::from(!(r.ci99.0 <= truth && truth <= r.ci99.1));
                naive += u64::from(!plain.contains(truth));
                total += 1;
            }
        }
    }
    (honest, naive, total)
}

#[test]
fn rare_event_intervals_cover_and_the_naive_ones_do_not() {
    let receiver = Receiver::new(glam::DVec3::ZERO, glam::DVec3::Z).unwrap();
    let disk = DiskLight::new(glam::DVec3::Z, -glam::DVec3::Z, 0.1f64.tan(), 1.0, false).unwrap();
    let scene = Scene::new(receiver, vec![Emitter::Disk(disk)]).unwrap();
    let truth = scene.emitters[0]
        .closed_form_irradiance(&scene.receiver)
        .unwrap();
    let alpha = sidak_level(0.001, SequenceKind::ALL.len());
    for sequence in SequenceKind::ALL {
        let (honest, naive, total) = misses(&scene, truth, sequence);
        let limit = binomial_upper(total, 0.01, alpha / 2.0);
        eprintln!(
            "{sequence}: {total} rare-event intervals, misses {honest} ({:.3} %), naive \
             {naive} ({:.2} %), limit {limit}",
            100.0 * honest as f64 / total as f64,
            100.0 * naive as f64 / total as f64
        );
        assert!(
            total >= 2000,
            "{sequence}: only {total} rare-event intervals"
        );
        assert!(
            honest <= limit,
            "{sequence}: {honest} misses of {total} (limit {limit})"
        );
        assert!(
            naive > limit,
            "{sequence}: negative control accepted, {naive} misses of {total} (limit {limit})"
        );
    }
}
