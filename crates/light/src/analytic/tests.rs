//! Closed forms against independent numerical integration, hard cases and
//! consistency identities. Every tolerance is stated next to its assertion:
//! "reference" errors are those of the nested adaptive Gauss–Kronrod area
//! integrals in `test_support` (each G–K level is asked for |K − G| below
//! 1e-14 to 1e-15 of the integral; the resulting true error is below 1e-13
//! relative even across the clipping kink), "formula" errors a few ulps
//! times the conditioning stated in the module docs.

use super::test_support::raw;
use super::test_support::*;
use super::*;
use glam::{DMat3, DQuat, DVec3};
use std::f64::consts::{FRAC_PI_2, PI};

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn tilted(beta: f64) -> DVec3 {
    DVec3::new(beta.sin(), 0.0, beta.cos())
}

// ---------- caps and skies ----------

#[test]
fn sky_and_dome() {
    assert_eq!(sky_irradiance(1.0), Ok(PI));
    // Dome: (1 + cos β)π/2; β = π gives 0 exactly (|n + z|² = 0).
    for &b in &[0.0, 0.5, FRAC_PI_2, 2.5, PI] {
        let e = dome_irradiance(1.0, tilted(b), DVec3::Z).unwrap();
        let expect = PI * 0.5 * (1.0 + f64::cos(b));
        assert!((e - expect).abs() < 1e-15, "β {b}");
    }
}

/// Caps of every size and tilt, including caps crossing the horizon and
/// caps larger than a hemisphere, against the (z, φ) hemisphere integral.
/// Reference: 1-D adaptive G–K of 2z·Φ(z) whose Φ has square-root ends,
/// converged to < 2e-13 relative (checked by tightening); tolerance 5e-13.
#[test]
fn cap_against_hemisphere_integral() {
    for &gamma in &[0.05, 0.3, 1.0, FRAC_PI_2, 2.0, 3.0] {
        for &beta in &[0.0, 0.2, 0.9, 1.4, FRAC_PI_2, 1.7, 2.3, 3.0] {
            let (n, a) = (DVec3::Z, tilted(beta));
            let e = sky_cap_irradiance(1.0, n, a, gamma).unwrap();
            let reference = cap_hemisphere_form(n, a, gamma);
            if reference < 1e-300 {
                assert!(e < 1e-300, "γ {gamma} β {beta}: {e}");
                continue;
            }
            assert!(
                rel(e, reference) < 5e-13,
                "γ {gamma} β {beta}: {e} vs {reference}"
            );
        }
    }
}

/// P(β) − P(π − β) = π sin²γ cos β (the cap's part below the horizon is the
/// mirror cap's part above, with cos θ negated). Formula error a few ulps
/// of π sin²γ: tolerance 1e-15 absolute for sin²γ ≤ 1.
#[test]
fn cap_mirror_identity() {
    for &gamma in &[1e-3, 0.2, 0.8, 1.3] {
        for i in 0..=40 {
            let beta = PI * i as f64 / 40.0;
            let (sg, cg) = f64::sin_cos(gamma);
            let cb = f64::cos(beta);
            let up = cap_projected_solid_angle(cb, sg, cg);
            let down = cap_projected_solid_angle(-cb, sg, cg);
            assert!(
                (up - down - PI * sg * sg * cb).abs() < 2e-15,
                "γ {gamma} β {beta}"
            );
        }
    }
}

/// α = 1e-8 straddling the horizon: the flat-disk limit (tangent plane) is
/// P = (2/3)w³ + δ(γ² acos(−δ/γ) + δw), w = √(γ² − δ²), for a disk of
/// radius γ whose centre is at height δ; its relative correction is O(γ²)
/// = 1e-16. Formula error: a few ulps times the cancellation factor γ/h
/// (≤ 2 here). Tolerance 1e-13.
#[test]
fn tiny_cap_straddling_matches_series() {
    let g: f64 = 1e-8;
    for &frac in &[0.9, 0.5, 0.1, 0.0, -0.1, -0.5] {
        let delta = frac * g;
        // Axis at elevation δ: β = π/2 − δ, cos β = sin δ.
        let cb = delta.sin();
        let p = cap_projected_solid_angle(cb, g.sin(), g.cos());
        let w = ((g - delta) * (g + delta)).sqrt();
        let flat = 2.0 / 3.0 * w * w * w + delta * (g * g * (-delta / g).acos() + delta * w);
        assert!(rel(p, flat) < 1e-13, "δ/γ {frac}: {p} vs {flat}");
    }
    // Wholly above with α = 1e-8: π sin²α cos β exactly.
    let p = cap_projected_solid_angle(0.5, 1e-8f64.sin(), 1e-8f64.cos());
    assert!(rel(p, PI * 1e-16 * 0.5) < 4e-16);
}

