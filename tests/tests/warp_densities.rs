//! Each warp's own `pdf`, integrated: deterministic checks (no sampling)
//! that complete the chi-square suite, which judges the samples against
//! densities written independently of the warps.
//!
//! * Smooth warps: the warp's `pdf` and the intended density
//!   ([`intended_density`]) integrated over the cells of the suite's
//!   binning must agree cell by cell — their total-variation distance
//!   ½ Σ |∫_cell pdf − ∫_cell intended| within the precision's rounding of
//!   the pdf — and ∫ pdf dω = 1.
//! * Partition-mode warps (spherical triangles and rectangles, area
//!   samplers): the warp's `pdf` integrated over each cell of the exact
//!   partition must equal the cell's closed-form probability, to a
//!   tolerance per precision; before, these warps' `pdf` was never
//!   evaluated by the suite.
//!
//! The quadratures converge to far below the tolerances (their error
//! estimates are part of each bound); the negative controls — a pdf off by
//! a tenth of the f64 tolerance's scale, a self-consistent warp of the
//! wrong density, a solid-angle pdf judged on an area partition — must fail
//! the same checks.

use glam::DVec3;
use lambert_tests::{
    angular_scale, binning_for, conditioning, intended_density, one_minus_cos, partition_for, runs,
};
use lambert_validate::catalog::{DirectionWarpSpec, Precision};
use lambert_validate::{integrate_cells, Smoothness};

fn eps(p: Precision) -> f64 {
    match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    }
}

/// Split budget per region of the smooth comparisons' quadratures.
const SPLITS: usize = 1 << 10;

/// Total-variation distance between `pdf` and `meant` over the cells of
/// the spec's binning, |∫pdf − 1|, and the two quadratures' summed error
/// estimate, each cell integrated to `cell_tolerance`.
///
/// In f64 the quadrature checks every region's edges too
/// ([`Smoothness::MayJump`]), so a pdf that departs from the intended
/// density anywhere, even in a sliver along a cell's edge, is integrated as
/// it is. In f32 it cannot: the f32 pdf's rim is blurred over ~ε₃₂ of
/// 1 − cos θ (the rounding of a direction), a band narrower than the edge
/// check's inset (1e-6 of a region), so the check would keep finding "a
/// jump" at the rim of every region it splits; there the Gauss rule alone
/// integrates the interior ([`Smoothness::Smooth`]: the rim band, whose mass
/// is within the allowance by construction, is not seen). A shape defect
/// of the f32 pdf would also be one of the f64 pdf — both precisions are
/// one implementation — and its samples are judged by the f32 chi-square
/// runs.
fn compare(
    spec: &DirectionWarpSpec,
    precision: Precision,
    pdf: impl FnMut(DVec3) -> f64,
    meant: impl FnMut(DVec3) -> f64,
    cell_tolerance: f64,
) -> (f64, f64, f64) {
    let binning = binning_for(spec);
    let smoothness = match precision {
        Precision::F64 => Smoothness::MayJump,
        Precision::F32 => Smoothness::Smooth,
    };
    let own = integrate_cells(&binning, pdf, cell_tolerance, SPLITS, smoothness).unwrap();
    let intended =
        integrate_cells(&binning, meant, cell_tolerance, SPLITS, Smoothness::MayJump).unwrap();
    assert!(own.invalid_pdf.is_none(), "{:?}", own.invalid_pdf);
    let tv = 0.5
        * own
            .probabilities
            .iter()
            .zip(&intended.probabilities)
            .map(|(a, b)| (a - b).abs())
            .sum::<f64>();
    (tv, (own.total - 1.0).abs(), own.error + intended.error)
}

/// How far a correct warp's pdf may be from the intended density in total
/// variation, in `precision`: its rim is located only to the rounding of a
/// direction, ~16ε in angle off the ±z axis (`SphereSolidAngle::pdf`
/// documents that band), which moves the mass of a cap of angular radius θ
/// by 2·16ε/θ relative; we allow twice that, 64ε/sin θ (`angular_scale`,
/// 1 for supports about ±z, whose directions are exact to relative
/// precision), which also covers the pdf's own value (1/Ω, cos θ/π: a few
/// roundings).
fn smooth_allowance(spec: &DirectionWarpSpec, precision: Precision) -> f64 {
    64.0 * eps(precision) / angular_scale(spec)
}

