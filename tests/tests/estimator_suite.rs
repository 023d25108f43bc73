//! The estimators against the closed forms: every built-in scene (every
//! emitter kind) × every strategy × every sequence, with z-tests at a
//! Šidák-corrected level; honest standard errors; exact and zero-variance
//! cases; variance orderings; bit-identical results across thread counts;
//! and the negative controls the same tests must reject.

use glam::DVec2;
use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind, RQMC_REPLICATES};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::strategy::{EmitterLight, Strategy};
use lambert_estimator::{run_chunked, Estimate};
use lambert_light::builtin::builtin_scenes;
use lambert_light::{Emitter, Scene};
use lambert_validate::sidak_level;
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

const FAMILY_ALPHA: f64 = 0.01;
const SAMPLES: u64 = 1 << 18;

fn closed_form(scene: &Scene) -> f64 {
    scene
        .emitters
        .iter()
        .map(|e| {
            e.closed_form_irradiance(&scene.receiver)
                .unwrap_or_else(|| panic!("{} has a closed form", e.kind()))
        })
        .sum()
}

/// The two-sided critical value at level `alpha`: normal for independent
/// samples (n ≥ 2^18, so the CLT's Student correction is < 1e-5), Student-t
/// with R − 1 degrees of freedom for randomized QMC (R replicates).
fn critical(sequence: SequenceKind, alpha: f64) -> f64 {
    match sequence {
        SequenceKind::Independent => Normal::new(0.0, 1.0)
            .unwrap()
            .inverse_cdf(1.0 - alpha / 2.0),
        _ => StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64)
            .unwrap()
            .inverse_cdf(1.0 - alpha / 2.0),
    }
}

fn config(strategy: Strategy, sequence: SequenceKind, seed: u64) -> EstimateConfig {
    EstimateConfig {
        strategy,
        sequence,
        samples: SAMPLES,
        seed,
        threads: 2,
    }
}