// ---------- spheres ----------

/// Spheres above, straddling and below the horizon, against the (z, φ)
/// hemisphere integral of the cap the sphere subtends (reference < 2e-13,
/// split at its square-root points and smoothed); tolerance 5e-13.
#[test]
fn sphere_against_area_integral() {
    let c = DVec3::new(0.3, -0.2, 0.0);
    for &(d, r) in &[(3.0, 1.0), (1.5, 1.0), (10.0, 0.5)] {
        for &beta in &[0.0, 0.6, 1.2, 1.5, FRAC_PI_2, 1.7, 1.9] {
            let p = c - tilted(beta) * d;
            let n = DVec3::Z;
            // Rotate the geometry so that the sphere is at angle β from n:
            // the centre is along −(p − c) from p.
            let e = raw::sphere_irradiance(1.0, p, n, c, r).unwrap();
            let reference = cap_hemisphere_form(n, (c - p) / d, (r / d).asin());
            if reference == 0.0 {
                assert_eq!(e, 0.0);
                continue;
            }
            assert!(
                rel(e, reference) < 5e-13,
                "d {d} β {beta}: {e} vs {reference}"
            );
        }
    }
}

/// A sphere is a cap: the same numbers through both entry points, to a few
/// ulps (tolerance 1e-15 relative).
#[test]
fn sphere_equals_cap() {
    for &beta in &[0.1, 1.0, 1.5, 1.8] {
        let (d, r) = (2.0f64, 1.2f64);
        let p = DVec3::ZERO;
        let n = tilted(beta);
        let e = raw::sphere_irradiance(1.0, p, n, DVec3::Z * d, r).unwrap();
        let cap = sky_cap_irradiance(1.0, n, DVec3::Z, (r / d).asin()).unwrap();
        assert!(rel(e, cap) < 1e-15, "β {beta}: {e} vs {cap}");
    }
}

/// A sphere wholly above the horizon is exactly the point light of
/// intensity I = Lπr² at its centre, at any distance (E = Lπ(r/d)² cos β):
/// relative 1e-15 at d = 1e6 r and α = 1e-8.
#[test]
fn sphere_far_and_tiny_is_point_light() {
    for &(d, r) in &[(1e6, 1.0), (1.0, 1e-8)] {
        let n = tilted(0.7);
        let e = raw::sphere_irradiance(2.0, DVec3::ZERO, n, DVec3::Z * d, r).unwrap();
        let point = point_light_irradiance(2.0 * PI * r * r, DVec3::ZERO, n, DVec3::Z * d).unwrap();
        assert!(rel(e, point) < 1e-15, "d {d} r {r}: {e} vs {point}");
    }
}

/// A receiver almost touching the sphere (d = r(1 + 1e-10)) is under a cap
/// of half-angle ≈ π/2 − 1.4e-5: overhead it gets Lπ sin²α = Lπ/(1 + 1e-10)²;
/// tilted by 1 rad (straddling) against the hemisphere integral (5e-13).
#[test]
fn sphere_almost_touching() {
    let (r, d) = (1.0, 1.0 + 1e-10);
    let e = raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::Z, DVec3::Z * d, r).unwrap();
    assert!(rel(e, PI * (r / d) * (r / d)) < 1e-15);
    let n = tilted(1.0);
    let e = raw::sphere_irradiance(1.0, DVec3::ZERO, n, DVec3::Z * d, r).unwrap();
    let reference = cap_hemisphere_form(n, DVec3::Z, (r / d).asin());
    assert!(rel(e, reference) < 5e-13, "{e} vs {reference}");
}

// ---------- disks ----------

