//! Emitters too strong for f64 sums (radiances up to 1e308): the estimator
//! scales every emitter's strength by a power of two, estimates, and scales
//! the report back (`lambert_estimator::strength_scale`).
//!
//! 1. Exactness: scaling commutes with every step of the estimate, so a
//!    scene at 2¹⁰⁰ times the strength must give the report at 1 times 2¹⁰⁰
//!    (the variance times 2²⁰⁰), bit for bit, for every built-in scene ×
//!    strategy × sequence. An exact assertion: no tolerance.
//! 2. Extreme strengths get answers: the inputs the fuzzer once found
//!    unanswered (a sky of 5e307, whose samples' sum overflowed; a sky of
//!    1e160, whose squared deviations overflowed; a triangle of 1e308,
//!    whose single samples overflowed) give finite estimates whose
//!    intervals cover the closed form — one family of intervals at a
//!    Šidák-corrected level for a family-wise α = 0.01. Negative control:
//!    the truth doubled (a scale undone one power of two short) must fall
//!    outside every one of those intervals.
//! 3. Real overflow is an error naming the quantity, never ∞ or NaN.

use glam::DVec3;
use lambert_estimator::estimation::{
    estimate, estimate_at_level, EstimateConfig, EstimateError, EstimateReport, SequenceKind,
};
use lambert_estimator::strategy::Strategy;
use lambert_light::builtin::builtin_scenes;
use lambert_light::emitter::{Emitter, PolygonLight, Sky};
use lambert_light::receiver::Receiver;
use lambert_light::Scene;
use lambert_validate::sidak_level;

fn config(strategy: Strategy, sequence: SequenceKind, samples: u64) -> EstimateConfig {
    EstimateConfig {
        strategy,
        sequence,
        samples,
        seed: 7,
        threads: 2,
        precision: lambert_estimator::precision::Precision::F64,
    }
}

fn scaled(scene: &Scene, factor: f64) -> Scene {
    Scene::new(
        scene.receiver,
        scene
            .emitters
            .iter()
            .map(|e| e.with_strength_scaled(factor))
            .collect(),
    )
    .expect("the same geometry")
}

fn assert_scaled(a: &EstimateReport, b: &EstimateReport, factor: f64, what: &str) {
    assert_eq!(b.mean, a.mean * factor, "{what}: mean");
    assert_eq!(b.std_error, a.std_error * factor, "{what}: std_error");
    assert_eq!(b.ci99.0, a.ci99.0 * factor, "{what}: ci99 lower");
    assert_eq!(b.ci99.1, a.ci99.1 * factor, "{what}: ci99 upper");
    assert_eq!(
        b.sample_variance,
        (a.sample_variance * factor * factor).min(f64::MAX),
        "{what}: sample_variance"
    );
    assert_eq!(b.hits, a.hits, "{what}: hits");
    assert_eq!(b.interval, a.interval, "{what}: interval");
    assert_eq!(b.warning, a.warning, "{what}: warning");
}

#[test]
fn a_scene_at_two_to_the_100_gives_the_scaled_estimate_to_the_bit() {
    let factor = 2f64.powi(100);
    let mut checked = 0;
    for named in builtin_scenes() {
        let strong = scaled(&named.scene, factor);
        for strategy in Strategy::ALL {
            for sequence in SequenceKind::ALL {
                let c = config(strategy, sequence, 1 << 10);
                let a = estimate(&named.scene, &c).expect("built-in scenes estimate");
                let b = estimate(&strong, &c).expect("scaled scenes estimate");
                assert_scaled(
                    &a,
                    &b,
                    factor,
                    &format!("{} {strategy} {sequence}", named.name),
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, builtin_scenes().len() * Strategy::ALL.len() * 3);
}

fn up() -> Receiver {
    Receiver::new(DVec3::ZERO, DVec3::Z).expect("a valid receiver")
}

fn sky(radiance: f64) -> Scene {
    Scene::new(up(), vec![Emitter::Sky(Sky::new(radiance).expect("a sky"))]).expect("a scene")
}

/// The fuzzer's triangle of radiance 1e308 (closed form ≈ 2.3e307).
fn strong_triangle() -> Scene {
    let v = vec![
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ];
    let light = PolygonLight::new(v, 1e308, true).expect("a triangle");
    Scene::new(up(), vec![Emitter::Polygon(light)]).expect("a scene")
}

#[test]
fn extreme_strengths_get_finite_estimates_that_cover_the_closed_form() {
    let scenes = [
        ("sky 5e307", sky(5e307)),
        ("sky 1e160", sky(1e160)),
        ("triangle 1e308", strong_triangle()),
    ];
    let family = scenes.len() * Strategy::ALL.len() * SequenceKind::ALL.len();
    let level = 1.0 - sidak_level(0.01, family);
    let mut failures = Vec::new();
    for (name, scene) in &scenes {
        let truth: f64 = scene
            .emitters
            .iter()
            .map(|e| {
                e.try_closed_form_irradiance(&scene.receiver)
                    .expect("finite")
            })
            .sum();
        for strategy in Strategy::ALL {
            for sequence in SequenceKind::ALL {
                let r = estimate_at_level(scene, &config(strategy, sequence, 1 << 12), level)
                    .unwrap_or_else(|e| panic!("{name} {strategy} {sequence}: {e}"));
                assert!(r.mean.is_finite() && r.std_error.is_finite());
                // Negative control: an unscaling off by one power of two
                // (the truth doubled) must fall outside every interval.
                if r.ci99.0 <= 2.0 * truth && 2.0 * truth <= r.ci99.1 {
                    failures.push(format!("{name} {strategy} {sequence}: 2·truth inside"));
                }
                if !(r.ci99.0 <= truth && truth <= r.ci99.1) {
                    failures.push(format!(
                        "{name} {strategy} {sequence}: {truth:e} outside [{:e}, {:e}]",
                        r.ci99.0, r.ci99.1
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn irradiance_beyond_the_f64_range_is_an_overflow_error() {
    // E = π·1.7e308 exceeds 1.8e308: every strategy must say so.
    let scene = sky(1.7e308);
    for strategy in Strategy::ALL {
        let e = estimate(&scene, &config(strategy, SequenceKind::Independent, 64))
            .expect_err("π·1.7e308 is not an f64");
        assert!(
            matches!(e, EstimateError::Overflow { .. }),
            "{strategy}: {e}"
        );
        assert!(e.to_string().contains("overflowed"), "{e}");
    }
}
