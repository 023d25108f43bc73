//! Accuracy of the rare-event estimators the normal z-tests leave out
//! (`clt_applies`): the small coaxial disk (α = 0.01 rad, Ω = 3.1e-4 sr) with
//! uniform-hemisphere, cosine-hemisphere and balance-heuristic MIS sampling,
//! 9 of the 252 scene × strategy × sequence combinations.
//!
//! * Hit counts, exact: with independent samples the uniform and cosine
//!   estimators are nonzero only on a hit of the disk, which happens with
//!   probability P = 1 − cos α (uniform) or sin²α (cosine), so the number
//!   of hits H in n samples is Bin(n, P) — exactly, whatever the skewness
//!   that defeats the normal interval — and each hit's value lies in
//!   [2πL cos α, 2πL] (uniform) or is πL (cosine), so H right and the
//!   values in range make the estimate right. The hits are counted here,
//!   through the estimator's public pieces (`prepare`,
//!   `PreparedEmitter::evaluate_u`), at n = 2^22 (≈ 210 and 420 hits).
//! * Enough samples: the other seven (stratified and Sobol for all three,
//!   independent MIS) are `estimate` itself at n = 2^23 (uniform) or 2^22
//!   (cosine and MIS, whose cosine samples hit twice as often), where the
//!   rare part has ≥ 26 hits in each of the 16 randomizations (fewer make
//!   the t interval dishonest: see the study's interval tests) and ≥ 420
//!   in all (skewness ≤ 0.05), and are z-tested against the closed form
//!   (normal; t(15) for randomized QMC).
//!
//! One family of 9 tests at α = 0.01, Šidák-corrected. Negative controls,
//! at the same n and level: the hit counts of a disk of 1.25 times the
//! radius (P 56 % high) judged against the true P, and the z-tests of an
//! estimate 25 % high (the disk's radiance misread as 1.25: the estimator
//! is linear in L, so the same run scaled) against the true closed form;
//! each states its power, required ≥ 0.999.
//!
//! When `EstimateReport` carries hit counts and rare-event intervals
//! (issue 12), the hit-count tests should read the report's count from
//! `estimate` (and test the stratified and Sobol counts too, against their
//! own, smaller, variance), and these estimators can join the main z-test
//! suite at 2^18 with the rare-event interval; `clt_applies` then loses its
//! exception.

use glam::{DVec2, DVec3};
use lambert_estimator::estimation::{
    estimate, prepare, EstimateConfig, SequenceKind, RQMC_REPLICATES,
};
use lambert_estimator::strategy::{Heuristic, Strategy};
use lambert_estimator::{run_chunked, Estimate};
use lambert_light::emitter::DiskLight;
use lambert_light::{Emitter, Receiver, Scene};
use lambert_validate::sidak_level;
use rand::{RngCore, SeedableRng};
use statrs::distribution::{Binomial, ContinuousCDF, DiscreteCDF, Normal, StudentsT};
use std::f64::consts::PI;

const ALPHA: f64 = 0.01;
const FAMILY: usize = 9;
const HIT_SAMPLES: u64 = 1 << 22;
const CONTROL_POWER: f64 = 0.999;
/// The disk's half-angle seen from the receiver, radians.
const ALPHA_DISK: f64 = 0.01;

fn level() -> f64 {
    sidak_level(ALPHA, FAMILY)
}

/// The built-in small coaxial disk: center (0, 0, 1), facing down, radius
/// `scale`·tan α, radiance `radiance`, seen from the origin.
fn disk_scene(scale: f64, radiance: f64) -> Scene {
    let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
    let disk = DiskLight::new(
        DVec3::Z,
        -DVec3::Z,
        scale * ALPHA_DISK.tan(),
        radiance,
        false,
    )
    .unwrap();
    Scene::new(receiver, vec![Emitter::Disk(disk)]).unwrap()
}

/// E = πL sin²α for the disk of half-angle α (its radius over its distance).
fn closed_form(scene: &Scene) -> f64 {
    scene.emitters[0]
        .closed_form_irradiance(&scene.receiver)
        .unwrap()
}

/// The two-sided acceptance band [lo, hi] of Bin(n, p) at level α.
fn binomial_band(n: u64, p: f64, alpha: f64) -> (u64, u64) {
    let b = Binomial::new(p, n).unwrap();
    let lo = b.inverse_cdf(alpha / 2.0);
    let hi = b.inverse_cdf(1.0 - alpha / 2.0);
    (lo, hi)
}

/// The hits of n independent samples of `strategy` on `scene`, counted
/// through the estimator's public pieces, with every nonzero value checked
/// to lie in `values` (the values of a hit).
fn hits(scene: &Scene, strategy: Strategy, values: (f64, f64)) -> u64 {
    let (prepared, _) = prepare(scene, strategy);
    let emitter = &prepared[0];
    let counted = run_chunked(HIT_SAMPLES, 1 << 16, 2, |chunk, range| {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(0x5eed ^ (chunk << 20));
        let scale = 1.0 / (1u64 << 53) as f64;
        let mut next = || (rng.next_u64() >> 11) as f64 * scale;
        let mut hits = 0;
        let samples = range.end - range.start;
        for _ in range {
            let u = DVec2::new(next(), next());
            let v = emitter.evaluate_u(&scene.receiver, u, DVec2::ZERO);
            if v != 0.0 {
                assert!(
                    (values.0..=values.1).contains(&v),
                    "{strategy}: a hit of value {v} outside {values:?}"
                );
                hits += 1;
            }
        }
        let mut e = Estimate::new();
        e.push_n(1.0, hits);
        e.push_n(0.0, samples - hits);
        e
    })
    .unwrap();
    counted.sum().unwrap() as u64
}