/// The parallel-offset closed form against the area integral (reference
/// < 1e-13), and the coaxial form (s = 0, a few ulps); tolerance 1e-12.
#[test]
fn disk_parallel_offset_against_area_integral() {
    for &(h, s, r) in &[
        (1.0, 0.0, 1.0),
        (0.5, 0.7, 1.0),
        (2.0, 3.0, 1.0),
        (0.3, 1.0, 1.0),
    ] {
        let e = disk_parallel_offset_irradiance(1.0, h, s, r).unwrap();
        let p = DVec3::new(-s, 0.0, -h);
        let reference = disk_area_form(p, DVec3::Z, DVec3::ZERO, DVec3::Z, r);
        assert!(rel(e, reference) < 1e-12, "h {h} s {s}: {e} vs {reference}");
    }
    assert!(
        rel(
            disk_parallel_offset_irradiance(1.0, 2.0, 0.0, 1.0).unwrap(),
            disk_coaxial_irradiance(1.0, 2.0, 1.0).unwrap()
        ) < 1e-15
    );
}

/// Tilted disks wholly above (closed form) and straddling the horizon
/// (contour quadrature), one- and two-sided, against the area integral
/// (reference < 1e-13 with the clipping kink); tolerance 1e-12.
#[test]
fn disk_tilted_against_area_integral() {
    let c = DVec3::new(0.2, 0.1, 1.0);
    for &(tilt, ny) in &[
        (0.0f64, 0.0),
        (0.4, 0.0),
        (1.0, 0.3),
        (1.3, 0.9),
        (2.0, 1.2),
    ] {
        let m = -DVec3::new(tilt.sin() * 0.6, tilt.sin() * 0.8, tilt.cos());
        for &beta in &[0.0, 0.5, 1.1, 1.45] {
            let n = DQuat::from_rotation_z(ny) * tilted(beta);
            let p = DVec3::ZERO;
            let two = raw::disk_irradiance(1.0, p, n, c, m, 0.8, Emission::TwoSided).unwrap();
            let reference = disk_area_form(p, n, c, m, 0.8);
            assert!(
                rel(two, reference) < 1e-12,
                "tilt {tilt} β {beta}: {two} vs {reference}"
            );
            // Two-sided = front + back (one of them 0).
            let front = raw::disk_irradiance(1.0, p, n, c, m, 0.8, Emission::OneSided).unwrap();
            let back = raw::disk_irradiance(1.0, p, n, c, -m, 0.8, Emission::OneSided).unwrap();
            assert_eq!(front + back, two);
            assert_eq!(front.min(back), 0.0);
        }
    }
}

/// Far disks (D = 1e6 R): E = L πR² cos θ cos θ′ / D² (1 + ε) with
/// |ε| ≤ 3R²/D² (second moment of the disk over the distance squared);
/// tolerance 5e-12. Coaxial, the exact form πR²/(R² + h²) to 1e-15.
#[test]
fn disk_far_is_point_light() {
    let d = 1e6;
    let e = raw::disk_irradiance(
        1.0,
        DVec3::ZERO,
        DVec3::Z,
        DVec3::Z * d,
        -DVec3::Z,
        1.0,
        Emission::OneSided,
    )
    .unwrap();
    assert!(rel(e, PI / (1.0 + d * d)) < 1e-15);
    let dir = DVec3::new(0.6, 0.0, 0.8);
    let m = -DVec3::new(0.0, 0.6, 0.8);
    let n = tilted(0.3);
    let e = raw::disk_irradiance(1.0, DVec3::ZERO, n, dir * d, m, 1.0, Emission::OneSided).unwrap();
    let point = PI * n.dot(dir) * (-m).dot(dir) / (d * d);
    assert!(rel(e, point) < 5e-12, "{e} vs {point}: {}", rel(e, point));
}

/// A receiver 1e-9 above the disk's interior (almost touching): the
/// parallel closed form gives Lπ(1 − O(h²)); the general function agrees to
/// 1e-15, and a tilted receiver agrees with the cap of half-angle π/2
/// (a dome) minus O(h) (tolerance 1e-8 from the disk's finite radius).
#[test]
fn disk_almost_touching() {
    let h = 1e-9;
    let e = raw::disk_irradiance(
        1.0,
        DVec3::new(0.3, 0.0, -h),
        DVec3::Z,
        DVec3::ZERO,
        -DVec3::Z,
        1.0,
        Emission::OneSided,
    )
    .unwrap();
    assert!(
        rel(
            e,
            disk_parallel_offset_irradiance(1.0, h, 0.3, 1.0).unwrap()
        ) < 1e-15
    );
    assert!(rel(e, PI) < 1e-15);
    let n = tilted(0.8);
    let e = raw::disk_irradiance(
        1.0,
        DVec3::new(0.3, 0.0, -h),
        n,
        DVec3::ZERO,
        -DVec3::Z,
        1.0,
        Emission::OneSided,
    )
    .unwrap();
    let dome = dome_irradiance(1.0, n, DVec3::Z).unwrap();
    assert!(rel(e, dome) < 1e-8, "{e} vs {dome}");
}

