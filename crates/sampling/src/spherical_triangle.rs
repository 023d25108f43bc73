//! Uniform sampling of the directions subtended by a triangle: the
//! spherical triangle warp of Arvo, "Stratified sampling of spherical
//! triangles", SIGGRAPH 1995, with its inverse (pbrt-v4's
//! `InvertSphericalTriangleSample`), rewritten so that tiny, sliver and
//! near-hemisphere triangles keep full precision in f32 and f64.

macro_rules! spherical_triangle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::error::SamplingError;
        use lambert_geometry::precision::$p::{wide3, Real, V2, V3};
        use lambert_geometry::$p::solid_angle_van_oosterom;
        use crate::trig::$p::{sin, sin_cos};

        /// The uniform density over the directions that a triangle
        /// subtends at a point: p(ω) = 1/Ω per steradian inside the
        /// spherical triangle, 0 outside (Arvo 1995, rewritten without
        /// cancellation; see the module docs).
        ///
        /// Uniform sampling of the directions subtended by a triangle: the
        /// spherical triangle warp of Arvo, "Stratified sampling of spherical
        /// triangles", SIGGRAPH 1995, with its inverse (pbrt-v4's
        /// `InvertSphericalTriangleSample`), rewritten so that tiny, sliver and
        /// near-hemisphere triangles keep full precision in f32 and f64.
        ///
        /// # Solid angle
        /// Van Oosterom & Strackee, "The solid angle of a plane triangle", IEEE
        /// Trans. Biomed. Eng. 30(2), 1983: with Rᵢ = vᵢ − p and rᵢ = |Rᵢ|,
        ///
        /// tan(Ω/2) = |R₀·(R₁×R₂)| / (r₀r₁r₂ + (R₀·R₁)r₂ + (R₀·R₂)r₁ + (R₁·R₂)r₀),
        ///
        /// evaluated as Ω = 2 atan2(num, den) (den ≤ 0 for triangles above a
        /// hemisphere's worth of area), with the triple product taken from the
        /// edges, R₀·((v₁−v₀)×(v₂−v₀)), which has no cancellation. The angle excess
        /// α+β+γ−π (pbrt-v4) loses ~1e-3 relative in f32 at Ω ≈ 1e-4 sr and is 0
        /// below ~1e-8 sr; it is used nowhere here.
        ///
        /// # Sampling (Arvo's construction, cancellation-free)
        /// With A, B, C the unit vertex directions, α the angle at A and c the arc
        /// AB, the sub-triangle A B C′ of area Â = u₀Ω has its vertex C′ on the arc
        /// AC at the arc length b′ given by the area formula for two sides and the
        /// included angle, tan(Â/2) = tan(b′/2)tan(c/2) sin α / (1 + tan(b′/2)tan(c/2)
        /// cos α), solved for b′:
        ///
        /// tan(b′/2) = sin(Â/2) (1 + cos c) / (sin c · sin(α − Â/2)).
        ///
        /// With X = sin c · sin(α − Â/2) ≥ 0 and Y = sin(Â/2)(1 + cos c) ≥ 0 this
        /// gives cos b′ = (X−Y)(X+Y)/(X²+Y²), sin b′ = 2XY/(X²+Y²) and
        /// 1 − cos b′ = 2Y²/(X²+Y²): only products and sums of non-negative terms.
        /// It equals Arvo's cos b′ (and the form 2sin²(Â/2)(1+cos c) /
        /// [2sin²(Â/2) + sin(α−Â) sin α (1−cos c)], whose denominator cancels when
        /// Â > α); the tests check both identities in f64. Because Ω < 2α for every
        /// spherical triangle, α − Â/2 ∈ (0, α]; when α > π/2, sin(α − Â/2) is
        /// evaluated as sin α cos(Â/2) − cos α sin(Â/2) (two non-negative terms), so
        /// slivers with α → π keep their relative precision.
        ///
        /// Then C′ = cos b′ A + sin b′ T_AC (T_AC the unit tangent at A towards C),
        /// and w is uniform in 1 − cos θ on the arc B C′:
        /// z = 1 − cos θ = u₁ |C′ − B|²/2, sin θ = √(z(2 − z)) with
        /// 2 − z = |C′ + B|²/2 + (1 − u₁)|C′ − B|²/2 (no cancellation near θ = π),
        /// w = cos θ B + sin θ normalize((C′ − B) + B|C′ − B|²/2).
        ///
        /// The edge normals and the tangent at A are built from the input points'
        /// edge vectors (Rᵢ × (vⱼ − vᵢ)), not from the cross product of nearly equal
        /// unit vectors, so they are accurate to a few ulps for tiny triangles.
        ///
        /// Internally the vertices are ordered so that A·(B×C) > 0: A is
        /// always `v0`; `v1` and `v2` are swapped if the triangle is seen
        /// clockwise. `sample` and `invert` are inverse to each other for
        /// that order.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::SphericalTriangle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // An octant of the sphere: 4π/8 sr.
        #[doc = concat!("let t = SphericalTriangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X, ", stringify!($v3), "::Y, ", stringify!($v3), "::Z)?;")]
        #[doc = concat!("assert!((t.solid_angle() - std::", stringify!($p), "::consts::FRAC_PI_2).abs() < 1e-6);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.6, 0.3);")]
        /// let d = t.sample(u);
        /// assert!(d.direction.min_element() >= 0.0 && t.pdf(d.direction) == d.pdf);
        /// assert!((t.invert(d.direction) - u).length() < 1e-4);
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphericalTriangle {
            /// Unit vertex directions, with a·(b×c) > 0.
            a: V3,
            b: V3,
            c: V3,
            /// Unit edge normals ∝ a×b, b×c, c×a (pointing inside).
            n_ab: V3,
            n_bc: V3,
            n_ca: V3,
            /// Unit tangent at `a` along the great circle towards `c`.
            t_ac: V3,
            /// The angle α at `a`, and its sine and cosine.
            alpha: Real,
            sin_alpha: Real,
            cos_alpha: Real,
            /// sin c and 1 + cos c of the arc c = ab.
            sin_c: Real,
            one_plus_cos_c: Real,
            /// Ω, steradians.
            solid_angle: Real,
        }

        impl SphericalTriangle {
            /// The spherical triangle that the triangle `v0 v1 v2` subtends at
            /// the reference point `p`.
            ///
            /// Errors: a non-finite coordinate ([`SamplingError::NotFinite`]);
            /// a vertex at `p`, a degenerate triangle, `p` in the triangle's
            /// plane, or a solid angle so small that 1/Ω overflows
            /// ([`SamplingError::Degenerate`]).
            pub fn new(p: V3, v0: V3, v1: V3, v2: V3) -> Result<Self, SamplingError> {
                for (field, v) in [("p", p), ("v0", v0), ("v1", v1), ("v2", v2)] {
                    crate::error::finite3(field, wide3(v))?;
                }
                let (mut v1, mut v2) = (v1, v2);
                let r0 = v0 - p;
                let mut triple = r0.dot((v1 - v0).cross(v2 - v0));
                if triple < 0.0 {
                    core::mem::swap(&mut v1, &mut v2);
                    triple = -triple;
                }
                let (r1, r2) = (v1 - p, v2 - p);
                let (l0, l1, l2) = (r0.length(), r1.length(), r2.length());
                if !(l0 > 0.0 && l1 > 0.0 && l2 > 0.0) || !(l0 * l1 * l2).is_finite() {
                    return Err(SamplingError::Degenerate {
                        what: "a triangle vertex coincides with the reference point \
                               (or the coordinates overflow)",
                    });
                }
                if !(triple > 0.0 && triple.is_finite()) {
                    return Err(SamplingError::Degenerate {
                        what: "the triangle is degenerate or its plane contains the \
                               reference point (zero solid angle)",
                    });
                }
                let solid_angle = solid_angle_van_oosterom(r0, r1, r2, triple);
                if !(solid_angle > 0.0 && (1.0 / solid_angle).is_finite()) {
                    return Err(SamplingError::Degenerate {
                        what: "the triangle's solid angle is too small for its density \
                               1/Ω to be representable",
                    });
                }
                let (a, b, c) = (r0 / l0, r1 / l1, r2 / l2);
                // Edge normals from the edges: R_i × (v_j − v_i) = R_i × R_j.
                let raw_ab = r0.cross(v1 - v0);
                let n_ab = raw_ab.normalize_or_zero();
                let n_bc = r1.cross(v2 - v1).normalize_or_zero();
                let n_ca = r2.cross(v0 - v2).normalize_or_zero();
                // Tangents at a towards b and towards c.
                let t_ab = n_ab.cross(a).normalize_or_zero();
                let t_ac = a.cross(n_ca).normalize_or_zero();
                let cross = t_ab.cross(t_ac);
                let sin_alpha = cross.length();
                let cos_alpha = t_ab.dot(t_ac);
                let alpha = sin_alpha.atan2(cos_alpha);
                // sin c = |R0 × R1| / (r0 r1); 1 + cos c without cancellation.
                let sin_c = raw_ab.length() / l0 / l1;
                let ab = a.dot(b);
                let one_plus_cos_c = if ab >= 0.0 {
                    1.0 + ab
                } else {
                    0.5 * (a + b).length_squared()
                };
                let all_finite = [n_ab, n_bc, n_ca, t_ac]
                    .iter()
                    .all(|v| v.is_finite() && v.length_squared() > 0.5)
                    && sin_alpha > 0.0
                    && sin_c.is_finite()
                    && sin_c > 0.0;
                if !all_finite {
                    return Err(SamplingError::Degenerate {
                        what: "the triangle's edges cannot be resolved in this precision",
                    });
                }
                Ok(SphericalTriangle {
                    a,
                    b,
                    c,
                    n_ab,
                    n_bc,
                    n_ca,
                    t_ac,
                    alpha,
                    sin_alpha,
                    cos_alpha,
                    sin_c,
                    one_plus_cos_c,
                    solid_angle,
                })
            }

            /// The solid angle Ω of the spherical triangle, in steradians
            /// (Van Oosterom & Strackee 1983).
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.solid_angle
            }

            /// The unit vertex directions (A, B, C) in the internal,
            /// counter-clockwise order (A·(B×C) > 0).
            #[inline]
            pub fn vertices(&self) -> [V3; 3] {
                [self.a, self.b, self.c]
            }

            /// A direction uniform in the spherical triangle, with density
            /// 1/Ω per steradian (Arvo 1995, cancellation-free; see the module
            /// docs). Every u ∈ [0, 1]², including exact 0 and 1, gives a
            /// finite unit vector for which [`SphericalTriangle::pdf`] returns
            /// the same density.
            ///
            /// The sines are [`sin_cos`](crate::f64::sin_cos)'s (inlined, so
            /// the estimator's block kernels vectorise this sampler), not
            /// libm's.
            #[inline(always)]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let half_area = 0.5 * (u.x * self.solid_angle);
                let (s, ch) = sin_cos(half_area);
                // sin(α − Â/2) ≥ 0 (Ω < 2α); two non-negative terms when
                // α > π/2, a direct sine of an angle in (0, π/2] otherwise.
                let q = if self.cos_alpha < 0.0 {
                    self.sin_alpha * ch - self.cos_alpha * s
                } else {
                    sin(self.alpha - half_area)
                }
                .max(0.0);
                let x = self.sin_c * q;
                let y = s * self.one_plus_cos_c;
                let m = x.max(y);
                let (cos_b, sin_b) = if m > 0.0 {
                    let (x, y) = (x / m, y / m);
                    let d = x * x + y * y;
                    ((x - y) * (x + y) / d, 2.0 * x * y / d)
                } else {
                    (1.0, 0.0)
                };
                let cp = self.a * cos_b + self.t_ac * sin_b;
                // Uniform in 1 − cos θ along the arc from B to C′.
                let d = cp - self.b;
                let half_m2 = 0.5 * d.length_squared();
                let z = (u.y * half_m2).min(2.0);
                let cos_t = 1.0 - z;
                // 2 − z = (1 + cos θmax) + (1 − u₁)(1 − cos θmax): no
                // cancellation when B and C′ are nearly antipodal.
                let two_minus_z = 0.5 * (cp + self.b).length_squared() + (1.0 - u.y) * half_m2;
                let sin_t = (z * two_minus_z).max(0.0).sqrt();
                let tangent = (d + self.b * half_m2).normalize_or_zero();
                let w = (self.b * cos_t + tangent * sin_t).normalize();
                DirectionSample {
                    direction: w,
                    pdf: 1.0 / self.solid_angle,
                }
            }

            /// Whether the unit direction `w` lies in the spherical triangle:
            /// w·n ≥ −τ for the three inward edge normals n, with
            /// τ = 32ε. The slack is absolute (an angle in radians): a unit
            /// vector cannot be placed closer than a few ε to a great circle,
            /// and a sample drawn on an edge carries that much rounding, so
            /// this keeps pdf(sample(u)) equal to the returned pdf. It widens
            /// the support by a band of width 32ε rad along the boundary.
            ///
            /// Inline and branch-free (`&`, not `&&`: the same answer, no
            /// side effects), so that a batch loop testing several
            /// triangles per sample vectorises.
            #[inline(always)]
            pub fn contains(&self, w: V3) -> bool {
                let tol = -32.0 * Real::EPSILON;
                (w.dot(self.n_ab) >= tol) & (w.dot(self.n_bc) >= tol) & (w.dot(self.n_ca) >= tol)
            }

            /// The density 1/Ω per steradian of the unit direction `w` if it
            /// lies in the spherical triangle (see
            /// [`SphericalTriangle::contains`] for the rounding slack), 0
            /// otherwise; never NaN for finite `w`.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if self.contains(w) {
                    1.0 / self.solid_angle
                } else {
                    0.0
                }
            }

            /// The u ∈ [0, 1]² that [`SphericalTriangle::sample`] maps to the
            /// unit direction `w` of the triangle (after pbrt-v4's
            /// `InvertSphericalTriangleSample`): C′ is where the great circle
            /// through B and w meets the arc AC; u₀ = area(A, B, C′)/Ω with
            /// the area from tan(Â/2) = t T sin α/(1 + t T cos α),
            /// t = tan(b′/2) = |C′−A|/|C′+A|, T = tan(c/2); and
            /// u₁ = (1 − cos∠(B, w))/(1 − cos∠(B, C′)) = |w−B|²/|C′−B|².
            /// At w = B (where u₀ is undetermined) it returns (0, 0).
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                // b × (w − b), not b × w: the normal stays ⊥ b to rounding,
                // so the great circle passes through B even when w ≈ B.
                let cp = self
                    .b
                    .cross(w - self.b)
                    .cross(self.n_ca)
                    .normalize_or_zero();
                if cp == V3::ZERO {
                    return V2::ZERO;
                }
                let cp = if cp.dot(self.a + self.c) < 0.0 {
                    -cp
                } else {
                    cp
                };
                let dm = (cp - self.a).length();
                let dp = (cp + self.a).length();
                // 2 atan2(t T sin α, 1 + t T cos α), scaled by |C′+A|(1+cos c).
                let sub = 2.0
                    * (dm * self.sin_c * self.sin_alpha)
                        .atan2(dp * self.one_plus_cos_c + dm * self.sin_c * self.cos_alpha);
                let u0 = (sub / self.solid_angle).clamp(0.0, 1.0);
                let den = (cp - self.b).length_squared();
                let u1 = if den > 0.0 {
                    ((w - self.b).length_squared() / den).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                V2::new(u0, u1)
            }
        }
    };
}