/// The hit probability and the value range of a hit, per strategy, for
/// the disk of half-angle α and radiance L.
fn hit_model(strategy: Strategy, alpha: f64, radiance: f64) -> (f64, (f64, f64)) {
    match strategy {
        Strategy::UniformHemisphere => {
            let p = 2.0 * (0.5 * alpha).sin().powi(2);
            // 2πL cos θ, a few roundings on either end.
            let slack = 1e-12;
            (
                p,
                (
                    2.0 * PI * radiance * alpha.cos() * (1.0 - slack),
                    2.0 * PI * radiance * (1.0 + slack),
                ),
            )
        }
        Strategy::CosineHemisphere => (alpha.sin().powi(2), (PI * radiance, PI * radiance)),
        _ => unreachable!(),
    }
}

#[test]
fn hit_counts_are_binomial_and_a_wider_disk_is_caught() {
    let scene = disk_scene(1.0, 1.0);
    let wider = disk_scene(1.25, 1.0);
    let wider_alpha = (1.25 * ALPHA_DISK.tan()).atan();
    for strategy in [Strategy::UniformHemisphere, Strategy::CosineHemisphere] {
        let (p, values) = hit_model(strategy, ALPHA_DISK, 1.0);
        let (lo, hi) = binomial_band(HIT_SAMPLES, p, level());
        let h = hits(&scene, strategy, values);
        // Control: a disk 25 % wider, counted the same way, judged against
        // the true P; power P(Bin(n, P′) outside the band).
        let (p_wide, values_wide) = hit_model(strategy, wider_alpha, 1.0);
        let b = Binomial::new(p_wide, HIT_SAMPLES).unwrap();
        let power = b.cdf(lo.saturating_sub(1)) + b.sf(hi);
        let h_wide = hits(&wider, strategy, values_wide);
        eprintln!(
            "{strategy}: {h} hits of n = 2^22, band {lo}..={hi} (nP = {:.0}); \
             control (radius × 1.25): {h_wide} hits, power {power:.6}",
            HIT_SAMPLES as f64 * p
        );
        assert!(
            (lo..=hi).contains(&h),
            "{strategy}: {h} hits, band {lo}..={hi}"
        );
        assert!(power >= CONTROL_POWER, "{strategy}: control power {power}");
        assert!(
            !(lo..=hi).contains(&h_wide),
            "{strategy}: control not rejected"
        );
    }
}

/// The two-sided critical value of the z-test at `alpha`: normal for
/// independent samples, t(15) for the 16 randomizations of randomized QMC.
fn critical(sequence: SequenceKind, alpha: f64) -> f64 {
    match sequence {
        SequenceKind::Independent => Normal::standard().inverse_cdf(1.0 - alpha / 2.0),
        _ => StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64)
            .unwrap()
            .inverse_cdf(1.0 - alpha / 2.0),
    }
}

#[test]
fn the_other_seven_agree_with_the_closed_form_at_enough_samples() {
    let scene = disk_scene(1.0, 1.0);
    let truth = closed_form(&scene);
    let mut failures = Vec::new();
    let rqmc = [SequenceKind::Stratified, SequenceKind::Sobol];
    for (strategy, sequences, samples) in [
        (Strategy::UniformHemisphere, &rqmc[..], 1 << 23),
        (Strategy::CosineHemisphere, &rqmc[..], 1 << 22),
        (
            Strategy::Mis(Heuristic::Balance),
            &SequenceKind::ALL[..],
            1 << 22,
        ),
    ] {
        for &sequence in sequences {
            let config = EstimateConfig {
                strategy,
                sequence,
                samples,
                seed: 12,
                threads: 2,
                precision: lambert_estimator::precision::Precision::F64,
            };
            let c = critical(sequence, level());
            let r = estimate(&scene, &config).unwrap();
            let z = (r.mean - truth) / r.std_error;
            // Control: an estimate 25 % high (mean and standard error × 1.25,
            // as for radiance 1.25), against the true E. Its power: the
            // estimate is off by δ = 0.25 E, so |z| exceeds c with
            // probability F(−c + δ/se′) + F(−c − δ/se′), F the test's
            // distribution, se′ = 1.25 se.
            let z_bright = (1.25 * r.mean - truth) / (1.25 * r.std_error);
            let shift = 0.25 * truth / (1.25 * r.std_error);
            let power = match sequence {
                SequenceKind::Independent => {
                    let n = Normal::standard();
                    n.cdf(shift - c) + n.cdf(-shift - c)
                }
                _ => {
                    let t = StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64).unwrap();
                    t.cdf(shift - c) + t.cdf(-shift - c)
                }
            };
            eprintln!(
                "{strategy} {sequence}: z = {z:.2} (critical {c:.2}); control: z = {z_bright:.1}, power {power:.6}"
            );
            if z.abs() > c {
                failures.push(format!("{strategy} {sequence}: z = {z}"));
            }
            assert!(
                power >= CONTROL_POWER,
                "{strategy} {sequence}: power {power}"
            );
            assert!(z_bright.abs() > c, "{strategy} {sequence}: control passed");
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
