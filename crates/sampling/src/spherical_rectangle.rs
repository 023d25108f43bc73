//! Uniform sampling of the directions subtended by a rectangle: the
//! area-preserving parametrization of Ureña, Fajardo & King, "An
//! Area-Preserving Parametrization for Spherical Rectangles", EGSR 2013,
//! rewritten so that it has no cancellation for tiny, distant, grazing or
//! huge rectangles, and with its inverse.

macro_rules! spherical_rectangle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::error::SamplingError;
        use crate::light_sample::$p::LightSample;
        use lambert_geometry::precision::$p::{wide3, Real, PI, V2, V3};
        use lambert_geometry::$p::solid_angle_van_oosterom;
        use crate::trig::$p::sin;

        /// The pieces of [a, a + w] on either side of 0, each reflected to
        /// non-negative coordinates, as (start, width); an absent piece has
        /// width 0. Solid angles of strips and rectangles at z = −d are
        /// symmetric under x → −x and y → −y, and for pieces with
        /// non-negative coordinates every term of the Van Oosterom–Strackee
        /// denominator is non-negative: no cancellation, even for huge or
        /// grazing rectangles.
        #[inline]
        fn split_at_zero(a: Real, w: Real) -> [(Real, Real); 2] {
            let b = a + w;
            if a >= 0.0 {
                [(a, w), (0.0, 0.0)]
            } else if b <= 0.0 {
                [(-b, w), (0.0, 0.0)]
            } else {
                [(0.0, -a), (0.0, b)]
            }
        }

        /// The solid angle T(x) of the half-strip [x, ∞) × [y₀, y₀ + h] at
        /// height d below the origin (see the module docs), summed over the
        /// pieces on either side of y = 0.
        #[inline]
        fn half_strip(x: Real, y0: Real, h: Real, d: Real) -> Real {
            let mut total = 0.0;
            for (ya, hy) in split_at_zero(y0, h) {
                if hy > 0.0 {
                    let yb = ya + hy;
                    let (q0, q1) = (ya * ya + d * d, yb * yb + d * d);
                    let (r0, r1) = ((x * x + q0).sqrt(), (x * x + q1).sqrt());
                    let (p0, p1) = if x >= 0.0 {
                        (r0 + x, r1 + x)
                    } else {
                        (q0 / (r0 - x), q1 / (r1 - x))
                    };
                    total += 2.0 * (d * hy).atan2(p0 * p1 + ya * yb + d * d);
                }
            }
            total
        }

        /// The solid angle of the rectangle [x₀, x₀+w] × [y₀, y₀+h] at
        /// z = −d: per quadrant piece, two Van Oosterom–Strackee triangles
        /// whose triple products are exactly d·w·h.
        #[inline]
        fn quad_solid_angle(x0: Real, y0: Real, w: Real, h: Real, d: Real) -> Real {
            let mut total = 0.0;
            for (xa, wx) in split_at_zero(x0, w) {
                for (ya, hy) in split_at_zero(y0, h) {
                    if wx > 0.0 && hy > 0.0 {
                        let v00 = V3::new(xa, ya, -d);
                        let v10 = V3::new(xa + wx, ya, -d);
                        let v11 = V3::new(xa + wx, ya + hy, -d);
                        let v01 = V3::new(xa, ya + hy, -d);
                        let triple = d * wx * hy;
                        total += solid_angle_van_oosterom(v00, v10, v11, triple)
                            + solid_angle_van_oosterom(v00, v11, v01, triple);
                    }
                }
            }
            total
        }

        /// `v.clamp(lo, hi)` for lo ≤ hi (the rectangle's bounds, ordered
        /// by construction), NaN passed through as `clamp` does, without
        /// `clamp`'s check of the bounds: that check is a possible panic
        /// inside the sampling loop, which keeps the compiler from
        /// vectorising the estimator's batch kernels.
        #[inline(always)]
        fn clamp_ordered(v: Real, lo: Real, hi: Real) -> Real {
            let v = if v < lo { lo } else { v };
            if v > hi {
                hi
            } else {
                v
            }
        }

        /// yb/√(δ² + yb²) − ya/√(δ² + ya²) for ya ≤ yb, without
        /// cancellation (`h` = yb − ya, exact from the caller).
        #[inline(always)]
        fn h_diff(ya: Real, yb: Real, h: Real, dd2: Real) -> Real {
            let (ra, rb) = ((dd2 + ya * ya).sqrt(), (dd2 + yb * yb).sqrt());
            if (ya >= 0.0) == (yb >= 0.0) && ya != 0.0 {
                h * (yb + ya) * dd2 / (ra * rb * (yb * ra + ya * rb))
            } else {
                yb / rb - ya / ra
            }
        }

        /// The uniform density over the directions that a rectangle subtends
        /// at a point: p(ω) = 1/S per steradian inside, 0 outside (Ureña,
        /// Fajardo & King 2013, rewritten without cancellation and without
        /// pbrt-v4's area-sampling fallback; see the module docs).
        ///
        /// Uniform sampling of the directions subtended by a rectangle: the
        /// area-preserving parametrization of Ureña, Fajardo & King, "An
        /// Area-Preserving Parametrization for Spherical Rectangles", EGSR 2013,
        /// rewritten so that it has no cancellation for tiny, distant, grazing or
        /// huge rectangles, and with its inverse.
        ///
        /// # Frame and strips
        /// In Ureña's local frame (x along `edge0`, y along `edge1`, the reference
        /// point at the origin, the rectangle at z = −d, d > 0) the rectangle is
        /// [x₀, x₁] × [y₀, y₁]. Let T(x) be the solid angle of the half-strip
        /// [x, ∞) × [y₀, y₁] and T′(x) that of (−∞, x] × [y₀, y₁]; T + T′ = 2ψ with
        /// ψ = φ₁ − φ₀, φᵢ = atan(yᵢ/d). Seen from the origin the half-strip is the
        /// spherical triangle (x, y₀, −d), (x, y₁, −d), (1, 0, 0), and Van Oosterom &
        /// Strackee give, with rᵢ = √(x² + yᵢ² + d²),
        ///
        /// T(x) = 2 atan2(d (y₁ − y₀), (r₀ + x)(r₁ + x) + y₀y₁ + d²),
        ///
        /// where rᵢ + x = (yᵢ² + d²)/(rᵢ − x) for x < 0; T′(x) is T(−x).
        ///
        /// # Sampling x (Ureña's first step, rewritten)
        /// The sub-rectangle [x₀, xᵤ] has solid angle u₀S, so T(xᵤ) = T(x₁) + (1−u₀)S
        /// and T′(xᵤ) = T′(x₀) + u₀S — sums of non-negative terms, with S itself the
        /// Van Oosterom–Strackee solid angle of the two triangles (not
        /// g₀+g₁+g₂+g₃−2π, which cancels for small rectangles: pbrt-v4 falls back to
        /// area sampling, with a wrong pdf, below 1e-3 sr). Ureña's
        /// fᵤ = (cos aᵤ b₀ − b₁)/sin aᵤ and xᵤ = −cᵤz₀/√(1 − cᵤ²) reduce (we derived
        /// and the tests check) to
        ///
        /// xᵤ = d sin β / √N,  β = (T′ − T)/2,
        /// N = 4 sin(T/2) sin(T′/2) cos(φ₁ − T/2) cos(φ₁ − T′/2),
        ///
        /// every factor positive. cos(φ₁ − T/2) is evaluated as sin of the smaller of
        /// φ̄₁ + T/2 and φ̃₀ + T′/2 (φ̄₁ = atan2(d, y₁), φ̃₀ = atan2(d, −y₀), the two
        /// arguments sum to π), likewise cos(φ₁ − T′/2) = sin(min(φ̄₁ + T′/2,
        /// φ̃₀ + T/2)), and sin(T/2) as sin(φ̄₁ + φ̃₀ + T′/2) when T > π: no
        /// argument near a zero of the function is ever formed by subtraction. (The
        /// brief's route via fᵤ needs 1 − cᵤ² ∝ fᵤ² − cos²φ₀, which cancels when xᵤ
        /// is far from the foot of the perpendicular, i.e. for grazing rectangles.)
        ///
        /// # Sampling y (Ureña's second step)
        /// On the line x = xᵤ, with δ² = xᵤ² + d², hᵢ = yᵢ/√(δ² + yᵢ²) and
        /// h = h₀ + u₁(h₁ − h₀), y = h δ/√(1 − h²). Here h₁ − h₀ =
        /// (y₁−y₀)(y₁+y₀)δ²/(R₀R₁(y₁R₀ + y₀R₁)) when y₀, y₁ have the same sign (a
        /// direct difference of opposite-sign terms otherwise), and
        /// 1 − h² = [(1 − h₁) + (1−u₁)(h₁−h₀)]·[(1 + h₀) + u₁(h₁−h₀)] with
        /// 1 − h₁ = δ²/(R₁(R₁+y₁)) for y₁ > 0 and 1 + h₀ = δ²/(R₀(R₀−y₀)) for
        /// y₀ < 0: again only sums of non-negative terms.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::SphericalRectangle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A face of the cube [−1, 1]³ seen from its centre: 4π/6 sr.
        #[doc = concat!("let r = SphericalRectangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::new(-1.0, -1.0, 1.0), ", stringify!($v3), "::X * 2.0, ", stringify!($v3), "::Y * 2.0)?;")]
        #[doc = concat!("assert!((r.solid_angle() - 4.0 * std::", stringify!($p), "::consts::PI / 6.0).abs() < 1e-5);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.2, 0.9);")]
        /// let d = r.sample(u);
        /// assert_eq!(r.pdf(d.direction), d.pdf);
        /// assert!((r.invert(d.direction) - u).length() < 1e-4);
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphericalRectangle {
            /// Reference point and the corner.
            p: V3,
            corner: V3,
            /// Local frame: x along edge0, y along edge1 (made exactly
            /// perpendicular), z away from the rectangle (z₀ = −d < 0).
            ex: V3,
            ey: V3,
            ez: V3,
            /// Rectangle [x0, x0 + w] × [y0, y0 + h] at z = −d.
            x0: Real,
            y0: Real,
            w: Real,
            h: Real,
            d: Real,
            /// S, T(x₁), T′(x₀), φ̄₁ = atan2(d, y₁), φ̃₀ = atan2(d, −y₀).
            solid_angle: Real,
            t_right: Real,
            t_left: Real,
            phibar1: Real,
            phitilde0: Real,
        }

        impl SphericalRectangle {
            /// Relative tolerance on perpendicularity: |ê₀·ê₁| ≤ 1e-4
            /// (cos 89.994°), enough for edges rounded to f32 or built from
            /// a rotation. `edge1` is then made exactly perpendicular to
            /// `edge0` (its component along `edge0` is dropped).
            pub const PERPENDICULAR_TOLERANCE: Real = 1e-4;

            /// The spherical rectangle that the rectangle `corner + s·edge0 +
            /// t·edge1`, s, t ∈ [0, 1], subtends at the reference point `p`.
            ///
            /// Errors: non-finite input ([`SamplingError::NotFinite`]); a zero
            /// edge ([`SamplingError::ZeroVector`]); edges not perpendicular
            /// within [`Self::PERPENDICULAR_TOLERANCE`]
            /// ([`SamplingError::OutOfRange`]); `p` in the rectangle's plane or
            /// a solid angle whose density 1/S overflows
            /// ([`SamplingError::Degenerate`]).
            pub fn new(p: V3, corner: V3, edge0: V3, edge1: V3) -> Result<Self, SamplingError> {
                for (field, v) in [
                    ("p", p),
                    ("corner", corner),
                    ("edge0", edge0),
                    ("edge1", edge1),
                ] {
                    crate::error::finite3(field, wide3(v))?;
                }
                let (l0, l1) = (edge0.length(), edge1.length());
                if !(l0 > 0.0 && l0.is_finite()) {
                    return Err(SamplingError::ZeroVector { field: "edge0" });
                }
                if !(l1 > 0.0 && l1.is_finite()) {
                    return Err(SamplingError::ZeroVector { field: "edge1" });
                }
                let ex = edge0 / l0;
                let cos = ex.dot(edge1 / l1);
                if cos.is_nan() || cos.abs() > Self::PERPENDICULAR_TOLERANCE {
                    return Err(SamplingError::OutOfRange {
                        field: "cos of the angle between edge0 and edge1",
                        value: cos as f64,
                        range: "[-1e-4, 1e-4] (a rectangle's edges are perpendicular)",
                    });
                }
                let ey = (edge1 - ex * ex.dot(edge1)).normalize();
                let h = (edge1 - ex * ex.dot(edge1)).length();
                let mut ez = ex.cross(ey);
                let rel = corner - p;
                let mut z0 = rel.dot(ez);
                if z0 > 0.0 {
                    z0 = -z0;
                    ez = -ez;
                }
                let d = -z0;
                let (x0, y0, w) = (rel.dot(ex), rel.dot(ey), l0);
                let degenerate = SamplingError::Degenerate {
                    what: "the reference point lies in the rectangle's plane, or the \
                           rectangle's solid angle is too small for its density 1/S",
                };
                if !(d > 0.0 && d.is_finite()) {
                    return Err(degenerate);
                }
                let solid_angle = quad_solid_angle(x0, y0, w, h, d);
                let t_right = half_strip(x0 + w, y0, h, d);
                let t_left = half_strip(-x0, y0, h, d);
                if !(solid_angle > 0.0 && (1.0 / solid_angle).is_finite())
                    || !t_right.is_finite()
                    || !t_left.is_finite()
                {
                    return Err(degenerate);
                }
                Ok(SphericalRectangle {
                    p,
                    corner,
                    ex,
                    ey,
                    ez,
                    x0,
                    y0,
                    w,
                    h,
                    d,
                    solid_angle,
                    t_right,
                    t_left,
                    phibar1: d.atan2(y0 + h),
                    phitilde0: d.atan2(-y0),
                })
            }

            /// The solid angle S of the spherical rectangle, in steradians:
            /// the sum of the Van Oosterom–Strackee solid angles of its two
            /// triangles.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.solid_angle
            }

            /// The rectangle in the local frame, (x₀, x₁, y₀, y₁, d): it is
            /// [x₀, x₁] × [y₀, y₁] at z = −d.
            #[inline]
            pub fn local_bounds(&self) -> [Real; 5] {
                [self.x0, self.x0 + self.w, self.y0, self.y0 + self.h, self.d]
            }

            /// The local (x, y) on the rectangle that u maps to. The sines
            /// are [`sin`](crate::f64::sin)'s (inlined, so the estimator's
            /// block kernels vectorise this sampler), not libm's.
            #[inline(always)]
            fn sample_local(&self, u: V2) -> (Real, Real) {
                let (x0, x1) = (self.x0, self.x0 + self.w);
                let t = self.t_right + (1.0 - u.x) * self.solid_angle;
                let tp = self.t_left + u.x * self.solid_angle;
                let psibar = self.phibar1 + self.phitilde0;
                // The argument is chosen, then one sine (not a sine on each
                // side of a branch: the batch kernels select, so both sides
                // would run).
                let sin_half =
                    |a: Real, other: Real| sin(if a <= PI { 0.5 * a } else { psibar + 0.5 * other });
                let (s, sp) = (sin_half(t, tp), sin_half(tp, t));
                let c1 = sin((self.phibar1 + 0.5 * t).min(self.phitilde0 + 0.5 * tp));
                let c2 = sin((self.phibar1 + 0.5 * tp).min(self.phitilde0 + 0.5 * t));
                let root = (s * sp).sqrt() * (c1 * c2).sqrt();
                let sin_beta = sin(0.5 * (tp - t));
                let xu = if root > 0.0 {
                    clamp_ordered(self.d * sin_beta / (2.0 * root), x0, x1)
                } else if u.x < 0.5 {
                    x0
                } else {
                    x1
                };
                // Second step: uniform in h = y/√(δ² + y²).
                let (y0, y1) = (self.y0, self.y0 + self.h);
                let dd2 = xu * xu + self.d * self.d;
                let (r0, r1) = ((dd2 + y0 * y0).sqrt(), (dd2 + y1 * y1).sqrt());
                let (h0, h1) = (y0 / r0, y1 / r1);
                let dh = h_diff(y0, y1, self.h, dd2);
                let hv = if u.y <= 0.5 {
                    h0 + u.y * dh
                } else {
                    h1 - (1.0 - u.y) * dh
                };
                let one_minus_h1 = if y1 > 0.0 {
                    dd2 / (r1 * (r1 + y1))
                } else {
                    1.0 - h1
                };
                let one_plus_h0 = if y0 < 0.0 {
                    dd2 / (r0 * (r0 - y0))
                } else {
                    1.0 + h0
                };
                let den = ((one_minus_h1 + (1.0 - u.y) * dh) * (one_plus_h0 + u.y * dh)).sqrt();
                let yv = if den > 0.0 {
                    clamp_ordered(hv * dd2.sqrt() / den, y0, y1)
                } else if u.y < 0.5 {
                    y0
                } else {
                    y1
                };
                (xu, yv)
            }

            /// A direction uniform in the spherical rectangle, density 1/S per
            /// steradian (Ureña et al. 2013, rewritten; see the module docs).
            /// Every u ∈ [0, 1]², including exact 0 and 1, gives a finite unit
            /// vector for which [`SphericalRectangle::pdf`] returns the same
            /// density.
            #[inline]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let s = self.sample_point(u);
                DirectionSample {
                    direction: s.direction,
                    pdf: s.pdf,
                }
            }

            /// As [`SphericalRectangle::sample`], also returning the point on
            /// the rectangle (`corner + (x − x₀) ê₀ + (y − y₀) ê₁`, in the
            /// rectangle's plane to rounding) and its distance from `p`.
            #[inline(always)]
            pub fn sample_point(&self, u: V2) -> LightSample {
                let (x, y) = self.sample_local(u);
                let offset = self.ex * x + self.ey * y - self.ez * self.d;
                let distance = offset.length();
                LightSample {
                    direction: offset / distance,
                    pdf: 1.0 / self.solid_angle,
                    point: self.corner + self.ex * (x - self.x0) + self.ey * (y - self.y0),
                    distance,
                }
            }

            /// Whether the unit direction `w` lies in the spherical rectangle:
            /// w·n ≥ −τ for the four inward edge normals n (in the local frame
            /// (0, d, y₀), (0, −d, −y₁), (d, 0, x₀), (−d, 0, −x₁), normalised),
            /// τ = 32ε rad. As for the triangle, the slack absorbs the few-ε
            /// rounding of a unit vector sampled on an edge, so that
            /// pdf(sample(u)) equals the returned density.
            ///
            /// Inlined and branch-free (the four tests joined by `&`, not
            /// `&&`): MIS kernels call it per sample through
            /// [`pdf`](Self::pdf), and a call left out of line kept their
            /// loops scalar (f32 MIS on a rectangle light took 113 ns a
            /// sample).
            #[inline(always)]
            pub fn contains(&self, w: V3) -> bool {
                let (wx, wy, wz) = (w.dot(self.ex), w.dot(self.ey), w.dot(self.ez));
                let (x1, y1, d) = (self.x0 + self.w, self.y0 + self.h, self.d);
                let tol = 32.0 * Real::EPSILON;
                let edge = |a: Real, b: Real, va: Real, vb: Real| {
                    a * va + b * vb >= -tol * (a * a + b * b).sqrt()
                };
                edge(d, self.y0, wy, wz)
                    & edge(-d, -y1, wy, wz)
                    & edge(d, self.x0, wx, wz)
                    & edge(-d, -x1, wx, wz)
            }

            /// The density 1/S per steradian of the unit direction `w` if it
            /// lies in the spherical rectangle (see
            /// [`SphericalRectangle::contains`]), 0 otherwise; never NaN for
            /// finite `w`.
            #[inline(always)]
            pub fn pdf(&self, w: V3) -> Real {
                if self.contains(w) {
                    1.0 / self.solid_angle
                } else {
                    0.0
                }
            }

            /// The u ∈ [0, 1]² that [`SphericalRectangle::sample`] maps to the
            /// unit direction `w` of the rectangle: with (x, y) the point hit,
            /// u₀ = S([x₀, x] × [y₀, y₁])/S (Van Oosterom–Strackee) and
            /// u₁ = (h(y) − h₀)/(h₁ − h₀) on the line x (cancellation-free
            /// differences). Directions that miss the rectangle's plane give
            /// a clamped, finite u.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                let (wx, wy, wz) = (w.dot(self.ex), w.dot(self.ey), w.dot(self.ez));
                let (x1, y1) = (self.x0 + self.w, self.y0 + self.h);
                let t = if wz < 0.0 { self.d / -wz } else { Real::MAX };
                let x = (t * wx).clamp(self.x0, x1);
                let y = (t * wy).clamp(self.y0, y1);
                let sub = quad_solid_angle(self.x0, self.y0, x - self.x0, self.h, self.d);
                let u0 = (sub / self.solid_angle).clamp(0.0, 1.0);
                let dd2 = x * x + self.d * self.d;
                let num = h_diff(self.y0, y, y - self.y0, dd2);
                let den = h_diff(self.y0, y1, self.h, dd2);
                let u1 = if den > 0.0 {
                    (num / den).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                V2::new(u0, u1)
            }

            /// The reference point.
            #[inline]
            pub fn reference_point(&self) -> V3 {
                self.p
            }
        }
    };
}

