//! The hard classes of configurations, swept, against the 1024-bit oracle.
//!
//! Each class has a generator of configurations (deterministic: fixed
//! orientations and magnitudes) and the relative error of the f64 closed
//! form against the oracle is measured on every one. `report_worst_errors`
//! (ignored; run with `--ignored --nocapture`) prints the worst error per
//! class; the other tests assert the documented bound per class.

use super::oracle;
use super::test_support::raw;
use super::test_support::{cap_hemisphere_form, disk_area_form};
use super::*;
use glam::{DQuat, DVec3};
use std::f64::consts::{FRAC_PI_2, PI};

/// One configuration of a class: a label and (library value, oracle value).
pub(crate) struct Case {
    pub key: String,
    pub label: String,
    pub value: Result<f64, AnalyticError>,
    pub exact: oracle::B,
}

impl Case {
    fn rel(&self) -> f64 {
        match &self.value {
            Ok(v) => self.exact.rel_err(*v),
            Err(_) => f64::INFINITY,
        }
    }
}

/// Fixed rotations used to tilt whole configurations.
fn rotations() -> Vec<DQuat> {
    vec![
        DQuat::IDENTITY,
        DQuat::from_euler(glam::EulerRot::ZYX, 0.7, -1.1, 0.4),
        DQuat::from_euler(glam::EulerRot::ZYX, -2.3, 0.35, 1.9),
    ]
}

fn decades(lo: i32, hi: i32) -> impl Iterator<Item = f64> {
    (lo..=hi).map(|k| 10f64.powi(k))
}

/// A convex polygon (square, triangle or pentagon) of size ≈ 1 in the
/// plane ⊥ `normal` around `center`, counter-clockwise about `normal`.
fn polygon_around(center: DVec3, normal: DVec3, shape: usize, spin: f64) -> Vec<DVec3> {
    let (u, v) = normal.any_orthonormal_pair();
    let k = [4, 3, 5][shape % 3];
    (0..k)
        .map(|i| {
            let t = spin + 2.0 * PI * i as f64 / k as f64 + 0.1 * (i % 2) as f64;
            center + (u * t.cos() + v * t.sin()) * 0.5
        })
        .collect()
}

/// Polygons of size ≈ 1 at distance D = 1 … 1e12 above the receiver's
/// horizon (elevation 0.3 … 1.2 rad), off the origin. The vertices must be
/// exactly coplanar in f64 (a rotated square 1e8 away is not, to 1e-9 of
/// its size): squares and pentagons lie in the plane z = const, and
/// triangles (always planar) take any orientation; the receiver's
/// direction and normal are turned instead.
pub(crate) fn far_polygons() -> Vec<Case> {
    let mut out = vec![];
    for (ri, q) in rotations().into_iter().enumerate() {
        for d in decades(0, 12) {
            for (si, &elev) in [0.3f64, 0.8, 1.2].iter().enumerate() {
                let center = DVec3::new(1.3, -0.4, 2.0);
                let verts = if si == 1 {
                    let facing = (q * DVec3::new(0.2, -0.3, 0.9)).normalize();
                    let mut t = polygon_around(center, facing, 1, 0.3);
                    t.truncate(3);
                    t
                } else {
                    polygon_around(center, DVec3::Z, si, 0.3 * ri as f64)
                };
                // The receiver sees the polygon's centre at elevation
                // `elev`, from distance ≈ 2D below it.
                let n = q * DVec3::Z;
                let n = if n.z < 0.0 { -n } else { n };
                let (u, _) = n.any_orthonormal_pair();
                let dir = u * elev.cos() + n * elev.sin();
                let p = center - dir * (2.0 * d);
                out.push(Case {
                    key: format!("D={d:e}"),
                    label: format!("far polygon D={d:e} rot {ri} elev {elev}"),
                    value: raw::polygon_irradiance(1.0, p, n, &verts, Emission::TwoSided),
                    exact: oracle::polygon(1.0, p, n, &verts, true),
                });
            }
        }
    }
    out
}

