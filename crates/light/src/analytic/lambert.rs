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
//!
//! # Polygons low over the horizon
//! The centred sum's terms are of the size of the solid angle Ω, its
//! result of the size of Ω sin ε (ε the elevation): a polygon clipped by
//! the horizon to a sliver, or lying just above it, cancels (a sliver of
//! height h relative to its size loses 2 log₁₀(1/h) digits). There the
//! contour integral of sin²ε dφ (module `sin2_contour`) has no such
//! cancellation; its terms need the vertices' heights n·(vᵢ − p) to
//! relative precision, however small they are next to |vᵢ − p|. Both
//! forms report their cancellation factor κ = Σ|termᵢ| / |Σ termᵢ| (the
//! factor by which rounding errors of relative size ε in the terms are
//! amplified): when the centred sum's κ exceeds 8, the sin² form is
//! evaluated too and the one with the smaller κ is kept if that κ is at
//! most 64.
//!
//! # When both cancel
//! A far polygon at a grazing elevation ε, between its angular size a
//! and one radian, cancels in both forms, by 1/ε and by ε/a (≈ 1e6 for
//! a = 1e-12 at ε = 1e-6), and so does a polygon seen nearly edge-on (its projected
//! solid angle ∝ the receiver's height δ over its plane, the terms not).
//! There the centred sum is evaluated again in double-double throughout
//! (positions relative to the centre and the centre relative to p
//! exactly, clipping with the exact heights; 106-bit arithmetic, atan2 and
//! the series of θ − sin θ), so its error is ~u²κ (u² ≈ 1.2e-32): ≤ 1e-14
//! on the swept classes except a polygon in a plane parallel to the
//! receiver's seen at a grazing angle δ, where κ ≈ 1/δ² (measured 2.6e-12
//! at δ = 1e-10). Cost ~2–3 µs per edge, only for those configurations.
//!
//! # Heights and clipping
//! The heights n·(vᵢ − p) are first formed in f64 (n·C + n·aᵢ) with a
//! bound on their error, 16ε(|C| + |aᵢ|). When every vertex is above the
//! horizon by more than its bound, no clipping is needed and nothing more
//! is computed; when every vertex is below, the result is 0. Otherwise the
//! heights are computed exactly (an exact dot product rounded to a
//! double-double, module `exact_sum`), so that which vertices are above,
//! where the edges cross the horizon (at the fraction zᵢ/(zᵢ − zⱼ) of the
//! edge) and the heights of the sliver left above are exact to rounding,
//! whatever the polygon's distance: rounding n·(vᵢ − p) in f64 would move
//! the horizon by ε|vᵢ − p| across the polygon.

use super::cap::v_minus_sin;
use super::dd_vector::Dd3;
use super::double_double::{self, Dd};
use super::exact_sum;
use super::sin2_contour::{self, LowEdge, LowVertex};
use glam::DVec3;

/// The centred sum's cancellation factor above which the sin² form is
/// tried as well.
const TRY_SIN2_ABOVE: f64 = 8.0;

/// The cancellation factor up to which the better of the two f64 forms is
/// kept (its error is then below ~64 · 10 rounding errors, 7e-14); beyond,
/// the centred sum is redone in double-double.
const ACCEPT_F64_UP_TO: f64 = 64.0;