// ---------- polygons ----------

fn square(center: DVec3, half: f64, frame: DMat3) -> Vec<DVec3> {
    // Counter-clockwise about frame.z_axis (its front face).
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, y)| center + frame * DVec3::new(x * half, y * half, 0.0))
        .collect()
}

/// Polygon area form: ∫ over the square (nested adaptive G–K in its own
/// coordinates) of (n·d)|m·d|/r⁴ over the part with n·d > 0; the clip line
/// A + x bₓ + y b_y = 0 sets the inner limits and splits the outer interval
/// where it meets y = ±half, so each piece is smooth.
fn square_area_form(p: DVec3, n: DVec3, center: DVec3, half: f64, frame: DMat3) -> f64 {
    let m = frame.z_axis;
    let a0 = n.dot(center - p);
    let (bx, by) = (n.dot(frame.x_axis), n.dot(frame.y_axis));
    let mut cuts = vec![-half, half];
    if bx != 0.0 {
        for yb in [-half, half] {
            let x = (-a0 - by * yb) / bx;
            if x > -half && x < half {
                cuts.push(x);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    let inner = |x: f64| {
        let rest = a0 + bx * x;
        let (mut lo, mut hi) = (-half, half);
        if by > 0.0 {
            lo = lo.max(-rest / by);
        } else if by < 0.0 {
            hi = hi.min(rest / -by);
        } else if rest <= 0.0 {
            return 0.0;
        }
        if !(hi > lo) {
            return 0.0;
        }
        super::quadrature::integrate(
            |y: f64| {
                let d = center + frame * DVec3::new(x, y, 0.0) - p;
                let r2 = d.length_squared();
                n.dot(d).max(0.0) * m.dot(d).abs() / (r2 * r2)
            },
            lo,
            hi,
            1e-15,
        )
    };
    cuts.windows(2)
        .map(|w| super::quadrature::integrate(inner, w[0], w[1], 1e-14))
        .sum()
}

/// Squares above and straddling the horizon, tilted, against the area
/// integral (reference < 1e-13); tolerance 1e-12.
#[test]
fn polygon_against_area_integral() {
    for &(tilt, beta) in &[(0.0, 0.0), (0.5, 0.3), (1.2, 1.0), (2.6, 1.4), (0.3, 1.55)] {
        let frame = DMat3::from_quat(DQuat::from_rotation_x(PI + tilt));
        let center = DVec3::new(0.3, 0.2, 1.0);
        let sq = square(center, 0.6, frame);
        let n = tilted(beta);
        let e = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &sq, Emission::TwoSided).unwrap();
        let reference = square_area_form(DVec3::ZERO, n, center, 0.6, frame);
        assert!(
            rel(e, reference) < 1e-12,
            "tilt {tilt} β {beta}: {e} vs {reference}"
        );
        let front = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &sq, Emission::OneSided).unwrap();
        let mut rev = sq.clone();
        rev.reverse();
        let back = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &rev, Emission::OneSided).unwrap();
        assert_eq!(front.min(back), 0.0);
        // The same sum over the reversed edges, whose rounding differs by
        // a few ulps: tolerance 1e-15.
        assert!(rel(front.max(back), e) < 1e-15, "tilt {tilt} β {beta}");
    }
}

/// A rectangle equals its two triangles (each clipped on its own); a few
/// ulps of the result: tolerance 1e-14.
#[test]
fn rectangle_is_two_triangles() {
    let frame = DMat3::from_quat(DQuat::from_rotation_x(PI + 0.7));
    let sq = square(DVec3::new(0.1, 0.4, 0.8), 0.5, frame);
    for &beta in &[0.0, 0.8, 1.3] {
        let n = tilted(beta);
        let whole = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &sq, Emission::OneSided).unwrap();
        let t1 = raw::polygon_irradiance(
            1.0,
            DVec3::ZERO,
            n,
            &[sq[0], sq[1], sq[2]],
            Emission::OneSided,
        )
        .unwrap();
        let t2 = raw::polygon_irradiance(
            1.0,
            DVec3::ZERO,
            n,
            &[sq[0], sq[2], sq[3]],
            Emission::OneSided,
        )
        .unwrap();
        assert!(rel(t1 + t2, whole) < 1e-14, "β {beta}");
    }
}

