//! The chi-square tool on known samplers, and the negative controls it must
//! reject at the same sample counts (docs/ARCHITECTURE.md, "Statistical tests").
//!
//! Family: the six tests expected to pass (uniform sphere, cosine
//! hemisphere, uniform cones at θmax = 1e-6, 1e-3, 1, 3 rad) at a family-wise
//! level of α = 0.01, so each runs at the Šidák level 1 − 0.99^(1/6)
//! ≈ 1.67e-3. The negative controls run the same tests, at the same level
//! and sample counts, and must be rejected.

use glam::{DVec2, DVec3};
use lambert_geometry::f64::Frame;
use lambert_sampling::f64::UniformCone;
use lambert_validate::{sidak_level, Binning, ChiSquareOutcome, ChiSquareTest, ImmediateFailure};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg32;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::f64::consts::PI;

const FAMILY_ALPHA: f64 = 0.01;
const FAMILY_SIZE: usize = 6;
const SPHERE_SAMPLES: u64 = 1_000_000;
const SPHERE: Binning = Binning::Sphere {
    theta_bins: 40,
    phi_bins: 80,
};
const CONE_SAMPLES: u64 = 1_000_000;
const CONE_ROWS: usize = 64;
const CONE_COLS: usize = 8;
const THETA_MAX: [f64; 4] = [1e-6, 1e-3, 1.0, 3.0];

fn alpha() -> f64 {
    sidak_level(FAMILY_ALPHA, FAMILY_SIZE)
}

fn sphere_test() -> ChiSquareTest {
    ChiSquareTest::new(SPHERE)
        .samples(SPHERE_SAMPLES)
        .significance(alpha())
}

fn cap_test(axis: DVec3, h: f64) -> ChiSquareTest {
    ChiSquareTest::new(Binning::Cap {
        axis,
        one_minus_cos_max: h,
        theta_bins: CONE_ROWS,
        phi_bins: CONE_COLS,
    })
    .samples(CONE_SAMPLES)
    .significance(alpha())
}

fn u2(rng: &mut Pcg32) -> DVec2 {
    DVec2::new(rng.random::<f64>(), rng.random::<f64>())
}

fn uniform_sphere(u: DVec2) -> DVec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    DVec3::new(r * c, r * s, z)
}

fn uniform_hemisphere(u: DVec2) -> DVec3 {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    DVec3::new(r * c, r * s, z)
}

/// Malley's method: a uniform point on the unit disk, lifted. `phi_turns`
/// is the fraction of the circle φ covers (1 for the correct sampler).
fn cosine_hemisphere(u: DVec2, phi_turns: f64) -> DVec3 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * phi_turns * u.y).sin_cos();
    DVec3::new(r * c, r * s, (1.0 - u.x).max(0.0).sqrt())
}

fn cosine_pdf(w: DVec3) -> f64 {
    w.z.max(0.0) / PI
}

/// The axes used for the cones: +z for the tiniest (exact frame), tilted
/// otherwise to exercise the cap's frame.
fn cone_axis(theta_max: f64) -> DVec3 {
    if theta_max < 1e-4 {
        DVec3::Z
    } else {
        DVec3::new(1.0, 2.0, -3.0).normalize()
    }
}

/// Runs the cap test for a cone sampled with 1 − cos θmax = `h_sampled`
/// and judged (pdf and binning) with `h_judged`.
fn run_cone(theta_max: f64, h_sampled: f64, h_judged: f64, seed: u64) -> ChiSquareOutcome {
    let axis = cone_axis(theta_max);
    let frame = Frame::from_normal(axis);
    let sampler = UniformCone::from_one_minus_cos(h_sampled).unwrap();
    let judge = UniformCone::from_one_minus_cos(h_judged).unwrap();
    let mut rng = Pcg32::seed_from_u64(seed);
    cap_test(axis, h_judged)
        .run(
            |_| frame.from_local(sampler.sample(u2(&mut rng))),
            |w| judge.pdf(frame.to_local(w)),
        )
        .unwrap()
}

