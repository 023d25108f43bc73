//! Lambert's polygon formula relative to the polygon's centre, so that a
//! polygon far away (distance D, size ℓ) keeps its digits.
//!
//! Lambert (1760): 2P = |n · Σᵢ Θᵢ ĝᵢ|, ĝᵢ = unit(Rᵢ × Rᵢ₊₁), Θᵢ the angle
//! between Rᵢ = vᵢ − p and Rᵢ₊₁. Written with the centre c (C = c − p,
//! D = |C|, aᵢ = vᵢ − c, eᵢ = aᵢ₊₁ − aᵢ), using
//! Rᵢ × Rᵢ₊₁ = C × eᵢ + aᵢ × aᵢ₊₁ and κᵢ = Θᵢ/sin Θᵢ:
//!
//! Θᵢ ĝᵢ = κᵢ (C × eᵢ + aᵢ × aᵢ₊₁)/(|Rᵢ||Rᵢ₊₁|).
//!
//! Since Σᵢ eᵢ = 0 around the closed polygon, Σᵢ (C × eᵢ)/D² = 0, and
//! subtracting it term by term gives
//!
//! Σᵢ Θᵢ ĝᵢ = Σᵢ [ βᵢ (C × eᵢ) + κᵢ (aᵢ × aᵢ₊₁)/(|Rᵢ||Rᵢ₊₁|) ],
//! βᵢ = κᵢ/(|Rᵢ||Rᵢ₊₁|) − 1/D²,
//!
//! whose terms are of the size of the result, (ℓ/D)², instead of ℓ/D: the
//! textbook sum loses log₁₀(D/ℓ) digits to cancellation, this one none.
//! βᵢ is formed without cancellation: with δᵢ = |Rᵢ|² − D² = aᵢ·(2C + aᵢ),
//! 1/(|Rᵢ||Rᵢ₊₁|) − 1/D² = (D² − |Rᵢ||Rᵢ₊₁|)/(D²|Rᵢ||Rᵢ₊₁|) and
//! D² − |Rᵢ||Rᵢ₊₁| = −(D²(δᵢ + δᵢ₊₁) + δᵢδᵢ₊₁)/(D² + |Rᵢ||Rᵢ₊₁|);
//! κᵢ − 1 = (Θᵢ − sin Θᵢ)/sin Θᵢ by the series of the cap module.
//!
//! The geometry is held relative to c throughout: the aᵢ (exact to
//! rounding at the polygon's own scale) and one C, so rounding C moves
//! the whole polygon rigidly by ε D (a relative change ε of P), while
//! rounding each vᵢ − p separately, as the textbook sum does, distorts the
//! polygon by ε D, a relative change ε D/ℓ. The clipping at the receiver's
//! plane is done in the same coordinates (heights n·C + n·aᵢ).
//!
//! When p is close to the polygon (D < ℓ) the subtraction would bring large
//! terms in, and the plain sum (with Rᵢ = C + aᵢ) is used; there it has no
//! far-field cancellation.

use super::cap::v_minus_sin;
use glam::DVec3;

/// The projected solid angle (sr) of the part of the convex polygon
/// `vertices` above the plane through `p` with unit normal `n`.
pub(crate) fn projected_solid_angle(p: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    let k = vertices.len();
    let centre = vertices.iter().fold(DVec3::ZERO, |s, &v| s + v) / k as f64;
    let big_c = centre - p;
    let a: Vec<DVec3> = vertices.iter().map(|&v| v - centre).collect();
    // Clip (Sutherland–Hodgman) in centre-relative coordinates.
    let h0 = n.dot(big_c);
    let mut clipped = Vec::with_capacity(k + 1);
    for i in 0..k {
        let (x, y) = (a[i], a[(i + 1) % k]);
        let (dx, dy) = (h0 + n.dot(x), h0 + n.dot(y));
        if dx >= 0.0 {
            clipped.push(x);
        }
        if (dx > 0.0 && dy < 0.0) || (dx < 0.0 && dy > 0.0) {
            clipped.push(x + (y - x) * (dx / (dx - dy)));
        }
    }
    let k = clipped.len();
    if k < 3 {
        return 0.0;
    }
    // Re-centre on the clipped polygon.
    let shift = clipped.iter().fold(DVec3::ZERO, |s, &v| s + v) / k as f64;
    let big_c = big_c + shift;
    let a: Vec<DVec3> = clipped.iter().map(|&v| v - shift).collect();
    let size = a.iter().fold(0.0f64, |s, v| s.max(v.length()));
    let d2 = big_c.length_squared();
    let far = d2 >= size * size;
    let mut sum = DVec3::ZERO;
    let mut comp = DVec3::ZERO;
    for i in 0..k {
        let (ai, aj) = (a[i], a[(i + 1) % k]);
        let e = aj - ai;
        let ce = big_c.cross(e);
        let cross = ce + ai.cross(aj);
        let len = cross.length();
        if !(len > 0.0) {
            continue;
        }
        let dot = d2 + big_c.dot(ai + aj) + ai.dot(aj);
        let theta = len.atan2(dot);
        let term = if far {
            let di = ai.dot(2.0 * big_c + ai);
            let dj = aj.dot(2.0 * big_c + aj);
            let rr = ((d2 + di) * (d2 + dj)).sqrt();
            let sin_theta = len / rr;
            let kappa_minus_1 = v_minus_sin(theta) / sin_theta;
            let inv_diff = -(d2 * (di + dj) + di * dj) / ((d2 + rr) * d2 * rr);
            let beta = kappa_minus_1 / rr + inv_diff;
            let kappa = 1.0 + kappa_minus_1;
            ce * beta + ai.cross(aj) * (kappa / rr)
        } else {
            cross * (theta / len)
        };
        // Neumaier summation, per component.
        let t = sum + term;
        let big = sum.abs().cmpge(term.abs());
        comp += DVec3::select(big, (sum - t) + term, (term - t) + sum);
        sum = t;
    }
    0.5 * n.dot(sum + comp).abs()
}
