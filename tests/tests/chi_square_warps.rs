//! Chi-square goodness of fit of every direction warp, in both precisions,
//! at ordinary and hard parameters, and the negative controls that the same
//! test must reject at the same sample count and the same level.
//!
//! What the samples are judged against: for the smooth warps (hemispheres,
//! sphere, cones, sphere lights) the density each is *meant* to have,
//! written independently in [`intended_density`] (cos θ/π,
//! 1/(2π(1 − cos θmax)), …), never the warp's own `pdf` — a sampler whose
//! samples and pdf agree with each other but not with the intended density
//! would pass against its own pdf. The warps uniform on a sharp-edged
//! support are judged on an exact partition of it whose cell probabilities
//! are closed-form solid angles or areas ([`partition_for`]). Whether each
//! warp's own `pdf` equals that density is checked separately, by
//! integration, in `warp_densities.rs`.
//!
//! Family: every (case, precision) pair is one test; the family-wise level
//! is α = 0.01, so each runs at the Šidák level α₁ = 1 − (1 − α)^(1/m)
//! (m = 60 runs: α₁ = 1.675e-4). Every negative control runs at that same α₁
//! and n, and its power there — the probability that the test rejects the
//! control's defect, from the noncentral χ² with the noncentrality the
//! defect gives (`lambert_validate::power`) — is computed, printed, and
//! required to be at least [`CONTROL_POWER`].

use glam::{DVec2, DVec3};
use lambert_sampling::sequence::{Independent, SampleSequence};
use lambert_tests::{
    angular_scale, binning_for, chi_square, intended_density, one_minus_cos, partition_for,
    run_case, runs, Case, CHI_SQUARE_SAMPLES,
};
use lambert_validate::catalog::{DirectionWarpSpec, Precision};
use lambert_validate::{
    chi_square_power, integrate_cells, noncentrality, sidak_level, Binning, ChiSquareOutcome,
    ChiSquareTest, Smoothness,
};
use std::f64::consts::PI;

const FAMILY_ALPHA: f64 = 0.01;
const SEED: u64 = 20261122;

/// The least power a negative control must have at the suite's level.
const CONTROL_POWER: f64 = 0.999;

/// The per-test level of the suite (and of its controls).
fn suite_alpha() -> f64 {
    sidak_level(FAMILY_ALPHA, runs().len())
}

/// The binning a smooth case is judged on. In f32 a cap off the ±z axis is
/// widened by 64ε₃₂/sin θ (relative, in 1 − cos θ): the f32 sampler rotates
/// its local direction into the world with absolute error ~ε₃₂ per
/// component, which moves 1 − cos θ near the rim by about 2ε₃₂/θ relative
/// (4.6e-6 for the grazing sphere, more than the grid's own rim allowance
/// of 1e-6), so a few of its samples may land that far outside the exact
/// cap; widened, they are binned in the last row (where a few samples among
/// ~3900 are a bias of ≪ 1 in X²) instead of in the outside cell, where the
/// intended density is 0 and a single sample is an immediate failure.
/// Supports about ±z keep the exact cap: their directions are computed
/// with relative precision near the axis, and the quadrature is cheapest
/// when the rim is a row edge (a rim inside the last row costs ~1e7 density
/// evaluations to integrate to the test's target).
fn binning_in(spec: &DirectionWarpSpec, precision: Precision) -> Binning {
    match (binning_for(spec), precision) {
        (
            Binning::Cap {
                axis,
                one_minus_cos_max,
                theta_bins,
                phi_bins,
            },
            Precision::F32,
        ) if angular_scale(spec) < 1.0 => Binning::Cap {
            axis,
            one_minus_cos_max: (one_minus_cos_max
                * (1.0 + 64.0 * f32::EPSILON as f64 / angular_scale(spec)))
            .min(2.0),
            theta_bins,
            phi_bins,
        },
        (binning, _) => binning,
    }
}