fn h_of(theta_max: f64) -> f64 {
    UniformCone::from_theta_max(theta_max)
        .unwrap()
        .one_minus_cos_theta_max()
}

#[test]
fn family_level_is_sidak() {
    let a = alpha();
    assert!((1.0 - (1.0 - a).powi(FAMILY_SIZE as i32) - FAMILY_ALPHA).abs() < 1e-15);
}

#[test]
fn uniform_sphere_passes() {
    let mut rng = Pcg32::seed_from_u64(1);
    let o = sphere_test()
        .run(|_| uniform_sphere(u2(&mut rng)), |_| 0.25 / PI)
        .unwrap();
    println!("uniform sphere: {o}");
    assert!((o.pdf_integral - 1.0).abs() < 1e-12);
    o.assert_passed();
}

#[test]
fn cosine_hemisphere_passes_and_integrates_to_one() {
    let mut rng = Pcg32::seed_from_u64(2);
    let o = sphere_test()
        .run(|_| cosine_hemisphere(u2(&mut rng), 1.0), cosine_pdf)
        .unwrap();
    println!("cosine hemisphere: {o}");
    assert!((o.pdf_integral - 1.0).abs() < 1e-12, "{o}");
    assert!(o.quadrature_error < 1e-9 && o.unconverged_cells == 0, "{o}");
    o.assert_passed();
}

#[test]
fn uniform_cones_pass_and_integrate_to_one() {
    for (k, &theta_max) in THETA_MAX.iter().enumerate() {
        let h = h_of(theta_max);
        let o = run_cone(theta_max, h, h, 10 + k as u64);
        println!("cone θmax = {theta_max:e} (h = {h:e}): {o}");
        assert!(
            (o.pdf_integral - 1.0).abs() < 1e-9,
            "θmax = {theta_max}: {o}"
        );
        assert_eq!(o.unconverged_cells, 0, "θmax = {theta_max}: {o}");
        o.assert_passed();
    }
}

#[test]
fn control_uniform_hemisphere_judged_as_cosine_is_rejected() {
    let mut rng = Pcg32::seed_from_u64(2);
    let o = sphere_test()
        .run(|_| uniform_hemisphere(u2(&mut rng)), cosine_pdf)
        .unwrap();
    println!("control (a) uniform vs cosine: {o}");
    assert!(
        o.failure.is_none(),
        "must be rejected by the statistic: {o}"
    );
    assert!(!o.passed(), "{o}");
}

#[test]
fn control_cone_too_wide_by_a_quarter_percent_is_rejected() {
    // Sampled from h·1.0025, judged against h: 0.25 % of the samples land
    // outside the cap, in the outside cell whose integrated pdf is 0.
    for (k, &theta_max) in THETA_MAX.iter().enumerate() {
        let h = h_of(theta_max);
        let o = run_cone(theta_max, (h * 1.0025).min(2.0), h, 10 + k as u64);
        println!("control (b) cone too wide, θmax = {theta_max:e}: {o}");
        assert!(
            matches!(
                o.failure,
                Some(ImmediateFailure::SamplesInZeroPdfCell { .. })
            ),
            "θmax = {theta_max}: {o}"
        );
        assert!(!o.passed());
    }
}

