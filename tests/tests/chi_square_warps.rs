//! Chi-square goodness of fit of every direction warp, in both precisions,
//! at ordinary and hard parameters; ∫pdf dω = 1 by the test's independent
//! per-cell quadrature; and the negative controls, at the same sample
//! count and binning, that the same test must reject.
//!
//! Family: every (case, precision) pair is one test; the family-wise level
//! is α = 0.01, so each runs at the Šidák level 1 − (1 − α)^(1/m).

use glam::DVec3;
use lambert_sampling::sequence::{Independent, SampleSequence};
use lambert_tests::{
    binning_for, chi_square, one_minus_cos, partition_for, run_case, runs, CHI_SQUARE_SAMPLES,
};
use lambert_validate::catalog::{DirectionWarpSpec, Precision};
use lambert_validate::{sidak_level, Binning, ChiSquareTest};

const FAMILY_ALPHA: f64 = 0.01;
const SEED: u64 = 20261122;

#[test]
fn every_warp_passes_in_both_precisions() {
    let runs = runs();
    let alpha = sidak_level(FAMILY_ALPHA, runs.len());
    let mut failures = Vec::new();
    for (case, precision) in &runs {
        let (case, precision) = (case, *precision);
        let outcome = run_case(case, precision, CHI_SQUARE_SAMPLES, SEED, alpha);
        eprintln!(
            "{:>26} {}: X² = {:9.1}, dof {:4}, p = {:.3}, ∫pdf = {:.9}",
            case.label,
            precision.name(),
            outcome.statistic,
            outcome.degrees_of_freedom,
            outcome.p_value,
            outcome.pdf_integral
        );
        // ∫pdf dω = 1: within the quadrature's error for smooth densities,
        // plus the f32 pdf's rim band (≤ 32ε/θmax relative, see
        // SphereSolidAngle::pdf); 1e-4 covers both on these cases.
        let integral_ok = (outcome.pdf_integral - 1.0).abs() <= 1e-4;
        if !outcome.passed() || !integral_ok {
            failures.push(format!("{} {}: {outcome}", case.label, precision.name()));
        }
    }
    assert!(failures.is_empty(), "failures:\n{}", failures.join("\n"));
}

/// A warp whose samples come from `sample_spec` but which is judged against
/// `judge_spec`'s pdf.
fn mismatched(
    sample_spec: &DirectionWarpSpec,
    judge_spec: &DirectionWarpSpec,
    binning: Binning,
) -> bool {
    let sampler = sample_spec.build(Precision::F64).unwrap();
    let judge = judge_spec.build(Precision::F64).unwrap();
    let alpha = 0.01;
    let outcome = chi_square(
        sampler.as_ref(),
        Precision::F64,
        binning,
        |w| judge.pdf(w),
        CHI_SQUARE_SAMPLES,
        SEED,
        alpha,
    );
    eprintln!("negative control: {outcome}");
    outcome.passed()
}

#[test]
fn rejects_uniform_samples_judged_against_the_cosine_pdf() {
    let spec = DirectionWarpSpec::CosineHemisphere;
    assert!(!mismatched(
        &DirectionWarpSpec::UniformHemisphere,
        &spec,
        binning_for(&spec)
    ));
}

#[test]
fn rejects_a_cone_whose_cos_theta_max_is_off_by_a_quarter_percent() {
    // Samples from the true cone, judged against a pdf whose cos θmax is
    // 0.25 % off (times 1 − 0.0025 for θmax < π/2, where that widens the
    // cap; times 1 + 0.0025 for θmax = 3 rad, where cos θmax < 0 and that
    // also widens it). The change in 1 − cos θmax is 0.29 % at 1 rad and
    // 0.124 % at 3 rad, the hardest case: λ ≈ n δ² (R + 1) ≈ 100 there, an
    // expected X² of 355 against a critical value of 309 at α = 0.01.
    for theta in [1e-6f64, 1e-3, 1.0, 3.0] {
        let h = one_minus_cos(theta);
        let cos = theta.cos();
        let wrong_cos = if cos > 0.0 {
            cos * (1.0 - 0.0025)
        } else {
            cos * (1.0 + 0.0025)
        };
        let truth = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h,
        };
        let wrong = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: 1.0 - wrong_cos,
        };
        assert!(
            !mismatched(&truth, &wrong, binning_for(&wrong)),
            "θmax = {theta}: a 0.25 % error in cos θmax was not detected"
        );
        // And the subtler relative error: 1 − cos θmax itself off by 0.25 %.
        let wrong_h = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h * 1.0025,
        };
        assert!(
            !mismatched(&truth, &wrong_h, binning_for(&wrong_h)),
            "θmax = {theta}: a 0.25 % error in 1 − cos θmax was not detected"
        );
    }
}

