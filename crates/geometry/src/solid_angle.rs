//! Solid angles, in steradians, computed without cancellation: the
//! formulas the shapes' `solid_angle_from` methods and the samplers share.
//!
//! Ω = A/r² for a small patch of sphere; dω = sin θ dθ dφ; the whole
//! sphere is 4π sr.

macro_rules! solid_angle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{Real, V3, PI};

        /// The solid angle of a cap (a cone of directions) of half-angle
        /// θ ∈ [0, π]: Ω = 2π(1 − cos θ), evaluated as 4π sin²(θ/2), which
        /// keeps full relative precision for θ = 1e-8 (where 1 − cos θ
        /// rounds to 0).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::cap_solid_angle;")]
        /// // The Moon, 0.25° in angular radius: about 60 μsr.
        #[doc = concat!("let omega = cap_solid_angle(0.25", stringify!($p), ".to_radians());")]
        /// assert!((omega - 59.811e-6).abs() < 1e-8);
        /// ```
        #[inline]
        pub fn cap_solid_angle(half_angle: Real) -> Real {
            let s = (0.5 * half_angle).sin();
            4.0 * PI * s * s
        }

        /// 1 − cos θ of a cap of half-angle θ ≤ π/2 given s² = sin²θ:
        /// s²/(1 + √(1 − s²)), exact algebra with no cancellation (the
        /// direct 1 − √(1 − s²) rounds to 0 for s² below ε).
        #[inline]
        pub fn one_minus_cos_from_sin2(sin2: Real) -> Real {
            sin2 / (1.0 + (1.0 - sin2).max(0.0).sqrt())
        }

        /// The solid angle of a cap of half-angle θ ≤ π/2 given s² = sin²θ:
        /// Ω = 2π s²/(1 + √(1 − s²)) (see [`one_minus_cos_from_sin2`]).
        #[inline]
        pub fn cap_solid_angle_from_sin2(sin2: Real) -> Real {
            2.0 * PI * one_minus_cos_from_sin2(sin2)
        }

        /// The solid angle of the triangle with vertices `r0`, `r1`, `r2`
        /// relative to the viewpoint, whose triple product r₀·(r₁×r₂) the
        /// caller has computed without cancellation as `triple` (its sign
        /// is ignored).
        ///
        /// Van Oosterom & Strackee, "The solid angle of a plane triangle",
        /// IEEE Trans. Biomed. Eng. 30(2), 1983:
        /// Ω = 2 atan2(|triple|, r₀r₁r₂ + (r₀·r₁)r₂ + (r₀·r₂)r₁ + (r₁·r₂)r₀).
        /// Accurate to a few ulps relative for small triangles and a few ulps
        /// of 2π absolute for huge ones. (The angle-excess form α + β + γ − π
        /// is off by ~1e-3 relative in f32 for Ω near 1e-4 sr, and gives 0
        /// for most triangles under 1e-8 sr.)
        #[inline]
        pub fn solid_angle_van_oosterom(r0: V3, r1: V3, r2: V3, triple: Real) -> Real {
            let (l0, l1, l2) = (r0.length(), r1.length(), r2.length());
            let den = l0 * l1 * l2 + r0.dot(r1) * l2 + r0.dot(r2) * l1 + r1.dot(r2) * l0;
            2.0 * triple.abs().atan2(den)
        }

        /// The solid angle that the triangle `v0 v1 v2` subtends at `p`
        /// ([`solid_angle_van_oosterom`]), with the triple product taken
        /// from the edges, (v₀ − p)·((v₁ − v₀)×(v₂ − v₀)), so tiny and
        /// distant triangles keep full relative precision. 0 for a
        /// degenerate triangle or one whose plane contains `p`.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::triangle_solid_angle;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // An octant of the sphere: 4π/8.
        #[doc = concat!("let o = triangle_solid_angle(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X, ", stringify!($v3), "::Y, ", stringify!($v3), "::Z);")]
        #[doc = concat!("assert!((o - ", "std::", stringify!($p), "::consts::FRAC_PI_2).abs() < 1e-6);")]
        /// ```
        #[inline]
        pub fn triangle_solid_angle(p: V3, v0: V3, v1: V3, v2: V3) -> Real {
            let r0 = v0 - p;
            let triple = r0.dot((v1 - v0).cross(v2 - v0));
            solid_angle_van_oosterom(r0, v1 - p, v2 - p, triple)
        }

        /// The solid angle of a planar convex polygon seen from `p`: the
        /// fan of triangles (v₀, vᵢ, vᵢ₊₁), each by Van Oosterom–Strackee.
        /// From any viewpoint the fan triangles of a convex polygon have
        /// the same orientation, so their unsigned solid angles add
        /// without cancellation. Fewer than 3 vertices give 0.
        #[inline]
        pub fn convex_polygon_solid_angle(p: V3, vertices: &[V3]) -> Real {
            if vertices.len() < 3 {
                return 0.0;
            }
            let v0 = vertices[0];
            vertices[1..]
                .windows(2)
                .map(|w| triangle_solid_angle(p, v0, w[0], w[1]))
                .sum()
        }

        /// The solid angle of a disk of `radius` R seen from a point at
        /// height `h` ≥ 0 above its plane whose foot lies at distance
        /// `s` ≥ 0 from its centre; 0 when h = 0.
        ///
        /// Ω = ∫∫ h/r³ dA is integrated in closed form along each ray of
        /// the pencil at the foot, leaving a one-dimensional integral of an
        /// analytic periodic function that the trapezoidal rule integrates
        /// with exponential convergence (Trefethen & Weideman, SIAM Review
        /// 56, 2014):
        /// - foot inside (s < R): Ω = ∫₀^{2π} ρ²/(r(r + h)) dφ with
        ///   ρ(φ) = s cos φ + √((R − s sin φ)(R + s sin φ)), r = √(h² + ρ²)
        ///   (that is 1 − h/r without cancellation);
        /// - foot outside (s ≥ R): substituting s sin φ = R sin ψ,
        ///   Ω = ∫_{−π/2}^{π/2} 4hR² cos²ψ / (r₁ r₂ (r₁ + r₂)) dψ with
        ///   ρ₂ = √((s − R sin ψ)(s + R sin ψ)) + R cos ψ,
        ///   ρ₁ = (s − R)(s + R)/ρ₂, rᵢ = √(h² + ρᵢ²).
        ///
        /// Work and accuracy: the node count doubles from 16 until two
        /// successive sums agree to max(1e-15, 4ε) relative, and stops at
        /// 2²² nodes whatever happens. The closed form in complete
        /// elliptic integrals (Paxton, Rev. Sci. Instrum. 30, 1959)
        /// computes a small Ω as 2π minus a number close to 2π and is not
        /// used.
        ///
        /// Ω depends only on the ratios of h, s and R, so the three are
        /// first scaled by the power of two 2^−k that brings the largest
        /// near 1: exact, so ordinary inputs give the same bits, and the
        /// squares inside can neither overflow (a disk 1e300 across, whose
        /// Ω was NaN) nor underflow.
        pub fn disk_solid_angle_hs(h: Real, s: Real, radius: Real) -> Real {
            if !(h > 0.0) || !(radius > 0.0) {
                return 0.0;
            }
            let largest = h.max(s).max(radius);
            let (h, s, r) = if largest.is_finite() {
                let k = largest.log2().floor() as i32;
                // 2^−k in two factors, each a normal number even at the
                // ends of the range (|k| up to 1074 in f64).
                let (a, b) = ((2.0 as Real).powi(-k / 2), (2.0 as Real).powi(-k + k / 2));
                (h * a * b, s * a * b, radius * a * b)
            } else {
                (h, s, radius)
            };
            if s < r {
                let f = |phi: Real| {
                    let (sp, cp) = phi.sin_cos();
                    let rho = s * cp + ((r - s * sp) * (r + s * sp)).sqrt();
                    let len = h.hypot(rho);
                    rho * rho / (len * (len + h))
                };
                periodic_trapezoid(f, 0.0, 2.0 * PI)
            } else {
                let f = |psi: Real| {
                    let (sp, cp) = psi.sin_cos();
                    let rho2 = ((s - r * sp) * (s + r * sp)).sqrt() + r * cp;
                    let rho1 = (s - r) * (s + r) / rho2;
                    let (r1, r2) = (h.hypot(rho1), h.hypot(rho2));
                    4.0 * h * r * r * cp * cp / (r1 * r2 * (r1 + r2))
                };
                periodic_trapezoid(f, -0.5 * PI, 0.5 * PI)
            }
        }

        /// The trapezoidal rule over one period [a, b] of a periodic
        /// function, doubling the nodes until two sums agree to
        /// max(1e-15, 4ε) relative, or 2²² nodes.
        fn periodic_trapezoid<F: Fn(Real) -> Real>(f: F, a: Real, b: Real) -> Real {
            let tolerance = (1e-15 as Real).max(4.0 * Real::EPSILON);
            let width = b - a;
            let mut n = 16usize;
            let mut sum: Real = (0..n).map(|j| f(a + width * j as Real / n as Real)).sum();
            let mut estimate = sum * width / n as Real;
            while n < (1 << 22) {
                // The new nodes are the midpoints of the old ones.
                let mid: Real = (0..n)
                    .map(|j| f(a + width * (j as Real + 0.5) / n as Real))
                    .sum();
                sum += mid;
                n *= 2;
                let next = sum * width / n as Real;
                let converged = (next - estimate).abs() <= tolerance * next.abs();
                estimate = next;
                if converged {
                    break;
                }
            }
            estimate
        }
    };
}

