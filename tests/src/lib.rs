//! Cross-crate validation suites for lambert; the suites live in `tests/`.
//! The catalogue of cases is the estimator's
//! [`warp_suite`](lambert_validate::warp_suite); this
//! library adds what only the property tests need.

use glam::DVec3;
use lambert_validate::catalog::DirectionWarpSpec;

pub use lambert_validate::warp_suite::*;

pub mod projected;

/// Samples on and near the edges of the unit square: 0, tiny, interior,
/// 1 − ε (for f64 and for f32) and exactly 1.
pub fn edge_values() -> Vec<f64> {
    vec![
        0.0,
        1e-12,
        1e-7,
        0.25,
        0.5,
        0.75,
        1.0 - f32::EPSILON as f64 / 2.0,
        1.0 - f64::EPSILON / 2.0,
        1.0,
    ]
}

/// How much a warp amplifies rounding, for the property tests' tolerances:
/// `(invert, f32)` factors multiplying the precision's ε.
///
/// * Spherical triangles: a direction known to a few ε, divided by the
///   triangle's angular height Ω/c (c the longest chord of the unit vertex
///   directions), moves u by ε·c/Ω, so invert gets 1 + c/Ω; f32 rounds the
///   vertices too, which moves a sliver's sampling by ε·c²/Ω: 1 + c²/Ω.
/// * Spherical rectangles: likewise 1 + c/Ω, times 1 + ρ/d for grazing
///   views (ρ the farthest corner, d the plane's distance: a direction near
///   the horizon moves the hit point by δ·ρ/d).
/// * Both spherical polygons also carry a base of 16 (their samplers chain
///   about four times as many roundings as a cone's, and near-hemisphere
///   triangles put two of the vertices nearly opposite: measured worst 62ε
///   for invert and 26 ε₃₂ for f32 against f64 on the cases here).
/// * Everything else: 1 (the warps are well conditioned on the interior).
pub fn conditioning(spec: &DirectionWarpSpec) -> (f64, f64) {
    let chord_and_angle = |dirs: &[DVec3], omega: f64| {
        let mut c: f64 = 0.0;
        for a in dirs {
            for b in dirs {
                c = c.max((*a - *b).length());
            }
        }
        (c, omega)
    };
    match spec {
        DirectionWarpSpec::SphericalTriangle { vertices } => {
            let dirs: Vec<DVec3> = vertices.iter().map(|v| v.normalize()).collect();
            let omega = lambert_geometry::f64::triangle_solid_angle(
                DVec3::ZERO,
                vertices[0],
                vertices[1],
                vertices[2],
            );
            let (c, omega) = chord_and_angle(&dirs, omega);
            (16.0 * (1.0 + c / omega), 16.0 * (1.0 + c * c / omega))
        }
        DirectionWarpSpec::SphericalRectangle {
            corner,
            edge0,
            edge1,
        } => {
            let corners = [
                *corner,
                *corner + *edge0,
                *corner + *edge0 + *edge1,
                *corner + *edge1,
            ];
            let dirs: Vec<DVec3> = corners.iter().map(|v| v.normalize()).collect();
            let rect = lambert_sampling::f64::SphericalRectangle::new(
                DVec3::ZERO,
                *corner,
                *edge0,
                *edge1,
            )
            .expect("a valid case");
            let (c, omega) = chord_and_angle(&dirs, rect.solid_angle());
            let n = edge0.cross(*edge1).normalize();
            let d = n.dot(*corner).abs();
            let rho = corners.iter().map(|p| p.length()).fold(0.0, f64::max);
            let grazing = 1.0 + rho / d;
            let factor = 16.0 * (1.0 + c / omega) * grazing;
            (factor, factor)
        }
        _ => (1.0, 1.0),
    }
}

/// The density per steradian each smooth warp is meant to have, written
/// here from its definition with glam alone — independently of the sampling
/// crate's code — so that a sampler whose samples and `pdf` agree with each
/// other but not with the intended density is caught; `None` for the warps
/// tested on an exact partition of their support ([`partition_for`]),
/// whose cell probabilities are closed-form solid angles or areas.
///
/// * uniform hemisphere 1/(2π) for z ≥ 0; cosine hemisphere max(z, 0)/π;
///   uniform sphere 1/(4π);
/// * uniform cone about +z with h = 1 − cos θmax: 1/(2πh) where
///   1 − cos θ ≤ h, with 1 − cos θ = (x² + y²)/(1 + z) for z > 0 (no
///   cancellation for tiny cones) and 1 − z otherwise;
/// * a sphere of center c and radius r seen from the origin: uniform in its
///   subtended cone, 1/(2πh) with h = s²/(1 + √(1 − s²)), s = r/|c|, where
///   1 − ω·ĉ = |ω − ĉ|²/2 ≤ h (exact for unit vectors, no cancellation).
pub fn intended_density(spec: &DirectionWarpSpec) -> Option<Box<dyn Fn(DVec3) -> f64 + Sync>> {
    use std::f64::consts::PI;
    fn cap(axis: DVec3, h: f64) -> Box<dyn Fn(DVec3) -> f64 + Sync> {
        let value = 1.0 / (2.0 * PI * h);
        Box::new(move |w: DVec3| {
            let t = if axis == DVec3::Z && w.z > 0.0 {
                (w.x * w.x + w.y * w.y) / (1.0 + w.z)
            } else {
                0.5 * (w - axis).length_squared()
            };
            if t <= h {
                value
            } else {
                0.0
            }
        })
    }
    match spec {
        DirectionWarpSpec::UniformHemisphere => {
            Some(Box::new(|w: DVec3| if w.z >= 0.0 { 0.5 / PI } else { 0.0 }))
        }
        DirectionWarpSpec::CosineHemisphere => Some(Box::new(|w: DVec3| w.z.max(0.0) / PI)),
        DirectionWarpSpec::UniformSphere => Some(Box::new(|_| 0.25 / PI)),
        DirectionWarpSpec::UniformCone {
            one_minus_cos_theta_max: h,
        } => Some(cap(DVec3::Z, *h)),
        DirectionWarpSpec::SphereLight { center, radius } => {
            let d = center.length();
            let s2 = (radius / d) * (radius / d);
            Some(cap(*center / d, s2 / (1.0 + (1.0 - s2).sqrt())))
        }
        _ => None,
    }
}

/// sin of the angular radius of the warp's support when it lies off the
/// ±z axis, 1 otherwise: a direction stored with absolute error ε per
/// component is located in such a support only to ε/that (components near
/// ±z are exact to relative precision, so supports about ±z lose nothing).
pub fn angular_scale(spec: &DirectionWarpSpec) -> f64 {
    match spec.bounding_cap() {
        Some(cap) if cap.axis.x != 0.0 || cap.axis.y != 0.0 => {
            let h = cap.one_minus_cos;
            (h * (2.0 - h)).sqrt().max(1e-300)
        }
        _ => 1.0,
    }
}

/// The README's Rust example, run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;
