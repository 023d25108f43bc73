//! The projected solid angle of a disk that the receiver's plane cuts: a
//! contour integral over the visible arc of its rim, in one of two exact
//! forms, chosen so that no term cancels.
//!
//! Lambert's contour form (Arvo 1995) is 2P = |∮ n·(R × dR)/|R|²| around
//! the visible part's boundary (rim arc + chord in the receiver's plane).
//! With ε the elevation above the horizon and φ the azimuth about n, its
//! integrand is cos²ε dφ. Because ∮ dφ = 0 around a contour that does not
//! wind around the zenith, 2P = |∮ sin²ε dφ| as well, and this second form
//! has two virtues: the chord (ε = 0) contributes nothing, and the arc's
//! integrand, sin²ε dφ = (n·R)² n·(R × dR) / (|R|² |n × R|²), is small
//! where the visible part is thin. For a disk that barely shows, Lambert's
//! arc term and chord term are each of the order of the chord's angle w
//! and cancel to P ∝ h² w (h the visible height): all digits lost at
//! h = 1e-8; the sin²ε form has no such cancellation (only the O(1)
//! geometric one where the rim's azimuth turns back, for disks seen
//! nearly edge-on).
//!
//! The sin²ε form is used when the visible rim stays below ≈ 44° of
//! elevation (sin ε ≤ (n·(c − p) + R|n × m|)/(|c − p| − R) ≤ 0.7): then the
//! disk does not cover the zenith (so ∮ dφ = 0) and |n × R| ≥ 0.7|R| keeps
//! the integrand smooth. Otherwise the visible part reaches high, its P is
//! not small next to Lambert's terms, and Lambert's form is used.
//!
//! A disk wholly above the horizon but low over it relative to its
//! angular size (far away, just above the horizon) makes the closed form
//! n·J a small difference of J's components; the same sin²ε form around
//! the whole rim (no chord, its height bottom + 2Rg cos²(t/2) a sum of
//! non-negative terms) is then evaluated too (module `disk`).
//!
//! The rim's height is taken from its exact top and bottom heights
//! f₀ ± Rg (computed by the caller in double-double from the exact inputs):
//! the visible arc's half-width t₁ and the height at the arc's ends, where
//! it vanishes, keep their relative precision however little shows.
//!
//! The arc integral is an adaptive Gauss–Kronrod quadrature with a work
//! bound ([`quadrature::MAX_PANELS`] panels, 30 720 evaluations); its
//! error bound is returned with the value.

use super::quadrature::{self, Integral};
use glam::DVec3;

/// A disk seen from the receiver, in lengths where max(|v|, r) ≈ 1: its
/// centre `v` (relative to the receiver, f64), unit normals `n`
/// (receiver) and `m` (disk), radius `r`, and, exact to rounding (the
/// caller forms them in double-double), the centre's height `f0` = n̂·v,
/// g = |n̂ × m̂| and the rim's `top` = f0 + rg and `bottom` = f0 − rg.
pub(crate) struct Rim {
    pub(crate) v: DVec3,
    pub(crate) n: DVec3,
    pub(crate) m: DVec3,
    pub(crate) r: f64,
    pub(crate) f0: f64,
    pub(crate) g: f64,
    pub(crate) top: f64,
    pub(crate) bottom: f64,
}

impl Rim {
    /// (e₁, e₂): e₁ along n's projection on the disk's plane (the rim's
    /// steepest ascent), e₂ = m × e₁; any pair when n ∥ m.
    fn frame(&self) -> (DVec3, DVec3) {
        let n_par = self.n - self.m * self.n.dot(self.m);
        let len = n_par.length();
        let e1 = if len > 0.0 {
            n_par / len
        } else {
            self.m.any_orthonormal_pair().0
        };
        (e1, self.m.cross(e1))
    }

    /// Whether the rim stays below ≈ 44° of elevation (sin ε ≤ 0.7) and
    /// the disk does not cover the zenith (a large disk overhead can do so
    /// with a low rim): then ∮ dφ = 0 and the sin² form applies. Every rim
    /// point is at least ||v| − r| from the receiver (also when the
    /// receiver is within the rim's sphere: a disk vastly larger than its
    /// distance), so sin ε ≤ top/||v| − r|.
    fn low(&self) -> bool {
        let clearance = (self.v.length() - self.r).abs();
        let rim_low = clearance > 0.0 && self.top <= 0.7 * clearance;
        // The vertical ray p + t n meets the disk's plane at t = m·v / m·n;
        // the zenith is covered when that point is within r of the centre
        // (decided far from the rim, so f64 suffices: a rim near the
        // zenith is not low).
        let mn = self.m.dot(self.n);
        let t = self.m.dot(self.v) / mn;
        let covers_zenith = mn != 0.0 && t > 0.0 && (self.n * t - self.v).length() <= self.r;
        rim_low && !covers_zenith
    }

