//! Disks whose solid-angle sampler cannot be built, and disks so far away
//! that it once could not be.
//!
//! 1. A disk of radius 2.2e199 about 1e200 from the receiver (the fuzz
//!    corpus case `giant-disk-no-light-sampler`): its squared distances
//!    overflow, and the spherical-ellipse sampler refused it, so `light`,
//!    `projected` and `auto` estimated 0 with an interval of width 0. The
//!    sampler now measures lengths without overflow; the light estimate's
//!    99 % interval must cover the closed form (two sequences, a Šidák
//!    family at α = 0.01), with no fallback reported. Negative control: the
//!    closed form 1 % off must lie outside both intervals (the relative
//!    standard error at 2^12 samples is ≈ 1.2e-4, measured below, so the
//!    intervals' half-widths are ≈ 3.3e-4 relative, well under 1 %).
//! 2. A disk of radius 1e300 at height 1e-20 above the receiver: its cone
//!    is the hemisphere to within rounding and the ellipse cannot be set
//!    up at all. Every strategy that would draw from it (`light`,
//!    `projected`, `auto`) falls back to cosine-hemisphere sampling and
//!    says so in the report; the estimate is then exact (every cosine
//!    direction above the horizon meets the disk, each sample is πL), an
//!    exact assertion. The control: the light sampler of that disk is
//!    indeed absent (what made the old estimate 0).
//! 3. The same fallback in the occluded estimator (the tracer's), for
//!    light sampling and the control variate's residual.
//! 4. The fuzz case `disk-huge-radius-near-receiver-no-ellipse` (a disk of
//!    radius 6.5e225 0.05 from the receiver, straddling its horizon, with a
//!    sky and a point light): light sampling falls back for the disk and
//!    its 99 % interval covers the closed form, at 2^12 samples (one
//!    test); the control: the closed form 15 % too high lies outside (the
//!    relative standard error, measured 1.2 %, makes the half-width ≈ 3 %).

use glam::DVec3;
use lambert_estimator::estimation::{estimate_at_level, EstimateConfig, SequenceKind};
use lambert_estimator::strategy::{EmitterLight, OccludedEmitter, Strategy, Technique};
use lambert_light::emitter::{DiskLight, Emitter};
use lambert_light::receiver::Receiver;
use lambert_light::Scene;
use lambert_sampling::sequence::{Independent, SampleSequence};
use lambert_validate::sidak_level;

fn receiver() -> Receiver {
    Receiver::new(
        DVec3::new(8.327100023168526, 8.2017798408916, -5.603971376149586),
        DVec3::new(
            -0.6702788113584796,
            -0.6972105634062097,
            -0.2542120086043531,
        ),
    )
    .unwrap()
}

fn giant_disk() -> Emitter {
    Emitter::Disk(
        DiskLight::new(
            DVec3::new(
                -7.454936534584011e199,
                -6.611208827807824e199,
                8.460727512693156e198,
            ),
            DVec3::new(0.0, 0.0, -1.0),
            2.173917869170567e199,
            1.0,
            true,
        )
        .unwrap(),
    )
}

fn wide_disk() -> (Receiver, Emitter) {
    let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
    let disk = DiskLight::new(DVec3::new(0.0, 0.0, 1e-20), -DVec3::Z, 1e300, 1.0, false).unwrap();
    (receiver, Emitter::Disk(disk))
}

fn config(strategy: Strategy, sequence: SequenceKind) -> EstimateConfig {
    EstimateConfig {
        strategy,
        sequence,
        samples: 1 << 12,
        seed: 85,
        threads: 1,
        precision: lambert_estimator::precision::Precision::F64,
    }
}

#[test]
fn far_giant_disk_is_light_sampled_and_covered() {
    let scene = Scene::new(receiver(), vec![giant_disk()]).unwrap();
    let truth = scene.emitters[0]
        .closed_form_irradiance(&scene.receiver)
        .expect("a closed form");
    let sequences = [SequenceKind::Independent, SequenceKind::Sobol];
    let level = sidak_level(0.99, sequences.len());
    for sequence in sequences {
        let r = estimate_at_level(&scene, &config(Strategy::Light, sequence), level).unwrap();
        assert_eq!(r.fallback, None, "{sequence:?}: the ellipse is built");
        assert_eq!(
            r.hits, r.samples,
            "{sequence:?}: every light sample sees it"
        );
        assert!(
            r.ci99.0 <= truth && truth <= r.ci99.1,
            "{sequence:?}: {truth} outside {:?}",
            r.ci99
        );
        // The control's premise, then the control: 1 % off is rejected.
        assert!(r.std_error / truth < 5e-4, "{sequence:?}: {}", r.std_error);
        let wrong = truth * 1.01;
        assert!(!(r.ci99.0 <= wrong && wrong <= r.ci99.1), "{sequence:?}");
    }
}