/// A regular 4096-gon inscribed in a disk lies between the disks of radius
/// R cos(π/N) and R, so (for a receiver on the axis, where E is increasing
/// in the radius) E_disk(R cos π/N) ≤ E_poly ≤ E_disk(R); the gap is
/// ≈ (π/N)² E ≈ 5.9e-7 E. Also tilted: |E_poly/E_disk − 1| ≤ 2(π/N)².
#[test]
fn polygon_4096_approximates_disk() {
    let nv = 4096;
    let verts: Vec<DVec3> = (0..nv)
        .map(|i| {
            let t = 2.0 * PI * i as f64 / nv as f64;
            DVec3::new(t.cos(), -t.sin(), 1.5)
        })
        .collect();
    let e =
        raw::polygon_irradiance(1.0, DVec3::ZERO, DVec3::Z, &verts, Emission::OneSided).unwrap();
    let inner = disk_coaxial_irradiance(1.0, 1.5, (PI / nv as f64).cos()).unwrap();
    let outer = disk_coaxial_irradiance(1.0, 1.5, 1.0).unwrap();
    assert!(inner <= e && e <= outer, "{inner} {e} {outer}");
    let bound = 2.0 * (PI / nv as f64).powi(2);
    for &beta in &[0.6, 1.2, 1.5] {
        let n = tilted(beta);
        let ep = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &verts, Emission::OneSided).unwrap();
        let ed = raw::disk_irradiance(
            1.0,
            DVec3::ZERO,
            n,
            DVec3::Z * 1.5,
            -DVec3::Z,
            1.0,
            Emission::OneSided,
        )
        .unwrap();
        assert!(rel(ep, ed) < bound, "β {beta}: {}", rel(ep, ed));
    }
}

/// A polygon 1e6 away (size 1): the point-light limit, whose relative
/// correction is O(ℓ²/D²) = 1e-12 (the square's second moment over the
/// distance squared, a few times that at most); the centred sum itself is
/// exact to a few ulps: tolerance 1e-11.
#[test]
fn polygon_far_is_point_light() {
    let d = 1e6;
    let frame = DMat3::from_quat(DQuat::from_rotation_x(PI));
    let sq = square(DVec3::Z * d, 0.5, frame);
    let n = tilted(0.4);
    let e = raw::polygon_irradiance(1.0, DVec3::ZERO, n, &sq, Emission::OneSided).unwrap();
    let point = n.z / (d * d);
    assert!(rel(e, point) < 1e-11, "{}", rel(e, point));
}

// ---------- invariance and errors ----------

/// Rotating and translating the whole scene leaves E unchanged to 1e-13.
#[test]
fn rigid_motion_invariance() {
    let q = DQuat::from_euler(glam::EulerRot::ZYX, 0.7, -1.1, 0.4);
    let shift = DVec3::new(3.0, -2.0, 5.0);
    let mv = |v: DVec3| q * v + shift;
    let (p, n) = (DVec3::ZERO, tilted(1.2));
    let c = DVec3::new(0.3, 0.1, 1.0);
    let m = -tilted(0.9);
    let sphere0 = raw::sphere_irradiance(1.0, p, n, c, 0.7).unwrap();
    let sphere1 = raw::sphere_irradiance(1.0, mv(p), q * n, mv(c), 0.7).unwrap();
    assert!(rel(sphere1, sphere0) < 1e-13);
    let disk0 = raw::disk_irradiance(1.0, p, n, c, m, 0.8, Emission::TwoSided).unwrap();
    let disk1 =
        raw::disk_irradiance(1.0, mv(p), q * n, mv(c), q * m, 0.8, Emission::TwoSided).unwrap();
    assert!(rel(disk1, disk0) < 1e-13);
    let frame = DMat3::from_quat(DQuat::from_rotation_x(PI + 0.5));
    let sq = square(c, 0.6, frame);
    let sq1: Vec<DVec3> = sq.iter().map(|&v| mv(v)).collect();
    let poly0 = raw::polygon_irradiance(1.0, p, n, &sq, Emission::TwoSided).unwrap();
    let poly1 = raw::polygon_irradiance(1.0, mv(p), q * n, &sq1, Emission::TwoSided).unwrap();
    assert!(rel(poly1, poly0) < 1e-13);
    let cap0 = sky_cap_irradiance(1.0, n, tilted(0.2), 1.0).unwrap();
    let cap1 = sky_cap_irradiance(1.0, q * n, q * tilted(0.2), 1.0).unwrap();
    assert!(rel(cap1, cap0) < 1e-13);
}

