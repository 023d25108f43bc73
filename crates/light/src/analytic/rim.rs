//! The projected solid angle of a disk that the receiver's plane cuts: a
//! contour integral over the visible arc of its rim, in one of two exact
//! forms, chosen so that no term cancels.
//!
//! Lambert's contour form (Arvo 1995) is 2P = |∮ n·(R × dR)/|R|²| around
//! the visible part's boundary (rim arc + chord in the receiver's plane).
//! With ε the elevation above the horizon and φ the azimuth about n, its
//! integrand is cos²ε dφ. Because ∮ dφ = 0 around a contour that does not
//! wind around the zenith, 2P = |∮ sin²ε dφ| as well, and this second form
//! has two virtues: the chord (ε = 0) contributes nothing, and the arc's
//! integrand, sin²ε dφ = (n·R)² n·(R × dR) / (|R|² |n × R|²), is small
//! where the visible part is thin. For a disk that barely shows, Lambert's
//! arc term and chord term are each of the order of the chord's angle w
//! and cancel to P ∝ h² w (h the visible height): all digits lost at
//! h = 1e-8; the sin²ε form has no such cancellation (only the O(1)
//! geometric one where the rim's azimuth turns back, for disks seen
//! nearly edge-on).
//!
//! The sin²ε form is used when the visible rim stays below ≈ 44° of
//! elevation (sin ε ≤ (n·(c − p) + R|n × m|)/(|c − p| − R) ≤ 0.7): then the
//! disk does not cover the zenith (so ∮ dφ = 0) and |n × R| ≥ 0.7|R| keeps
//! the integrand smooth. Otherwise the visible part reaches high, its P is
//! not small next to Lambert's terms, and Lambert's form is used.
//!
//! The arc integral is an adaptive Gauss–Kronrod quadrature with a work
//! bound ([`quadrature::MAX_PANELS`] panels, 30 720 evaluations); its
//! error bound is returned with the value.

use super::quadrature::{self, Integral};
use glam::DVec3;

/// The visible part's projected solid angle P (sr) divided by r², with an
/// absolute error bound on that quotient, for a disk (centre at `v` from
/// the receiver, unit normal `m`, radius `r`) that the receiver's plane
/// (unit normal `n`) cuts: |n·v| < r|n × m|. Lengths in units where
/// max(|v|, r) = 1.
pub(crate) fn straddling_over_r2(v: DVec3, n: DVec3, m: DVec3, r: f64) -> Integral {
    let f0 = n.dot(v);
    let n_par = n - m * n.dot(m);
    let g = n_par.length();
    let e1 = n_par / g;
    let e2 = m.cross(e1);
    let rg = r * g;
    // Visible for |t| < t₁, cos t₁ = −f0/(rg).
    let sin_t1 = ((rg - f0) * (rg + f0)).max(0.0).sqrt() / rg;
    let t1 = sin_t1.atan2(-f0 / rg);
    let w = n.cross(v);
    let (wa, wb) = (w.dot(e1), w.dot(e2));
    let nm = n.dot(m);
    let at = |t: f64| {
        let (st, ct) = t.sin_cos();
        let rr = v + (e1 * ct + e2 * st) * r;
        // n·(R × R′)/r, R′ = r(−sin t e₁ + cos t e₂), without forming
        // the r² m part's cancellation against r(v × u′).
        let rate = wb * ct - wa * st + r * nm;
        (rr, rate, st, ct)
    };
    let distance = v.length();
    let high = !(distance > r) || (f0 + rg) > 0.7 * (distance - r);
    if high {
        // Lambert's form: arc + chord, P = |arc + chord|/2.
        let arc = quadrature::integrate_bounded(
            |t: f64| {
                let (rr, rate, _, _) = at(t);
                rate / rr.length_squared()
            },
            -t1,
            t1,
            1e-14,
            quadrature::MAX_PANELS,
        );
        let (st, ct) = t1.sin_cos();
        let ra = v + (e1 * ct + e2 * st) * r;
        let rb = v + (e1 * ct - e2 * st) * r;
        let cross = ra.cross(rb);
        let chord = cross.length().atan2(ra.dot(rb)) * n.dot(cross).signum();
        // The arc integrand carries one factor r.
        let total = r * arc.value + chord;
        let scale = 0.5 / (r * r);
        return Integral {
            value: (total * scale).abs(),
            error: (r * arc.error + 4.0 * f64::EPSILON * chord.abs()) * scale,
            converged: arc.converged,
        };
    }
    // The sin²ε form; the integrand divided by r², with the height
    // H = n·R = rg(cos t − cos t₁) = 2rg sin((t₁ − t)/2) sin((t₁ + t)/2)
    // as a product (it vanishes at the ends).
    let m_int = quadrature::integrate_bounded(
        |t: f64| {
            let (rr, rate, _, _) = at(t);
            let h = 2.0 * g * (0.5 * (t1 - t)).sin() * (0.5 * (t1 + t)).sin();
            let r2 = rr.length_squared();
            let perp2 = n.cross(rr).length_squared();
            // (rH̃)² · r·rate / (|R|²|n × R|²) / r²  with H = r H̃.
            r * h * h * rate / (r2 * perp2)
        },
        -t1,
        t1,
        1e-14,
        quadrature::MAX_PANELS,
    );
    Integral {
        value: 0.5 * m_int.value.abs(),
        error: 0.5 * m_int.error,
        converged: m_int.converged,
    }
}
