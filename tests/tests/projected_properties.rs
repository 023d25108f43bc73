//! Deterministic properties of the projected-solid-angle samplers (caps,
//! spheres, polygons) and of solid-angle sampling of disks, on every hard
//! case, in both precisions: u on the square's edges gives finite unit
//! directions of positive density; the density a sample reports is the one
//! `pdf` returns for it; samples lie in the support (tested by plain
//! geometry, with the samplers' rounding band); `invert` undoes `sample`.

use glam::DVec2;
use lambert_tests::edge_values;
use lambert_tests::projected::{angular_size, build, cases, in_support, Shape};
use lambert_validate::catalog::Precision;

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
    use lambert_geometry::{f32 as g32, f64 as g64};
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
                let shape = g64::ConvexPolygon::new(vertices.clone()).unwrap();
                let s = s64::ProjectedPolygon::new(*p, *n, &shape).unwrap();
                let v32: Vec<glam::Vec3> = vertices.iter().map(|v| v.as_vec3()).collect();
                let t = g32::ConvexPolygon::new(v32)
                    .ok()
                    .and_then(|q| s32::ProjectedPolygon::new(p.as_vec3(), n.as_vec3(), &q).ok());
                for &u in &us {
                    polygon[0] = polygon[0].max(s.newton_steps(u));
                    if let Some(t) = &t {
                        polygon[1] = polygon[1].max(t.newton_steps(u.as_vec2()));
                    }
                }
            }
            Shape::Disk { p, c, normal, r } => {
                let s = s64::DiskSolidAngle::new(*p, &g64::Disk::new(*c, *normal, *r).unwrap())
                    .unwrap();
                let t = g32::Disk::new(c.as_vec3(), normal.as_vec3(), *r as f32)
                    .ok()
                    .and_then(|d| s32::DiskSolidAngle::new(p.as_vec3(), &d).ok());
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

/// Bad input is a clear error naming the field (or what is degenerate),
/// never a panic; a NaN direction has density 0, not NaN. Shapes are
/// validated by the geometry crate (its errors name their fields); the
/// samplers check what depends on the shading point.
#[test]
fn bad_input_is_a_clear_error() {
    use glam::DVec3;
    use lambert_geometry::f64::{ConvexPolygon, Disk, Sphere};
    use lambert_sampling::f64::{DiskSolidAngle, ProjectedCap, ProjectedPolygon, ProjectedSphere};
    use lambert_sampling::SamplingError;
    let nan = DVec3::new(f64::NAN, 0.0, 1.0);
    let (o, z) = (DVec3::ZERO, DVec3::Z);
    let field = |e: SamplingError| match e {
        SamplingError::NotFinite { field, .. }
        | SamplingError::OutOfRange { field, .. }
        | SamplingError::ZeroVector { field } => field.to_string(),
        SamplingError::Degenerate { what } => what.to_string(),
        SamplingError::InsideLight { .. } => "inside".to_string(),
        SamplingError::Geometry(g) => g.field().to_string(),
        SamplingError::TooManyVertices { .. } => "vertices".to_string(),
    };
    // Caps.
    assert_eq!(field(ProjectedCap::new(nan, 0.1).unwrap_err()), "axis");
    assert_eq!(
        field(ProjectedCap::new(DVec3::ZERO, 0.1).unwrap_err()),
        "axis"
    );
    for h in [0.0, 2.5, f64::NAN] {
        assert_eq!(
            field(ProjectedCap::new(z, h).unwrap_err()),
            "one_minus_cos_theta_max"
        );
    }
    for theta in [0.0, 3.5, f64::INFINITY] {
        assert_eq!(
            field(ProjectedCap::from_theta_max(z, theta).unwrap_err()),
            "theta_max"
        );
    }
    assert!(field(ProjectedCap::new(-z, 0.1).unwrap_err()).contains("below the receiver's horizon"));
    // Spheres.
    let c = DVec3::new(0.0, 0.0, 3.0);
    let sphere = Sphere::new(c, 1.0).unwrap();
    assert_eq!(
        field(ProjectedSphere::new(nan, z, &sphere).unwrap_err()),
        "reference"
    );
    assert_eq!(
        field(ProjectedSphere::new(o, DVec3::ZERO, &sphere).unwrap_err()),
        "normal"
    );
    assert_eq!(
        field(ProjectedSphere::new(o, nan, &sphere).unwrap_err()),
        "normal"
    );
    assert_eq!(
        field(ProjectedSphere::new(o, z, &Sphere::new(c, 3.0).unwrap()).unwrap_err()),
        "inside"
    );
    let below = Sphere::new(-c, 1.0).unwrap();
    assert!(field(ProjectedSphere::new(o, z, &below).unwrap_err()).contains("below"));
    // Polygons.
    let tri = ConvexPolygon::new(vec![
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
    ])
    .unwrap();
    let nonagon = ConvexPolygon::new(
        (0..9)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 9.0;
                DVec3::new(a.cos(), a.sin(), 1.0)
            })
            .collect(),
    )
    .unwrap();
    assert_eq!(
        field(ProjectedPolygon::new(o, z, &nonagon).unwrap_err()),
        "polygon.vertices().len()"
    );
    assert_eq!(
        field(ProjectedPolygon::new(nan, z, &tri).unwrap_err()),
        "reference"
    );
    assert_eq!(
        field(ProjectedPolygon::new(o, DVec3::ZERO, &tri).unwrap_err()),
        "normal"
    );
    assert!(field(ProjectedPolygon::new(o, -z, &tri).unwrap_err()).contains("below"));
    let edge_on = ConvexPolygon::new(vec![
        DVec3::new(1.0, 0.0, 0.5),
        DVec3::new(2.0, 0.0, 1.0),
        DVec3::new(2.0, 1.0, 1.0),
    ])
    .unwrap();
    let on_its_plane = DVec3::new(0.0, 5.0, 0.0);
    assert!(ProjectedPolygon::new(on_its_plane, z, &edge_on).is_err());
    assert!(ProjectedPolygon::new(DVec3::new(0.0, 0.0, 1.0), z, &tri).is_err());
    // Disks.
    let disk = Disk::new(c, z, 1.0).unwrap();
    assert_eq!(
        field(DiskSolidAngle::new(nan, &disk).unwrap_err()),
        "reference"
    );
    let in_plane = Disk::new(DVec3::new(3.0, 0.0, 0.0), z, 1.0).unwrap();
    assert!(field(DiskSolidAngle::new(o, &in_plane).unwrap_err()).contains("edge-on"));
    // A NaN direction has density 0 everywhere.
    let cap = ProjectedCap::new(z, 0.1).unwrap();
    let sphere = ProjectedSphere::new(o, z, &sphere).unwrap();
    let poly = ProjectedPolygon::new(o, z, &tri).unwrap();
    let disk = DiskSolidAngle::new(o, &disk).unwrap();
    for pdf in [cap.pdf(nan), sphere.pdf(nan), poly.pdf(nan), disk.pdf(nan)] {
        assert_eq!(pdf, 0.0);
    }
}
