//! Which cosine-hemisphere samples may see a cone, decided from the unit
//! square before the warp: a conservative test that lets cone MIS skip the
//! cosine half's warp (a division, two sine polynomials, a square root)
//! for whole vectors of samples that all miss.
//!
//! The cosine-hemisphere warp (Shirley & Chiu 1997's concentric map, then
//! z = √(1 − r²)) sends `u` to the direction of polar angle asin r and
//! azimuth φ, where, with `a = 2u_x − 1`, `b = 2u_y − 1`:
//!
//! * `r = max(|a|, |b|)`, the larger coordinate's magnitude;
//! * in each of the four wedges (which of `a`, `b` is larger, and its
//!   sign) φ is an affine, monotone function of `t = num/den ∈ [−1, 1]`,
//!   the smaller coordinate over the larger: φ = (π/4)t, π/2 − (π/4)t,
//!   π + (π/4)t or 3π/2 − (π/4)t.
//!
//! A direction within angle β of an axis at polar angle θ_a and azimuth
//! φ_a has polar angle in [θ_a − β, θ_a + β] (a ring of `r`), and, when
//! the cone contains neither pole (β < θ_a < π − β), azimuth within
//! asin(sin β / sin θ_a) of φ_a (a window of `t` per wedge). Both tests
//! are a few multiplies and comparisons on `(a, b)`, with no division:
//! `t ∈ [lo, hi]` is `num′ ∈ [lo·r, hi·r]` with `num′ = num·sign(den)`.
//!
//! The angle β is the cone's, from the test the estimator applies,
//! `|ω − axis|² ≤ rim`, widened so that no direction that test can accept
//! fails this one: the chord bound gets an absolute `64ε` (the computed
//! |ω − axis|² carries a few ulps of unit-length terms), and the angles a
//! margin of `16√ε` radians, far above the error of the warp's sine
//! polynomials, its division and its square root (a few ulps each).

