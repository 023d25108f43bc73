//! A prototype of Arvo's projected-solid-angle sampling of spherical
//! polygons (J. Arvo, "Stratified sampling of 2-manifolds", SIGGRAPH 2001
//! course notes), written here only to measure it against
//! `lambert_sampling::f64::ProjectedPolygon` (Peters 2021's sector
//! decomposition), which the sampling crate chose: cost per sample (bench
//! `projected`) and accuracy (the tests below). f64 only; not a library
//! sampler.
//!
//! The polygon (unit vertex directions, counter-clockwise seen from the
//! receiver looking out, above the horizon) is fanned into triangles from
//! vertex 0; a triangle is picked with probability ∝ its projected solid
//! angle Φ, Lambert's sum ½ Σₑ Θₑ (n·m̂ₑ). In the triangle (A, B, C), the
//! point Cₛ at arc length s from A along AC bounds the sub-triangle
//! (A, B, Cₛ); Φ(A, B, Cₛ) = u₀ Φ is solved for s by Newton's method, with
//! dΦ/ds = (sin γₛ / sin ℓ)·[n_B sin²ℓ/2 + n_D (ℓ − sin ℓ cos ℓ)/2] (γₛ the
//! angle at Cₛ, ℓ the arc BCₛ, D the unit tangent at B toward Cₛ,
//! n_B = n·B, n_D = n·D). Then the point at arc length t from B on BCₛ has
//! the density ∝ (n_B cos t + n_D sin t) sin t, whose CDF
//! G(t) ∝ n_B sin²t/2 + n_D (t − sin t cos t)/2 is inverted by Newton's
//! method again.

use glam::{DVec2, DVec3};

/// Projected solid angle of the spherical triangle (a, b, c) (unit vectors,
/// counter-clockwise) for the normal +z: Lambert's formula.
pub fn lambert_triangle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    lambert_with_scale(a, b, c).0
}

/// Lambert's formula and the sum of the absolute values of its terms (which
/// bounds its rounding error).
fn lambert_with_scale(a: DVec3, b: DVec3, c: DVec3) -> (f64, f64) {
    let edge = |p: DVec3, q: DVec3| {
        let m = p.cross(q);
        let len = m.length();
        if len == 0.0 {
            return 0.0;
        }
        len.atan2(p.dot(q)) * m.z / len
    };
    let (x, y, z) = (edge(a, b), edge(b, c), edge(c, a));
    (0.5 * (x + y + z), 0.5 * (x.abs() + y.abs() + z.abs()))
}

/// The prototype, prepared for one polygon seen from the origin with
/// normal +z.
pub struct Arvo {
    vertices: Vec<DVec3>,
    /// Cumulative projected solid angles of the fan triangles.
    cumulative: Vec<f64>,
}

/// Newton steps of the two inversions, for the statistics of the tests.
#[derive(Clone, Copy, Debug, Default)]
pub struct ArvoSteps {
    /// Steps of the sub-triangle inversion.
    pub outer: usize,
    /// Steps of the arc inversion.
    pub inner: usize,
    /// |Φ(A, B, Cₛ) − target| at the end of the first inversion, over Φ.
    pub backward_error: f64,
}

impl Arvo {
    /// Prepares the polygon with `vertices` (points seen from the origin,
    /// counter-clockwise seen from the origin looking out, above z = 0).
    pub fn new(vertices: &[DVec3]) -> Self {
        let vertices: Vec<DVec3> = vertices.iter().map(|v| v.normalize()).collect();
        let mut cumulative = Vec::new();
        let mut total = 0.0;
        for i in 1..vertices.len() - 1 {
            total += lambert_triangle(vertices[0], vertices[i], vertices[i + 1]);
            cumulative.push(total);
        }
        Arvo {
            vertices,
            cumulative,
        }
    }

    /// Φ of the whole polygon (Lambert's formula per fan triangle).
    pub fn projected_solid_angle(&self) -> f64 {
        *self.cumulative.last().unwrap()
    }

