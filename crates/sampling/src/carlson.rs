//! Carlson's symmetric elliptic integrals of the first and third kinds,
//!
//! R_F(x, y, z) = ½ ∫₀^∞ dt / √((t + x)(t + y)(t + z)),
//! R_J(x, y, z, p) = (3/2) ∫₀^∞ dt / ((t + p) √((t + x)(t + y)(t + z))),
//!
//! for x, y, z ≥ 0 (at most one of them 0) and p > 0, evaluated together by
//! Carlson's duplication algorithm (B. C. Carlson, "Numerical computation of
//! real or complex elliptic integrals", Numerical Algorithms 10, 1995; the
//! form of DLMF §19.36(i), eqs. 19.36.1–2). Each duplication step replaces
//! every argument v by (v + λ)/4 with λ = √x√y + √x√z + √y√z, which leaves
//! R_F unchanged and R_J unchanged up to an added term 6·4⁻ᵐ R_C(1, 1 + eₘ)/dₘ;
//! it shrinks the arguments' spread about their mean A by 4. When the spread
//! is below (3r)^{1/6} A (R_F) or (r/4)^{1/6} A (R_J), a fifth-order Taylor
//! polynomial in the normalised deviations gives the integrals to relative
//! error r; we take r = ε of the precision. The number of steps is about
//! 4.5 + log₄(spread/A) in f64 and 2 + log₄(spread/A) in f32, at most
//! `CARLSON_MAX_STEPS` (enough for a spread
//! of 4⁵⁰ ≈ 1e30 times the mean).
//!
//! These are written here rather than taken from a crate because the
//! samplers need them in both precisions from one source, in their
//! non-negative real domain only, and fused (one loop for R_F and R_J at the
//! same x, y, z); the crates we found offer f64 only.

macro_rules! carlson_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::Real;
        /// The most duplication steps [`carlson_rf_rj`] takes.
        pub const CARLSON_MAX_STEPS: usize = 56;

        /// (3ε)^{-1/6} and (ε/4)^{-1/6}, rounded up: the stopping factors of
        /// R_F and R_J for relative error ε (Carlson 1995).
        const STOP_F: Real = if Real::EPSILON > 1e-10 { 11.9 } else { 338.4 };
        const STOP_J: Real = if Real::EPSILON > 1e-10 { 18.0 } else { 512.0 };

        /// R_C(1, 1 + e) for e > −1: atan(√e)/√e for e > 0,
        /// atanh(√−e)/√−e for e < 0; for |e| < 1/64 the series
        /// Σ (−e)ᵏ/(2k + 1), summed until a term is below ε/4 of the sum.
        #[inline]
        fn rc_one(e: Real) -> Real {
            if e.abs() < 1.0 / 64.0 {
                let mut sum: Real = 0.0;
                let mut power: Real = 1.0;
                let mut k: Real = 0.0;
                for _ in 0..16 {
                    let term = power / (2.0 * k + 1.0);
                    sum += term;
                    if term.abs() <= 0.25 * Real::EPSILON * sum {
                        break;
                    }
                    power *= -e;
                    k += 1.0;
                }
                sum
            } else if e > 0.0 {
                let s = e.sqrt();
                s.atan() / s
            } else {
                let s = (-e).sqrt();
                s.atanh() / s
            }
        }

        /// (R_F(x, y, z), R_J(x, y, z, p)) for x, y, z ≥ 0 with at most one
        /// of them 0, and p > 0, each to a few ulps (module docs).
        ///
        /// # Panics
        /// Debug builds check the domain.
        #[inline]
        pub fn carlson_rf_rj(x: Real, y: Real, z: Real, p: Real) -> (Real, Real) {
            debug_assert!(
                x >= 0.0 && y >= 0.0 && z >= 0.0 && p > 0.0,
                "R_F/R_J domain"
            );
            let (x0, y0, z0) = (x, y, z);
            let (mut x, mut y, mut z, mut p) = (x, y, z, p);
            let af0 = (x + y + z) / 3.0;
            let aj0 = (x + y + z + 2.0 * p) / 5.0;
            let delta = (p - x) * (p - y) * (p - z);
            let qf = STOP_F * (af0 - x).abs().max((af0 - y).abs()).max((af0 - z).abs());
            let qj = STOP_J
                * (aj0 - x)
                    .abs()
                    .max((aj0 - y).abs())
                    .max((aj0 - z).abs())
                    .max((aj0 - p).abs());
            let (mut af, mut aj) = (af0, aj0);
            // 4⁻ᵐ, and the R_C sum of R_J.
            let mut scale: Real = 1.0;
            let mut sum: Real = 0.0;
            for _ in 0..CARLSON_MAX_STEPS {
                if scale * qf < af.abs() && scale * qj < aj.abs() {
                    break;
                }
                let (sx, sy, sz, sp) = (x.sqrt(), y.sqrt(), z.sqrt(), p.sqrt());
                let lambda = sx * sy + sx * sz + sy * sz;
                let d = (sp + sx) * (sp + sy) * (sp + sz);
                let e = scale * scale * scale * delta / (d * d);
                sum += scale * rc_one(e) / d;
                x = 0.25 * (x + lambda);
                y = 0.25 * (y + lambda);
                z = 0.25 * (z + lambda);
                p = 0.25 * (p + lambda);
                af = 0.25 * (af + lambda);
                aj = 0.25 * (aj + lambda);
                scale *= 0.25;
            }
            // Deviations from the mean, as (A₀ − v₀)/(4ᵐ Aₘ): no cancellation.
            let (xf, yf) = (scale * (af0 - x0) / af, scale * (af0 - y0) / af);
            let zf = -xf - yf;
            let e2 = xf * yf - zf * zf;
            let e3 = xf * yf * zf;
            let rf =
                (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0) / af.sqrt();
            let (xj, yj, zj) = (
                scale * (aj0 - x0) / aj,
                scale * (aj0 - y0) / aj,
                scale * (aj0 - z0) / aj,
            );
            let pj = -0.5 * (xj + yj + zj);
            let e2 = xj * yj + xj * zj + yj * zj - 3.0 * pj * pj;
            let xyz = xj * yj * zj;
            let e3 = xyz + 2.0 * e2 * pj + 4.0 * pj * pj * pj;
            let e4 = (2.0 * xyz + e2 * pj + 3.0 * pj * pj * pj) * pj;
            let e5 = xyz * pj * pj;
            let series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
                - 3.0 * e4 / 22.0
                - 9.0 * e2 * e3 / 52.0
                + 3.0 * e5 / 26.0;
            let rj = scale * series / (aj * aj.sqrt()) + 6.0 * sum;
            (rf, rj)
        }
    };
}

