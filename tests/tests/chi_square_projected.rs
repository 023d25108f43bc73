//! Chi-square goodness of fit of the projected-solid-angle samplers (caps,
//! spheres, polygons) and of solid-angle sampling of disks, on every hard
//! case in both precisions, against densities written independently of the
//! samplers (cos θ/Ω⊥ with Ω⊥ from the light crate's closed forms and the
//! support from plain geometry; 1/Ω for disks with Ω from the test crate's
//! quadrature; `lambert_tests::projected`), with negative controls at the
//! same sample count and level that the test must reject.
//!
//! Family: every (case, precision) pair is one test; the family-wise level
//! is α = 0.01, so each runs at the Šidák level 1 − (1 − α)^(1/m). The
//! negative controls run at that same per-test level.

use glam::{DVec2, DVec3};
use lambert_sampling::sequence::{Independent, SampleSequence};
use lambert_tests::projected::{
    bounding_cap, build, cases, partition, reference_density, Case, Shape,
};
use lambert_validate::catalog::Precision;
use lambert_validate::{sidak_level, Binning, ChiSquareOutcome, ChiSquareTest};

const FAMILY_ALPHA: f64 = 0.01;
const SEED: u64 = 20_260_611;
/// Samples per test, and per negative control.
const SAMPLES: u64 = 1_000_000;

/// Caps and spheres: 16 rows × 4 sectors of equal solid angle within the
/// cap widened 2 % (the horizon and the rim cut cells, which the test's
/// adaptive quadrature resolves), or 8 × 8 over the sphere for caps wider
/// than a hemisphere. 64 cells: few enough that a density off by 1 % (a
/// noncentrality of n·1e-4 = 100 whatever the binning) clears the critical
/// excess at the Šidák level (≈ 3.6 √(2·63) ≈ 40), enough rows to see a
/// wrong radial profile such as a missing cos θ. Polygons and disks use the
/// exact partitions of `lambert_tests::projected::partition` instead (an
/// indicator of a straight or curved edge inside a cell is what adaptive
/// quadrature resolves worst).
fn binning(shape: &Shape) -> Binning {
    match bounding_cap(shape) {
        Some((axis, h)) => Binning::Cap {
            axis,
            one_minus_cos_max: h,
            theta_bins: 16,
            phi_bins: 4,
        },
        None => Binning::Sphere {
            theta_bins: 8,
            phi_bins: 8,
        },
    }
}

/// u for sample i: the independent sequence's stream i (24-bit uniforms for
/// f32).
fn uniform(sequence: &mut Independent, i: u64, precision: Precision) -> DVec2 {
    sequence.start_sample(i);
    match precision {
        Precision::F32 => sequence.next_2d_f32().as_dvec2(),
        Precision::F64 => sequence.next_2d(),
    }
}

/// Runs the test of `sample` (u ↦ direction) against `pdf`: binned with
/// quadrature for caps and spheres, on the exact partition for polygons
/// and disks (where `pdf` is not used).
fn run(
    case: &Case,
    precision: Precision,
    alpha: f64,
    sample: impl Fn(DVec2) -> DVec3,
    pdf: impl Fn(DVec3) -> f64,
) -> ChiSquareOutcome {
    let mut sequence = Independent::new(SEED);
    let test = ChiSquareTest::new(binning(&case.shape))
        .samples(SAMPLES)
        .significance(alpha);
    match partition(&case.shape, precision) {
        Some(part) => test
            .run_partition(&part.probabilities, |i| {
                (part.locate)(sample(uniform(&mut sequence, i, precision)))
            })
            .expect("a valid partition"),
        None => test
            .run(|i| sample(uniform(&mut sequence, i, precision)), pdf)
            .expect("a valid chi-square configuration"),
    }
}

fn runs() -> Vec<(Case, Precision)> {
    cases()
        .into_iter()
        .flat_map(|case| {
            let f32_too = case.f32_resolvable;
            Precision::ALL
                .into_iter()
                .filter(move |p| *p == Precision::F64 || f32_too)
                .map(move |p| (case.clone(), p))
        })
        .collect()
}

fn per_test_alpha() -> f64 {
    sidak_level(FAMILY_ALPHA, runs().len())
}

#[test]
fn every_sampler_has_its_density_on_every_case() {
    let runs = runs();
    let alpha = sidak_level(FAMILY_ALPHA, runs.len());
    let mut failures = Vec::new();
    for (case, precision) in &runs {
        let warp = build(&case.shape, *precision).expect("valid case");
        let pdf = reference_density(&case.shape);
        let outcome = run(case, *precision, alpha, |u| warp.sample(u).direction, pdf);
        eprintln!(
            "{:>40} {}: X² = {:9.1}, dof {:4}, p = {:.3}, ∫pdf = {:.6}",
            case.label,
            precision.name(),
            outcome.statistic,
            outcome.degrees_of_freedom,
            outcome.p_value,
            outcome.pdf_integral
        );
        // ∫pdf dω = 1 to the quadrature's error (binned cases only): a
        // normalisation error that no histogram can show is caught here.
        let normalised = partition(&case.shape, *precision).is_some()
            || (outcome.pdf_integral - 1.0).abs() <= 1e-4;
        if !outcome.passed() || !normalised {
            failures.push(format!("{} {}: {outcome}", case.label, precision.name()));
        }
    }
    assert!(failures.is_empty(), "failures:\n{}", failures.join("\n"));
}