use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The t-interval of each wedge and the ring of radii (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct CosineWindow {
    /// Radii below this cannot see the cone.
    r_lo: f64,
    /// Radii above this cannot see the cone (2 when there is no bound).
    r_hi: f64,
    /// `[lo, hi]` of t per wedge: a wins with den ≥ 0, b wins with den ≥ 0,
    /// a wins with den < 0, b wins with den < 0 (an empty wedge has
    /// lo > hi).
    t: [[f64; 2]; 4],
}

/// The wedges' azimuths: φ = base + direction·(π/4)·t.
const WEDGES: [(f64, f64); 4] = [
    (0.0, 1.0),
    (FRAC_PI_2, -1.0),
    (PI, 1.0),
    (3.0 * FRAC_PI_2, -1.0),
];

impl CosineWindow {
    /// The window of the cone `|ω − axis|² ≤ rim`, `axis` in the
    /// receiver's frame (z its normal), for the f64 warp.
    pub(super) fn new(axis: DVec3, rim: f64) -> Self {
        let epsilon = f64::EPSILON;
        let margin = 16.0 * epsilon.sqrt();
        let chord = (rim.max(0.0) + 64.0 * epsilon).sqrt();
        let beta = 2.0 * (chord / 2.0).min(1.0).asin() + margin;
        let theta_a = axis.truncate().length().atan2(axis.z);
        let phi_a = axis.y.atan2(axis.x);
        let r_lo = (theta_a - beta).max(0.0).sin();
        let r_hi = if theta_a + beta >= FRAC_PI_2 {
            2.0
        } else {
            (theta_a + beta).sin()
        };
        let every = [[-2.0, 2.0]; 4];
        if !(beta < theta_a && beta < PI - theta_a) {
            // The cone holds a pole (or the bound is not finite): any azimuth.
            return CosineWindow {
                r_lo,
                r_hi,
                t: every,
            };
        }
        let half = (beta.sin() / theta_a.sin()).asin() + margin;
        if !(half < PI) {
            return CosineWindow {
                r_lo,
                r_hi,
                t: every,
            };
        }
        let mut t = [[2.0f64, -2.0]; 4];
        for (bounds, (base, direction)) in t.iter_mut().zip(WEDGES) {
            let (from, to) = (base - FRAC_PI_4, base + FRAC_PI_4);
            for turn in [-2.0 * PI, 0.0, 2.0 * PI] {
                let (lo, hi) = (from.max(phi_a + turn - half), to.min(phi_a + turn + half));
                if lo <= hi {
                    // φ ↦ t is affine: t = direction·(φ − base)/(π/4).
                    let (t0, t1) = (
                        direction * (lo - base) / FRAC_PI_4,
                        direction * (hi - base) / FRAC_PI_4,
                    );
                    bounds[0] = bounds[0].min(t0.min(t1));
                    bounds[1] = bounds[1].max(t0.max(t1));
                }
            }
        }
        CosineWindow { r_lo, r_hi, t }
    }

    /// False only if the cosine-hemisphere direction of `u` cannot see the
    /// cone (module docs).
    #[inline(always)]
    pub(super) fn may_see(&self, u: DVec2) -> bool {
        let a = 2.0 * u.x - 1.0;
        let b = 2.0 * u.y - 1.0;
        let a_wins = a.abs() > b.abs();
        let (num, den) = if a_wins { (b, a) } else { (a, b) };
        // den = −0 only at r = 0, where every wedge passes the azimuth
        // test (num = 0 against lo·0 and hi·0).
        let negative = den < 0.0;
        let r = den.abs();
        let num = if negative { -num } else { num };
        // Every wedge's test, masked by whether the sample lies in it:
        // choosing the wedge's bounds by selects compiled to a lookup by
        // lane (eight scalar loads per vector).
        let within = |[lo, hi]: [f64; 2]| (num >= lo * r) & (num <= hi * r);
        let [t0, t1, t2, t3] = self.t;
        let azimuth = (a_wins & !negative & within(t0))
            | (!a_wins & !negative & within(t1))
            | (a_wins & negative & within(t2))
            | (!a_wins & negative & within(t3));
        (r >= self.r_lo) & (r <= self.r_hi) & azimuth
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_sampling::f64::sample_cosine_hemisphere;

    /// Every u of a fine grid (and the square's edges) whose direction the
    /// cone test accepts passes the window, for cones of every size, near
    /// the normal, at the horizon, below it, and straddling the azimuth
    /// ±π seam; and the window rejects most of the square for the small
    /// ones (else it would save nothing).
    #[test]
    fn no_direction_inside_the_cone_fails_the_window() {
        let axes = [
            DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6),
            DVec3::new(-0.9, 0.01, 0.2),
            DVec3::new(-0.9, -0.01, 0.2),
            DVec3::new(0.3, 0.4, 0.1),
            DVec3::new(0.2, -0.7, -0.1),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(0.01, 0.0, 1.0),
            DVec3::new(0.0, -1.0, 0.0),
        ];
        let steps = 600u32;
        for axis in axes.map(DVec3::normalize) {
            for theta_max in [1e-3f64, 0.05, 0.1, 0.5, 1.2, 2.5] {
                let rim = 2.0 * (1.0 - theta_max.cos()) * (1.0 + 8.0 * f64::EPSILON);
                let window = CosineWindow::new(axis, rim);
                let (mut inside, mut passed) = (0usize, 0usize);
                for i in 0..=steps {
                    for j in 0..=steps {
                        let u = DVec2::new(f64::from(i), f64::from(j)) / f64::from(steps);
                        let u = u.min(DVec2::splat(1.0 - f64::EPSILON / 2.0));
                        let w = sample_cosine_hemisphere(u);
                        let sees = (w - axis).length_squared() <= rim;
                        let may = window.may_see(u);
                        assert!(may || !sees, "axis {axis} θ {theta_max} u {u}");
                        inside += usize::from(sees);
                        passed += usize::from(may);
                    }
                }
                let total = ((steps + 1) * (steps + 1)) as usize;
                if theta_max <= 0.1 && axis.z > 0.15 && axis.z < 0.99 {
                    assert!(passed * 10 < total, "axis {axis} θ {theta_max}: {passed}");
                }
                assert!(passed >= inside);
            }
        }
    }

    /// Samples drawn right at a small cone's rim, where the window is
    /// tightest: every one the cone test accepts passes.
    #[test]
    fn the_rim_of_a_small_cone_passes() {
        use lambert_sampling::f64::invert_cosine_hemisphere;
        let axis = DVec3::new(0.5, -0.2, 0.8).normalize();
        let theta_max = 0.01f64;
        let rim = 2.0 * (1.0 - theta_max.cos()) * (1.0 + 8.0 * f64::EPSILON);
        let window = CosineWindow::new(axis, rim);
        let frame = lambert_geometry::f64::Frame::from_normal(axis);
        let mut accepted = 0;
        for k in 0..10_000 {
            let phi = f64::from(k) * 2.0 * PI / 10_000.0;
            for theta in [theta_max * (1.0 - 1e-12), theta_max] {
                let local = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let u = invert_cosine_hemisphere(frame.from_local(local));
                let w = sample_cosine_hemisphere(u);
                if (w - axis).length_squared() <= rim {
                    accepted += 1;
                    assert!(window.may_see(u), "φ {phi} θ {theta} u {u}");
                }
            }
        }
        assert!(accepted > 10_000, "{accepted}");
    }

    /// Negative control: a window built for another axis rejects samples
    /// that see this cone, so the tests above can fail.
    #[test]
    fn a_window_for_another_axis_rejects_the_cone() {
        let axis = DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6);
        let rim = 2.0 * (1.0 - 0.1f64.cos());
        let wrong = CosineWindow::new(DVec3::new(-0.5, 0.0, 0.866_025_403_784_438_6), rim);
        let u = lambert_sampling::f64::invert_cosine_hemisphere(axis);
        assert!(CosineWindow::new(axis, rim).may_see(u));
        assert!(!wrong.may_see(u));
    }
}
