//! Which cosine-hemisphere samples may see a cone, decided from the unit
//! square before the warp: a conservative test that lets cone MIS skip the
//! cosine half's warp (a division, two sine polynomials, a square root)
//! for every sample that misses, computing it only for the samples the
//! test lists.
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
//!
//! **The test the kernels run** is not the ring and wedges themselves but
//! the smallest rectangle of the unit square that holds them (in each
//! wedge, the larger coordinate spans the ring's radii and the smaller
//! the wedge's `t·r`): four comparisons of `u` with no arithmetic. For a
//! small cone away from the pole, whose window lies in one wedge, the
//! rectangle is barely larger than the window (on the speed table's
//! sphere, 1.3 % of the square against 1.1 %). Against the ring-and-wedge
//! test, whose eighteen bounds the kernels kept partly on the stack, it
//! measured 0.83× the time of an f32 MIS estimate and 0.86× of an f64
//! one (the same values: it only decides which groups are skipped).
//!
//! The f32 kernel's window ([`CosineWindowF32`]) takes f32's ε in both
//! margins (16√ε ≈ 5.5·10⁻³ rad, against warp errors of a few f32 ulps,
//! about 10⁻⁶) and rounds the rectangle outward to f32; its comparisons
//! are exact.

use glam::{DVec2, DVec3, Vec2};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The window's bounds in f64, for a warp whose precision has machine
/// epsilon `epsilon` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bounds {
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