#[test]
fn smooth_warp_pdfs_equal_the_intended_densities() {
    let mut failures = Vec::new();
    for (case, precision) in runs() {
        let Some(meant) = intended_density(&case.spec) else {
            continue;
        };
        let warp = case.spec.build(precision).unwrap();
        let allowance = smooth_allowance(&case.spec, precision);
        // Inside the support both densities are constant or linear in
        // 1 − cos θ, integrated exactly on the first level (see `compare`).
        let (tv, total, error) = compare(
            &case.spec,
            precision,
            |w| warp.pdf(w),
            &meant,
            allowance / 4.0,
        );
        eprintln!(
            "{:>24} {}: TV {tv:.2e}, |∫pdf − 1| {total:.2e}, quadrature {error:.1e}, allowance {allowance:.1e}",
            case.label,
            precision.name()
        );
        if tv > allowance + error || total > allowance + error || error > allowance {
            failures.push(format!(
                "{} {}: TV {tv:e}, |∫pdf − 1| {total:e}, quadrature {error:e} > {allowance:e}",
                case.label,
                precision.name()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn smooth_comparison_rejects_a_wrong_pdf() {
    // A self-consistent cone 0.25 % too narrow (its own pdf), and the
    // cosine pdf scaled by 1 + 1e-9: both far outside the f64 allowance
    // (TV 2.5e-3 and 5e-10 against 1.4e-14).
    let h = one_minus_cos(1.0);
    let meant = DirectionWarpSpec::UniformCone {
        one_minus_cos_theta_max: h,
    };
    let built = DirectionWarpSpec::UniformCone {
        one_minus_cos_theta_max: h * (1.0 - 0.0025),
    };
    let narrow = built.build(Precision::F64).unwrap();
    let allowance = smooth_allowance(&meant, Precision::F64);
    let (tv, _, error) = compare(
        &meant,
        Precision::F64,
        |w| narrow.pdf(w),
        intended_density(&meant).unwrap(),
        allowance / 4.0,
    );
    eprintln!(
        "control narrow cone: TV {tv:.3e} (allowance {allowance:.1e}, quadrature {error:.1e})"
    );
    assert!(tv > allowance + error, "TV {tv}");
    let cosine = DirectionWarpSpec::CosineHemisphere;
    let warp = cosine.build(Precision::F64).unwrap();
    let allowance = smooth_allowance(&cosine, Precision::F64);
    let (tv, total, error) = compare(
        &cosine,
        Precision::F64,
        |w| warp.pdf(w) * (1.0 + 1e-9),
        intended_density(&cosine).unwrap(),
        allowance / 4.0,
    );
    eprintln!("control cosine pdf × (1 + 1e-9): TV {tv:.3e}, |∫pdf − 1| {total:.3e}");
    assert!(tv > allowance + error && total > allowance + error);
}

/// The worst relative deviation of ∫_cell pdf dω from the cell's
/// probability over the partition of `spec`, the deviation of the total
/// from 1, and the quadratures' worst relative error estimate.
fn partition_deviation(
    spec: &DirectionWarpSpec,
    precision: Precision,
    pdf: impl Fn(DVec3) -> f64,
) -> (f64, f64, f64) {
    let partition = partition_for(spec, precision).unwrap();
    // The integrand pdf·|n·p|/|p|³ is smooth on each cell: the quadrature
    // reaches a hundredth of the tolerance in a few splits (hundreds on the
    // cells nearest the foot of a huge triangle's plane), 1e-13 in f64; in
    // f32 not much below the pdf's own rounding noise (~1e-7), which only
    // more splits would chase.
    let target = 0.01 * partition_tolerance(spec, precision);
    let mut worst: f64 = 0.0;
    let mut worst_error: f64 = 0.0;
    let mut total = 0.0;
    for (cell, &p) in partition.cells.iter().zip(&partition.probabilities) {
        let integral = cell.integrate_solid_angle(&pdf, target, 1 << 10);
        worst = worst.max((integral.value - p).abs() / p);
        worst_error = worst_error.max(integral.error / p);
        total += integral.value;
    }
    (worst, (total - 1.0).abs(), worst_error)
}

/// The tolerance, relative to each cell's probability, of ∫_cell pdf dω in
/// `precision`. The pdf is 1/Ω (spherical polygons) or 1/A converted to
/// solid angle (area samplers), and the cell probabilities are closed-form
/// solid angles or areas computed in f64, so their difference is the
/// rounding of the warp's Ω, or of its conversion, in its precision:
///
/// * Ω of a small polygon comes from vectors of length ~1 whose triple
///   product is ~Ω, so it carries ε·c/Ω relative error (c the polygon's
///   angular size), which [`conditioning`] bounds (base factor 16; c²/Ω
///   for f32's rounded vertices; 1 + ρ/d for a grazing rectangle);
/// * an area light's conversion d²/|cos θₗ| amplifies the rounding of the
///   point where the direction meets the plane by 1 + ρ/d as well (ρ the
///   farthest point of the light, d the plane's distance), times 16 for the
///   few operations of the intersection and the conversion;
///
/// and we allow 4 times that, plus 1e-11 for the partition itself (its 256
/// solid angles, each to a few ε, summed and normalised) and the quadrature
/// (1e-13). In f64 that is 1e-11 … 1.3e-9 over the cases here (measured:
/// at most 9e-12, on the tiny rectangle).
fn partition_tolerance(spec: &DirectionWarpSpec, precision: Precision) -> f64 {
    let grazing = |points: &[DVec3], normal: DVec3| {
        let rho = points.iter().map(|p| p.length()).fold(0.0, f64::max);
        1.0 + rho / normal.normalize().dot(points[0]).abs()
    };
    let area_factor = match spec {
        DirectionWarpSpec::TriangleArea {
            vertices: [a, b, c],
        } => Some(16.0 * grazing(&[*a, *b, *c], (*b - *a).cross(*c - *a))),
        DirectionWarpSpec::ParallelogramArea {
            corner,
            edge0,
            edge1,
        } => Some(
            16.0 * grazing(
                &[
                    *corner,
                    *corner + *edge0,
                    *corner + *edge1,
                    *corner + *edge0 + *edge1,
                ],
                edge0.cross(*edge1),
            ),
        ),
        DirectionWarpSpec::DiskArea {
            center,
            normal,
            radius,
        } => {
            Some(16.0 * (1.0 + (center.length() + radius) / normal.normalize().dot(*center).abs()))
        }
        _ => None,
    };
    let (f64_factor, f32_factor) = conditioning(spec);
    let factor = area_factor.unwrap_or(match precision {
        Precision::F64 => f64_factor,
        Precision::F32 => f32_factor,
    });
    4.0 * factor * eps(precision) + 1e-11
}

#[test]
fn partition_warp_pdfs_integrate_to_their_cell_probabilities() {
    let mut failures = Vec::new();
    for (case, precision) in runs() {
        if partition_for(&case.spec, precision).is_none() {
            continue;
        }
        let warp = case.spec.build(precision).unwrap();
        let (worst, total, error) = partition_deviation(&case.spec, precision, |w| warp.pdf(w));
        let tolerance = partition_tolerance(&case.spec, precision);
        eprintln!(
            "{:>24} {}: worst cell {worst:.2e}, |Σ − 1| {total:.2e}, quadrature {error:.1e}, tolerance {tolerance:.1e}",
            case.label,
            precision.name()
        );
        if worst + error > tolerance || total > tolerance {
            failures.push(format!(
                "{} {}: worst {worst:e}, total {total:e}, quadrature {error:e}, tolerance {tolerance:e}",
                case.label,
                precision.name()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn partition_check_rejects_wrong_pdfs() {
    let vertices = [
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    ];
    let area = DirectionWarpSpec::TriangleArea { vertices };
    let solid = DirectionWarpSpec::SphericalTriangle { vertices };
    let tolerance = partition_tolerance(&solid, Precision::F64);
    // The solid-angle pdf on the area partition: off by up to ~30 %.
    let warp = solid.build(Precision::F64).unwrap();
    let (worst, _, _) = partition_deviation(&area, Precision::F64, |w| warp.pdf(w));
    eprintln!("control solid angle on the area partition: worst cell {worst:.3e}");
    assert!(worst > tolerance);
    // The right pdf off by 1e-10 relative, below what the old 1e-4 check
    // on ∫pdf saw by six orders of magnitude.
    let (worst, total, _) =
        partition_deviation(&solid, Precision::F64, |w| warp.pdf(w) * (1.0 + 1e-10));
    eprintln!("control pdf × (1 + 1e-10): worst cell {worst:.3e}, |Σ − 1| {total:.3e}, tolerance {tolerance:.1e}");
    assert!(worst > tolerance && total > tolerance);
}