/// A rectangle 1 × 2 (size 1 … 2) standing across the receiver's plane,
/// only a height h = 1e-3 … 1e-12 of it above the plane, at distance 1.5
/// from the receiver, tilted and turned; heights measured along n.
pub(crate) fn sliver_polygons() -> Vec<Case> {
    let mut out = vec![];
    let p = DVec3::new(0.25, -0.5, 1.0);
    for (ri, q) in rotations().into_iter().enumerate() {
        for h in decades(-12, -3) {
            for &(lean, turn) in &[(0.0f64, 0.0f64), (0.5, 0.8), (-0.7, 2.0)] {
                let n = q * DVec3::Z;
                // In the local frame (n = z): a rectangle through the
                // point (1.5 cos turn, 1.5 sin turn, ·), its long side along
                // the horizontal direction w, leaning by `lean` from vertical.
                let w = DVec3::new(-turn.sin(), turn.cos(), 0.0);
                let up = DVec3::new(turn.cos() * lean.sin(), turn.sin() * lean.sin(), lean.cos());
                let base = DVec3::new(1.5 * turn.cos(), 1.5 * turn.sin(), 0.0);
                // Top edge at height h: base + up·s with s·up.z = h.
                let top = h / up.z;
                let bottom = top - 1.0;
                let local = [
                    base + up * bottom - w,
                    base + up * bottom + w,
                    base + up * top + w,
                    base + up * top - w,
                ];
                let verts: Vec<DVec3> = local.iter().map(|&x| p + q * x).collect();
                let value = raw::polygon_irradiance(1.0, p, n, &verts, Emission::TwoSided);
                let exact = oracle::polygon(1.0, p, n, &verts, true);
                out.push(Case {
                    key: format!("h={h:e}"),
                    label: format!("sliver polygon h={h:e} rot {ri} lean {lean}"),
                    value,
                    exact,
                });
            }
        }
    }
    out
}

/// Caps of directions (γ = 1e-8 … 1.2) whose centre is below the horizon
/// and whose visible part is a sliver of angular height h = f·γ,
/// f = 1e-3 … 1e-12; as sky caps and as spheres.
pub(crate) fn barely_showing_caps() -> Vec<Case> {
    let mut out = vec![];
    for (ri, q) in rotations().into_iter().enumerate() {
        for &gamma in &[1e-8f64, 1e-4, 0.1, 0.5, 1.2] {
            for f in decades(-12, -3) {
                let elev = -(gamma * (1.0 - f));
                let n = q * DVec3::Z;
                let axis = q * DVec3::new(elev.cos() * 0.8, elev.cos() * 0.6, elev.sin());
                out.push(Case {
                    key: format!("f={f:e}"),
                    label: format!("sky cap γ={gamma:e} f={f:e} rot {ri}"),
                    value: sky_cap_irradiance(1.0, n, axis, gamma),
                    exact: oracle::sky_cap(1.0, n, axis, gamma),
                });
                // A sphere of radius sin γ · d at d = 3 from p.
                let p = DVec3::new(-0.3, 0.2, 0.7);
                let c = p + axis * 3.0;
                let r = 3.0 * gamma.sin();
                out.push(Case {
                    key: format!("f={f:e}"),
                    label: format!("sphere γ={gamma:e} f={f:e} rot {ri}"),
                    value: raw::sphere_irradiance(1.0, p, n, c, r),
                    exact: oracle::sphere(1.0, p, n, c, r).expect("outside"),
                });
            }
        }
    }
    out
}