crate::both_precisions!(solid_angle_impl);

#[cfg(test)]
mod tests {
    use super::f64::*;
    use glam::DVec3;
    use std::f64::consts::PI;

    #[test]
    fn caps_small_and_large() {
        assert_eq!(cap_solid_angle(PI), 4.0 * PI);
        let tiny = cap_solid_angle(1e-8);
        assert!((tiny / (PI * 1e-16) - 1.0).abs() < 1e-15);
        assert!((cap_solid_angle_from_sin2(1.0) - 2.0 * PI).abs() < 1e-15);
        assert!((cap_solid_angle_from_sin2(1e-20) / (PI * 1e-20) - 1.0).abs() < 1e-15);
    }

    /// Disks whose squared lengths overflow or underflow: Ω is scale
    /// invariant, so a disk 2^600 times larger (or smaller), seen from 2^600
    /// times farther (nearer), has the same Ω to the bit (scaling by a
    /// power of two is exact); a disk 1e300 across 1e-20 above the receiver
    /// subtends the hemisphere, 2π(1 − h/√(h² + R²)) = 2π to rounding
    /// (it was NaN: R² overflowed).
    #[test]
    fn disks_at_the_ends_of_the_range() {
        for (h, s, r) in [(0.7, 0.2, 1.3), (0.4, 3.0, 1.0), (1e-3, 0.0, 1.0)] {
            let omega = disk_solid_angle_hs(h, s, r);
            for f in [2f64.powi(600), 2f64.powi(-600)] {
                assert_eq!(
                    disk_solid_angle_hs(h * f, s * f, r * f),
                    omega,
                    "{h} {s} {r} × {f}"
                );
            }
        }
        assert!((disk_solid_angle_hs(1e-20, 0.0, 1e300) - 2.0 * PI).abs() <= 4.0 * f64::EPSILON);
        assert!((disk_solid_angle_hs(1e-20, 1e299, 1e300) - 2.0 * PI).abs() <= 4.0 * f64::EPSILON);
        // f32: a disk 1e30 across (R² overflows f32).
        let w = super::f32::disk_solid_angle_hs(1e-3, 0.0, 1e30);
        assert!((w - 2.0 * std::f32::consts::PI).abs() <= 4.0 * f32::EPSILON);
    }