/// The projected solid angle (sr) of the part of the convex polygon
/// `vertices` above the plane through `p` with unit normal `n`. Lengths
/// scaled so that coordinates are at most 1 in magnitude.
pub(crate) fn projected_solid_angle(p: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    let k = vertices.len();
    let centre = vertices.iter().fold(DVec3::ZERO, |s, &v| s + v) / k as f64;
    let big_c = centre - p;
    let a: Vec<DVec3> = vertices.iter().map(|&v| v - centre).collect();
    // f64 heights and their error bounds: decide when that is safe.
    let h0 = n.dot(big_c);
    let (mut all_above, mut all_below) = (true, true);
    for &ai in &a {
        let z = h0 + n.dot(ai);
        let bound = 16.0 * f64::EPSILON * (big_c.length() + ai.length());
        all_above &= z > bound;
        all_below &= z < -bound;
    }
    if all_below {
        return 0.0;
    }
    let exact_heights = |vs: &[DVec3]| -> Vec<Dd> {
        vs.iter()
            .map(|&v| exact_sum::dot_of_difference(n, v, p))
            .collect()
    };
    // The vertices' exact heights when the polygon may be clipped, and the
    // visible polygon (centre-relative) with its heights.
    let vertex_heights = (!all_above).then(|| exact_heights(vertices));
    let (clipped, clipped_heights) = match &vertex_heights {
        None => (a, None),
        Some(z) => {
            let (c, zc) = clip(&a, z);
            (c, Some(zc))
        }
    };
    if clipped.len() < 3 {
        return 0.0;
    }
    let (lambert, kappa) = centred_sum(big_c, n, &clipped);
    if kappa <= TRY_SIN2_ABOVE {
        return lambert;
    }
    let heights = clipped_heights.unwrap_or_else(|| exact_heights(vertices));
    // The f64 form with the smaller cancellation, when it cancels little.
    let (best, best_kappa) = match low_sum(big_c, n, &clipped, &heights) {
        Some((low, low_kappa)) if low_kappa < kappa => (low, low_kappa),
        _ => (lambert, kappa),
    };
    if best_kappa <= ACCEPT_F64_UP_TO {
        return best;
    }
    // Both forms cancel (a far polygon at a grazing elevation, one seen
    // nearly edge-on): the centred sum again, in double-double, clipped
    // with the vertices' exact heights.
    centred_sum_dd(centre, p, n, vertices, vertex_heights.as_deref())
}

/// Sutherland–Hodgman clipping against the receiver's plane with exact
/// heights: the visible polygon (centre-relative positions) and its
/// heights (0 at the cut points).
pub(crate) fn clip(a: &[DVec3], z: &[Dd]) -> (Vec<DVec3>, Vec<Dd>) {
    let k = a.len();
    let (mut out, mut heights) = (Vec::with_capacity(k + 1), Vec::with_capacity(k + 1));
    for i in 0..k {
        let j = (i + 1) % k;
        let (zx, zy) = (z[i], z[j]);
        if zx.hi >= 0.0 {
            out.push(a[i]);
            heights.push(zx);
        }
        if (zx.hi > 0.0 && zy.hi < 0.0) || (zx.hi < 0.0 && zy.hi > 0.0) {
            let t = zx.hi / (zx - zy).hi;
            out.push(a[i] + (a[j] - a[i]) * t);
            heights.push(Dd::ZERO);
        }
    }
    (out, heights)
}

/// The sin² contour form over the visible polygon (module docs): its
/// value and cancellation factor, or `None` where it does not apply.
fn low_sum(big_c: DVec3, n: DVec3, a: &[DVec3], z: &[Dd]) -> Option<(f64, f64)> {
    let (t1, t2) = n.any_orthonormal_pair();
    let flat = |v: DVec3| DVec3::new(t1.dot(v), t2.dot(v), 0.0);
    let hc = flat(big_c);
    let k = a.len();
    let vertices: Vec<LowVertex> = (0..k)
        .map(|i| LowVertex {
            h: hc + flat(a[i]),
            z: z[i].to_f64(),
        })
        .collect();
    let edges: Vec<LowEdge> = (0..k)
        .map(|i| {
            let j = (i + 1) % k;
            LowEdge {
                dh: flat(a[j] - a[i]),
                dz: (z[j] - z[i]).to_f64(),
            }
        })
        .collect();
    sin2_contour::projected_solid_angle(&vertices, &edges)
}

