//! Deterministic properties of the projected-solid-angle samplers (caps,
//! spheres, polygons) and of solid-angle sampling of disks, on every hard
//! case, in both precisions: u on the square's edges gives finite unit
//! directions of positive density; the density a sample reports is the one
//! `pdf` returns for it; samples lie in the support (tested by plain
//! geometry, with the samplers' rounding band); `invert` undoes `sample`.

use glam::DVec2;
use lambert_sampling::catalog::Precision;
use lambert_tests::edge_values;
use lambert_tests::projected::{angular_size, build, cases, in_support, Shape};

fn eps(p: Precision) -> f64 {
    match p {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    }
}

#[test]
fn edge_samples_are_finite_unit_directions_with_the_pdf_they_report() {
    let edges = edge_values();
    for case in cases() {
        for precision in Precision::ALL {
            let warp = match build(&case.shape, precision) {
                Ok(w) => w,
                // Every case is valid in f64; in f32 a light below f32's
                // resolution may round to a degenerate one, a clear error.
                Err(e) => {
                    assert!(precision == Precision::F32, "{}: {e}", case.label);
                    continue;
                }
            };
            for &a in &edges {
                for &b in &edges {
                    let u = DVec2::new(a, b);
                    let s = warp.sample(u);
                    let w = s.direction;
                    let what = format!("{} {} u={u}", case.label, precision.name());
                    assert!(w.is_finite(), "{what}: {w}");
                    // A unit vector to a few roundings of its components.
                    assert!(
                        (w.length() - 1.0).abs() <= 8.0 * eps(precision),
                        "{what}: |w| = {}",
                        w.length()
                    );
                    assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{what}: pdf {}", s.pdf);
                    // The same expression on the same vector: exactly equal.
                    assert_eq!(warp.pdf(w), s.pdf, "{what}: w = {w}");
                }
            }
        }
    }
}

/// Samples on an interior grid lie in the support, checked by geometry
/// that shares no code with the samplers (angle to the cap's axis; the ray
/// hitting the polygon or the disk) — up to the samplers' documented band
/// of a few tens of ε (rad) beyond the boundary, which the check allows by
/// also accepting samples that a 64ε-rotated copy would put inside.
#[test]
fn samples_lie_in_the_support() {
    let n = 32;
    for case in cases() {
        let warp = build(&case.shape, Precision::F64).unwrap();
        let mut outside = 0;
        for i in 0..n {
            for j in 0..n {
                let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                let w = warp.sample(u).direction;
                if !in_support(&case.shape, w) {
                    // Nudge toward the support's interior by 64ε (absolute):
                    // toward the axis for caps/spheres, toward the sample of
                    // u = ½ otherwise.
                    let center = warp.sample(DVec2::splat(0.5)).direction;
                    let nudged =
                        (w + (center - w).normalize_or_zero() * 64.0 * f64::EPSILON).normalize();
                    if !in_support(&case.shape, nudged) {
                        outside += 1;
                    }
                }
            }
        }
        assert_eq!(
            outside, 0,
            "{}: {outside} samples outside the support",
            case.label
        );
    }
}

/// invert(sample(u)) = u on an interior grid. Tolerance: the inverse is a
/// handful of well-conditioned operations (measured ≤ 32ε for lights at the
/// zenith or of size ~1), and a direction off the coordinate axes carries an
/// absolute error of a few ε, which is ε/s of a light of angular size s.
/// So |Δu| ≤ 64 ε (1 + 1/s); for the grazing triangle and the sliver (whose
/// sectors are thin in one direction, so u₀ moves by ε/thickness) 32 times
/// that (measured: 5× and 13×). Lights below f32's resolution are checked in
/// f64 only.
#[test]
fn invert_undoes_sample() {
    let n = 24;
    for case in cases() {
        for precision in Precision::ALL {
            if precision == Precision::F32 && !case.f32_resolvable {
                continue;
            }
            let Ok(warp) = build(&case.shape, precision) else {
                continue;
            };
            let aspect = match &case.shape {
                Shape::Polygon { .. }
                    if case.label.contains("grazing") || case.label.contains("sliver") =>
                {
                    32.0
                }
                _ => 1.0,
            };
            let tol = 64.0 * eps(precision) * (1.0 + 1.0 / angular_size(&case.shape)) * aspect;
            let mut worst: f64 = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                    let back = warp.invert(warp.sample(u).direction);
                    worst = worst.max((back - u).abs().max_element());
                }
            }
            eprintln!(
                "{:>40} {}: worst {worst:.2e} tol {tol:.2e}",
                case.label,
                precision.name()
            );
            assert!(
                worst <= tol,
                "{} {}: |invert(sample(u)) − u| = {worst:e} > {tol:e}",
                case.label,
                precision.name()
            );
        }
    }
}

/// The iteration counts the samplers' docs state: Newton steps per sample of
/// a non-central polygon sector and of the disk's sector area, worst over
/// every hard case on a 64 × 64 grid of u plus the square's edges.
#[test]
fn iteration_counts_are_as_documented() {
    use lambert_sampling::{f32 as s32, f64 as s64};
    let mut us: Vec<DVec2> = Vec::new();
    for i in 0..64 {
        for j in 0..64 {
            us.push(DVec2::new((i as f64 + 0.5) / 64.0, (j as f64 + 0.5) / 64.0));
        }
    }
    for &a in &edge_values() {
        for &b in &edge_values() {
            us.push(DVec2::new(a, b));
        }
    }
    let (mut polygon, mut disk) = ([0usize; 2], [0usize; 2]);
    for case in cases() {
        match &case.shape {
            Shape::Polygon { p, n, vertices } => {
                let s = s64::ProjectedPolygon::new(*p, *n, vertices).unwrap();
                let v32: Vec<glam::Vec3> = vertices.iter().map(|v| v.as_vec3()).collect();
                let t = s32::ProjectedPolygon::new(p.as_vec3(), n.as_vec3(), &v32).ok();
                for &u in &us {
                    polygon[0] = polygon[0].max(s.newton_steps(u));
                    if let Some(t) = &t {
                        polygon[1] = polygon[1].max(t.newton_steps(u.as_vec2()));
                    }
                }
            }
            Shape::Disk { p, c, normal, r } => {
                let s = s64::DiskSolidAngle::new(*p, *c, *normal, *r).unwrap();
                let t =
                    s32::DiskSolidAngle::new(p.as_vec3(), c.as_vec3(), normal.as_vec3(), *r as f32)
                        .ok();
                for &u in &us {
                    disk[0] = disk[0].max(s.newton_steps(u));
                    if let Some(t) = &t {
                        disk[1] = disk[1].max(t.newton_steps(u.as_vec2()));
                    }
                }
            }
            _ => {}
        }
    }
    eprintln!(
        "Newton steps, worst: polygon f64 {} f32 {}; disk f64 {} f32 {}",
        polygon[0], polygon[1], disk[0], disk[1]
    );
    assert!(
        polygon[0] <= 7 && polygon[1] <= 8,
        "polygon steps {polygon:?}"
    );
    assert!(disk[0] <= 3 && disk[1] <= 2, "disk steps {disk:?}");
}
