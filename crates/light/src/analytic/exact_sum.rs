//! Exact sums and dot products of f64 values, rounded once to a
//! double-double: the heights n·(v − p) of the closed forms, whose true
//! value may be 10⁻²⁴ of the terms it is summed from (a sliver 10⁻¹² of
//! its size high, 10¹² sizes away).
//!
//! A dot product of f64 vectors is a sum of products; each product is
//! split exactly into two f64 (TwoProd), each difference c − p into two
//! (TwoSum), and the resulting terms are accumulated without any error into
//! a nonoverlapping expansion by Shewchuk's Grow-Expansion with zero
//! elimination (J. R. Shewchuk, "Adaptive precision floating-point
//! arithmetic and fast robust geometric predicates", Discrete Comput.
//! Geom. 18, 1997, §2.5). The expansion is the exact sum; it is rounded to
//! a double-double by adding its components from the smallest up (each
//! addition within 2u² of its partial sum, and the partial sums of a
//! nonoverlapping expansion grow geometrically, so the result is within a
//! few u² of the exact sum, relative to the sum itself — however small,
//! unlike Ogita–Rump–Oishi's Dot2, whose error is relative to the terms).
//!
//! Cost: k terms take at most k(k − 1)/2 TwoSums (6 flops each); a height
//! n·(v − p) has 12 terms, ≤ 66 TwoSums, ~0.1–0.2 µs.
//!
//! Exact as long as no product underflows below 2⁻⁹⁶⁹ (callers scale
//! lengths into [½, 1] by a power of two first; a product that small is
//! below 1e-291 of the unit) and nothing overflows.

use super::double_double::{two_prod, two_sum, Dd};
use glam::DVec3;

/// The most terms one exact sum takes.
const MAX_TERMS: usize = 32;

/// Σ terms exactly, rounded to a double-double (relative error a few u²).
///
/// # Panics
/// If more than 32 terms are given (a programming error: the callers'
/// counts are fixed).
pub(crate) fn exact_sum(terms: &[f64]) -> Dd {
    assert!(terms.len() <= MAX_TERMS);
    let mut e = [0.0f64; MAX_TERMS];
    let mut len = 0;
    for &b in terms {
        // Grow-Expansion: add b to the expansion e[..len] (increasing
        // magnitude, nonoverlapping), dropping zero components.
        let mut q = b;
        let mut out = 0;
        for i in 0..len {
            let (s, h) = two_sum(q, e[i]);
            if h != 0.0 {
                e[out] = h;
                out += 1;
            }
            q = s;
        }
        if q != 0.0 {
            e[out] = q;
            out += 1;
        }
        len = out;
    }
    e[..len].iter().fold(Dd::ZERO, |acc, &x| acc.add_f64(x))
}

/// a·b exactly, rounded to a double-double.
pub(crate) fn dot(a: DVec3, b: DVec3) -> Dd {
    let (x, ex) = two_prod(a.x, b.x);
    let (y, ey) = two_prod(a.y, b.y);
    let (z, ez) = two_prod(a.z, b.z);
    exact_sum(&[x, ex, y, ey, z, ez])
}

/// n·(c − p) exactly, rounded to a double-double.
pub(crate) fn dot_of_difference(n: DVec3, c: DVec3, p: DVec3) -> Dd {
    let mut terms = [0.0f64; 12];
    for k in 0..3 {
        let (d, e) = two_sum(c[k], -p[k]);
        let (a, ea) = two_prod(n[k], d);
        let (b, eb) = two_prod(n[k], e);
        terms[4 * k..4 * k + 4].copy_from_slice(&[a, ea, b, eb]);
    }
    exact_sum(&terms)
}

/// a × b exactly, each component rounded to a double-double.
pub(crate) fn cross(a: DVec3, b: DVec3) -> [Dd; 3] {
    let component = |p: f64, q: f64, r: f64, s: f64| {
        let (x, ex) = two_prod(p, q);
        let (y, ey) = two_prod(r, s);
        exact_sum(&[x, ex, -y, -ey])
    };
    [
        component(a.y, b.z, a.z, b.y),
        component(a.z, b.x, a.x, b.z),
        component(a.x, b.y, a.y, b.x),
    ]
}

/// |v| for a vector given as double-doubles (the sum of squares has no
/// cancellation; a few u² relative).
pub(crate) fn length(v: [Dd; 3]) -> Dd {
    (v[0].square() + v[1].square() + v[2].square()).sqrt()
}

/// |v| of an f64 vector, as a double-double.
pub(crate) fn length_f64(v: DVec3) -> Dd {
    length([Dd::from(v.x), Dd::from(v.y), Dd::from(v.z)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::oracle::{B, V};

    fn rel(exact: &B, x: Dd) -> f64 {
        exact.rel_err_dd(x.hi, x.lo)
    }

    /// Sums whose value is 1e-30 … 1e-60 of their terms, and exact zeros,
    /// come out to a few u² of the exact value (1024-bit oracle);
    /// tolerance 8u² ≈ 1e-31.
    #[test]
    fn sums_keep_relative_precision_under_total_cancellation() {
        let third = 1.0f64 / 3.0;
        let cases: Vec<Vec<f64>> = vec![
            vec![1.0, 1e-30, -1.0],
            vec![third, -third, 1e-60, 3e-45],
            vec![1e20, 1.0, -1e20, -1.0],
            vec![0.1, 0.2, -0.3],
            vec![1.5, -0.5, -1.0],
        ];
        for t in cases {
            let exact = t.iter().fold(B::zero(), |s, &x| s + B::from(x));
            let got = exact_sum(&t);
            assert!(rel(&exact, got) < 1e-31, "{t:?}: {got:?}");
        }
        // A dot product with a height 1e-24 of its terms: n·(c − p).
        let n = DVec3::new(0.36, 0.48, 0.8);
        let p = DVec3::new(0.1, -0.7, 0.3);
        let base = DVec3::new(0.6, 0.0, -0.27);
        let c = p + base + DVec3::new(0.0, 0.0, 1e-24);
        let exact = V::from(n).dot(&V::from(c).sub(&V::from(p)));
        assert!(rel(&exact, dot_of_difference(n, c, p)) < 1e-31);
        let [x, y, z] = cross(n, c);
        let e = V::from(n).cross(&V::from(c));
        assert!(rel(&e.0, x) < 1e-31 && rel(&e.1, y) < 1e-31 && rel(&e.2, z) < 1e-31);
        assert!(rel(&V::from(c).dot(&V::from(n)), dot(c, n)) < 1e-31);
    }
}