#[test]
fn every_scene_strategy_and_sequence_agrees_with_the_closed_form() {
    let scenes = builtin_scenes();
    let strategies: Vec<Strategy> = std::iter::once(Strategy::Auto)
        .chain(Strategy::ALL)
        .collect();
    let family = scenes.len() * strategies.len() * SequenceKind::ALL.len();
    let alpha = sidak_level(FAMILY_ALPHA, family);
    let mut failures = Vec::new();
    for named in &scenes {
        let truth = closed_form(&named.scene);
        for &strategy in &strategies {
            for sequence in SequenceKind::ALL {
                let r = estimate(&named.scene, &config(strategy, sequence, 7)).unwrap();
                assert!(r.mean.is_finite() && r.std_error.is_finite());
                // A central-limit interval is judged by the z-test (its
                // standard error is at least the rounding floor, so exact
                // estimates are judged too); the others, formed from
                // rare-event bounds because part of the estimate had few
                // hits, are conservative and must contain the truth.
                let verdict = if r.interval == IntervalKind::CentralLimit {
                    ((r.mean - truth) / r.std_error).abs() <= critical(sequence, alpha)
                } else {
                    r.warning.is_some() && r.ci99.0 <= truth && truth <= r.ci99.1
                };
                if !verdict {
                    failures.push(format!(
                        "{} {strategy} {sequence}: mean {} truth {truth} se {:e} z {:.2}",
                        named.name,
                        r.mean,
                        r.std_error,
                        (r.mean - truth) / r.std_error
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// z = (mean − truth)/se over 200 seeds: its mean must be within ±3/√200 of
/// 0 and its variance within the χ²(199)/199 band at α = 0.0027 each side
/// (for randomized QMC z is Student-t(15), variance 15/13, and the band is
/// scaled by it). Too small a spread is as wrong as too large.
fn z_spread(
    scene: &Scene,
    strategy: Strategy,
    sequence: SequenceKind,
    scale_se: f64,
) -> (f64, f64) {
    let truth = closed_form(scene);
    let zs: Vec<f64> = (0..200u64)
        .map(|seed| {
            let mut c = config(strategy, sequence, 1000 + seed);
            c.samples = 1 << 14;
            let r = estimate(scene, &c).unwrap();
            (r.mean - truth) / (r.std_error * scale_se)
        })
        .collect();
    let e: Estimate = zs.iter().copied().collect();
    (e.mean().unwrap(), e.variance().unwrap())
}

fn honest(mean: f64, variance: f64, sequence: SequenceKind) -> bool {
    let t_variance = match sequence {
        SequenceKind::Independent => 1.0,
        _ => {
            let nu = (RQMC_REPLICATES - 1) as f64;
            nu / (nu - 2.0)
        }
    };
    // χ²(199) quantiles at 0.00135 and 0.99865, divided by 199.
    let (lo, hi) = (0.726, 1.328);
    mean.abs() <= 3.0 * (t_variance / 200.0f64).sqrt()
        && variance >= lo * t_variance
        && variance <= hi * t_variance
}

#[test]
fn standard_errors_are_honest_and_a_mis_scaled_one_is_caught() {
    let scenes = builtin_scenes();
    let find = |name: &str| &scenes.iter().find(|s| s.name == name).unwrap().scene;
    for (scene, strategy, sequence) in [
        (
            find("sphere-tilted-30"),
            Strategy::Light,
            SequenceKind::Independent,
        ),
        (
            find("disk-close-offset"),
            Strategy::Mis(lambert_estimator::strategy::Heuristic::Power),
            SequenceKind::Independent,
        ),
        (find("triangle"), Strategy::Light, SequenceKind::Sobol),
    ] {
        let (m, v) = z_spread(scene, strategy, sequence, 1.0);
        assert!(
            honest(m, v, sequence),
            "{strategy} {sequence}: z mean {m}, variance {v}"
        );
        // Negative control: a standard error 1.5× too large shrinks the
        // variance of z to 1/2.25 of its value: rejected.
        let (m, v) = z_spread(scene, strategy, sequence, 1.5);
        assert!(!honest(m, v, sequence), "control: z mean {m}, variance {v}");
    }
}

#[test]
fn cosine_sampling_of_a_uniform_sky_is_exact() {
    let scenes = builtin_scenes();
    let sky = &scenes
        .iter()
        .find(|s| s.name == "uniform-sky")
        .unwrap()
        .scene;
    for sequence in SequenceKind::ALL {
        let r = estimate(sky, &config(Strategy::CosineHemisphere, sequence, 3)).unwrap();
        // Every sample is π·L exactly, so the mean is, and the variance 0:
        // the standard error is the rounding floor, and the interval the
        // central-limit one, without a warning.
        assert_eq!(r.mean, std::f64::consts::PI);
        assert_eq!(r.sample_variance, 0.0);
        let floor = lambert_estimator::statistics::rounding::mean_rounding_floor(r.mean, SAMPLES);
        assert_eq!(r.std_error, floor);
        assert_eq!(
            (r.interval, r.warning, r.hits),
            (IntervalKind::CentralLimit, None, SAMPLES)
        );
    }
}

#[test]
fn variance_orderings_that_theory_predicts() {
    let scenes = builtin_scenes();
    let find = |name: &str| &scenes.iter().find(|s| s.name == name).unwrap().scene;
    let se = |scene: &Scene, s: Strategy| {
        estimate(scene, &config(s, SequenceKind::Independent, 5))
            .unwrap()
            .std_error
    };
    // Under a sky, cosine (variance 0) < uniform.
    let sky = find("uniform-sky");
    assert!(se(sky, Strategy::CosineHemisphere) < se(sky, Strategy::UniformHemisphere));
    // For a small sphere (α ≈ 0.1 rad), light sampling ≪ cosine: the cosine
    // estimator's variance is ≈ E²(1/p − 1) with p ≈ sin²α ≈ 0.01, the light
    // estimator's only the spread of cos θ over the cap; a factor 10 in
    // standard error is far inside both.
    let sphere = find("sphere-overhead");
    assert!(10.0 * se(sphere, Strategy::Light) < se(sphere, Strategy::CosineHemisphere));
}

#[test]
fn results_are_bit_identical_across_threads_and_runs() {
    let scenes = builtin_scenes();
    let scene = &scenes
        .iter()
        .find(|s| s.name == "several-lights")
        .unwrap()
        .scene;
    for sequence in SequenceKind::ALL {
        let run = |threads| {
            let mut c = config(Strategy::Auto, sequence, 11);
            c.threads = threads;
            let r = estimate(scene, &c).unwrap();
            (r.mean.to_bits(), r.std_error.to_bits())
        };
        let one = run(1);
        assert_eq!(one, run(2), "{sequence}");
        assert_eq!(one, run(8), "{sequence}");
        assert_eq!(one, run(1), "{sequence}: a second run");
    }
}

/// An estimator built from the public pieces, with a deliberate defect:
/// returns (mean, standard error) over 2^18 independent samples.
fn defective(scene: &Scene, f: impl Fn(&EmitterLight, DVec2) -> f64 + Sync) -> (f64, f64) {
    let emitter = &scene.emitters[0];
    let sampler = EmitterLight::new(emitter, &scene.receiver);
    let e = run_chunked(SAMPLES, 4096, 2, |_, range| {
        let mut seq = lambert_sampling::sequence::Independent::new(1);
        range
            .map(|i| {
                lambert_sampling::sequence::SampleSequence::start_sample(&mut seq, i);
                f(
                    &sampler,
                    lambert_sampling::sequence::SampleSequence::next_2d(&mut seq),
                )
            })
            .collect::<Estimate>()
    })
    .unwrap();
    (e.mean().unwrap(), e.std_error().unwrap())
}

#[test]
fn negative_controls_are_rejected() {
    let scenes = builtin_scenes();
    let find = |name: &str| &scenes.iter().find(|s| s.name == name).unwrap().scene;
    let z_crit = Normal::new(0.0, 1.0).unwrap().inverse_cdf(1.0 - 0.01 / 2.0);
    // (1) A pdf off by 1 %: the sphere light's density reported 1 % high.
    let sphere = find("sphere-tilted-30");
    let truth = closed_form(sphere);
    let radiance = match &sphere.emitters[0] {
        Emitter::Sphere(s) => s.radiance,
        _ => unreachable!(),
    };
    let n = sphere.receiver.normal;
    let (m, se) = defective(sphere, |s, u| match s.sample(u) {
        Some(d) => radiance * d.direction.dot(n).max(0.0) / (1.01 * d.pdf),
        None => 0.0,
    });
    assert!(
        ((m - truth) / se).abs() > z_crit,
        "pdf off by 1 % not detected: z {}",
        (m - truth) / se
    );
    // The control's control: the same estimator without the defect passes.
    let (m, se) = defective(sphere, |s, u| match s.sample(u) {
        Some(d) => radiance * d.direction.dot(n).max(0.0) / d.pdf,
        None => 0.0,
    });
    assert!(
        ((m - truth) / se).abs() <= z_crit,
        "the honest estimator failed: z {}",
        (m - truth) / se
    );
    // (2) A strategy that ignores part of a light: directions toward the
    // rectangle's half with y < 0 are dropped.
    let rect = find("rectangle-grazing");
    let truth = closed_form(rect);
    let emitter = rect.emitters[0].clone();
    let p = rect.receiver.point;
    let n = rect.receiver.normal;
    let (m, se) = defective(rect, |s, u| match s.sample(u) {
        Some(d) if d.direction.y >= 0.0 => {
            emitter.radiance_toward(p, d.direction) * d.direction.dot(n).max(0.0) / d.pdf
        }
        _ => 0.0,
    });
    assert!(
        ((m - truth) / se).abs() > z_crit,
        "half a light ignored, not detected: z {}",
        (m - truth) / se
    );
}
