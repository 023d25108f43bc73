//! Independent numerical integration for the tests: nested adaptive
//! Gauss–Kronrod over an emitter's area with the area-form integrand
//! cos θ cos θ′ / r², never through the closed forms. The clipping at the
//! receiver's plane is done by the integration limits (solved per outer
//! node), and the outer interval is split where the clip line meets the
//! emitter's edge, so every piece is smooth and the quadrature converges
//! to rounding.

use super::quadrature::integrate;
use glam::DVec3;
use std::f64::consts::PI;

/// ∫ over the pieces of [a, b] cut at `breaks` (those inside).
fn integrate_pieces<F: Fn(f64) -> f64>(f: F, a: f64, b: f64, breaks: &[f64], tol: f64) -> f64 {
    let mut cuts: Vec<f64> = breaks.iter().copied().filter(|&x| x > a && x < b).collect();
    cuts.push(a);
    cuts.push(b);
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2)
        .map(|w| integrate(&f, w[0], w[1], tol))
        .sum()
}

/// ∫_0^{2π} ∫_0^R f(ρ cos t, ρ sin t) ρ dρ dt (nested adaptive G–K).
pub(crate) fn integrate_disk_polar<F: Fn(f64, f64) -> f64>(radius: f64, f: F) -> f64 {
    integrate(
        |t: f64| {
            let (st, ct) = t.sin_cos();
            integrate(|rho: f64| f(rho * ct, rho * st) * rho, 0.0, radius, 1e-15)
        },
        0.0,
        2.0 * PI,
        1e-14,
    )
}

/// The projected solid angle of a disk (centre c, unit normal m, radius R)
/// from (p, n) by the area form ∫ (n·d)|m·d| / r⁴ dA over the part with
/// n·d > 0 (d = x − p), in polar coordinates about the centre.
pub(crate) fn disk_area_form(p: DVec3, n: DVec3, c: DVec3, m: DVec3, r: f64) -> f64 {
    let (e1, e2) = m.any_orthonormal_pair();
    let a0 = n.dot(c - p);
    let (b1, b2) = (n.dot(e1), n.dot(e2));
    let rho_b = b1.hypot(b2);
    let phi_b = b2.atan2(b1);
    let mut breaks = vec![];
    if rho_b > 0.0 && (a0 / (r * rho_b)).abs() < 1.0 {
        let w = (-a0 / (r * rho_b)).acos();
        for k in -1..=2 {
            breaks.push(phi_b + w + 2.0 * PI * k as f64);
            breaks.push(phi_b - w + 2.0 * PI * k as f64);
        }
    }
    integrate_pieces(
        |t: f64| {
            let (st, ct) = t.sin_cos();
            let u = e1 * ct + e2 * st;
            let b = n.dot(u);
            // Visible: a0 + ρ b > 0.
            let (mut lo, mut hi) = (0.0, r);
            if b > 0.0 {
                lo = (-a0 / b).max(0.0);
            } else if b < 0.0 {
                hi = (a0 / -b).min(r);
            } else if a0 <= 0.0 {
                return 0.0;
            }
            if !(hi > lo) {
                return 0.0;
            }
            integrate(
                |rho: f64| {
                    let d = c + u * rho - p;
                    let r2 = d.length_squared();
                    n.dot(d).max(0.0) * m.dot(d).abs() / (r2 * r2) * rho
                },
                lo,
                hi,
                1e-15,
            )
        },
        0.0,
        2.0 * PI,
        &breaks,
        1e-14,
    )
}