lambert_geometry::both_precisions!(spherical_triangle_impl);

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg32;

    /// Named test triangles `(name, [p, v0, v1, v2])` in f64; the f32 tests
    /// use them rounded to f32. `tiny` has Ω ≈ 1e-10 sr in f64 scale and
    /// `tiny32` Ω ≈ 1e-6 sr.
    fn cases() -> Vec<(&'static str, [DVec3; 4])> {
        let p = DVec3::new(3.0, -2.0, 5.0);
        let dir = DVec3::new(0.48, 0.6, 0.64);
        let tiny = |s: f64| {
            [
                p,
                p + dir + DVec3::new(1.0, 0.0, 0.0) * s,
                p + dir + DVec3::new(0.0, 1.0, 0.3) * s,
                p + dir + DVec3::new(-0.5, -0.4, 0.2) * s,
            ]
        };
        let (c, s) = (0.5, 0.75f64.sqrt());
        vec![
            (
                "ordinary",
                [
                    DVec3::ZERO,
                    DVec3::new(0.3, -0.2, -1.0),
                    DVec3::new(1.1, 0.4, -1.2),
                    DVec3::new(-0.2, 0.9, -0.8),
                ],
            ),
            ("tiny", tiny(1.6e-5)),
            ("tiny32", tiny(1.6e-3)),
            (
                // A (v0) almost on the edge v1 v2: α → π.
                "sliver_at_a",
                [
                    DVec3::ZERO,
                    DVec3::new(0.1, 1e-3, -1.0),
                    DVec3::new(-1.0, 0.0, -1.0),
                    DVec3::new(1.0, 0.0, -1.0),
                ],
            ),
            (
                // v1 almost on the edge v2 v0.
                "sliver_at_b",
                [
                    DVec3::ZERO,
                    DVec3::new(-1.0, 0.0, -1.0),
                    DVec3::new(0.1, 1e-3, -1.0),
                    DVec3::new(1.0, 0.0, -1.0),
                ],
            ),
            (
                // Circumradius 1 at height 0.01: Ω ≈ 2π − 0.1 (den < 0).
                "near_hemisphere",
                [
                    DVec3::ZERO,
                    DVec3::new(1.0, 0.0, -0.01),
                    DVec3::new(-c, s, -0.01),
                    DVec3::new(-c, -s, -0.01),
                ],
            ),
            (
                // p 1e-3 from the triangle's plane, the triangle 1–2 away.
                "grazing",
                [
                    DVec3::ZERO,
                    DVec3::new(1.0, 0.0, -1e-3),
                    DVec3::new(2.0, 1.0, -1e-3),
                    DVec3::new(2.0, -1.0, -1e-3),
                ],
            ),
        ]
    }

    /// Angle excess α+β+γ−π with acos of normalised tangents: an
    /// independent (cancelling, so only for ordinary triangles) reference.
    fn excess(p: DVec3, v: [DVec3; 3]) -> f64 {
        let d = v.map(|x| (x - p).normalize());
        let angle = |a: DVec3, b: DVec3, c: DVec3| {
            let tb = (b - a * a.dot(b)).normalize();
            let tc = (c - a * a.dot(c)).normalize();
            tb.dot(tc).clamp(-1.0, 1.0).acos()
        };
        angle(d[0], d[1], d[2]) + angle(d[1], d[2], d[0]) + angle(d[2], d[0], d[1])
            - std::f64::consts::PI
    }

    /// Arvo's (1995) original cos b′ and the brief's 1 − cos b′ form against
    /// the tangent-half-angle form the sampler uses, in f64 on random
    /// ordinary triangles; and the sampler's C′ (its sample at u₁ = 1) against
    /// Arvo's C′.
    #[test]
    fn cos_b_prime_matches_arvo() {
        use std::f64::consts::PI;
        let mut rng = Pcg32::seed_from_u64(11);
        let mut unit = || {
            DVec3::new(
                rng.random::<f64>() - 0.5,
                rng.random::<f64>() - 0.5,
                rng.random::<f64>() - 0.5,
            )
            .normalize()
        };
        let mut checked = 0;
        while checked < 200 {
            let (a, b, c) = (unit(), unit(), unit());
            let Ok(tri) = super::f64::SphericalTriangle::new(DVec3::ZERO, a, b, c) else {
                continue;
            };
            let [a, b, c] = tri.vertices();
            let omega = tri.solid_angle();
            if omega < 1e-3 {
                continue;
            }
            let ang = |a: DVec3, b: DVec3, c: DVec3| {
                let tb = (b - a * a.dot(b)).normalize();
                let tc = (c - a * a.dot(c)).normalize();
                tb.dot(tc).clamp(-1.0, 1.0).acos()
            };
            let alpha = ang(a, b, c);
            let cos_c = a.dot(b);
            let cc = cos_c.clamp(-1.0, 1.0).acos();
            for k in 0..=10 {
                let u0 = k as f64 / 10.0;
                let ah = u0 * omega;
                // Arvo 1995, Fig. 2 (Â measured as the sub-triangle's area).
                let (s, t) = (ah - alpha).sin_cos();
                let uu = t - alpha.cos();
                let v = s + alpha.sin() * cos_c;
                let q_arvo =
                    ((v * t - uu * s) * alpha.cos() - v) / ((v * s + uu * t) * alpha.sin());
                // The brief's form.
                let sh2 = (0.5 * ah).sin().powi(2);
                let h_brief = 2.0 * sh2 * (1.0 + cos_c)
                    / (2.0 * sh2 + (alpha - ah).sin() * alpha.sin() * (1.0 - cos_c));
                // The implemented tan(b′/2) form.
                let tb = (0.5 * ah).sin() / ((0.5 * cc).tan() * (alpha - 0.5 * ah).sin());
                let q_ours = (1.0 - tb * tb) / (1.0 + tb * tb);
                assert!((q_ours - q_arvo).abs() < 1e-9, "{q_ours} vs Arvo {q_arvo}");
                if (1.0 - q_arvo) > 1e-3 {
                    let rel = ((1.0 - q_ours) - h_brief).abs() / h_brief;
                    assert!(
                        rel < 1e-7,
                        "1 − cos b′: {} vs brief {h_brief}",
                        1.0 - q_ours
                    );
                }
                // The sampler's C′ against Arvo's.
                let cp_arvo = a * q_arvo
                    + (c - a * c.dot(a)).normalize() * (1.0 - q_arvo * q_arvo).max(0.0).sqrt();
                let cp = tri.sample(glam::DVec2::new(u0, 1.0)).direction;
                // Arvo's q has error ~1e-12 here, and √(1 − q²) amplifies
                // it near q = 1 to ~√(2·1e-12) ≈ 1.4e-6.
                assert!((cp - cp_arvo).length() < 2e-6, "C′ {cp} vs Arvo {cp_arvo}");
            }
            assert!(omega < 2.0 * PI);
            checked += 1;
        }
    }

    #[test]
    fn bad_input_is_a_clear_error() {
        use super::f64::SphericalTriangle as T;
        use crate::SamplingError;
        let (o, x, y) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let z = -DVec3::Z;
        assert!(matches!(
            T::new(o, DVec3::new(f64::NAN, 0.0, -1.0), x + z, y + z),
            Err(SamplingError::NotFinite { field: "v0", .. })
        ));
        // A vertex at p, collinear vertices, p in the triangle's plane.
        assert!(matches!(
            T::new(o, o, x + z, y + z),
            Err(SamplingError::Degenerate { .. })
        ));
        assert!(matches!(
            T::new(o, z, 2.0 * z, 3.0 * z),
            Err(SamplingError::Degenerate { .. })
        ));
        assert!(matches!(
            T::new(o, x, y, x + y),
            Err(SamplingError::Degenerate { .. })
        ));
        // Both orientations give the same solid angle and support.
        let a = T::new(o, z, x + z, y + z).unwrap();
        let b = T::new(o, z, y + z, x + z).unwrap();
        assert_eq!(a.solid_angle(), b.solid_angle());
        let w = (DVec3::new(0.2, 0.2, 0.0) + z).normalize();
        assert!(a.pdf(w) > 0.0 && b.pdf(w) > 0.0 && a.pdf(-w) == 0.0);
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

                /// The case rounded to this precision, and widened back (so
                /// f64 references see exactly the same inputs).
                fn case(g: [DVec3; 4]) -> ([V3; 4], [DVec3; 4]) {
                    let r = g.map(narrow3);
                    (r, r.map(wide3))
                }
                const EPS: f64 = Real::EPSILON as f64;
                /// Longest chord between vertex directions, radians-ish.
                fn longest_chord(t: &crate::f64::SphericalTriangle) -> f64 {
                    let [a, b, c] = t.vertices();
                    (a - b).length().max((b - c).length()).max((c - a).length())
                }
                fn skip(name: &str) -> bool {
                    // Ω ≈ 1e-10 sr is below f32's reach (see the module
                    // tests' limits); f32 uses `tiny32` instead.
                    Real::EPSILON as f64 > 1e-10 && name == "tiny"
                }

                #[test]
                fn solid_angle_against_references() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let tri = SphericalTriangle::new(r[0], r[1], r[2], r[3]).unwrap();
                        let omega = tri.solid_angle() as f64;
                        let omega64 =
                            lambert_geometry::f64::triangle_solid_angle(w[0], w[1], w[2], w[3]);
                        // Same inputs: only this precision's rounding, a
                        // few tens of ulps relative.
                        let rel = (omega - omega64).abs() / omega64;
                        assert!(rel < 64.0 * EPS, "{name}: {omega} vs f64 {omega64}");
                        if name.starts_with("tiny") {
                            // Planar approximation A cos θ / d² about the
                            // centroid: relative error ≤ size/d.
                            let cen = (w[1] + w[2] + w[3]) / 3.0 - w[0];
                            let n = (w[2] - w[1]).cross(w[3] - w[1]);
                            let planar = 0.5 * n.dot(cen).abs() / cen.length().powi(3);
                            let size = (w[2] - w[1]).length().max((w[3] - w[1]).length());
                            let rel = (omega64 - planar).abs() / planar;
                            assert!(rel <= size / cen.length(), "{name}: {omega64} vs {planar}");
                        } else if name == "ordinary" || name == "near_hemisphere" {
                            let ex = excess(w[0], [w[1], w[2], w[3]]);
                            assert!(
                                (omega64 - ex).abs() < 1e-12 * ex,
                                "{name}: {omega64} vs {ex}"
                            );
                        }
                    }
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
                fn samples_are_unit_inside_and_corners_work() {
                    let one = 1.0 as Real;
                    let corners = [0.0, ONE_MINUS_EPSILON, one, 0.5];
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, _) = case(g);
                        let tri = SphericalTriangle::new(r[0], r[1], r[2], r[3]).unwrap();
                        let mut us = grid(41, 0.0, 1.0);
                        for a in corners {
                            for b in corners {
                                us.push(V2::new(a, b));
                            }
                        }
                        for u in us {
                            let s = tri.sample(u);
                            let w = s.direction;
                            assert!(w.is_finite(), "{name} {u}: {w}");
                            assert!((w.length() - 1.0).abs() < 4.0 * Real::EPSILON, "{name} {u}");
                            assert!(s.pdf > 0.0 && s.pdf.is_finite());
                            assert_eq!(tri.pdf(w), s.pdf, "{name} {u}: {w} outside");
                            let inv = tri.invert(w);
                            assert!(inv.is_finite() && inv.min_element() >= 0.0);
                        }
                        // A direction well outside: pdf 0, no NaN.
                        let out = -(tri.vertices()[0] + tri.vertices()[1] + tri.vertices()[2]);
                        assert_eq!(tri.pdf(out.normalize()), 0.0);
                    }
                }

                /// invert(sample(u)) ≈ u. A sample carries an absolute
                /// direction error δ ≈ a few ε; moving w by δ moves C′ by at
                /// most δ/√u₁ ≤ 4.5δ (u₁ ≥ 0.05) and so the sub-area by
                /// ≲ 4.5δ·c_max, i.e. u₀ by 4.5δ c_max/Ω, and u₁ by
                /// ≲ 2δ/|BC′| ≤ δ c_max/Ω (|BC′| ≥ the height from B,
                /// 2Ω/c_max). Hence |Δu| ≤ K ε (1 + c_max/Ω) with K = 256
                /// (δ ≈ 16ε, slack ×3).
                #[test]
                fn invert_inverts_sample() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let tri = SphericalTriangle::new(r[0], r[1], r[2], r[3]).unwrap();
                        let t64 =
                            crate::f64::SphericalTriangle::new(w[0], w[1], w[2], w[3]).unwrap();
                        let tol = 256.0 * EPS * (1.0 + longest_chord(&t64) / t64.solid_angle());
                        let mut worst: f64 = 0.0;
                        for u in grid(19, 0.05, 0.95) {
                            let back = tri.invert(tri.sample(u).direction);
                            let err = (back - u).abs().max_element() as f64;
                            worst = worst.max(err);
                        }
                        assert!(worst <= tol, "{name}: worst {worst:e} > tol {tol:e}");
                    }
                }

                /// This precision against f64 on the same (rounded) inputs.
                /// The map u → w has sensitivity ~c_max²/Ω to a relative
                /// perturbation of the vertices (a sliver's area, hence the
                /// placement of C′, changes by ~δ c_max/Ω per δ); the
                /// algorithm's own rounding is such a perturbation of a few
                /// tens of ε. Tolerance: 64 ε (1 + c_max²/Ω), in radians.
                #[test]
                fn agrees_with_f64() {
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let tri = SphericalTriangle::new(r[0], r[1], r[2], r[3]).unwrap();
                        let t64 =
                            crate::f64::SphericalTriangle::new(w[0], w[1], w[2], w[3]).unwrap();
                        let c = longest_chord(&t64);
                        let tol = 64.0 * EPS * (1.0 + c * c / t64.solid_angle());
                        let mut worst: f64 = 0.0;
                        for u in grid(21, 0.0, 1.0) {
                            let a = wide3(tri.sample(u).direction);
                            let b = t64
                                .sample(glam::DVec2::new(u.x as f64, u.y as f64))
                                .direction;
                            worst = worst.max((a - b).length());
                        }
                        assert!(worst <= tol, "{name}: worst {worst:e} > tol {tol:e}");
                    }
                }

                /// Fraction of 200k samples in the sub-triangle of the edge
                /// midpoints (not aligned with Arvo's construction) against
                /// its solid-angle fraction, within 4.5 binomial sigmas; and a
                /// negative control (u₀ → u₀^0.9) that the same test rejects.
                #[test]
                fn fraction_in_midpoint_triangle() {
                    let n = 200_000;
                    for (name, g) in cases() {
                        if skip(name) {
                            continue;
                        }
                        let (r, w) = case(g);
                        let tri = SphericalTriangle::new(r[0], r[1], r[2], r[3]).unwrap();
                        let t64 =
                            crate::f64::SphericalTriangle::new(w[0], w[1], w[2], w[3]).unwrap();
                        let mid = |i: usize, j: usize| 0.5 * (w[i] + w[j]);
                        let sub = crate::f64::SphericalTriangle::new(
                            w[0],
                            mid(1, 2),
                            mid(2, 3),
                            mid(3, 1),
                        )
                        .unwrap();
                        let frac = sub.solid_angle() / t64.solid_angle();
                        let sigma = (frac * (1.0 - frac) / n as f64).sqrt();
                        for (skew, must_pass) in [(1.0, true), (0.9, false)] {
                            let mut rng = Pcg32::seed_from_u64(2024);
                            let mut hits = 0usize;
                            for _ in 0..n {
                                let u0: Real = rng.random();
                                let u = V2::new(u0.powf(skew as Real), rng.random());
                                if sub.contains(wide3(tri.sample(u).direction)) {
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
