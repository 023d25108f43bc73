//! The projected solid angle of a polygon low over the horizon, as the
//! contour integral of sin²ε dφ along its edges, each edge's integral in a
//! closed form whose two terms have the same sign.
//!
//! # Why
//! Lambert's form 2P = |Σᵢ θᵢ n·ĝᵢ| is the contour integral ∮ cos²ε dφ
//! (ε the elevation above the receiver's horizon, φ the azimuth about its
//! normal n, θᵢ the angle an edge subtends, ĝᵢ the unit normal of the
//! plane through the receiver and the edge). For a polygon clipped by the
//! horizon to a sliver of height h (relative to its width w), the chord
//! in the horizon contributes its whole angle ≈ w and the top edge nearly
//! the opposite: they cancel to P ∝ h²w, losing 2 log₁₀(1/h) digits. When
//! the polygon does not wind around the zenith, ∮ dφ = 0, so
//! 2P = |∮ sin²ε dφ| as well (the form Arvo 1995 obtains for the disk,
//! used here per edge): the chord (ε = 0) contributes nothing, and every
//! edge's integral is of the size of the result.
//!
//! # The edge integral, without cancellation
//! Along an edge from R_a to R_b (receiver-relative), split each point
//! into its height z = n·R and horizontal part H (R = H + z n). With
//! K = n·(H_a × H_b), M = |z_b H_a − z_a H_b| (the horizontal part of
//! R_a × R_b), G = |R_a × R_b| = √(K² + M²), the edge lies on the great
//! circle of pole ĝ = (R_a × R_b)/G, inclined to the horizon by ι with
//! cos ι = c = K/G, sin ι = k = M/G. On it tan u = c tan s (s arc length
//! and u azimuth, both from the ascending node), dφ = c ds / cos²ε, and
//!
//! F = ∫ sin²ε dφ = Δu − c Δs,   Δs = atan2(G, R_a·R_b), Δu = φ_b − φ_a.
//!
//! Let Δu₀ = atan2(c sin Δs, cos Δs), the azimuth an arc of the same length
//! would sweep from the node. Then F = (Δu − Δu₀) + (Δu₀ − c Δs) where
//!
//! - Δu − Δu₀ = atan2(K z_a z_b, |H_a|²|H_b|² + (H_a·H_b) z_a z_b), by the
//!   difference formula of atan2 with (cos Δu, sin Δu) ∝ (H_a·H_b, K),
//!   (cos Δu₀, sin Δu₀) ∝ (R_a·R_b, K) and (H_a·H_b)² + K² = |H_a|²|H_b|²:
//!   a product of the heights, no difference;
//! - Δu₀ − c Δs = sign(K)·E(|c|, Δs), E(c, θ) = atan2(c sin θ, cos θ) − cθ
//!   = c k² ∫₀^θ sin²σ/(1 − k² sin²σ) dσ ≥ 0, evaluated by whichever of
//!   three exact forms has no cancellation (see [`edge_excess`]).
//!
//! Both terms have the sign of K (heights ≥ 0 above the horizon), so F
//! keeps the relative precision of its inputs. The inputs needed to that
//! precision are the heights z (and their differences along edges), which
//! the caller computes exactly (double-double from an exact dot product):
//! a sliver 1e-12 of its size high, 1e12 sizes away, has z ≈ 1e-24 |R|.
//! Horizontal quantities enter only through products and sums of
//! positive terms, so f64 (rigidly shifted by the rounding of the centre,
//! as in Lambert's centred sum) suffices for them.
//!
//! The sum over edges still cancels when the polygon is high above the
//! horizon compared with its own extent in elevation (a small polygon at
//! elevation 0.5: the edges' terms are of order sin²ε·Δφ, the result of
//! order Δε·ε·Δφ): there Lambert's centred sum is exact, and the caller
//! keeps whichever form has the smaller measured cancellation factor
//! Σ|termᵢ| / |Σ termᵢ|.

use super::cap::segment;
use glam::DVec3;

/// A vertex of the (clipped) polygon: its horizontal coordinates in a
/// frame ⊥ n, relative to the receiver, and its height above the horizon.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LowVertex {
    /// Horizontal position (x, y) relative to the receiver (the z
    /// component is unused).
    pub(crate) h: DVec3,
    /// Height n·(v − p) ≥ 0, exact to f64 rounding.
    pub(crate) z: f64,
}