#[test]
fn disk_without_a_light_sampler_falls_back_to_cosine_sampling() {
    let (receiver, disk) = wide_disk();
    assert!(
        matches!(EmitterLight::new(&disk, &receiver), EmitterLight::None),
        "control: no ellipse can be built for this disk"
    );
    let truth = disk.closed_form_irradiance(&receiver).unwrap();
    assert_eq!(truth, std::f64::consts::PI);
    let scene = Scene::new(receiver, vec![disk]).unwrap();
    for strategy in [Strategy::Light, Strategy::Projected, Strategy::Auto] {
        let r =
            estimate_at_level(&scene, &config(strategy, SequenceKind::Independent), 0.99).unwrap();
        let (index, fallback) = r.fallback.expect("the fallback is reported");
        assert_eq!(index, 0);
        assert_eq!(fallback.requested, Technique::Light, "{strategy}");
        assert_eq!(fallback.used, Technique::CosineHemisphere, "{strategy}");
        assert!(fallback.to_string().contains("cosine-hemisphere"));
        // Every cosine direction above the horizon meets a disk that
        // covers the hemisphere to rounding: each sample is exactly πL.
        assert_eq!(r.hits, r.samples, "{strategy}");
        assert_eq!(r.mean, truth, "{strategy}");
    }
    // The control variate needs no sampler here: its closed form is exact.
    let r = estimate_at_level(
        &scene,
        &config(Strategy::ControlVariate, SequenceKind::Independent),
        0.99,
    )
    .unwrap();
    assert_eq!((r.fallback, r.mean), (None, truth));
}

#[test]
fn occluded_estimator_falls_back_too() {
    let (receiver, disk) = wide_disk();
    let visible = |_: DVec3, _: DVec3, _: f64| true;
    let hidden = |_: DVec3, _: DVec3, _: f64| false;
    for strategy in [Strategy::Light, Strategy::ControlVariate] {
        let e = OccludedEmitter::new(&disk, &receiver, strategy);
        let f = e.fallback.expect("fallback");
        assert_eq!(e.technique, Technique::CosineHemisphere, "{strategy}");
        assert_eq!(f.used, e.technique);
        let mut sequence = Independent::new(3);
        for i in 0..64 {
            sequence.start_sample(i);
            let seen = e.evaluate(&receiver, &mut sequence, &visible);
            sequence.start_sample(i);
            let none = e.evaluate(&receiver, &mut sequence, &hidden);
            // πL for every direction seen; the same direction hidden
            // gives exactly 0 (the control variate's residual with
            // cosine sampling is E_u − πL = 0 only by rounding, so the
            // fallback drops the control and samples E directly).
            assert_eq!((seen, none), (std::f64::consts::PI, 0.0), "{strategy}");
        }
    }
}

#[test]
fn fuzz_case_of_a_huge_disk_near_the_receiver_is_covered() {
    let text =
        include_str!("../../fuzz/corpus/fixed/disk-huge-radius-near-receiver-no-ellipse.toml");
    let scene = Scene::from_toml(text).unwrap();
    let truth: f64 = scene
        .emitters
        .iter()
        .map(|e| e.closed_form_irradiance(&scene.receiver).unwrap())
        .sum();
    let r = estimate_at_level(
        &scene,
        &config(Strategy::Light, SequenceKind::Independent),
        0.99,
    )
    .unwrap();
    let (index, f) = r.fallback.expect("the disk falls back");
    assert_eq!((index, f.used), (2, Technique::CosineHemisphere));
    assert!(
        r.ci99.0 <= truth && truth <= r.ci99.1,
        "{truth} outside {:?}",
        r.ci99
    );
    assert!(r.std_error / truth < 0.02, "{}", r.std_error);
    let wrong = truth * 1.15;
    assert!(!(r.ci99.0 <= wrong && wrong <= r.ci99.1), "control");
}
