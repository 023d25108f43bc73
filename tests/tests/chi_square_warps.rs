//! Chi-square goodness of fit of every direction warp, in both precisions,
//! at ordinary and hard parameters; ∫pdf dω = 1 by the test's independent
//! per-cell quadrature; and the negative controls, at the same sample
//! count and binning, that the same test must reject.
//!
//! Family: every (case, precision) pair is one test; the family-wise level
//! is α = 0.01, so each runs at the Šidák level 1 − (1 − α)^(1/m).

use glam::DVec3;
use lambert_estimator::goodness_of_fit::{sidak_level, Binning};
use lambert_sampling::catalog::{DirectionWarpSpec, Precision};
use lambert_tests::{binning_for, chi_square, direction_cases, one_minus_cos, CHI_SQUARE_SAMPLES};

const FAMILY_ALPHA: f64 = 0.01;
const SEED: u64 = 20261122;

#[test]
fn every_warp_passes_in_both_precisions() {
    let cases = direction_cases();
    let alpha = sidak_level(FAMILY_ALPHA, cases.len() * Precision::ALL.len());
    let mut failures = Vec::new();
    for case in &cases {
        for precision in Precision::ALL {
            let warp = case.spec.build(precision).unwrap();
            let outcome = chi_square(
                warp.as_ref(),
                precision,
                binning_for(&case.spec),
                |w| warp.pdf(w),
                CHI_SQUARE_SAMPLES,
                SEED,
                alpha,
            );
            eprintln!(
                "{:>26} {}: X² = {:9.1}, dof {:4}, p = {:.3}, ∫pdf = {:.9}",
                case.label,
                precision.name(),
                outcome.statistic,
                outcome.degrees_of_freedom,
                outcome.p_value,
                outcome.pdf_integral
            );
            // ∫pdf dω = 1: the quadrature's own error bound, plus the f32
            // pdf's rim band (32ε/θmax relative, see SphereSolidAngle::pdf)
            // for f32 lights; 1e-6 covers both on these cases.
            let integral_ok = (outcome.pdf_integral - 1.0).abs() <= 1e-6;
            if !outcome.passed() || !integral_ok {
                failures.push(format!("{} {}: {outcome}", case.label, precision.name()));
            }
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
fn rejects_a_cone_off_by_a_quarter_percent() {
    // Samples from the true cone, judged against a pdf whose cos θmax is off
    // by 0.25 % of 1 − cos θmax (so the judged density is 0.25 % low inside
    // a 0.25 % larger cap). With 256 cells and n = 4e5 the noncentrality is
    // λ ≈ n·δ²·(k − 1)... ≈ 4e5 · 0.0025² · 255 ≈ 640 ≫ the 1 % critical
    // excess (≈ 2.33·√(2·255) ≈ 53), so the control must be rejected.
    for theta in [1e-6, 1e-3, 1.0, 3.0] {
        let h = one_minus_cos(theta);
        let truth = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h,
        };
        let wrong = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h * 1.0025,
        };
        assert!(
            !mismatched(&truth, &wrong, binning_for(&wrong)),
            "θmax = {theta}: a 0.25 % error in the cone was not detected"
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
    let outcome = lambert_estimator::goodness_of_fit::ChiSquareTest::new(Binning::Sphere {
        theta_bins: 20,
        phi_bins: 40,
    })
    .samples(CHI_SQUARE_SAMPLES)
    .significance(0.01)
    .run(
        |i| {
            let mut s = lambert_sampling::Independent::new(SEED);
            lambert_sampling::SampleSequence::start_sample(&mut s, i);
            let mut u = lambert_sampling::SampleSequence::next_2d(&mut s);
            u.y *= 0.5;
            warp.sample(u).direction
        },
        |w: DVec3| warp.pdf(w),
    )
    .unwrap();
    assert!(!outcome.passed(), "{outcome}");
}