impl Bounds {
    /// The bounds of the cone `|ω − axis|² ≤ rim`, `axis` in the
    /// receiver's frame (z its normal), for a warp and cone test computed
    /// with machine epsilon `epsilon`: the chord widened by `64·epsilon`,
    /// the angles by `16√epsilon` radians.
    fn new(axis: DVec3, rim: f64, epsilon: f64) -> Self {
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
            return Bounds {
                r_lo,
                r_hi,
                t: every,
            };
        }
        let half = (beta.sin() / theta_a.sin()).asin() + margin;
        if !(half < PI) {
            return Bounds {
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
        Bounds { r_lo, r_hi, t }
    }
}

impl Bounds {
    /// The smallest rectangle of the unit square, `[x, y]` ranges of `u`,
    /// that holds every `u` whose `(a, b)` passes the ring and wedge
    /// tests, widened by `8ε` (ε = 2⁻⁵³) for the rounding of `u ↦ 2u − 1`
    /// and of this computation.
    ///
    /// In a wedge, the larger coordinate is ±r and the smaller ±t·r, so
    /// over `r ∈ [r_lo, min(r_hi, 1)]` and the wedge's `t ∈ [lo, hi]`
    /// (within [−1, 1]) the wedge's part of the window lies in the
    /// rectangle of those ranges; the window's is the union of the four.
    /// An empty window gives an empty rectangle (`x[0] > x[1]`).
    fn u_rectangle(&self) -> [[f64; 2]; 2] {
        let (r0, r1) = (self.r_lo, self.r_hi.min(1.0));
        let mut a = [f64::INFINITY, f64::NEG_INFINITY];
        let mut b = [f64::INFINITY, f64::NEG_INFINITY];
        let cover = |range: &mut [f64; 2], lo: f64, hi: f64| {
            range[0] = range[0].min(lo);
            range[1] = range[1].max(hi);
        };
        for (wedge, [lo, hi]) in self.t.into_iter().enumerate() {
            let (lo, hi) = (lo.max(-1.0), hi.min(1.0));
            if !(lo <= hi && r0 <= r1) {
                continue;
            }
            // The smaller coordinate's range, num′ = t·r (module docs).
            let ends = [lo * r0, lo * r1, hi * r0, hi * r1];
            let n_lo = ends.into_iter().fold(f64::INFINITY, f64::min);
            let n_hi = ends.into_iter().fold(f64::NEG_INFINITY, f64::max);
            match wedge {
                // a wins, a ≥ 0: a = r, b = num′.
                0 => {
                    cover(&mut a, r0, r1);
                    cover(&mut b, n_lo, n_hi);
                }
                // b wins, b ≥ 0: b = r, a = num′.
                1 => {
                    cover(&mut b, r0, r1);
                    cover(&mut a, n_lo, n_hi);
                }
                // a wins, a < 0: a = −r, b = −num′.
                2 => {
                    cover(&mut a, -r1, -r0);
                    cover(&mut b, -n_hi, -n_lo);
                }
                // b wins, b < 0: b = −r, a = −num′.
                _ => {
                    cover(&mut b, -r1, -r0);
                    cover(&mut a, -n_hi, -n_lo);
                }
            }
        }
        let widen = 8.0 * f64::EPSILON / 2.0;
        [a, b].map(|[lo, hi]| [0.5 * (lo + 1.0) - widen, 0.5 * (hi + 1.0) + widen])
    }
}

/// `[lo, hi]` rounded outward to f32 (so that the f32 interval holds the
/// f64 one).
fn outward_f32([lo, hi]: [f64; 2]) -> [f32; 2] {
    let (l, h) = (lo as f32, hi as f32);
    [
        if f64::from(l) > lo { l.next_down() } else { l },
        if f64::from(h) < hi { h.next_up() } else { h },
    ]
}

/// `CosineWindow` (for the f64 warp) and `CosineWindowF32` (for the f32
/// warp, its bounds widened for f32's epsilon and rounded outward).
macro_rules! cosine_window {
    ($name:ident, $real:ident, $v2:ty, $epsilon:expr, $convert:expr) => {
        /// The t-interval of each wedge and the ring of radii (module
        /// docs), for the cosine-hemisphere warp in
        #[doc = concat!("`", stringify!($real), "`.")]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub(super) struct $name {
            /// The range of `u.x` that may see the cone.
            x: [$real; 2],
            /// The range of `u.y` that may see the cone.
            y: [$real; 2],
        }

        impl $name {
            /// The window of the cone `|ω − axis|² ≤ rim`, `axis` in the
            /// receiver's frame (z its normal), for the
            #[doc = concat!("`", stringify!($real), "`")]
            /// warp and cone test.
            pub(super) fn new(axis: DVec3, rim: f64) -> Self {
                let bounds = Bounds::new(axis, rim, $epsilon);
                let [x, y] = bounds.u_rectangle().map($convert);
                $name { x, y }
            }

            /// False only if the cosine-hemisphere direction of `u` cannot
            /// see the cone (module docs).
            #[inline(always)]
            pub(super) fn may_see(&self, u: $v2) -> bool {
                (u.x >= self.x[0]) & (u.x <= self.x[1]) & (u.y >= self.y[0]) & (u.y <= self.y[1])
            }
        }
    };
}

cosine_window!(
    CosineWindow,
    f64,
    DVec2,
    f64::EPSILON,
    |bounds: [f64; 2]| bounds
);
cosine_window!(
    CosineWindowF32,
    f32,
    Vec2,
    f64::from(f32::EPSILON),
    outward_f32
);