/// Lambert's sum relative to the visible polygon's centre (module docs):
/// (P, κ) with κ = Σ|termᵢ| / |n·Σ termᵢ| (the terms' rounding is
/// relative to their length, and n·Σ may be much smaller than the sum's
/// length: a polygon low over the horizon).
fn centred_sum(big_c: DVec3, n: DVec3, clipped: &[DVec3]) -> (f64, f64) {
    let k = clipped.len();
    // Re-centre on the clipped polygon.
    let shift = clipped.iter().fold(DVec3::ZERO, |s, &v| s + v) / k as f64;
    let big_c = big_c + shift;
    let a: Vec<DVec3> = clipped.iter().map(|&v| v - shift).collect();
    let size = a.iter().fold(0.0f64, |s, v| s.max(v.length()));
    let d2 = big_c.length_squared();
    let far = d2 >= size * size;
    let mut sum = DVec3::ZERO;
    let mut comp = DVec3::ZERO;
    let mut abs_sum = 0.0f64;
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
            let (first, second) = (ce * beta, ai.cross(aj) * (kappa / rr));
            abs_sum += first.length() + second.length();
            first + second
        } else {
            abs_sum += theta;
            cross * (theta / len)
        };
        // Neumaier summation, per component.
        let t = sum + term;
        let big = sum.abs().cmpge(term.abs());
        comp += DVec3::select(big, (sum - t) + term, (term - t) + sum);
        sum = t;
    }
    let total = n.dot(sum + comp);
    let kappa = if total != 0.0 {
        abs_sum / total.abs()
    } else {
        f64::INFINITY
    };
    (0.5 * total.abs(), kappa)
}

/// Lambert's centred sum in double-double throughout, for the polygons on
/// which both f64 forms cancel: the vertices relative to the f64 point
/// `centre` and the centre relative to `p`, exactly (TwoSum), clipped with
/// the exact `heights` (when given) at fractions zᵢ/(zᵢ − zⱼ) in
/// double-double, then the sum of [`centred_sum`] with every operation in
/// double-double. Its error is ~u²κ (u² ≈ 1.2e-32): 1e-16 at κ = 1e16.
/// Cost ~2–3 µs per edge.
fn centred_sum_dd(
    centre: DVec3,
    p: DVec3,
    n: DVec3,
    vertices: &[DVec3],
    heights: Option<&[Dd]>,
) -> f64 {
    let k = vertices.len();
    let a: Vec<Dd3> = vertices
        .iter()
        .map(|&v| Dd3::difference(v, centre))
        .collect();
    let visible: Vec<Dd3> = match heights {
        None => a,
        Some(z) => {
            let mut out = Vec::with_capacity(k + 1);
            for i in 0..k {
                let j = (i + 1) % k;
                if z[i].hi >= 0.0 {
                    out.push(a[i]);
                }
                if (z[i].hi > 0.0 && z[j].hi < 0.0) || (z[i].hi < 0.0 && z[j].hi > 0.0) {
                    let t = z[i] / (z[i] - z[j]);
                    out.push(a[i] + (a[j] - a[i]).scale(t));
                }
            }
            out
        }
    };
    let k = visible.len();
    if k < 3 {
        return 0.0;
    }
    let shift = visible
        .iter()
        .fold(Dd3::ZERO, |s, &v| s + v)
        .scale(Dd::ONE.div_f64(k as f64));
    let big_c = Dd3::difference(centre, p) + shift;
    let a: Vec<Dd3> = visible.iter().map(|&v| v - shift).collect();
    let size = a.iter().fold(0.0f64, |s, v| s.max(v.length().hi));
    let d2 = big_c.dot(big_c);
    let far = d2.hi >= size * size;
    let two_c = big_c.scale(Dd::from(2.0));
    let mut sum = Dd3::ZERO;
    for i in 0..k {
        let (ai, aj) = (a[i], a[(i + 1) % k]);
        let ce = big_c.cross(aj - ai);
        let axa = ai.cross(aj);
        let cross = ce + axa;
        let len = cross.length();
        if !(len.hi > 0.0) {
            continue;
        }
        let dot = d2 + big_c.dot(ai + aj) + ai.dot(aj);
        let theta = Dd::atan2(len, dot);
        let term = if far {
            let di = ai.dot(two_c + ai);
            let dj = aj.dot(two_c + aj);
            let rr = ((d2 + di) * (d2 + dj)).sqrt();
            let kappa_minus_1 = double_double::v_minus_sin(theta) / (len / rr);
            let inv_diff = -(d2 * (di + dj) + di * dj) / ((d2 + rr) * d2 * rr);
            let beta = kappa_minus_1 / rr + inv_diff;
            ce.scale(beta) + axa.scale((Dd::ONE + kappa_minus_1) / rr)
        } else {
            cross.scale(theta / len)
        };
        sum = sum + term;
    }
    0.5 * Dd3::from_f64(n).dot(sum).abs().to_f64()
}