    /// A direction with density cos θ/Φ, and the iteration statistics.
    pub fn sample(&self, u: DVec2) -> (DVec3, ArvoSteps) {
        let mut steps = ArvoSteps::default();
        let total = self.projected_solid_angle();
        let target = u.x * total;
        let k = self
            .cumulative
            .iter()
            .position(|&c| target <= c)
            .unwrap_or(self.cumulative.len() - 1);
        let before = if k > 0 { self.cumulative[k - 1] } else { 0.0 };
        let phi_t = self.cumulative[k] - before;
        let target = (target - before).clamp(0.0, phi_t);
        let (a, b, c) = (self.vertices[0], self.vertices[k + 1], self.vertices[k + 2]);
        // Arc AC: C_s = cos s A + sin s T.
        let arc_ac = a.cross(c).length().atan2(a.dot(c));
        let t_ac = (c - a * a.dot(c)).normalize();
        let point = |s: f64| a * s.cos() + t_ac * s.sin();
        let n = DVec3::Z;
        // The fan from B toward C_s: tangent D, arc ℓ, and the integral
        // I(ℓ) = n_B sin²ℓ/2 + n_D (ℓ − sin ℓ cos ℓ)/2.
        let fan = |cs: DVec3| {
            let ell = b.cross(cs).length().atan2(b.dot(cs));
            let d = (cs - b * b.dot(cs)).normalize_or_zero();
            let (nb, nd) = (n.dot(b), n.dot(d));
            let (sl, cl) = ell.sin_cos();
            (
                ell,
                d,
                nb,
                nd,
                nb * sl * sl / 2.0 + nd * (ell - sl * cl) / 2.0,
            )
        };
        let mut s = arc_ac * u.x.clamp(0.0, 1.0);
        let (mut lo, mut hi) = (0.0, arc_ac);
        let mut previous = f64::INFINITY;
        for _ in 0..64 {
            steps.outer += 1;
            let cs = point(s);
            let (area, scale) = lambert_with_scale(a, b, cs);
            let f = area - target;
            steps.backward_error = f.abs() / total;
            // Stop at the rounding floor of Lambert's sum, or when the
            // residual stops halving (Lambert's terms from nearly parallel
            // unit vectors carry more than that floor for small triangles).
            if f.abs() <= 8.0 * f64::EPSILON * (scale + target)
                || (steps.outer > 2 && f.abs() > 0.5 * previous)
            {
                break;
            }
            previous = f.abs();
            if f > 0.0 {
                hi = s;
            } else {
                lo = s;
            }
            let (ell, _, _, _, integral) = fan(cs);
            // The angle γ at C_s between the arcs toward A and toward B.
            let to_a = (a - cs * cs.dot(a)).normalize_or_zero();
            let to_b = (b - cs * cs.dot(b)).normalize_or_zero();
            let sin_gamma = to_a.cross(to_b).length();
            let slope = sin_gamma / ell.sin() * integral;
            let step = f / slope;
            let next = s - step;
            s = if slope > 0.0 && next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if step.abs() <= 4.0 * f64::EPSILON * s || hi - lo <= 4.0 * f64::EPSILON * hi {
                break;
            }
        }
        let cs = point(s);
        let (ell, d, nb, nd, whole) = fan(cs);
        let goal = u.y.clamp(0.0, 1.0) * whole;
        // The density ∝ sin t near B: the CDF grows like t², so start from
        // ℓ√u₁.
        let mut t = u.y.clamp(0.0, 1.0).sqrt() * ell;
        let (mut lo, mut hi) = (0.0, ell);
        for _ in 0..64 {
            steps.inner += 1;
            let (st, ct) = t.sin_cos();
            let (first, second) = (nb * st * st / 2.0, nd * (t - st * ct) / 2.0);
            let g = first + second - goal;
            if g.abs() <= 8.0 * f64::EPSILON * (first.abs() + second.abs() + goal) {
                break;
            }
            if g > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let slope = (nb * ct + nd * st) * st;
            let step = g / slope;
            let next = t - step;
            t = if slope > 0.0 && next > lo && next < hi {
                next
            } else {
                0.5 * (lo + hi)
            };
            if step.abs() <= 4.0 * f64::EPSILON * t || hi - lo <= 4.0 * f64::EPSILON * hi {
                break;
            }
        }
        (b * t.cos() + d * t.sin(), steps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_sampling::f64::ProjectedPolygon;

    /// The comparison that the sampling crate's docs report: for a set of
    /// polygons (moderate, non-central, grazing, small and far), Φ from
    /// Lambert's formula against `ProjectedPolygon`'s (which is checked
    /// against independent references in the tests crate), the iteration
    /// counts, and the residual left by each method's iteration (relative
    /// to Φ). Prints the table; asserts only that both sample the polygon.
    #[test]
    fn compare_with_the_sector_method() {
        let cases: [(&str, Vec<DVec3>); 4] = [
            (
                "triangle (central)",
                vec![
                    DVec3::new(-1.0, -1.0, 3.0),
                    DVec3::new(2.0, -0.5, 3.5),
                    DVec3::new(0.0, 1.5, 2.5),
                ],
            ),
            (
                "square (non-central)",
                vec![
                    DVec3::new(0.5, -0.5, 1.0),
                    DVec3::new(1.5, -0.5, 1.0),
                    DVec3::new(1.5, 0.5, 1.0),
                    DVec3::new(0.5, 0.5, 1.0),
                ],
            ),
            (
                "grazing triangle",
                vec![
                    DVec3::new(1.0, 0.0, 0.05),
                    DVec3::new(3.0, 0.0, 0.01),
                    DVec3::new(2.0, 1.0, 0.2),
                ],
            ),
            (
                "small far triangle (3e-5 rad)",
                vec![
                    DVec3::new(2.0, 0.75, 2.5),
                    DVec3::new(2.0001, 0.75, 2.50002),
                    DVec3::new(2.00003, 0.7501, 2.49999),
                ],
            ),
        ];
        for (name, vertices) in cases {
            let polygon = lambert_geometry::f64::ConvexPolygon::new(vertices.clone()).unwrap();
            let ours = ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &polygon).unwrap();
            // Arvo's fan needs the counter-clockwise order seen from the
            // origin looking out.
            let mut v = vertices.clone();
            if (v[1] - v[0]).cross(v[2] - v[0]).dot(v[0]) < 0.0 {
                v.reverse();
            }
            let arvo = Arvo::new(&v);
            let phi_error = (arvo.projected_solid_angle() - ours.projected_solid_angle()).abs()
                / ours.projected_solid_angle();
            let (mut outer, mut inner, mut backward, mut ours_steps) = (0usize, 0usize, 0.0f64, 0);
            let (mut arvo_total, mut ours_total) = (0usize, 0usize);
            let n = 64;
            for i in 0..n {
                for j in 0..n {
                    let u = DVec2::new((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                    let (w, steps) = arvo.sample(u);
                    assert!(
                        ours.pdf(w) > 0.0 || steps.backward_error > 1e-9,
                        "{name}: {w} outside"
                    );
                    outer = outer.max(steps.outer);
                    inner = inner.max(steps.inner);
                    backward = backward.max(steps.backward_error);
                    ours_steps = ours_steps.max(ours.newton_steps(u));
                    arvo_total += steps.outer + steps.inner;
                    ours_total += ours.newton_steps(u);
                }
            }
            let count = (n * n) as f64;
            eprintln!(
                "{name:>30}: Lambert Φ vs ours {phi_error:.1e}; Arvo steps ≤ {outer} + {inner} \
                 (mean {:.1}), residual ≤ {backward:.1e}; ours steps ≤ {ours_steps} (mean {:.1})",
                arvo_total as f64 / count,
                ours_total as f64 / count
            );
        }
    }
}