impl CosineWindowF32 {
    /// `masks[g]`, bit `k` set iff [`may_see`](Self::may_see) holds for
    /// sample `16g + k`, for the whole groups of sixteen of `ux`, `uy`;
    /// returns how many groups it wrote (`masks` must hold them).
    ///
    /// Why explicit: a mask is four comparisons of a vector and one mask
    /// register with AVX-512 (`vcmpps` into `k`), two `vmovmskps` with AVX2.
    /// The compiler's own form of the scalar loop (bits shifted into an
    /// integer) compared lane by lane and OR-reduced vectors, and it made
    /// the f32 MIS kernel that lists samples by these masks 7 % slower than
    /// the one before it; one lane at a time is the remaining sets' form.
    #[inline(always)]
    pub(super) fn group_masks(&self, ux: &[f32], uy: &[f32], masks: &mut [u16]) -> usize {
        use lambert_sampling::isa::Isa;
        let groups = ux.len().min(uy.len()) / 16;
        let (ux, uy, masks) = (&ux[..16 * groups], &uy[..16 * groups], &mut masks[..groups]);
        let (xs, _) = ux.as_chunks::<16>();
        let (ys, _) = uy.as_chunks::<16>();
        #[cfg(target_arch = "x86_64")]
        {
            use core::arch::x86_64::{__m256, __m512, _CMP_GE_OQ, _CMP_LE_OQ};
            let isa = Isa::selected();
            if isa >= Isa::Avx512 {
                if let Some(simd) = pulp::x86::V4::try_new() {
                    simd.vectorize(
                        #[inline(always)]
                        || {
                            // No closures in here (see `splitmix_avx2::fill_groups_f32`
                            // in lambert-sampling).
                            let f = simd.avx512f;
                            let (x0, x1) =
                                (f._mm512_set1_ps(self.x[0]), f._mm512_set1_ps(self.x[1]));
                            let (y0, y1) =
                                (f._mm512_set1_ps(self.y[0]), f._mm512_set1_ps(self.y[1]));
                            for (mask, (x, y)) in masks.iter_mut().zip(xs.iter().zip(ys)) {
                                let (x, y): (__m512, __m512) = (pulp::cast(*x), pulp::cast(*y));
                                let k = f._mm512_cmp_ps_mask::<_CMP_GE_OQ>(x, x0);
                                let k = f._mm512_mask_cmp_ps_mask::<_CMP_LE_OQ>(k, x, x1);
                                let k = f._mm512_mask_cmp_ps_mask::<_CMP_GE_OQ>(k, y, y0);
                                *mask = f._mm512_mask_cmp_ps_mask::<_CMP_LE_OQ>(k, y, y1);
                            }
                        },
                    );
                    return groups;
                }
            }
            if isa >= Isa::Avx2Fma {
                if let Some(simd) = pulp::x86::V3::try_new() {
                    simd.vectorize(
                        #[inline(always)]
                        || {
                            let a = simd.avx;
                            let (x0, x1) =
                                (a._mm256_set1_ps(self.x[0]), a._mm256_set1_ps(self.x[1]));
                            let (y0, y1) =
                                (a._mm256_set1_ps(self.y[0]), a._mm256_set1_ps(self.y[1]));
                            for (mask, (x, y)) in masks.iter_mut().zip(xs.iter().zip(ys)) {
                                let [xl, xh]: [__m256; 2] = pulp::cast(*x);
                                let [yl, yh]: [__m256; 2] = pulp::cast(*y);
                                let mut bits = 0u16;
                                for (half, (x, y)) in [(xl, yl), (xh, yh)].into_iter().enumerate() {
                                    let inside = a._mm256_and_ps(
                                        a._mm256_and_ps(
                                            a._mm256_cmp_ps::<_CMP_GE_OQ>(x, x0),
                                            a._mm256_cmp_ps::<_CMP_LE_OQ>(x, x1),
                                        ),
                                        a._mm256_and_ps(
                                            a._mm256_cmp_ps::<_CMP_GE_OQ>(y, y0),
                                            a._mm256_cmp_ps::<_CMP_LE_OQ>(y, y1),
                                        ),
                                    );
                                    bits |= (a._mm256_movemask_ps(inside) as u16) << (8 * half);
                                }
                                *mask = bits;
                            }
                        },
                    );
                    return groups;
                }
            }
        }
        for (mask, (x, y)) in masks.iter_mut().zip(xs.iter().zip(ys)) {
            *mask = (0..16).fold(0, |m, k| {
                m | u16::from(self.may_see(Vec2::new(x[k], y[k]))) << k
            });
        }
        groups
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    impl Bounds {
        /// The ring-and-wedge test itself (module docs), which the
        /// rectangle must hold.
        fn ring_and_wedges(&self, u: DVec2) -> bool {
            let (a, b) = (2.0 * u.x - 1.0, 2.0 * u.y - 1.0);
            let a_wins = a.abs() > b.abs();
            let (num, den) = if a_wins { (b, a) } else { (a, b) };
            let negative = den < 0.0;
            let r = den.abs();
            let num = if negative { -num } else { num };
            let within = |[lo, hi]: [f64; 2]| num >= lo * r && num <= hi * r;
            let wedge = usize::from(!a_wins) + 2 * usize::from(negative);
            r >= self.r_lo && r <= self.r_hi && within(self.t[wedge])
        }
    }

    /// Cones of every size, near the normal, at the horizon, below it, and
    /// straddling the azimuth ±π seam: `check(axis, θ_max)` for each.
    fn each_cone(mut check: impl FnMut(DVec3, f64)) {
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
        for axis in axes.map(DVec3::normalize) {
            for theta_max in [1e-3f64, 0.05, 0.1, 0.5, 1.2, 2.5] {
                check(axis, theta_max);
            }
        }
    }

    /// The points of a 601 × 601 grid of the unit square, its edges
    /// included (the top edge at the largest value below 1 of `top`).
    fn grid(top: f64) -> impl Iterator<Item = DVec2> {
        let steps = 600u32;
        (0..=steps).flat_map(move |i| {
            (0..=steps).map(move |j| {
                let u = DVec2::new(f64::from(i), f64::from(j)) / f64::from(steps);
                u.min(DVec2::splat(top))
            })
        })
    }

    /// `(inside, passed, total)` over [`grid`]: how many points `sees`
    /// and `may_see` accept, after asserting that none `sees` accepts
    /// fails `may_see`.
    fn tally(
        top: f64,
        sees: impl Fn(DVec2) -> bool,
        may_see: impl Fn(DVec2) -> bool,
    ) -> (usize, usize, usize) {
        let (mut inside, mut passed, mut total) = (0, 0, 0);
        for u in grid(top) {
            let (s, m) = (sees(u), may_see(u));
            assert!(m || !s, "u {u}");
            inside += usize::from(s);
            passed += usize::from(m);
            total += 1;
        }
        (inside, passed, total)
    }

    /// The rim as the estimator's cone test has it (`ConeMis`).
    fn rim(theta_max: f64, epsilon: f64) -> f64 {
        2.0 * (1.0 - theta_max.cos()) * (1.0 + 8.0 * epsilon)
    }

    /// Every u of the grid whose f64 direction the cone test accepts passes
    /// the f64 window; the window rejects most of the square for the small
    /// cones away from the pole and the horizon (else it would save
    /// nothing).
    #[test]
    fn no_direction_inside_the_cone_fails_the_window() {
        use lambert_sampling::f64::sample_cosine_hemisphere;
        each_cone(|axis, theta_max| {
            let rim = rim(theta_max, f64::EPSILON);
            let window = CosineWindow::new(axis, rim);
            let (inside, passed, total) = tally(
                1.0 - f64::EPSILON / 2.0,
                |u| (sample_cosine_hemisphere(u) - axis).length_squared() <= rim,
                |u| window.may_see(u),
            );
            if theta_max <= 0.1 && axis.z > 0.15 && axis.z < 0.99 {
                assert!(passed * 10 < total, "axis {axis} θ {theta_max}: {passed}");
            }
            assert!(passed >= inside);
        });
    }

    /// The same for the f32 warp, cone test and window, on the grid's
    /// points rounded to f32.
    #[test]
    fn no_f32_direction_inside_the_cone_fails_the_f32_window() {
        use lambert_sampling::f32::sample_cosine_hemisphere;
        each_cone(|axis, theta_max| {
            let axis32 = axis.as_vec3();
            let rim = rim(theta_max, f64::from(f32::EPSILON)) as f32;
            let window = CosineWindowF32::new(axis32.as_dvec3(), f64::from(rim));
            let (inside, passed, total) = tally(
                f64::from(1.0 - f32::EPSILON / 2.0),
                |u| (sample_cosine_hemisphere(u.as_vec2()) - axis32).length_squared() <= rim,
                |u| window.may_see(u.as_vec2()),
            );
            if theta_max <= 0.1 && axis.z > 0.15 && axis.z < 0.99 {
                assert!(passed * 10 < total, "axis {axis} θ {theta_max}: {passed}");
            }
            assert!(passed >= inside);
        });
    }

    /// The rectangle holds the ring-and-wedge window it is built from,
    /// for both precisions' margins.
    #[test]
    fn the_rectangle_holds_the_ring_and_wedges() {
        each_cone(|axis, theta_max| {
            for epsilon in [f64::EPSILON, f64::from(f32::EPSILON)] {
                let bounds = Bounds::new(axis, rim(theta_max, epsilon), epsilon);
                let [x, y] = bounds.u_rectangle();
                let (inside, passed, _) = tally(
                    1.0 - f64::EPSILON / 2.0,
                    |u| bounds.ring_and_wedges(u),
                    |u| u.x >= x[0] && u.x <= x[1] && u.y >= y[0] && u.y <= y[1],
                );
                assert!(passed >= inside);
            }
        });
    }

    /// On the sphere of the speed table (radius 1 at distance 10, 30°
    /// off the normal), the rectangle passes 1.3 % of the square's grid
    /// points and the ring and wedges 1.1 % (the module docs' figures;
    /// asserted to the grid's resolution).
    #[test]
    fn the_speed_table_sphere_passes_about_one_percent() {
        let axis = DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6);
        let theta_max = 0.1f64.asin();
        let bounds = Bounds::new(axis, rim(theta_max, f64::EPSILON), f64::EPSILON);
        let [x, y] = bounds.u_rectangle();
        let (inside, passed, total) = tally(
            1.0 - f64::EPSILON / 2.0,
            |u| bounds.ring_and_wedges(u),
            |u| u.x >= x[0] && u.x <= x[1] && u.y >= y[0] && u.y <= y[1],
        );
        let percent = |n: usize| 100.0 * n as f64 / total as f64;
        assert_eq!(
            (
                format!("{:.1}", percent(passed)),
                format!("{:.1}", percent(inside))
            ),
            ("1.3".to_string(), "1.1".to_string())
        );
    }

