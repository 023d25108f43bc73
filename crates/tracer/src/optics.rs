//! Mirror reflection, Snell refraction and the exact Fresnel reflectance
//! of a dielectric interface.

use glam::DVec3;

/// The mirror reflection of the direction `d` about the unit normal `n`:
/// r = d − 2(d·n)n (the angle of reflection equals the angle of
/// incidence).
#[inline]
pub fn reflect(d: DVec3, n: DVec3) -> DVec3 {
    d - 2.0 * d.dot(n) * n
}

/// The refracted direction of the unit direction `d` arriving at a surface
/// whose unit normal `n` faces it (d·n < 0), going from a medium of index
/// η_i into one of index η_t, with `eta` = η_i / η_t: Snell's law
/// η_i sin θ_i = η_t sin θ_t gives sin²θ_t = η² (1 − cos²θ_i) and
/// t = η d + (η cos θ_i − cos θ_t) n (unit). `None` at total internal
/// reflection (sin²θ_t > 1). Returns the direction and cos θ_t.
#[inline]
pub fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<(DVec3, f64)> {
    let cos_i = (-d.dot(n)).min(1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n, cos_t))
}

/// The exact Fresnel reflectance of unpolarised light at a smooth
/// dielectric interface, F = (r_s² + r_p²)/2 with the amplitude
/// coefficients r_s = (η_i cos θ_i − η_t cos θ_t)/(η_i cos θ_i + η_t cos θ_t)
/// and r_p = (η_t cos θ_i − η_i cos θ_t)/(η_t cos θ_i + η_i cos θ_t)
/// (Born & Wolf, *Principles of Optics*, §1.5.2; pbrt-v4 §9.3.6). `eta` =
/// η_i / η_t and `cos_i` ∈ [0, 1] is the cosine of the angle of incidence;
/// 1 at total internal reflection. The transmitted fraction is 1 − F (no
/// absorption).
///
/// ```
/// use lambert_tracer::optics::fresnel_dielectric;
/// // Normal incidence on glass: ((1.5 − 1)/(1.5 + 1))² = 0.04.
/// assert!((fresnel_dielectric(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-15);
/// assert_eq!(fresnel_dielectric(0.0, 1.0 / 1.5), 1.0);
/// ```
#[inline]
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    // With η_i = eta, η_t = 1 (only the ratio matters).
    let rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (rs * rs + rp * rp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snell_holds_and_total_internal_reflection_happens() {
        let n = DVec3::Z;
        for k in 0..90 {
            let theta = (k as f64).to_radians();
            let d = DVec3::new(theta.sin(), 0.0, -theta.cos());
            // Air into glass.
            let (t, cos_t) = refract(d, n, 1.0 / 1.5).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-15);
            let sin_t = (1.0 - cos_t * cos_t).sqrt();
            assert!((theta.sin() - 1.5 * sin_t).abs() < 1e-14, "{k}°");
            assert!((t.z + cos_t).abs() < 1e-15);
            // Glass into air: past the critical angle asin(1/1.5) = 41.8°.
            let out = refract(d, n, 1.5);
            assert_eq!(out.is_none(), theta.sin() * 1.5 > 1.0, "{k}°");
            assert_eq!(fresnel_dielectric(theta.cos(), 1.5) == 1.0, out.is_none());
        }
    }

    #[test]
    fn fresnel_reflectance_at_brewster_and_grazing() {
        // At Brewster's angle tan θ_B = η_t/η_i the p-polarised part
        // vanishes: F = r_s²/2.
        let eta_t: f64 = 1.5;
        let theta_b = eta_t.atan();
        let cos_i = theta_b.cos();
        let cos_t = theta_b.sin(); // θ_i + θ_t = 90° at Brewster's angle
        let rs = (cos_i - eta_t * cos_t) / (cos_i + eta_t * cos_t);
        let f = fresnel_dielectric(cos_i, 1.0 / eta_t);
        assert!((f - 0.5 * rs * rs).abs() < 1e-15, "{f}");
        // Grazing incidence reflects everything; reflectance rises with θ.
        assert!((fresnel_dielectric(1e-9, 1.0 / 1.5) - 1.0).abs() < 1e-8);
        // Against the coefficients written with both indices (1 and 1.5)
        // and cos θ_t from Snell's law.
        for k in 0..90 {
            let theta = (k as f64).to_radians();
            let d = DVec3::new(theta.sin(), 0.0, -theta.cos());
            let (_, cos_t) = refract(d, DVec3::Z, 1.0 / 1.5).unwrap();
            let (ci, ni, nt) = (theta.cos(), 1.0, 1.5);
            let rs = (ni * ci - nt * cos_t) / (ni * ci + nt * cos_t);
            let rp = (nt * ci - ni * cos_t) / (nt * ci + ni * cos_t);
            let f = fresnel_dielectric(ci, ni / nt);
            assert!((f - 0.5 * (rs * rs + rp * rp)).abs() < 1e-15, "{k}°");
        }
    }
}