/// Disks cut by the receiver's plane: the part above a fraction
/// 0.9 … 1e-12 of the diameter, at distance/size 1 … 1e12, tilted.
pub(crate) fn straddling_disks() -> Vec<Case> {
    let mut out = vec![];
    let p = DVec3::new(0.1, 0.2, -0.3);
    for (ri, q) in rotations().into_iter().enumerate() {
        let n = q * DVec3::Z;
        for d in decades(0, 12) {
            for &frac in &[0.9f64, 0.5, 1e-3, 1e-6, 1e-12] {
                for &tilt in &[0.3f64, 1.2, FRAC_PI_2] {
                    // Disk normal tilted from the vertical by `tilt` about
                    // the horizontal axis ⊥ the direction to the disk.
                    let az = 0.4f64;
                    let dir = DVec3::new(az.cos(), az.sin(), 0.0);
                    let side = DVec3::new(-az.sin(), az.cos(), 0.0);
                    let m_local = DQuat::from_axis_angle(side, tilt) * DVec3::Z;
                    // The rim's height amplitude is r·|n × m|; put the centre
                    // so that the top of the disk is frac·2r·g above.
                    let r = 1.0;
                    let g = DVec3::Z.cross(m_local).length();
                    let z = r * g * (2.0 * frac - 1.0);
                    let c_local = dir * (2.0 * d) + DVec3::new(0.0, 0.0, z);
                    let (c, m) = (p + q * c_local, q * m_local);
                    let facing = if m.dot(p - c) > 0.0 { m } else { -m };
                    out.push(Case {
                        key: format!("D={d:e} frac={frac:e}"),
                        label: format!(
                            "straddling disk D={d:e} frac={frac:e} tilt {tilt} rot {ri}"
                        ),
                        value: raw::disk_irradiance(1.0, p, n, c, facing, r, Emission::OneSided),
                        exact: oracle::disk(1.0, p, n, c, facing, r, false),
                    });
                }
            }
        }
    }
    out
}

/// Extreme magnitudes: every length scaled by s and the radiance set to
/// L, s and L over 1e-300 … 1e300 (E = L·P(shape), P scale-free), for a
/// sphere, a disk and a polygon, with the result in the f64 range.
pub(crate) fn extreme_magnitudes() -> Vec<Case> {
    let mut out = vec![];
    let n = DVec3::new(0.36, 0.48, 0.8);
    for k in (-300..=300).step_by(25) {
        let s = 10f64.powi(k);
        for j in (-300..=300).step_by(50) {
            let l = 10f64.powi(j);
            let p = DVec3::new(0.3, -0.1, 0.2) * s;
            let c = DVec3::new(0.5, 0.4, 1.6) * s;
            let exact = oracle::sphere(l, p, n, c, 0.7 * s).unwrap();
            // Only configurations whose true result is an ordinary f64.
            let e = exact.to_f64();
            if !(e.is_normal() && e < f64::MAX / 4.0) {
                continue;
            }
            out.push(Case {
                key: format!("s={s:e}"),
                label: format!("sphere s={s:e} L={l:e}"),
                value: raw::sphere_irradiance(l, p, n, c, 0.7 * s),
                exact,
            });
            let m = DVec3::new(0.0, -0.6, -0.8);
            out.push(Case {
                key: format!("s={s:e}"),
                label: format!("disk s={s:e} L={l:e}"),
                value: raw::disk_irradiance(l, p, n, c, m, 0.7 * s, Emission::OneSided),
                exact: oracle::disk(l, p, n, c, m, 0.7 * s, false),
            });
            let verts_s: Vec<DVec3> = polygon_around(DVec3::ZERO, -m, 0, 0.2)
                .iter()
                .map(|&v| v * s + c)
                .collect();
            out.push(Case {
                key: format!("s={s:e}"),
                label: format!("polygon s={s:e} L={l:e}"),
                value: raw::polygon_irradiance(l, p, n, &verts_s, Emission::OneSided),
                exact: oracle::polygon(l, p, n, &verts_s, false),
            });
        }
    }
    // The example: a disk of radius 1e-300, radiance 1e300, at
    // distance 1 on its axis: π·1e-300.
    out.push(Case {
        key: "issue".into(),
        label: "disk r=1e-300 L=1e300 at 1".into(),
        value: raw::disk_irradiance(
            1e300,
            DVec3::ZERO,
            DVec3::Z,
            DVec3::Z,
            -DVec3::Z,
            1e-300,
            Emission::OneSided,
        ),
        exact: oracle::disk(
            1e300,
            DVec3::ZERO,
            DVec3::Z,
            DVec3::Z,
            -DVec3::Z,
            1e-300,
            false,
        ),
    });
    out
}

