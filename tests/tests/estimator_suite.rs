//! The estimators against the closed forms: every built-in scene (every
//! emitter kind) × every strategy × every sequence, with z-tests at a
//! Šidák-corrected level; honest standard errors; exact and zero-variance
//! cases; variance orderings; bit-identical results across thread counts;
//! and the negative controls the same tests must reject.

use glam::DVec2;
use lambert_estimator::clt::normal_score;
use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind, RQMC_REPLICATES};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::strategy::{EmitterLight, Strategy};
use lambert_estimator::{run_chunked, Estimate};
use lambert_light::builtin::builtin_scenes;
use lambert_light::{Emitter, Scene};
use lambert_validate::critical_value;
use lambert_validate::sidak_level;
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal, StudentsT};

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
        precision: lambert_estimator::precision::Precision::F64,
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

/// The estimators whose standard error is checked for honesty over many
/// seeds, and the seeds.
const SPREAD_SEEDS: u64 = 200;

/// z = (mean − truth)/se over 200 seeds (N = 2^14), as normal scores: z
/// itself for independent samples, Φ⁻¹(F_t15(z)) for randomized QMC (whose
/// z is Student-t with 15 degrees of freedom); `scale_se` multiplies the
/// reported standard error (1 for the estimator as it is).
fn z_scores(scene: &Scene, strategy: Strategy, sequence: SequenceKind, scale_se: f64) -> Vec<f64> {
    let truth = closed_form(scene);
    (0..SPREAD_SEEDS)
        .map(|seed| {
            let mut c = config(strategy, sequence, 1000 + seed);
            c.samples = 1 << 14;
            let r = estimate(scene, &c).unwrap();
            normal_score((r.mean - truth) / (r.std_error * scale_se), sequence)
        })
        .collect()
}