/// The edge data for the sin² sum: horizontal edge vector and exact height
/// difference.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LowEdge {
    /// H_b − H_a (from the polygon's own coordinates, exact at its scale).
    pub(crate) dh: DVec3,
    /// z_b − z_a, exact to f64 rounding.
    pub(crate) dz: f64,
}

/// The result of the sin² sum: 2P's absolute value halved, and the
/// cancellation factor Σ|Fᵢ| / |Σ Fᵢ|; `None` when the polygon winds
/// around the zenith (or touches the vertical through the receiver), where
/// ∮ dφ ≠ 0 and the form does not apply.
pub(crate) fn projected_solid_angle(
    vertices: &[LowVertex],
    edges: &[LowEdge],
) -> Option<(f64, f64)> {
    let k = vertices.len();
    let mut sum = 0.0f64;
    let mut comp = 0.0f64;
    let mut abs_sum = 0.0f64;
    let mut winding = 0.0f64;
    for i in 0..k {
        let (a, b, e) = (vertices[i], vertices[(i + 1) % k], edges[i]);
        let (ha, hb) = (a.h, b.h);
        let (ha2, hb2) = (ha.x * ha.x + ha.y * ha.y, hb.x * hb.x + hb.y * hb.y);
        if !(ha2 > 0.0 && hb2 > 0.0) {
            return None;
        }
        let kk = ha.x * e.dh.y - ha.y * e.dh.x;
        let hab = ha.x * hb.x + ha.y * hb.y;
        winding += kk.atan2(hab);
        let f = edge_integral(ha, ha2, hb2, hab, kk, a.z, b.z, e);
        abs_sum += f.abs();
        // Neumaier summation.
        let t = sum + f;
        comp += if sum.abs() >= f.abs() {
            (sum - t) + f
        } else {
            (f - t) + sum
        };
        sum = t;
    }
    // ∮ dφ is 0 or ±2π: accept only 0 (half a turn is a safe separator).
    if !(winding.abs() < std::f64::consts::PI) {
        return None;
    }
    let total = sum + comp;
    let kappa = if total != 0.0 {
        abs_sum / total.abs()
    } else if abs_sum == 0.0 {
        1.0
    } else {
        f64::INFINITY
    };
    Some((0.5 * total.abs(), kappa))
}

/// F = ∫ sin²ε dφ along one edge (module docs).
#[allow(clippy::too_many_arguments)]
fn edge_integral(
    ha: DVec3,
    ha2: f64,
    hb2: f64,
    hab: f64,
    kk: f64,
    za: f64,
    zb: f64,
    e: LowEdge,
) -> f64 {
    // M = |Δz H_a − z_a ΔH|, the horizontal part of R_a × R_b.
    let mx = e.dz * ha.x - za * e.dh.x;
    let my = e.dz * ha.y - za * e.dh.y;
    let m = mx.hypot(my);
    let g = kk.hypot(m);
    if !(g > 0.0) {
        return 0.0;
    }
    let rab = hab + za * zb;
    let ds = g.atan2(rab);
    let first = (kk * za * zb).atan2(ha2 * hb2 + hab * za * zb);
    let c = kk.abs() / g;
    let k = m / g;
    let k2 = k * k;
    first + kk.signum() * edge_excess(c, k2 / (1.0 + c), k2, ds)
}