fn worst(cases: &[Case]) -> (f64, String) {
    let mut w = (0.0f64, String::new());
    for c in cases {
        let e = c.rel();
        if !(e <= w.0) {
            w = (
                e,
                format!("{} → {:?} vs {:.17e}", c.label, c.value, c.exact.to_f64()),
            );
        }
    }
    w
}

#[test]
#[ignore = "a report, not a check: prints the worst relative error per hard class"]
fn report_worst_errors() {
    for (name, cases) in [
        ("far polygons", far_polygons()),
        ("sliver polygons", sliver_polygons()),
        ("barely showing caps", barely_showing_caps()),
        ("straddling disks", straddling_disks()),
        ("extreme magnitudes", extreme_magnitudes()),
    ] {
        let (e, label) = worst(&cases);
        println!("{name:>22}: {} cases, worst {e:.2e} ({label})", cases.len());
        let mut keys: Vec<&String> = vec![];
        for c in &cases {
            if !keys.contains(&&c.key) {
                keys.push(&c.key);
            }
        }
        for k in keys {
            let sub: Vec<&Case> = cases.iter().filter(|c| &c.key == k).collect();
            let w =
                sub.iter()
                    .map(|c| c.rel())
                    .fold(0.0f64, |a, b| if b > a || b.is_nan() { b } else { a });
            println!("    {k:>28}: worst {w:.2e}");
        }
    }
}

/// The oracle itself against the independent f64 area integrals of
/// `test_support` on ordinary configurations (those are accurate to
/// < 1e-13 there): a wrong formula in the oracle would show as an O(1)
/// difference; tolerance 1e-12.
#[test]
fn oracle_matches_area_integrals() {
    let c = DVec3::new(0.2, 0.1, 1.0);
    for &(tilt, beta) in &[(0.0f64, 0.0f64), (0.4, 0.5), (1.0, 1.1), (2.0, 1.45)] {
        let m = -DVec3::new(tilt.sin() * 0.6, tilt.sin() * 0.8, tilt.cos());
        let n = DVec3::new(beta.sin(), 0.0, beta.cos());
        let reference = disk_area_form(DVec3::ZERO, n, c, m, 0.8);
        let o = oracle::disk(1.0, DVec3::ZERO, n, c, m, 0.8, true).to_f64();
        assert!(
            (o / reference - 1.0).abs() < 1e-12,
            "disk {tilt} {beta}: {o} vs {reference}"
        );
    }
    for &(h, s, r) in &[(0.5, 0.7, 1.0), (2.0, 3.0, 1.0)] {
        let a = oracle::disk_parallel(1.0, h, s, r).to_f64();
        let b = oracle::disk(
            1.0,
            DVec3::ZERO,
            DVec3::Z,
            DVec3::new(s, 0.0, h),
            -DVec3::Z,
            r,
            false,
        )
        .to_f64();
        assert!((a / b - 1.0).abs() < 1e-15, "{a} vs {b}");
    }
    for &gamma in &[0.05, 1.0, 2.0] {
        for &beta in &[0.2, 1.4, 1.7, 2.3] {
            let a = DVec3::new(f64::sin(beta), 0.0, f64::cos(beta));
            let reference = cap_hemisphere_form(DVec3::Z, a, gamma);
            let o = oracle::sky_cap(1.0, DVec3::Z, a, gamma).to_f64();
            assert!(
                (o - reference).abs() <= 1e-12 * reference.max(1e-300),
                "cap {gamma} {beta}"
            );
        }
    }
}