    /// The sin²ε dφ integrand over the rim divided by r² (module docs),
    /// with the rim's height above the receiver's plane given by `height`.
    fn sin2_integrand(&self, height: impl Fn(f64) -> f64) -> impl Fn(f64) -> f64 {
        let (e1, e2) = self.frame();
        let w = self.n.cross(self.v);
        let (wa, wb) = (w.dot(e1), w.dot(e2));
        let nm = self.n.dot(self.m);
        let (v, n, r) = (self.v, self.n, self.r);
        move |t: f64| {
            let (st, ct) = t.sin_cos();
            let rr = v + (e1 * ct + e2 * st) * r;
            // n·(R × R′)/r, R′ = r(−sin t e₁ + cos t e₂), without forming
            // the r² m part's cancellation against r(v × u′).
            let rate = wb * ct - wa * st + r * nm;
            // (rH̃)² · r·rate / (|R|²|n × R|²) / r² with H = r H̃.
            let h = height(t);
            r * h * h * rate / (rr.length_squared() * n.cross(rr).length_squared())
        }
    }

    /// The visible part's projected solid angle P (sr) divided by r², with
    /// an absolute error bound on that quotient, for a disk that the
    /// receiver's plane cuts (top > 0 > bottom).
    pub(crate) fn straddling_over_r2(&self) -> Integral {
        let (r, g, f0) = (self.r, self.g, self.f0);
        let rg = r * g;
        // Visible for |t| < t₁, cos t₁ = −f0/(rg), sin t₁ from the exact
        // top and bottom (no cancellation for a rim that barely shows).
        let sin_t1 = (self.top * -self.bottom).max(0.0).sqrt() / rg;
        let t1 = sin_t1.atan2(-f0 / rg);
        if !self.low() {
            return self.lambert_over_r2(t1, sin_t1, -f0 / rg);
        }
        // The height H = rg(cos t − cos t₁) = 2rg sin((t₁ − t)/2)
        // sin((t₁ + t)/2) as a product (it vanishes at the ends), divided
        // by r.
        let m_int = quadrature::integrate_bounded(
            self.sin2_integrand(|t| 2.0 * g * (0.5 * (t1 - t)).sin() * (0.5 * (t1 + t)).sin()),
            -t1,
            t1,
            1e-14,
            quadrature::MAX_PANELS,
        );
        Integral {
            value: 0.5 * m_int.value.abs(),
            error: 0.5 * m_int.error,
            converged: m_int.converged,
            magnitude: 0.5 * m_int.magnitude,
        }
    }

    /// For a disk wholly above the horizon and low over it: P/r² by the
    /// sin² form around the whole rim, with its error bound, and the
    /// cancellation factor ∫|f| / |∫f|; `None` when the rim rises too high
    /// for the form.
    pub(crate) fn whole_over_r2(&self) -> Option<(Integral, f64)> {
        if !self.low() {
            return None;
        }
        let (g, bottom_over_r) = (self.g, self.bottom / self.r);
        // H/r = bottom/r + g(1 + cos t) = bottom/r + 2g cos²(t/2): both ≥ 0.
        let f = self.sin2_integrand(move |t| {
            let c = (0.5 * t).cos();
            bottom_over_r + 2.0 * g * c * c
        });
        let i = quadrature::integrate_bounded(
            f,
            -std::f64::consts::PI,
            std::f64::consts::PI,
            1e-14,
            quadrature::MAX_PANELS,
        );
        let kappa = i.magnitude / i.value.abs();
        Some((
            Integral {
                value: 0.5 * i.value.abs(),
                error: 0.5 * i.error,
                converged: i.converged,
                magnitude: 0.5 * i.magnitude,
            },
            kappa,
        ))
    }

    /// Lambert's form for a straddling disk whose visible part reaches
    /// high: arc + chord, P = |arc + chord|/2, divided by r². The chord's
    /// ends are R_{a,b} = v + r(c e₁ ± s e₂) (s, c = sin t₁, cos t₁ from
    /// the exact heights); its angle comes from
    /// R_a × R_b = −2rs (v × e₂ + rc m) and
    /// R_a·R_b = |v|² + 2rc v·e₁ + r²(c² − s²), without forming the long
    /// vectors' cross product, so its sign stays right when the chord
    /// passes close to the receiver (a receiver almost in the plane of a
    /// disk vastly larger than its distance to it).
    fn lambert_over_r2(&self, t1: f64, s: f64, c: f64) -> Integral {
        let (v, n, r) = (self.v, self.n, self.r);
        let (e1, e2) = self.frame();
        let w = n.cross(v);
        let (wa, wb) = (w.dot(e1), w.dot(e2));
        let nm = n.dot(self.m);
        let arc = quadrature::integrate_bounded(
            |t: f64| {
                let (st, ct) = t.sin_cos();
                let rr = v + (e1 * ct + e2 * st) * r;
                let rate = wb * ct - wa * st + r * nm;
                rate / rr.length_squared()
            },
            -t1,
            t1,
            1e-14,
            quadrature::MAX_PANELS,
        );
        let cross = (v.cross(e2) + self.m * (r * c)) * (-2.0 * r * s);
        let dot = v.length_squared() + 2.0 * r * c * v.dot(e1) + r * r * (c - s) * (c + s);
        let chord = cross.length().atan2(dot) * n.dot(cross).signum();
        // The arc integrand carries one factor r.
        let total = r * arc.value + chord;
        let scale = 0.5 / (r * r);
        Integral {
            value: (total * scale).abs(),
            error: (r * arc.error + 4.0 * f64::EPSILON * chord.abs()) * scale,
            converged: arc.converged,
            magnitude: (r * arc.magnitude + chord.abs()) * scale,
        }
    }
}