#[test]
fn control_cone_too_narrow_by_a_quarter_percent_is_rejected() {
    // Sampled from h, judged against h_j = 1.0025 h (all samples inside the
    // judged cap): every full row gets the fraction (1 + ε)/R instead of
    // 1/R, ε = 0.0025, and the last row the deficit. The noncentrality is
    // λ = n Σ (qᵢ − pᵢ)²/pᵢ = n ε² (R − 1) (the columns split each row
    // evenly and do not change it), so E[X²] ≈ dof + λ with standard
    // deviation √(2(dof + 2λ)). R = 64 rows, 8 columns, n = 1e6 give
    // λ ≈ 394 against a null spread √(2·511) ≈ 32.
    let eps: f64 = 0.0025;
    let n = CONE_SAMPLES as f64;
    let lambda = n * eps * eps * (CONE_ROWS as f64 - 1.0);
    let dof = (CONE_ROWS * CONE_COLS - 1) as f64;
    let critical = ChiSquared::new(dof).unwrap().inverse_cdf(1.0 - alpha());
    let mean = dof + lambda;
    let sd = (2.0 * (dof + 2.0 * lambda)).sqrt();
    println!(
        "control (b'): λ = {lambda:.1}, dof = {dof}, critical X² = {critical:.1}, \
         expected X² ≈ {mean:.1} ± {sd:.1} ({:.1} sd above the critical value)",
        (mean - critical) / sd
    );
    assert!(mean - critical > 4.0 * sd, "the design must have power");
    for (k, &theta_max) in THETA_MAX.iter().enumerate() {
        let h = h_of(theta_max);
        let o = run_cone(theta_max, h, h * (1.0 + eps), 10 + k as u64);
        println!("control (b') cone too narrow, θmax = {theta_max:e}: {o}");
        assert!(
            o.failure.is_none(),
            "must be rejected by the statistic: {o}"
        );
        assert!(!o.passed(), "θmax = {theta_max}: {o}");
    }
}

#[test]
fn control_half_circle_of_phi_is_rejected() {
    let mut rng = Pcg32::seed_from_u64(2);
    let o = sphere_test()
        .run(|_| cosine_hemisphere(u2(&mut rng), 0.5), cosine_pdf)
        .unwrap();
    println!("control (c) φ over half the circle: {o}");
    assert!(
        o.failure.is_none(),
        "must be rejected by the statistic: {o}"
    );
    assert!(!o.passed(), "{o}");
}

#[test]
fn control_sample_in_zero_pdf_cell_fails_immediately() {
    let mut rng = Pcg32::seed_from_u64(2);
    let o = sphere_test()
        .run(
            |i| {
                let w = cosine_hemisphere(u2(&mut rng), 1.0);
                if i == 123_456 {
                    -w
                } else {
                    w
                }
            },
            cosine_pdf,
        )
        .unwrap();
    println!("control (d) one sample below the horizon: {o}");
    match o.failure {
        Some(ImmediateFailure::SamplesInZeroPdfCell {
            observed,
            cells,
            samples,
            ..
        }) => {
            assert_eq!((observed, cells, samples), (1, 1, 1));
        }
        other => panic!("expected a zero-pdf failure, got {other:?}"),
    }
    assert!(!o.passed());
    assert!(o.table().contains("ZERO PDF"));
}

/// Partition mode: 16 equal cells of the unit square, sampled uniformly,
/// pass; the same cells sampled with u₀ warped by u₀^0.98 (a 2 % skew) are
/// rejected at the same count; probabilities that do not sum to 1 and a
/// sample outside every cell are errors or immediate failures.
#[test]
fn partition_mode_passes_uniform_and_rejects_skew() {
    use lambert_validate::ImmediateFailure;
    use rand::{Rng, SeedableRng};
    let probabilities = vec![1.0 / 16.0; 16];
    let test = ChiSquareTest::new(Binning::Sphere {
        theta_bins: 2,
        phi_bins: 2,
    })
    .samples(1_000_000)
    .significance(0.01);
    let cell = |u0: f64, u1: f64| Some((4.0 * u0) as usize * 4 + (4.0 * u1) as usize);
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(11);
    let good = test
        .run_partition(&probabilities, |_| cell(rng.random(), rng.random()))
        .unwrap();
    assert!(good.passed(), "{good}");
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(11);
    let skewed = test
        .run_partition(&probabilities, |_| {
            cell(rng.random::<f64>().powf(0.98), rng.random())
        })
        .unwrap();
    assert!(!skewed.passed(), "{skewed}");
    assert!(test.run_partition(&[0.5, 0.4], |_| Some(0)).is_err());
    assert!(test.run_partition(&[0.5, f64::NAN], |_| Some(0)).is_err());
    let stray = test
        .run_partition(&[0.5, 0.5], |i| {
            if i == 7 {
                None
            } else {
                Some((i % 2) as usize)
            }
        })
        .unwrap();
    assert!(matches!(
        stray.failure,
        Some(ImmediateFailure::OutsidePartition { index: 7, count: 1 })
    ));
}