/// Asserts every case of a class within `bound(case)` (relative, against
/// the oracle), reporting the worst offender.
fn assert_within(cases: &[Case], bound: impl Fn(&Case) -> f64) {
    let mut bad = vec![];
    for c in cases {
        let (e, b) = (c.rel(), bound(c));
        if !(e <= b) {
            bad.push(format!("{}: error {e:.2e} > bound {b:.2e}", c.label));
        }
    }
    assert!(
        bad.is_empty(),
        "{} case(s) out of bound:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// The number after `name=` in a case's key.
fn param(c: &Case, name: &str) -> f64 {
    let tail = &c.key[c.key.find(&format!("{name}=")).expect("param") + name.len() + 1..];
    tail.split_whitespace().next().unwrap().parse().unwrap()
}

/// Far polygons, D/ℓ = 1 … 1e12: the centred Lambert sum has no
/// far-field cancellation; measured worst 2.2e-15. Tolerance 1e-14: a few
/// ulps per term times the O(1) geometric cancellation of a tilted
/// receiver (n·J against |J|), 1e-12 being the target.
#[test]
fn far_polygons_are_exact() {
    assert_within(&far_polygons(), |_| 1e-14);
}

/// Extreme magnitudes (lengths and radiance 1e-300 … 1e300) for spheres,
/// disks and polygons, and the disk of radius 1e-300 and radiance
/// 1e300 (π·1e-300): exact scaling, so the ordinary few-ulp error;
/// measured worst 8.2e-16, tolerance 4e-15.
#[test]
fn extreme_magnitudes_are_exact() {
    assert_within(&extreme_magnitudes(), |_| 4e-15);
}

/// Disks cut by the receiver's plane, D/r = 1 … 1e12, visible fraction
/// 0.9 … 1e-12 of the diameter: the sin²ε form removes the chord/arc
/// cancellation, but the inputs' own rounding remains: c − p and n·(c − p)
/// are rounded at ε·D, which moves the disk by ε D/r of its radius and
/// its visible height by ε D/(r·frac) of itself. Documented bound
/// (measured to hold with margin ≥ 4): 4e-15 · (D/r) / frac, i.e. 1e-12 is
/// reached for D/r ≤ 1e2 at frac ≥ 0.5 and not beyond (open: exact
/// c − p as a double-double). Cases whose bound exceeds 1 are only
/// required to be finite and non-negative.
#[test]
fn straddling_disks_within_documented_bound() {
    let cases = straddling_disks();
    for c in &cases {
        let v = c.value.clone().expect("a value, not an error");
        assert!(v.is_finite() && v >= 0.0, "{}: {v}", c.label);
    }
    assert_within(&cases, |c| {
        let b = 4e-15 * param(c, "D") / param(c, "frac");
        if b >= 1.0 {
            f64::INFINITY
        } else {
            b
        }
    });
}

/// Polygons clipped to a sliver of height h (relative to their size)
/// above the horizon: still Lambert's cancellation between the chord term
/// and the others, ≈ 2 log₁₀(1/h) digits lost (open). Documented bound:
/// 2e-15/h² (measured worst 8.8e8 at h = 1e-12, 7.3e-10 at 1e-3).
#[test]
fn sliver_polygons_within_documented_bound() {
    assert_within(&sliver_polygons(), |c| 2e-15 / param(c, "h").powi(2));
}

/// Caps whose centre is below the horizon and that show a sliver of
/// angular height f·γ: the inputs' rounding (cos β = n·a to ε) against the
/// visible height f·γ, and the cancellation of the two terms of the
/// straddling formula (module docs of `cap`), give ≈ ε/(fγ) relative.
/// Documented bound 1e-14/(f·min(γ, 1)), capped at 4 (measured ≤ 4.7e-15/(f·min(γ, 1))) (open: cos β and
/// sin γ in double-double).
#[test]
fn barely_showing_caps_within_documented_bound() {
    assert_within(&barely_showing_caps(), |c| {
        let f = param(c, "f");
        let g: f64 = c
            .label
            .split("γ=")
            .nth(1)
            .unwrap()
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap();
        (1e-14 / (f * g.min(1.0))).min(4.0)
    });
}

/// The hanging case: a disk of radius ~1e188 whose plane crosses
/// the receiver's, seen from a receiver 8.4e116 away from its centre. It
/// used to run for minutes (|R|² overflowed to ∞, the quadrature never
/// converged and bisected to depth 60); now the lengths are rescaled and
/// the quadrature's work is bounded. It must answer, and agree with the
/// oracle (the receiver sees essentially an infinite plane 2 units away):
/// the disk's rounding here is the straddling class's, tolerance 1e-9.
#[test]
fn huge_straddling_disk_answers() {
    let c = DVec3::new(0.0, 0.0, 0.23);
    let m = DVec3::new(0.6, 0.0, -3.7e10).normalize();
    let p = DVec3::new(4.8, -8.4e116, -1.8);
    let n = DVec3::new(0.0, 0.9, -1e-5).normalize();
    for two in [false, true] {
        let emission = if two {
            Emission::TwoSided
        } else {
            Emission::OneSided
        };
        let b = raw::disk_irradiance_with_error_bound(1.0, p, n, c, m, 1e188, emission).unwrap();
        let exact = oracle::disk(1.0, p, n, c, m, 1e188, two);
        assert!(
            exact.rel_err(b.irradiance) < 1e-9,
            "{b:?} vs {}",
            exact.to_f64()
        );
        assert!(b.error_bound <= 1e-12 * b.irradiance.max(1e-300));
    }
}

/// Overflow is an error naming the quantity; a receiver on a sphere is an
/// error at any magnitude; two sphere lights of radiance 1e308 each give a
/// finite value or an overflow error, never ∞.
#[test]
fn overflow_and_receiver_on_the_light_are_errors() {
    let overflow = Err(AnalyticError::Overflow {
        quantity: "irradiance",
    });
    assert_eq!(try_sky_irradiance(1e308), overflow);
    assert_eq!(dome_irradiance(1e308, DVec3::Z, DVec3::Z), overflow);
    // A sphere covering a wide cone overhead: P = π·0.95² > 1.8, E > 1.8e308.
    assert_eq!(
        raw::sphere_irradiance(1e308, DVec3::ZERO, DVec3::Z, DVec3::Z * 2.0, 1.9),
        overflow
    );
    // A small one: P = π·1e-6, E = π·1e302.
    let e = raw::sphere_irradiance(1e308, DVec3::ZERO, DVec3::Z, DVec3::Z * 1e3, 1.0).unwrap();
    assert!((e / (PI * 1e302 / (1.0 + 0.0)) - 1.0).abs() < 1e-6, "{e}");
    // On the light, at the top of the range.
    assert_eq!(
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::X, DVec3::X * 1e308, 1e308),
        Err(AnalyticError::ReceiverInsideLight { light: "sphere" })
    );
    assert_eq!(
        raw::sphere_irradiance(1.0, DVec3::ZERO, DVec3::X, DVec3::X * 5e-324, 5e-324),
        Err(AnalyticError::ReceiverInsideLight { light: "sphere" })
    );
    // A square of side 200 at height 1 overhead: P ≈ π − 0.02.
    let big = [
        DVec3::new(-100.0, -100.0, 1.0),
        DVec3::new(100.0, -100.0, 1.0),
        DVec3::new(100.0, 100.0, 1.0),
        DVec3::new(-100.0, 100.0, 1.0),
    ];
    assert_eq!(
        raw::polygon_irradiance(1e308, DVec3::ZERO, DVec3::Z, &big, Emission::TwoSided),
        overflow
    );
    assert_eq!(
        raw::disk_irradiance(
            1e308,
            DVec3::ZERO,
            DVec3::Z,
            DVec3::Z,
            -DVec3::Z,
            10.0,
            Emission::OneSided
        ),
        overflow
    );
}