#[test]
fn point_and_directional() {
    let e = point_light_irradiance(10.0, DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 3.0, 4.0)).unwrap();
    assert!((e - 10.0 * 0.8 / 25.0).abs() < 1e-15);
    assert_eq!(
        point_light_irradiance(10.0, DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 3.0, -4.0)).unwrap(),
        0.0
    );
    let e = directional_light_irradiance(1000.0, DVec3::Z, tilted(1.0)).unwrap();
    assert!((e - 1000.0 * f64::cos(1.0)).abs() < 1e-12);
    assert_eq!(
        directional_light_irradiance(1000.0, DVec3::Z, -DVec3::Z).unwrap(),
        0.0
    );
}

#[test]
fn bad_input_is_an_error() {
    use lambert_geometry::GeometryError;
    assert!(matches!(
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::Z, DVec3::Z * 0.5, 1.0),
        Err(AnalyticError::ReceiverInsideLight { .. })
    ));
    // A normal of any non-zero length is normalised, as everywhere.
    assert_eq!(
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::Z * 2.0, DVec3::Z * 5.0, 1.0),
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::Z, DVec3::Z * 5.0, 1.0)
    );
    assert!(matches!(
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::ZERO, DVec3::Z * 5.0, 1.0),
        Err(AnalyticError::Input(GeometryError::ZeroVector {
            field: "normal"
        }))
    ));
    assert!(matches!(
        raw::disk_irradiance(
            1.0,
            DVec3::ZERO,
            DVec3::Z,
            DVec3::Z,
            DVec3::Z,
            -1.0,
            Emission::OneSided
        ),
        Err(AnalyticError::Input(GeometryError::NotPositive {
            field: "radius",
            ..
        }))
    ));
    let bent = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.1), DVec3::Y];
    assert!(matches!(
        raw::polygon_irradiance(1.0, DVec3::Z, DVec3::Z, &bent, Emission::OneSided),
        Err(AnalyticError::Input(GeometryError::Shape {
            field: "vertices",
            ..
        }))
    ));
    let concave = [
        DVec3::ZERO,
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(1.0, 0.3, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
    ];
    assert!(matches!(
        raw::polygon_irradiance(1.0, DVec3::Z, DVec3::Z, &concave, Emission::OneSided),
        Err(AnalyticError::Input(GeometryError::Shape {
            field: "vertices",
            ..
        }))
    ));
    assert!(matches!(
        point_light_irradiance(f64::NAN, DVec3::ZERO, DVec3::Z, DVec3::Z),
        Err(AnalyticError::Input(GeometryError::NotFinite { .. }))
    ));
    assert!(matches!(
        sky_cap_irradiance(1.0, DVec3::Z, DVec3::Z, 4.0),
        Err(AnalyticError::Input(GeometryError::OutOfRange {
            field: "half_angle",
            ..
        }))
    ));
}

/// The disk's solid angle (`lambert-geometry`) against an independent 2-D
/// integration of h/r³ over the disk (Gauss–Legendre in polar coordinates
/// about the centre, composite over 64 × 64 panels of 8 × 8 points): that
/// reference has a relative error < 1e-13 for these well-separated cases
/// (checked by halving the panels), so the tolerance is 1e-12.
#[test]
fn disk_solid_angle_matches_area_integral() {
    for &(h, s, r) in &[
        (1.0, 0.0, 1.0),
        (0.7, 0.3, 1.0),
        (1.5, 2.5, 1.0),
        (0.5, 1.2, 1.0),
        (3.0, 1.0, 1.0),
    ] {
        let reference = crate::analytic::test_support::integrate_disk_polar(r, |x, y| {
            let d2 = (x - s) * (x - s) + y * y + h * h;
            h / (d2 * d2.sqrt())
        });
        let omega = lambert_geometry::f64::disk_solid_angle_hs(h, s, r);
        assert!(
            (omega / reference - 1.0).abs() < 1e-12,
            "h {h} s {s}: {omega} vs {reference}"
        );
    }
}