#[test]
fn rejects_half_circle_azimuths() {
    // The sphere warp with φ folded into [0, π): samples judged against the
    // uniform pdf.
    let warp = DirectionWarpSpec::UniformSphere
        .build(Precision::F64)
        .unwrap();
    let outcome = lambert_validate::ChiSquareTest::new(Binning::Sphere {
        theta_bins: 20,
        phi_bins: 40,
    })
    .samples(CHI_SQUARE_SAMPLES)
    .significance(0.01)
    .run(
        |i| {
            let mut s = lambert_sampling::sequence::Independent::new(SEED);
            lambert_sampling::sequence::SampleSequence::start_sample(&mut s, i);
            let mut u = lambert_sampling::sequence::SampleSequence::next_2d(&mut s);
            u.y *= 0.5;
            warp.sample(u).direction
        },
        |w: DVec3| warp.pdf(w),
    )
    .unwrap();
    assert!(!outcome.passed(), "{outcome}");
}

/// Runs the partition test of `judge`'s support on samples drawn by
/// `sample` (u → direction), at the suite's count; true if it passed.
fn partition_passes(judge: &DirectionWarpSpec, sample: impl Fn(glam::DVec2) -> DVec3) -> bool {
    let partition = partition_for(judge, Precision::F64).unwrap();
    let mut sequence = Independent::new(SEED);
    let outcome = ChiSquareTest::new(binning_for(judge))
        .samples(CHI_SQUARE_SAMPLES)
        .significance(0.01)
        .run_partition(&partition.probabilities, |i| {
            sequence.start_sample(i);
            (partition.locate)(sample(sequence.next_2d()))
        })
        .unwrap();
    eprintln!("negative control (partition): {outcome}");
    outcome.passed()
}

#[test]
fn partition_mode_rejects_area_sampling_judged_as_solid_angle() {
    // The classic light-sampling mistake: uniform in area is not uniform in
    // solid angle (the densities differ by d²/cos θ, here by up to ~30 %).
    let vertices = [
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    ];
    let area = DirectionWarpSpec::TriangleArea { vertices }
        .build(Precision::F64)
        .unwrap();
    let solid = DirectionWarpSpec::SphericalTriangle { vertices };
    assert!(!partition_passes(&solid, |u| area.sample(u).direction));
    // The control's control: the right sampler passes the same test.
    let right = solid.build(Precision::F64).unwrap();
    assert!(partition_passes(&solid, |u| right.sample(u).direction));
}

#[test]
fn partition_mode_rejects_a_two_percent_skew() {
    // u₀ ↦ u₀^0.98 changes the density along u₀ by a factor
    // 0.98⁻¹ u₀^(1/0.98 − 1) ≈ 1 + 0.0204 (1 + ln u₀); the noncentrality is
    // λ ≈ n · 0.0204² · E[(1 + ln u₀)²] = n · 4.2e-4 ≈ 420 at n = 1e6,
    // against a 1 % critical excess of ≈ 54 over 255 dof.
    for spec in [
        DirectionWarpSpec::SphericalRectangle {
            corner: DVec3::new(-0.5, -0.3, 2.0),
            edge0: DVec3::new(1.0, 0.0, 0.0),
            edge1: DVec3::new(0.0, 0.8, 0.0),
        },
        DirectionWarpSpec::SphericalTriangle {
            vertices: [
                DVec3::new(-1.0, 0.0, 2.0),
                DVec3::new(1.0, 0.0, 2.0),
                DVec3::new(0.0, 0.001, 2.0),
            ],
        },
    ] {
        let warp = spec.build(Precision::F64).unwrap();
        assert!(
            !partition_passes(&spec, |u| warp
                .sample(glam::DVec2::new(u.x.powf(0.98), u.y))
                .direction),
            "{spec:?}"
        );
    }
}