/// E(c, θ) = atan2(c sin θ, cos θ) − cθ = c k² ∫₀^θ sin²σ/(1 − k² sin²σ) dσ
/// ≥ 0 for c ∈ [0, 1], θ ∈ [0, π], given k² = 1 − c² and c′ = 1 − c
/// accurately (as ratios of the geometry, not as differences from 1).
/// Three exact forms, each used where it does not cancel:
///
/// - c′ ≤ 1/4 (the great circle within 41° of the horizon): with
///   x = 1 − c′ sin²θ and w = c′ sin θ cos θ / x (|w| ≤ 1/6),
///   E = c′θ − atan w = c′ (S(θ) − c′ sin³θ cos θ / x) + (w − atan w),
///   S(θ) = θ − sin θ cos θ by its series (the bracket's second term is at
///   most 3/8 of the first for θ ≤ π/2, and adds for θ > π/2; w − atan w
///   by its series);
/// - otherwise, tan θ ≤ 1/2: the series in T = tan θ of
///   atan(cT) − c atan T = c k² Σⱼ (−1)ʲ (1 + c² + … + c²ʲ) T²ʲ⁺³/(2j + 3),
///   alternating with ratio ≤ T²(j + 2)/(j + 1);
/// - otherwise directly: E/(cθ) ≥ 1/31 there, at most 5 bits lost.
pub(crate) fn edge_excess(c: f64, c1: f64, k2: f64, theta: f64) -> f64 {
    if c1 <= 0.25 {
        let (s, co) = theta.sin_cos();
        let x = 1.0 - c1 * s * s;
        let w = c1 * s * co / x;
        return c1 * (segment(theta) - c1 * s * s * s * co / x) + w_minus_atan(w);
    }
    if theta <= 0.463_647_609_000_806_1 {
        // atan(1/2)
        let t = theta.tan();
        let (c2, t2) = (c * c, t * t);
        let mut a = 1.0f64;
        let mut power = t * t2;
        let mut sum = power / 3.0;
        // T² ≤ 1/4 and a ≤ 1/k² < 16/7 (c < 3/4): below 1e-17 of the sum by
        // j = 30; the bound also ends the loop for a NaN argument.
        for j in 1..=40 {
            a = 1.0 + c2 * a;
            power *= -t2;
            let term = a * power / (2.0 * j as f64 + 3.0);
            sum += term;
            if term.abs() <= 1e-17 * sum.abs() {
                break;
            }
        }
        return c * k2 * sum;
    }
    (c * theta.sin()).atan2(theta.cos()) - c * theta
}

/// w − atan w for |w| ≤ 1/2: the series w³/3 − w⁵/5 + … (no cancellation).
fn w_minus_atan(w: f64) -> f64 {
    let w2 = w * w;
    let mut power = w * w2;
    let mut sum = 0.0f64;
    // |w| ≤ 1/2: w²ʲ/(2j + 3) < 1e-17 by j = 27.
    for j in 0..=30 {
        let term = power / (2 * j + 3) as f64;
        sum += term;
        if term.abs() <= 1e-17 * sum.abs() || term == 0.0 {
            break;
        }
        power *= -w2;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::oracle::B;

    /// E(c, θ) against its definition atan2(c sin θ, cos θ) − cθ in 1024
    /// bits, over inclinations from 1e-12 rad (k = sin ι) to vertical and
    /// arcs from 1e-9 to 3 rad, across the three forms' boundaries: the
    /// forms are exact to a few ulps times their stated cancellation
    /// (≤ 31 in the direct form): tolerance 8e-15 relative.
    #[test]
    fn edge_excess_matches_its_definition() {
        for &iota in &[
            1e-12,
            1e-6,
            0.3,
            0.72,
            0.73,
            1.0,
            1.5,
            std::f64::consts::FRAC_PI_2 - 1e-6,
        ] {
            // k exact; c, c′ = k²/(1 + c) and k² from it in 1024 bits,
            // rounded once (as the callers form them from the geometry).
            let kb = B::from(f64::sin(iota));
            let k2b = &kb * &kb;
            let cb = (B::from(1.0) - &k2b).sqrt();
            let c1 = (&k2b / (B::from(1.0) + &cb)).to_f64();
            let (c, k2) = (cb.to_f64(), k2b.to_f64());
            for &theta in &[1e-9, 1e-4, 0.1, 0.46, 0.47, 1.0, 1.6, 2.5, 3.0] {
                let got = edge_excess(c, c1, k2, theta);
                let tb = B::from(theta);
                let exact = B::atan2(&(&cb * tb.sin()), &tb.cos()) - &cb * &tb;
                let err = exact.rel_err(got);
                assert!(
                    err < 8e-15,
                    "ι {iota} θ {theta}: {got} vs {}: {err:e}",
                    exact.to_f64()
                );
            }
        }
    }
}