    /// The group masks (AVX-512 or AVX2 comparisons where the process
    /// runs them) are the lanes' own tests, bit by bit: on the speed
    /// table's sphere, on a grid of the unit square around the window
    /// that includes the window's four bounds and the floats next to
    /// them, 16 lanes to a group, with a partial group left out. Negative
    /// control: a window for another axis gives other masks.
    #[test]
    fn group_masks_are_the_lanes_tests() {
        let axis = DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6);
        let rim = rim(0.1f64.asin(), f64::from(f32::EPSILON));
        let window = CosineWindowF32::new(axis, rim);
        let mut xs = vec![window.x[0], window.x[1], 0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
        let mut ys = vec![window.y[0], window.y[1], 0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
        for v in [window.x[0], window.x[1]] {
            xs.extend([v.next_down(), v.next_up()]);
        }
        for v in [window.y[0], window.y[1]] {
            ys.extend([v.next_down(), v.next_up()]);
        }
        let (mid_x, mid_y) = (
            0.5 * (window.x[0] + window.x[1]),
            0.5 * (window.y[0] + window.y[1]),
        );
        for k in 0..40 {
            let t = k as f32 / 39.0;
            xs.push(mid_x + (t - 0.5) * 4.0 * (window.x[1] - window.x[0]));
            ys.push(mid_y + (t - 0.5) * 4.0 * (window.y[1] - window.y[0]));
        }
        let (mut ux, mut uy) = (Vec::new(), Vec::new());
        for &x in &xs {
            for &y in &ys {
                ux.push(x);
                uy.push(y);
            }
        }
        ux.truncate(ux.len() / 16 * 16 + 7);
        uy.truncate(ux.len());
        let mut masks = vec![0u16; ux.len() / 16];
        assert_eq!(window.group_masks(&ux, &uy, &mut masks), ux.len() / 16);
        let mut seen = 0;
        for (g, &mask) in masks.iter().enumerate() {
            for k in 0..16 {
                let i = 16 * g + k;
                let want = window.may_see(Vec2::new(ux[i], uy[i]));
                assert_eq!(mask >> k & 1 == 1, want, "sample {i}");
                seen += usize::from(want);
            }
        }
        assert!(
            seen > 100,
            "{seen} samples inside: the grid must cover the window"
        );
        let other = CosineWindowF32::new(DVec3::new(-0.5, 0.0, 0.866_025_403_784_438_6), rim);
        let mut wrong = vec![0u16; masks.len()];
        other.group_masks(&ux, &uy, &mut wrong);
        assert_ne!(wrong, masks);
    }

    /// Samples drawn right at a small cone's rim, where the window is
    /// tightest: every one the cone test accepts passes, in f64 and f32.
    #[test]
    fn the_rim_of_a_small_cone_passes() {
        use lambert_sampling::f64::{invert_cosine_hemisphere, sample_cosine_hemisphere};
        let axis = DVec3::new(0.5, -0.2, 0.8).normalize();
        let theta_max = 0.01f64;
        let rim64 = rim(theta_max, f64::EPSILON);
        let window = CosineWindow::new(axis, rim64);
        let (axis32, rim32) = (
            axis.as_vec3(),
            rim(theta_max, f64::from(f32::EPSILON)) as f32,
        );
        let window32 = CosineWindowF32::new(axis32.as_dvec3(), f64::from(rim32));
        let frame = lambert_geometry::f64::Frame::from_normal(axis);
        let mut accepted = [0, 0];
        for k in 0..10_000 {
            let phi = f64::from(k) * 2.0 * PI / 10_000.0;
            for theta in [
                theta_max * (1.0 - 1e-12),
                theta_max,
                theta_max * (1.0 + 1e-6),
            ] {
                let local = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let u = invert_cosine_hemisphere(frame.from_local(local));
                if (sample_cosine_hemisphere(u) - axis).length_squared() <= rim64 {
                    accepted[0] += 1;
                    assert!(window.may_see(u), "φ {phi} θ {theta} u {u}");
                }
                let u32 = u.as_vec2();
                let w32: Vec3 = lambert_sampling::f32::sample_cosine_hemisphere(u32);
                if (w32 - axis32).length_squared() <= rim32 {
                    accepted[1] += 1;
                    assert!(window32.may_see(u32), "f32 φ {phi} θ {theta} u {u32}");
                }
            }
        }
        assert!(accepted[0] > 10_000 && accepted[1] > 10_000, "{accepted:?}");
    }

    /// Negative control: a window built for another axis rejects samples
    /// that see this cone, so the tests above can fail.
    #[test]
    fn a_window_for_another_axis_rejects_the_cone() {
        let axis = DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6);
        let other = DVec3::new(-0.5, 0.0, 0.866_025_403_784_438_6);
        let rim = 2.0 * (1.0 - 0.1f64.cos());
        let u = lambert_sampling::f64::invert_cosine_hemisphere(axis);
        assert!(CosineWindow::new(axis, rim).may_see(u));
        assert!(!CosineWindow::new(other, rim).may_see(u));
        assert!(CosineWindowF32::new(axis, rim).may_see(u.as_vec2()));
        assert!(!CosineWindowF32::new(other, rim).may_see(u.as_vec2()));
    }
}