/// One run of the suite: the partition test where the warp has one, else
/// its samples judged against the intended density.
fn run(case: &Case, precision: Precision, alpha: f64) -> ChiSquareOutcome {
    match intended_density(&case.spec) {
        None => run_case(case, precision, CHI_SQUARE_SAMPLES, SEED, alpha),
        Some(density) => {
            let warp = case.spec.build(precision).unwrap();
            chi_square(
                warp.as_ref(),
                precision,
                binning_in(&case.spec, precision),
                density,
                CHI_SQUARE_SAMPLES,
                SEED,
                alpha,
            )
        }
    }
}

#[test]
fn every_warp_passes_in_both_precisions() {
    let runs = runs();
    let alpha = suite_alpha();
    eprintln!("{} runs at the Šidák level α₁ = {alpha:.3e}", runs.len());
    let mut failures = Vec::new();
    for (case, precision) in &runs {
        let outcome = run(case, *precision, alpha);
        eprintln!(
            "{:>26} {}: X² = {:9.1}, dof {:4}, p = {:.3}",
            case.label,
            precision.name(),
            outcome.statistic,
            outcome.degrees_of_freedom,
            outcome.p_value,
        );
        if !outcome.passed() {
            failures.push(format!("{} {}: {outcome}", case.label, precision.name()));
        }
    }
    assert!(failures.is_empty(), "failures:\n{}", failures.join("\n"));
}

/// The power, at the suite's level, of the chi-square test on `binning`
/// against samples whose true density is `truth` judged against `claimed`:
/// λ = n Σ (qᵢ − pᵢ)²/pᵢ from the two densities integrated over the cells,
/// dof = (cells of positive claimed probability) − 1.
fn power_on_grid(
    binning: Binning,
    truth: impl FnMut(DVec3) -> f64,
    claimed: impl FnMut(DVec3) -> f64,
) -> f64 {
    // λ needs each cell's probability to a small fraction of its difference
    // (≳ 1e-5 of a cell here): 1e-9 absolute is ample.
    let q = integrate_cells(&binning, truth, 1e-9, 1 << 10, Smoothness::MayJump).unwrap();
    let p = integrate_cells(&binning, claimed, 1e-9, 1 << 10, Smoothness::MayJump).unwrap();
    let lambda = noncentrality(&q.probabilities, &p.probabilities, CHI_SQUARE_SAMPLES);
    let dof = p.probabilities.iter().filter(|&&x| x > 0.0).count() - 1;
    chi_square_power(dof as f64, lambda, suite_alpha())
}

/// Samples of `sampler` (f64) judged against `claimed` on `binning`, at the
/// suite's count and level; asserts the power and the rejection.
fn assert_rejected(
    what: &str,
    sampler: &DirectionWarpSpec,
    truth: impl FnMut(DVec3) -> f64,
    claimed: impl Fn(DVec3) -> f64,
    binning: Binning,
) {
    let power = power_on_grid(binning, truth, &claimed);
    let warp = sampler.build(Precision::F64).unwrap();
    let outcome = chi_square(
        warp.as_ref(),
        Precision::F64,
        binning,
        &claimed,
        CHI_SQUARE_SAMPLES,
        SEED,
        suite_alpha(),
    );
    eprintln!(
        "control {what}: power {power:.6} (miss probability {:.1e}) at α₁; {outcome}",
        1.0 - power
    );
    assert!(
        power >= CONTROL_POWER,
        "{what}: power {power} < {CONTROL_POWER}"
    );
    assert!(!outcome.passed(), "{what}: not rejected: {outcome}");
}

fn density(spec: &DirectionWarpSpec) -> impl Fn(DVec3) -> f64 {
    let d = intended_density(spec).expect("a smooth warp");
    move |w| d(w)
}

#[test]
fn rejects_uniform_samples_judged_against_the_cosine_density() {
    let cosine = DirectionWarpSpec::CosineHemisphere;
    let uniform = DirectionWarpSpec::UniformHemisphere;
    assert_rejected(
        "uniform hemisphere judged as cosine",
        &uniform,
        density(&uniform),
        density(&cosine),
        binning_for(&cosine),
    );
}