/// A negative control's outcome: printed, and asserted to be a rejection.
fn must_reject(what: &str, outcome: &ChiSquareOutcome) {
    eprintln!("{what}: {outcome}");
    assert!(!outcome.passed(), "{what}: not rejected");
}

fn find(label: &str) -> Case {
    cases()
        .into_iter()
        .find(|c| c.label == label)
        .unwrap_or_else(|| panic!("no case {label}"))
}

/// Negative control 1 (binned cases): the right sampler judged against its
/// density off by 1 % (the expected counts all 1 % high: noncentrality
/// ≈ n·1e-4 = 100 on 63 degrees of freedom, against a critical excess of
/// ≈ 40 at the Šidák level).
#[test]
fn rejects_a_density_off_by_one_percent() {
    let alpha = per_test_alpha();
    for label in ["cap 0.3 rad straddling above", "sphere straddling"] {
        let case = find(label);
        let warp = build(&case.shape, Precision::F64).unwrap();
        let pdf = reference_density(&case.shape);
        let outcome = run(
            &case,
            Precision::F64,
            alpha,
            |u| warp.sample(u).direction,
            |w| 1.01 * pdf(w),
        );
        must_reject(&format!("{label}, pdf × 1.01"), &outcome);
    }
}

/// Negative control 1 (partition cases): the right sampler with u₀ skewed to
/// u₀^0.98, which changes the density by about 2 % (1 + ln u₀): on an exact
/// partition that must be rejected.
#[test]
fn rejects_a_two_percent_skew() {
    let alpha = per_test_alpha();
    for label in [
        "pentagon tilted",
        "square offset",
        "disk tilted",
        "disk coaxial",
    ] {
        let case = find(label);
        let warp = build(&case.shape, Precision::F64).unwrap();
        let pdf = reference_density(&case.shape);
        let outcome = run(
            &case,
            Precision::F64,
            alpha,
            |u| warp.sample(DVec2::new(u.x.powf(0.98), u.y)).direction,
            pdf,
        );
        must_reject(&format!("{label}, u₀^0.98"), &outcome);
    }
}

/// Negative control 2: uniform-solid-angle samplers (the ones the projected
/// samplers replace) judged against the cosine-weighted density, on lights
/// wholly above the horizon (else the test fails trivially on samples where
/// the density is 0).
#[test]
fn rejects_uniform_solid_angle_samples_judged_as_cosine_weighted() {
    let alpha = per_test_alpha();
    use lambert_sampling::f64 as s;
    // A cap: the uniform cone about its axis.
    let case = find("cap 0.3 rad above");
    let Shape::Cap { axis, h } = case.shape else {
        unreachable!()
    };
    let cone = s::UniformCone::from_one_minus_cos(h).unwrap();
    let frame = lambert_geometry::f64::Frame::from_normal(axis);
    let outcome = run(
        &case,
        Precision::F64,
        alpha,
        |u| frame.from_local(cone.sample(u)),
        reference_density(&case.shape),
    );
    must_reject("uniform cone judged as projected cap", &outcome);
    // A sphere tilted 1 rad from the receiver's normal: uniform in its cone.
    let case = find("sphere tilted 1 rad");
    let Shape::Sphere { p, c, r, .. } = case.shape else {
        unreachable!()
    };
    let sphere =
        s::SphereSolidAngle::new(p, &lambert_geometry::f64::Sphere::new(c, r).unwrap()).unwrap();
    let outcome = run(
        &case,
        Precision::F64,
        alpha,
        |u| sphere.sample(u).direction,
        reference_density(&case.shape),
    );
    must_reject("sphere solid angle judged as projected", &outcome);
    // A triangle: Arvo's uniform spherical triangle.
    let case = find("triangle tilted receiver");
    let Shape::Polygon {
        p, ref vertices, ..
    } = case.shape
    else {
        unreachable!()
    };
    let tri = s::SphericalTriangle::new(p, vertices[0], vertices[1], vertices[2]).unwrap();
    let outcome = run(
        &case,
        Precision::F64,
        alpha,
        |u| tri.sample(u).direction,
        reference_density(&case.shape),
    );
    must_reject("spherical triangle judged as projected", &outcome);
}

/// Negative control 3 (disks): area sampling, whose directions are not
/// uniform in solid angle, judged against 1/Ω.
#[test]
fn rejects_area_sampled_disk_judged_as_uniform_solid_angle() {
    let alpha = per_test_alpha();
    let case = find("disk tilted");
    let Shape::Disk { p, c, normal, r } = case.shape else {
        unreachable!()
    };
    let disk = lambert_geometry::f64::Disk::new(c, normal, r).unwrap();
    let area = lambert_sampling::f64::UniformDiskArea::new(&disk);
    let outcome = run(
        &case,
        Precision::F64,
        alpha,
        |u| (area.sample(u).point - p).normalize(),
        reference_density(&case.shape),
    );
    must_reject("disk area sampling judged as solid angle", &outcome);
}
