//! Deterministic properties of every direction warp, in both precisions:
//! unit, finite samples of positive density even for u on the square's edge;
//! the density the sampler reports equals its pdf function; the inverse maps
//! samples back to u; f32 agrees with f64 on hard cases.

use glam::DVec2;
use lambert_tests::{angular_scale, conditioning, direction_cases, edge_values};
use lambert_validate::catalog::{DirectionWarpSpec, Precision};

fn eps(p: Precision) -> f64 {
    match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    }
}

#[test]
fn edge_samples_are_finite_unit_vectors_with_positive_pdf() {
    let edges = edge_values();
    for case in direction_cases() {
        for precision in Precision::ALL {
            let warp = case.spec.build(precision).unwrap();
            for &a in &edges {
                for &b in &edges {
                    let s = warp.sample(DVec2::new(a, b));
                    let w = s.direction;
                    assert!(
                        w.is_finite(),
                        "{} {:?}: u=({a},{b}) gave {w}",
                        case.label,
                        precision
                    );
                    // A unit vector to the precision's rounding (a few ulps
                    // from the sqrt and the products that build it).
                    assert!(
                        (w.length() - 1.0).abs() <= 8.0 * eps(precision),
                        "{} {:?}: |w| = {}",
                        case.label,
                        precision,
                        w.length()
                    );
                    assert!(
                        s.pdf > 0.0 && s.pdf.is_finite(),
                        "{} {:?}: u=({a},{b}) pdf {}",
                        case.label,
                        precision,
                        s.pdf
                    );
                    // The pdf function agrees with what the sampler reported:
                    // exactly where both are the same expression; for area
                    // sampling, pdf(w) re-intersects the plane and converts
                    // again, each step a few roundings: 64ε relative.
                    let again = warp.pdf(w);
                    if is_area_sampled(&case.spec) {
                        assert!(
                            (again - s.pdf).abs() <= 64.0 * eps(precision) * s.pdf,
                            "{} {:?}: u=({a},{b}) pdf(w) {again} vs sampled {}",
                            case.label,
                            precision,
                            s.pdf
                        );
                    } else {
                        assert_eq!(
                            again, s.pdf,
                            "{} {:?}: u=({a},{b}) w={w}",
                            case.label, precision
                        );
                    }
                }
            }
        }
    }
}

fn is_area_sampled(spec: &DirectionWarpSpec) -> bool {
    matches!(
        spec,
        DirectionWarpSpec::TriangleArea { .. }
            | DirectionWarpSpec::DiskArea { .. }
            | DirectionWarpSpec::ParallelogramArea { .. }
    )
}

#[test]
fn invert_undoes_sample_on_a_grid() {
    let n = 40;
    for case in direction_cases() {
        for precision in Precision::ALL {
            let warp = case.spec.build(precision).unwrap();
            // Tolerance: the inverse composes a handful of correctly rounded
            // operations of condition ≤ 2 on the interior grid (measured
            // worst: 3ε), so 16ε; a
            // support of angular radius s off the coordinate axes is located
            // only to ε/s (components of a unit vector carry absolute error ε).
            let tol =
                16.0 * eps(precision) * conditioning(&case.spec).0 / angular_scale(&case.spec);
            let mut worst: f64 = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                    let back = warp.invert(warp.sample(u).direction);
                    let d0 = (back.x - u.x).abs();
                    // u₁ is an azimuth: compare on the circle.
                    let d1 = (back.y - u.y).abs();
                    let d1 = d1.min(1.0 - d1);
                    worst = worst.max(d0).max(d1);
                }
            }
            eprintln!(
                "{:>24} {:?}: worst {worst:.2e} tol {tol:.2e}",
                case.label, precision
            );
            assert!(
                worst <= tol,
                "{} {:?}: worst |invert(sample(u)) - u| = {worst:e} > {tol:e}",
                case.label,
                precision
            );
        }
    }
}

#[test]
fn f32_agrees_with_f64_on_every_case() {
    let n = 32;
    for case in direction_cases() {
        let w64 = case.spec.build(Precision::F64).unwrap();
        let w32 = case.spec.build(Precision::F32).unwrap();
        // Tolerance: f32 rounding of the parameters and of ~10 operations
        // moves a direction by ≲ 16 ε₃₂ in absolute terms; lateral offsets
        // from a ±z axis are computed in relative precision (the robust
        // 1 − cos θ forms), so there the error is ≲ 16 ε₃₂ relative to the
        // support's angular radius, which we also check.
        let tol = 16.0 * f32::EPSILON as f64 * conditioning(&case.spec).1;
        let cap = case.spec.bounding_cap();
        for i in 0..n {
            for j in 0..n {
                let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let a = w64.sample(u).direction;
                let b = w32.sample(u).direction;
                assert!(
                    (a - b).length() <= tol,
                    "{}: u={u} f64 {a} f32 {b}",
                    case.label
                );
                if let Some(cap) = cap {
                    if cap.axis == glam::DVec3::Z {
                        let lateral = a.truncate().length().max(f64::MIN_POSITIVE);
                        let err = (a.truncate() - b.truncate()).length();
                        assert!(
                            err <= tol * lateral,
                            "{}: u={u} lateral error {err:e} vs offset {lateral:e}",
                            case.label
                        );
                    }
                }
            }
        }
    }
}