#[test]
fn rejects_a_self_consistent_warp_of_the_wrong_density() {
    // The defect a warp's own pdf cannot reveal: a cone (and a sphere
    // light) whose sampler and pdf agree with each other — both built for
    // 1 − cos θmax 0.25 % too small (a sphere radius 0.125 % too small) —
    // judged against the density the case is meant to have.
    for theta in [1e-6f64, 1e-3, 1.0, 3.0] {
        let h = one_minus_cos(theta);
        let meant = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h,
        };
        let built = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h * (1.0 - 0.0025),
        };
        assert_rejected(
            &format!("self-consistent cone 0.25 % narrow, θmax = {theta}"),
            &built,
            density(&built),
            density(&meant),
            binning_for(&meant),
        );
    }
    let center = DVec3::new(10.0 * 0.5, 0.0, 10.0 * 0.75f64.sqrt());
    let meant = DirectionWarpSpec::SphereLight {
        center,
        radius: 1.0,
    };
    let built = DirectionWarpSpec::SphereLight {
        center,
        radius: 1.0 - 0.00125,
    };
    assert_rejected(
        "self-consistent sphere light 0.125 % small",
        &built,
        density(&built),
        density(&meant),
        binning_for(&meant),
    );
}

#[test]
fn rejects_a_cone_whose_rim_is_off() {
    // Samples from the true cone judged against the intended density of a
    // wider one: cos θmax off by 0.5 % (widening the cap: times 1 − 0.005
    // for θmax < π/2, times 1 + 0.005 for θmax = 3 rad, where cos θmax < 0),
    // and 1 − cos θmax itself off by 0.25 %. Every full row then gets the
    // fraction (1 + δ)/R instead of 1/R (δ the relative change in 1 − cos
    // θmax) and λ ≈ n δ² (R − 1): δ = 0.25 % gives λ ≈ 394 over 255 dof.
    // The smallest change is that of cos θmax at 3 rad, δ = 0.25 %: a
    // 0.25 % change of cos θmax there (0.124 % in 1 − cos θmax, λ ≈ 100)
    // would have only ≈ 60 % power at the suite's level.
    let h3 = one_minus_cos(3.0);
    let truth3 = DirectionWarpSpec::UniformCone {
        one_minus_cos_theta_max: h3,
    };
    let old3 = DirectionWarpSpec::UniformCone {
        one_minus_cos_theta_max: 1.0 - 3f64.cos() * (1.0 + 0.0025),
    };
    let old_power = power_on_grid(binning_for(&old3), density(&truth3), density(&old3));
    eprintln!("the former control, cos θmax off by 0.25 % at 3 rad: power {old_power:.3} at α₁");
    assert!(old_power < CONTROL_POWER);
    for theta in [1e-6f64, 1e-3, 1.0, 3.0] {
        let h = one_minus_cos(theta);
        let cos = theta.cos();
        let wrong_cos = if cos > 0.0 {
            cos * (1.0 - 0.005)
        } else {
            cos * (1.0 + 0.005)
        };
        let truth = DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h,
        };
        for (what, wrong_h) in [
            ("cos θmax off by 0.5 %", 1.0 - wrong_cos),
            ("1 − cos θmax off by 0.25 %", h * 1.0025),
        ] {
            let wrong = DirectionWarpSpec::UniformCone {
                one_minus_cos_theta_max: wrong_h,
            };
            assert_rejected(
                &format!("{what}, θmax = {theta}"),
                &truth,
                density(&truth),
                density(&wrong),
                binning_for(&wrong),
            );
        }
    }
}