lambert_geometry::both_precisions!(spherical_rectangle_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg32;

    /// A rectangle [x0, x1] × [y0, y1] at height d below `p`, in a rotated
    /// frame, as `[p, corner, edge0, edge1]`.
    fn rect(p: DVec3, x0: f64, x1: f64, y0: f64, y1: f64, d: f64) -> [DVec3; 4] {
        let ex = DVec3::new(0.6, 0.0, 0.8);
        let ey = DVec3::new(0.0, 1.0, 0.0);
        let ez = ex.cross(ey);
        [
            p,
            p + ex * x0 + ey * y0 - ez * d,
            ex * (x1 - x0),
            ey * (y1 - y0),
        ]
    }

    /// Named cases; `tiny` has S ≈ 1e-12 sr (f64 only), `tiny32` ≈ 1e-6 sr.
    fn cases() -> Vec<(&'static str, [DVec3; 4])> {
        let far = DVec3::new(3.0, -2.0, 5.0);
        vec![
            ("ordinary", rect(DVec3::ZERO, -0.3, 1.2, -0.2, 0.7, 1.0)),
            ("off_side", rect(DVec3::ZERO, -3.0, -2.0, -5.0, -4.5, 0.5)),
            ("tiny", rect(far, 0.3, 0.3 + 1e-6, 0.4, 0.4 + 1e-6, 1.0)),
            ("tiny32", rect(far, 0.3, 0.3 + 1e-3, 0.4, 0.4 + 1e-3, 1.0)),
            ("grazing", rect(DVec3::ZERO, 0.5, 1.5, -0.5, 0.5, 1e-3)),
            ("grazing_far", rect(DVec3::ZERO, 1.0, 11.0, 2.0, 3.0, 1e-2)),
            ("huge", rect(DVec3::ZERO, -10.0, 10.0, -10.0, 10.0, 1e-3)),
        ]
    }

    /// F(x, y) = atan(xy/(d√(x²+y²+d²))), the solid angle of [0,x]×[0,y].
    fn corner_f(x: f64, y: f64, d: f64) -> f64 {
        (x * y / (d * (x * x + y * y + d * d).sqrt())).atan()
    }

    /// Ureña et al. (2013), Alg. 1, as published (f64): the straightforward
    /// reference for the rewritten x and y steps on ordinary rectangles.
    fn urena(x0: f64, x1: f64, y0: f64, y1: f64, z0: f64, u: DVec2) -> (f64, f64) {
        use std::f64::consts::PI;
        let v00 = DVec3::new(x0, y0, z0);
        let v01 = DVec3::new(x0, y1, z0);
        let v10 = DVec3::new(x1, y0, z0);
        let v11 = DVec3::new(x1, y1, z0);
        let n0 = v00.cross(v10).normalize();
        let n1 = v10.cross(v11).normalize();
        let n2 = v11.cross(v01).normalize();
        let n3 = v01.cross(v00).normalize();
        let g0 = (-n0.dot(n1)).acos();
        let g1 = (-n1.dot(n2)).acos();
        let g2 = (-n2.dot(n3)).acos();
        let g3 = (-n3.dot(n0)).acos();
        let (b0, b1) = (n0.z, n2.z);
        let k = 2.0 * PI - g2 - g3;
        let s = g0 + g1 - k;
        let au = u.x * s + k;
        let fu = (au.cos() * b0 - b1) / au.sin();
        let cu = (1.0 / (fu * fu + b0 * b0).sqrt() * fu.signum()).clamp(-1.0, 1.0);
        let xu = (-(cu * z0) / (1.0 - cu * cu).sqrt()).clamp(x0, x1);
        let d = (xu * xu + z0 * z0).sqrt();
        let h0 = y0 / (d * d + y0 * y0).sqrt();
        let h1 = y1 / (d * d + y1 * y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        (xu, hv * d / (1.0 - hv * hv).sqrt())
    }

    #[test]
    fn rewritten_steps_match_urena() {
        let mut rng = Pcg32::seed_from_u64(5);
        for case in 0..100 {
            let mut r = |lo: f64, hi: f64| lo + (hi - lo) * rng.random::<f64>();
            let (x0, y0, d) = (r(-2.0, 1.0), r(-2.0, 1.0), r(0.3, 2.0));
            let (x1, y1) = (x0 + r(0.2, 2.0), y0 + r(0.2, 2.0));
            let g = rect(DVec3::ZERO, x0, x1, y0, y1, d);
            let sr = super::f64::SphericalRectangle::new(g[0], g[1], g[2], g[3]).unwrap();
            let [bx0, bx1, by0, by1, bd] = sr.local_bounds();
            let s_ref = corner_f(bx1, by1, bd) - corner_f(bx1, by0, bd) - corner_f(bx0, by1, bd)
                + corner_f(bx0, by0, bd);
            assert!((sr.solid_angle() - s_ref).abs() < 1e-13, "case {case}");
            for i in 0..=8 {
                for j in 0..=8 {
                    let u = DVec2::new(i as f64 / 8.0, j as f64 / 8.0);
                    let (xu, yv) = urena(bx0, bx1, by0, by1, -bd, u);
                    let want = (g[1] - g[0]
                        + g[2].normalize() * (xu - bx0)
                        + g[3].normalize() * (yv - by0))
                        .normalize();
                    let got = sr.sample(u).direction;
                    assert!(
                        (got - want).length() < 1e-9,
                        "case {case} u {u}: {got} vs {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn bad_input_is_a_clear_error() {
        use super::f64::SphericalRectangle as R;
        use crate::SamplingError;
        let (o, x, y, z) = (DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z);
        assert!(matches!(
            R::new(o, -z, DVec3::new(f64::INFINITY, 0.0, 0.0), y),
            Err(SamplingError::NotFinite { field: "edge0", .. })
        ));
        assert!(matches!(
            R::new(o, -z, DVec3::ZERO, y),
            Err(SamplingError::ZeroVector { field: "edge0" })
        ));
        assert!(matches!(
            R::new(o, -z, x, DVec3::ZERO),
            Err(SamplingError::ZeroVector { field: "edge1" })
        ));
        assert!(matches!(
            R::new(o, -z, x, x + y),
            Err(SamplingError::OutOfRange { .. })
        ));
        // p in the plane.
        assert!(matches!(
            R::new(o, x, x, y),
            Err(SamplingError::Degenerate { .. })
        ));
        // Slightly non-perpendicular edges within the tolerance are accepted.
        assert!(R::new(o, -z, x, y + 5e-5 * x).is_ok());
        // The far side of the plane and either edge order: same solid angle.
        let a = R::new(o, -z, x, y).unwrap();
        let b = R::new(o, -z, y, x).unwrap();
        let c = R::new(-2.0 * z, -z, x, y).unwrap();
        assert!((a.solid_angle() - b.solid_angle()).abs() < 1e-15);
        assert!((a.solid_angle() - c.solid_angle()).abs() < 1e-15);
        assert_eq!(a.pdf(DVec3::new(f64::NAN, 0.0, 0.0)), 0.0);
    }

    macro_rules! precision_tests {
        ($m:ident) => {
            mod $m {
                use super::*;
                use crate::$m::*;
                use lambert_geometry::precision::$m::{
                    narrow3, wide3, Real, ONE_MINUS_EPSILON, V2, V3,
                };

                fn case(g: [DVec3; 4]) -> ([V3; 4], [DVec3; 4]) {
                    let r = g.map(narrow3);
                    (r, r.map(wide3))
                }
                const EPS: f64 = Real::EPSILON as f64;
                fn skip(name: &str) -> bool {
                    Real::EPSILON as f64 > 1e-10 && name == "tiny"
                }
                fn build(r: [V3; 4]) -> SphericalRectangle {
                    SphericalRectangle::new(r[0], r[1], r[2], r[3]).unwrap()
                }
                fn build64(w: [DVec3; 4]) -> crate::f64::SphericalRectangle {
                    crate::f64::SphericalRectangle::new(w[0], w[1], w[2], w[3]).unwrap()
                }
                /// (size, S): the larger edge over the farthest corner's
                /// distance (a lower bound of the larger angular extent) and
                /// the solid angle.
                fn aspect(r: &crate::f64::SphericalRectangle) -> (f64, f64) {
                    let [x0, x1, y0, y1, d] = r.local_bounds();
                    let far =
                        (x0.abs().max(x1.abs()).powi(2) + y0.abs().max(y1.abs()).powi(2) + d * d)
                            .sqrt();
                    ((x1 - x0).max(y1 - y0) / far, r.solid_angle())
                }
                fn grid(n: usize, lo: f64, hi: f64) -> Vec<V2> {
                    let mut out = Vec::new();
                    for i in 0..n {
                        for j in 0..n {
                            let t = |k: usize| lo + (hi - lo) * k as f64 / (n - 1) as f64;
                            out.push(V2::new(t(i) as Real, t(j) as Real));
                        }
                    }
                    out
                }

                #[test]
                fn solid_angle_against_references() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let s = build(r).solid_angle() as f64;
                        let r64 = build64(w);
                        let s64 = r64.solid_angle();
                        let rel = (s - s64).abs() / s64;
                        assert!(rel < 64.0 * EPS, "{name}: {s} vs f64 {s64} ({rel:e})");
                        let [x0, x1, y0, y1, d] = r64.local_bounds();
                        if name.starts_with("tiny") {
                            // Planar approximation A cos θ/ρ² about the
                            // centre: relative error ≤ size/ρ.
                            let c = DVec3::new(0.5 * (x0 + x1), 0.5 * (y0 + y1), d);
                            let a = (x1 - x0) * (y1 - y0);
                            let planar = a * d / c.length().powi(3);
                            let size = (x1 - x0).max(y1 - y0);
                            let rel = (s64 - planar).abs() / planar;
                            assert!(rel <= size / c.length(), "{name}: {s64} vs {planar}");
                        } else {
                            let f = |x, y| corner_f(x, y, d);
                            let s_ref = f(x1, y1) - f(x1, y0) - f(x0, y1) + f(x0, y0);
                            assert!(
                                (s64 - s_ref).abs() < 1e-12 * s_ref,
                                "{name}: {s64} vs {s_ref}"
                            );
                        }
                        if name == "huge" {
                            assert!(s64 > 6.2 && s64 < 2.0 * std::f64::consts::PI);
                        }
                    }
                }

                #[test]
                fn samples_are_unit_inside_and_corners_work() {
                    let one = 1.0 as Real;
                    let corners = [0.0, ONE_MINUS_EPSILON, one, 0.5];
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, _) = case(g);
                        let sr = build(r);
                        let mut us = grid(41, 0.0, 1.0);
                        for a in corners {
                            for b in corners {
                                us.push(V2::new(a, b));
                            }
                        }
                        for u in us {
                            let s = sr.sample(u);
                            let w = s.direction;
                            assert!(w.is_finite(), "{name} {u}: {w}");
                            assert!((w.length() - 1.0).abs() < 4.0 * Real::EPSILON, "{name} {u}");
                            assert!(s.pdf > 0.0 && s.pdf.is_finite());
                            assert_eq!(sr.pdf(w), s.pdf, "{name} {u}: {w} outside");
                            let sp = sr.sample_point(u);
                            assert_eq!(sp.direction, w);
                            // The point is formed in world coordinates,
                            // with an error of a few ε·|corner − p|, seen
                            // from a distance `distance`.
                            let back = (sp.point - r[0]) / sp.distance;
                            let scale = (r[1] - r[0]).length() + r[2].length() + r[3].length();
                            let tol = 64.0 * Real::EPSILON * (1.0 + scale / sp.distance);
                            assert!((back - w).length() < tol, "{name} {u}");
                            assert!(sr.invert(w).is_finite());
                        }
                        assert_eq!(sr.pdf(-sr.sample(V2::splat(0.5)).direction), 0.0);
                    }
                }

                /// invert(sample(u)) ≈ u. A sample's direction carries an
                /// absolute error δ ≈ a few ε; u₀ = S(x)/S moves by at most
                /// δ·(angular height of the column)/S ≤ δ·size/S, and u₁ by
                /// δ/(angular height) ≤ δ·size/S (height·width ≥ S).
                /// Grazing views add a factor 1 + ρ_max/d: a direction near
                /// the horizon, moved by δ, moves the hit point by δρ, which
                /// near the foot of the perpendicular (distance d) is an
                /// angle δρ/d. Tolerance: 256 ε (1 + size/S)(1 + ρ_max/d),
                /// size the larger angular extent; grid u ∈ [0.02, 0.98]².
                #[test]
                fn invert_inverts_sample() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let sr = build(r);
                        let r64 = build64(w);
                        let (size, s) = aspect(&r64);
                        let [x0, x1, y0, y1, d] = r64.local_bounds();
                        let rho = (x0.abs().max(x1.abs()).powi(2) + y0.abs().max(y1.abs()).powi(2))
                            .sqrt();
                        let tol = 256.0 * EPS * (1.0 + size / s) * (1.0 + rho / d);
                        let mut worst: f64 = 0.0;
                        for u in grid(21, 0.02, 0.98) {
                            let back = sr.invert(sr.sample(u).direction);
                            worst = worst.max((back - u).abs().max_element() as f64);
                        }
                        assert!(worst <= tol, "{name}: worst {worst:e} > tol {tol:e}");
                    }
                }

                /// This precision against f64 on the same rounded inputs, in
                /// radians. The map u → w is well conditioned (no sliver
                /// angles): its rounding is an input perturbation of a few
                /// tens of ε relative to the rectangle's distance, moving w by
                /// that much; grazing cases amplify by ρ_max/d through d's own
                /// rounding (d = (corner − p)·ẑ is known only to ε ρ_max).
                /// Tolerance: 64 ε (1 + ρ_max/d).
                #[test]
                fn agrees_with_f64() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let sr = build(r);
                        let r64 = build64(w);
                        let [x0, x1, y0, y1, d] = r64.local_bounds();
                        let rho = (x0.abs().max(x1.abs()).powi(2) + y0.abs().max(y1.abs()).powi(2))
                            .sqrt();
                        let tol = 64.0 * EPS * (1.0 + rho / d);
                        let mut worst: f64 = 0.0;
                        for u in grid(21, 0.0, 1.0) {
                            let a = wide3(sr.sample(u).direction);
                            let b = r64.sample(DVec2::new(u.x as f64, u.y as f64)).direction;
                            worst = worst.max((a - b).length());
                        }
                        assert!(worst <= tol, "{name}: worst {worst:e} > tol {tol:e}");
                    }
                }

                /// Fraction of 200k samples in the central sub-rectangle
                /// [¼, ¾]² (both sampling steps matter) against its
                /// solid-angle fraction, within 4.5 binomial sigmas; and a
                /// negative control (u₁ → u₁^0.9) that must be rejected.
                #[test]
                fn fraction_in_central_sub_rectangle() {
                    let n = 200_000;
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let sr = build(r);
                        let sub = crate::f64::SphericalRectangle::new(
                            w[0],
                            w[1] + 0.25 * w[2] + 0.25 * w[3],
                            0.5 * w[2],
                            0.5 * w[3],
                        )
                        .unwrap();
                        let frac = sub.solid_angle() / build64(w).solid_angle();
                        let sigma = (frac * (1.0 - frac) / n as f64).sqrt();
                        for (skew, must_pass) in [(1.0, true), (0.9, false)] {
                            let mut rng = Pcg32::seed_from_u64(77);
                            let mut hits = 0usize;
                            for _ in 0..n {
                                let u0: Real = rng.random();
                                let u1: Real = rng.random();
                                let u = V2::new(u0, u1.powf(skew as Real));
                                if sub.contains(wide3(sr.sample(u).direction)) {
                                    hits += 1;
                                }
                            }
                            let z = (hits as f64 / n as f64 - frac) / sigma;
                            if must_pass {
                                assert!(z.abs() < 4.5, "{name}: z = {z}");
                            } else if name == "ordinary" {
                                assert!(z.abs() > 4.5, "negative control passed: z = {z}");
                            }
                        }
                    }
                }
            }
        };
    }
    precision_tests!(f64);
    precision_tests!(f32);
}