lambert_geometry::both_precisions!(carlson_impl);

#[cfg(test)]
mod tests {
    use super::f64::carlson_rf_rj;

    /// The test values of Carlson (1995) (R_F(1, 2, 0), R_F(2, 3, 4),
    /// R_J(0, 1, 2, 3), R_J(2, 3, 4, 5)), here to 17 digits from mpmath's
    /// `elliprf`/`elliprj` at 30-digit precision; and special cases of DLMF
    /// §19.20.
    #[test]
    fn known_values() {
        // A few ulps: the series truncation is below ε and each step rounds.
        let close = |a: f64, b: f64| (a - b).abs() <= 8.0 * f64::EPSILON * b.abs();
        let (rf, _) = carlson_rf_rj(1.0, 2.0, 0.0, 1.0);
        assert!(close(rf, 1.311_028_777_146_06), "{rf}");
        let (rf, rj) = carlson_rf_rj(2.0, 3.0, 4.0, 5.0);
        assert!(close(rf, 0.584_082_841_677_151_7), "{rf}");
        assert!(close(rj, 0.142_975_796_671_567_54), "{rj}");
        let (_, rj) = carlson_rf_rj(0.0, 1.0, 2.0, 3.0);
        assert!(close(rj, 0.776_886_237_785_823_3), "{rj}");
        // R_F(x, x, x) = x^{-1/2}, R_J(x, x, x, x) = x^{-3/2} (DLMF 19.20.1, .15).
        let (rf, rj) = carlson_rf_rj(4.0, 4.0, 4.0, 4.0);
        assert!((rf - 0.5).abs() < 4.0 * f64::EPSILON && (rj - 0.125).abs() < 4.0 * f64::EPSILON);
        // R_F(0, 1, 1) = π/2 (complete, k = 0).
        let (rf, _) = carlson_rf_rj(0.0, 1.0, 1.0, 1.0);
        assert!((rf - std::f64::consts::FRAC_PI_2).abs() < 4.0 * f64::EPSILON);
        // Widely spread arguments: homogeneity R_F(λ·) = λ^{-1/2} R_F,
        // R_J(λ·) = λ^{-3/2} R_J.
        let (a, b) = carlson_rf_rj(1e-20, 1.0, 3.0, 1e-18);
        let (c, d) = carlson_rf_rj(4e-20, 4.0, 12.0, 4e-18);
        assert!((a - 2.0 * c).abs() < 8.0 * f64::EPSILON * a, "{a} {c}");
        assert!((b - 8.0 * d).abs() < 8.0 * f64::EPSILON * b, "{b} {d}");
    }

    #[test]
    fn f32_agrees_with_f64() {
        for &(x, y, z, p) in &[
            (0.5f64, 1.0, 2.0, 0.3),
            (1e-6, 1.0, 1.0, 2.0),
            (3.0, 0.0, 1.0, 0.1),
            (10.0, 1e-3, 2e-3, 5e-3),
        ] {
            let (rf, rj) = carlson_rf_rj(x, y, z, p);
            let (rf32, rj32) = super::f32::carlson_rf_rj(x as f32, y as f32, z as f32, p as f32);
            assert!(((rf32 as f64 - rf) / rf).abs() < 8.0 * f32::EPSILON as f64);
            assert!(
                ((rj32 as f64 - rj) / rj).abs() < 16.0 * f32::EPSILON as f64,
                "{rj32} {rj}"
            );
        }
    }
}