#[test]
fn rejects_half_circle_azimuths() {
    // The sphere warp with φ folded into [0, π) (u₁ halved): half the
    // sphere's cells get twice their share, the other half none; judged
    // against the uniform density, λ = n.
    let sphere = DirectionWarpSpec::UniformSphere;
    let warp = sphere.build(Precision::F64).unwrap();
    let binning = binning_for(&sphere);
    let power = power_on_grid(
        binning,
        |w: DVec3| {
            let phi = w.y.atan2(w.x).rem_euclid(2.0 * PI);
            if phi < PI {
                0.5 / PI
            } else {
                0.0
            }
        },
        density(&sphere),
    );
    let mut sequence = Independent::new(SEED);
    let claimed = density(&sphere);
    let outcome = ChiSquareTest::new(binning)
        .samples(CHI_SQUARE_SAMPLES)
        .significance(suite_alpha())
        .run(
            |i| {
                sequence.start_sample(i);
                let mut u = sequence.next_2d();
                u.y *= 0.5;
                warp.sample(u).direction
            },
            claimed,
        )
        .unwrap();
    eprintln!("control half-circle azimuths: power {power:.6}; {outcome}");
    assert!(power >= CONTROL_POWER, "power {power}");
    assert!(!outcome.passed(), "{outcome}");
}

/// Runs the partition test of `judge`'s support on samples drawn by
/// `sample` (u → direction) at the suite's count and level, whose true cell
/// probabilities are `truth`; asserts the power and the rejection.
fn assert_partition_rejects(
    what: &str,
    judge: &DirectionWarpSpec,
    truth: &[f64],
    sample: impl Fn(DVec2) -> DVec3,
) {
    let partition = partition_for(judge, Precision::F64).unwrap();
    let lambda = noncentrality(truth, &partition.probabilities, CHI_SQUARE_SAMPLES);
    let dof = (partition.probabilities.len() - 1) as f64;
    let power = chi_square_power(dof, lambda, suite_alpha());
    let mut sequence = Independent::new(SEED);
    let outcome = ChiSquareTest::new(binning_for(judge))
        .samples(CHI_SQUARE_SAMPLES)
        .significance(suite_alpha())
        .run_partition(&partition.probabilities, |i| {
            sequence.start_sample(i);
            (partition.locate)(sample(sequence.next_2d()))
        })
        .unwrap();
    eprintln!("control {what}: λ = {lambda:.1}, power {power:.6}; {outcome}");
    assert!(power >= CONTROL_POWER, "{what}: power {power}");
    assert!(!outcome.passed(), "{what}: not rejected: {outcome}");
}

#[test]
fn partition_mode_rejects_area_sampling_judged_as_solid_angle() {
    // The classic light-sampling mistake: uniform in area is not uniform in
    // solid angle (the densities differ by d²/cos θ, here by up to ~30 %).
    // Both partitions cut the triangle into the same sub-triangles, so the
    // area partition's probabilities are the control's true ones.
    let vertices = [
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    ];
    let area_spec = DirectionWarpSpec::TriangleArea { vertices };
    let area = area_spec.build(Precision::F64).unwrap();
    let truth = partition_for(&area_spec, Precision::F64)
        .unwrap()
        .probabilities;
    let solid = DirectionWarpSpec::SphericalTriangle { vertices };
    assert_partition_rejects("area sampling judged as solid angle", &solid, &truth, |u| {
        area.sample(u).direction
    });
}

#[test]
fn partition_mode_rejects_a_two_percent_skew() {
    // u₀ ↦ u₀^0.98 changes the density along u₀ by the factor
    // g(u₀) = u₀^(1/0.98 − 1)/0.98 ≈ 1 + 0.0204 (1 + ln u₀). The true cell
    // probabilities are ∫_cell pdf(ω) g(u₀(ω)) dω, u(ω) the warp's inverse,
    // integrated over each cell.
    let g = |u0: f64| u0.max(0.0).powf(1.0 / 0.98 - 1.0) / 0.98;
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
        let partition = partition_for(&spec, Precision::F64).unwrap();
        let truth: Vec<f64> = partition
            .cells
            .iter()
            .map(|cell| {
                cell.integrate_solid_angle(|w| warp.pdf(w) * g(warp.invert(w).x), 1e-7, 1 << 10)
                    .value
            })
            .collect();
        assert_partition_rejects(
            &format!("2 % skew of {}", spec.name()),
            &spec,
            &truth,
            |u| warp.sample(DVec2::new(u.x.powf(0.98), u.y)).direction,
        );
    }
}