/// The projected solid angle of a cap of directions (axis a, half-angle γ)
/// by integrating cos θ over the hemisphere in (z = cos θ, φ): for each z the
/// cap is an interval of azimuths of half-width Φ(z) found from a·ω ≥ cos γ.
/// z is split at cos(β + γ) and cos(|β − γ|), where Φ has square-root ends,
/// and each piece is mapped by z = z₀ + (z₁ − z₀)(1 − cos u)/2, which makes
/// those ends smooth.
pub(crate) fn cap_hemisphere_form(n: DVec3, a: DVec3, gamma: f64) -> f64 {
    let cb = n.dot(a).clamp(-1.0, 1.0);
    let sb = n.cross(a).length();
    let beta = sb.atan2(cb);
    let cg = gamma.cos();
    let half_width = |z: f64| -> f64 {
        let sz = ((1.0 - z) * (1.0 + z)).sqrt();
        if sb * sz == 0.0 {
            return if cb * z >= cg { PI } else { 0.0 };
        }
        let k = (cg - cb * z) / (sb * sz);
        k.clamp(-1.0, 1.0).acos()
    };
    let mut cuts = vec![0.0, 1.0, (beta + gamma).cos(), (beta - gamma).abs().cos()];
    cuts.retain(|&z| (0.0..=1.0).contains(&z));
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts.windows(2)
        .map(|w| {
            let (z0, z1) = (w[0], w[1]);
            integrate(
                |u: f64| {
                    let z = z0 + (z1 - z0) * 0.5 * (1.0 - u.cos());
                    2.0 * z * half_width(z) * (z1 - z0) * 0.5 * u.sin()
                },
                0.0,
                PI,
                1e-15,
            )
        })
        .sum()
}

/// The closed forms with the plain-vector arguments the tests are written
/// in: each builds the shapes and the receiver (validated as every caller's
/// are) and calls the public function.
pub(crate) mod raw {
    use super::super::{AnalyticError, BoundedIrradiance, Emission};
    use crate::receiver::Receiver;
    use glam::DVec3;
    use lambert_geometry::f64::{unit_vector, ConvexPolygon, Disk, Frame, Sphere};
    use lambert_geometry::validate;

    /// The unit normal a shape or receiver built from `n` stores (the
    /// library's input, which the oracle takes as exact).
    pub(crate) fn normal(n: DVec3) -> DVec3 {
        unit_vector("normal", n).expect("a non-zero normal")
    }

    fn receiver(p: DVec3, n: DVec3) -> Result<Receiver, AnalyticError> {
        validate::finite3("p", p)?;
        let normal = unit_vector("normal", n)?;
        Ok(Receiver {
            point: p,
            normal,
            frame: Frame::from_normal(normal),
        })
    }

    pub(crate) fn sphere_irradiance(
        radiance: f64,
        p: DVec3,
        n: DVec3,
        center: DVec3,
        radius: f64,
    ) -> Result<f64, AnalyticError> {
        let sphere = Sphere::new(center, radius)?;
        super::super::sphere_irradiance(&sphere, radiance, &receiver(p, n)?)
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn disk_irradiance_with_error_bound(
        radiance: f64,
        p: DVec3,
        n: DVec3,
        center: DVec3,
        disk_normal: DVec3,
        radius: f64,
        emission: Emission,
    ) -> Result<BoundedIrradiance, AnalyticError> {
        let disk = Disk::new(center, disk_normal, radius)?;
        super::super::disk_irradiance_with_error_bound(&disk, emission, radiance, &receiver(p, n)?)
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn disk_irradiance(
        radiance: f64,
        p: DVec3,
        n: DVec3,
        center: DVec3,
        disk_normal: DVec3,
        radius: f64,
        emission: Emission,
    ) -> Result<f64, AnalyticError> {
        let disk = Disk::new(center, disk_normal, radius)?;
        super::super::disk_irradiance(&disk, emission, radiance, &receiver(p, n)?)
    }

    pub(crate) fn polygon_irradiance(
        radiance: f64,
        p: DVec3,
        n: DVec3,
        vertices: &[DVec3],
        emission: Emission,
    ) -> Result<f64, AnalyticError> {
        let polygon = ConvexPolygon::new(vertices.to_vec())?;
        super::super::polygon_irradiance(&polygon, emission, radiance, &receiver(p, n)?)
    }
}