/// Honest standard errors make the scores N(0, 1), so Σ s² over the 200
/// seeds is χ²(200): too small a spread (standard errors too large) is as
/// wrong as too large (too small, or a bias). Two-sided, one test per
/// estimator, Šidák-corrected over the three. Negative control: the same
/// estimators reporting a standard error 1.5 times too large (scores
/// shrunk by 1.5) must be rejected; its power, P(χ²(200)/2.25 outside the
/// band) for normal z (the t scores shrink at least as much), is stated.
#[test]
fn standard_errors_are_honest_and_a_mis_scaled_one_is_caught() {
    let scenes = builtin_scenes();
    let find = |name: &str| &scenes.iter().find(|s| s.name == name).unwrap().scene;
    let cases = [
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
    ];
    let alpha = sidak_level(FAMILY_ALPHA, cases.len());
    let k = SPREAD_SEEDS as f64;
    let chi = ChiSquared::new(k).unwrap();
    let band = (chi.inverse_cdf(alpha / 2.0), critical_value(k, alpha / 2.0));
    let power = chi.cdf(band.0 * 2.25) + chi.sf(band.1 * 2.25);
    eprintln!("Σs² band {band:.1?} at α₁ = {alpha:.2e}; control power {power:.6}");
    assert!(power >= 0.999);
    for (scene, strategy, sequence) in cases {
        let s: f64 = z_scores(scene, strategy, sequence, 1.0)
            .iter()
            .map(|x| x * x)
            .sum();
        let control: f64 = z_scores(scene, strategy, sequence, 1.5)
            .iter()
            .map(|x| x * x)
            .sum();
        eprintln!("{strategy} {sequence}: Σs² = {s:.1}, control {control:.1}");
        assert!(
            (band.0..=band.1).contains(&s),
            "{strategy} {sequence}: Σs² = {s} outside {band:?}"
        );
        assert!(
            !(band.0..=band.1).contains(&control),
            "control: {strategy} {sequence}: Σs² = {control}"
        );
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

/// The instruction-set decision: results do not depend on the set the
/// kernels run with. Every built-in scene × strategy × sequence, forced to
/// each set this processor has (baseline SSE2, AVX2+FMA, AVX-512, AVX-512
/// with GFNI), on one
/// and on two threads, gives the bits of the baseline on one thread.
#[test]
fn results_are_bit_identical_across_instruction_sets() {
    use lambert_estimator::estimation::estimate_with_isa;
    use lambert_sampling::isa::Isa;
    let sets = Isa::available();
    assert!(sets.contains(&Isa::Baseline));
    for named in builtin_scenes() {
        for strategy in std::iter::once(Strategy::Auto).chain(Strategy::ALL) {
            for sequence in SequenceKind::ALL {
                let mut c = config(strategy, sequence, 5);
                c.samples = 20_003;
                let run = |isa, threads| {
                    let c = EstimateConfig { threads, ..c };
                    let r = estimate_with_isa(&named.scene, &c, 0.99, isa).unwrap();
                    (r.mean.to_bits(), r.std_error.to_bits(), r.hits)
                };
                let want = run(Isa::Baseline, 1);
                for &isa in &sets {
                    for threads in [1, 2] {
                        assert_eq!(
                            run(isa, threads),
                            want,
                            "{} {strategy} {sequence} {isa} {threads} thread(s)",
                            named.name
                        );
                    }
                }
            }
        }
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

/// The per-test level of the closed-form suite
/// (`every_scene_strategy_and_sequence_agrees_with_the_closed_form`).
fn suite_alpha() -> f64 {
    let strategies = Strategy::ALL.len() + 1;
    sidak_level(
        FAMILY_ALPHA,
        builtin_scenes().len() * strategies * SequenceKind::ALL.len(),
    )
}

/// The power of the two-sided normal z-test at critical value `c` against
/// an estimate off by `bias` with standard error `se`.
fn z_power(bias: f64, se: f64, c: f64) -> f64 {
    let n = Normal::standard();
    n.cdf(bias.abs() / se - c) + n.cdf(-bias.abs() / se - c)
}

/// Deliberately defective estimators, z-tested at the closed-form suite's
/// level and sample count (2^18 independent samples); each control's power
/// is stated and must be ≥ 0.999: (1) the sphere light's density reported
/// 1 % high (bias −E/101); (2) directions toward the grazing rectangle's
/// half with y < 0 dropped (bias: that half's irradiance, estimated by the
/// honest estimator on its own seed).
#[test]
fn negative_controls_are_rejected() {
    let scenes = builtin_scenes();
    let find = |name: &str| &scenes.iter().find(|s| s.name == name).unwrap().scene;
    let z_crit = Normal::standard().inverse_cdf(1.0 - suite_alpha() / 2.0);
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
    let power = z_power(truth / 101.0, se, z_crit);
    eprintln!(
        "control (1) pdf 1 % high: z = {:.1} (critical {z_crit:.2}), power {power:.6}",
        (m - truth) / se
    );
    assert!(power >= 0.999);
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
    // The dropped half's irradiance, from the honest estimator restricted
    // to it, on a seed of its own.
    let dropped = estimate(
        rect,
        &config(Strategy::Light, SequenceKind::Independent, 77),
    )
    .unwrap()
    .mean
        - {
            let e = run_chunked(SAMPLES, 4096, 2, |_, range| {
                let sampler = EmitterLight::new(&emitter, &rect.receiver);
                let mut seq = lambert_sampling::sequence::Independent::new(77);
                range
                    .map(|i| {
                        lambert_sampling::sequence::SampleSequence::start_sample(&mut seq, i);
                        let u = lambert_sampling::sequence::SampleSequence::next_2d(&mut seq);
                        match sampler.sample(u) {
                            Some(d) if d.direction.y >= 0.0 => {
                                emitter.radiance_toward(p, d.direction)
                                    * d.direction.dot(n).max(0.0)
                                    / d.pdf
                            }
                            _ => 0.0,
                        }
                    })
                    .collect::<Estimate>()
            })
            .unwrap();
            e.mean().unwrap()
        };
    let power = z_power(dropped, se, z_crit);
    eprintln!(
        "control (2) half a light dropped: z = {:.1}, dropped ≈ {dropped:.4} of {truth:.4}, power {power:.6}",
        (m - truth) / se
    );
    assert!(power >= 0.999);
    assert!(
        ((m - truth) / se).abs() > z_crit,
        "half a light ignored, not detected: z {}",
        (m - truth) / se
    );
}

/// Strengths beyond the f64 range of a sum: each of two skies of radiance
/// 0.9·f64::MAX/π gives a finite π·L per sample under cosine sampling and
/// one of them is answered exactly; their sum, 1.8·f64::MAX, is an overflow
/// error naming the quantity (the estimator scales strengths by a power of
/// two, so no sample overflows on the way: `strength_scale`), as is a sky
/// of radiance f64::MAX under any strategy.
#[test]
fn strengths_near_the_f64_limit_are_answered_or_named_overflows() {
    use lambert_estimator::estimation::EstimateError;
    let radiance = 0.9 * f64::MAX / std::f64::consts::PI;
    let skies = |count: usize| {
        let mut text = String::from(
            "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
             [[emitters]]\nkind = \"point\"\nposition = [0.0, 0.0, 1.0]\nintensity = 1.0\n",
        );
        for _ in 0..count {
            text += &format!("[[emitters]]\nkind = \"sky\"\nradiance = {radiance:e}\n");
        }
        Scene::from_toml(&text).unwrap()
    };
    for sequence in SequenceKind::ALL {
        // Cosine sampling under a sky: every sample is π·L exactly, so the
        // mean is π·L + 1 (the point light) rounded once.
        let one = estimate(&skies(1), &config(Strategy::CosineHemisphere, sequence, 1))
            .unwrap_or_else(|e| panic!("{sequence}: {e}"));
        assert_eq!(
            one.mean,
            std::f64::consts::PI * radiance + 1.0,
            "{sequence}"
        );
        let error =
            estimate(&skies(2), &config(Strategy::CosineHemisphere, sequence, 1)).unwrap_err();
        assert!(
            matches!(error, EstimateError::Overflow { .. })
                && error.to_string().contains("overflowed"),
            "{sequence}: {error:?}"
        );
    }
    let text = "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\
                [[emitters]]\nkind = \"sky\"\nradiance = 1.7976931348623157e308\n";
    let scene = Scene::from_toml(text).unwrap();
    for strategy in Strategy::ALL {
        let error = estimate(&scene, &config(strategy, SequenceKind::Independent, 2)).unwrap_err();
        assert!(
            matches!(error, EstimateError::Overflow { .. }),
            "{strategy}: {error:?}"
        );
    }
}