    #[test]
    fn a_cube_face_from_the_centre_is_a_sixth_of_the_sphere() {
        let corners = [
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(1.0, -1.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, 1.0, 1.0),
        ];
        let o = convex_polygon_solid_angle(DVec3::ZERO, &corners);
        assert!((o - 4.0 * PI / 6.0).abs() < 1e-14);
    }

    #[test]
    fn disk_on_axis_is_a_cap() {
        let o = disk_solid_angle_hs(2.0, 0.0, 1.0);
        assert!((o - cap_solid_angle_from_sin2(1.0 / 5.0)).abs() < 1e-15);
        // Off axis, inside and outside the rim: against a fine midpoint sum
        // of h/r³ over the disk in polar coordinates.
        for (h, s) in [(0.5, 0.3), (0.2, 2.0), (0.3, 0.9)] {
            let n = 2000;
            let mut sum = 0.0;
            for i in 0..n {
                let rho = (i as f64 + 0.5) / n as f64;
                for j in 0..n {
                    let phi = 2.0 * PI * (j as f64 + 0.5) / n as f64;
                    let (x, y) = (rho * phi.cos() - s, rho * phi.sin());
                    let r2 = x * x + y * y + h * h;
                    sum += h / (r2 * r2.sqrt()) * rho;
                }
            }
            let reference = sum * (1.0 / n as f64) * (2.0 * PI / n as f64);
            let o = disk_solid_angle_hs(h, s, 1.0);
            // The midpoint sum's own error is O(1/n²) of the integrand's
            // curvature (h/r³ varies on the scale h ≥ 0.2 here, 400 cells
            // per h): a few 1e-6 relative; the rim's kink adds O(1/n) of a
            // cell row, 5e-4 at most.
            assert!(
                (o / reference - 1.0).abs() < 1e-3,
                "{h} {s}: {o} vs {reference}"
            );
        }
    }

    #[test]
    fn cap_forms_agree_and_keep_tiny_angles() {
        for &t in &[1e-8, 1e-4, 0.3, 1.2, std::f64::consts::FRAC_PI_2] {
            let s = f64::sin(t);
            // Both forms are exact rewrites; a few ulps apart.
            assert!(
                (cap_solid_angle(t) - cap_solid_angle_from_sin2(s * s)).abs()
                    <= 4e-16 * cap_solid_angle(t)
            );
        }
        // α = 1e-8: Ω = πα²(1 − α²/12 …) to 1e-16 relative.
        assert!((cap_solid_angle(1e-8) / (PI * 1e-16) - 1.0).abs() < 4e-16);
    }

    #[test]
    fn disk_far_away_is_area_over_distance_squared() {
        // Far on the axis: Ω = 2π(1 − cos α) exact; off axis at distance D,
        // Ω = πR² h/D³ (1 + O(R²/D²)): relative correction ~1e-12 at D=1e6.
        let o = disk_solid_angle_hs(1e6, 0.0, 1.0);
        assert!((o / cap_solid_angle_from_sin2(1.0 / (1e12 + 1.0)) - 1.0).abs() < 1e-14);
        let (h, s) = (6e5, 8e5);
        let o = disk_solid_angle_hs(h, s, 1.0);
        assert!((o / (PI * h / 1e18) - 1.0).abs() < 1e-11);
    }
}
