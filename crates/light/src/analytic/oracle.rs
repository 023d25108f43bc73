//! The test oracle: every closed form evaluated again in 1024-bit binary
//! floating point (astro-float, pure Rust), from the same f64 inputs taken
//! as exact. At that precision the textbook formulas — Lambert's edge sum
//! after clipping, Snyder's horizon-clipped cap, the parallel-disk form
//! factor, the contour integral of a straddling disk — can be evaluated as
//! written: their worst cancellation in our sweeps (about 10⁴⁸ for a sliver
//! 10⁻¹² high seen from 10¹² sizes away) leaves more than 250 correct
//! digits, so the oracle's error is negligible next to f64's 1.1e-16.
//!
//! The oracle shares the *mathematics* of the library (the same closed
//! forms), not its evaluation: it is checked against the independent f64
//! area integrals of `test_support` on ordinary configurations (tests in
//! `accuracy.rs`), which catches a wrong formula, while its precision
//! catches lost digits.

use astro_float::{BigFloat, Consts, RoundingMode, Sign};
use glam::DVec3;
use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Working precision, bits.
const PREC: usize = 1024;
const RM: RoundingMode = RoundingMode::ToEven;

thread_local! {
    static CONSTS: RefCell<Consts> = RefCell::new(Consts::new().expect("astro-float constants"));
}

fn with_consts<T>(f: impl FnOnce(&mut Consts) -> T) -> T {
    CONSTS.with(|c| f(&mut c.borrow_mut()))
}

/// A 1024-bit float.
#[derive(Clone, Debug)]
pub(crate) struct B(BigFloat);

impl B {
    pub(crate) fn from(x: f64) -> B {
        B(BigFloat::from_f64(x, PREC))
    }
    pub(crate) fn zero() -> B {
        B::from(0.0)
    }
    pub(crate) fn pi() -> B {
        B(with_consts(|cc| cc.pi(PREC, RM)))
    }
    pub(crate) fn sqrt(&self) -> B {
        B(self.0.sqrt(PREC, RM))
    }
    pub(crate) fn sin(&self) -> B {
        B(with_consts(|cc| self.0.sin(PREC, RM, cc)))
    }
    pub(crate) fn cos(&self) -> B {
        B(with_consts(|cc| self.0.cos(PREC, RM, cc)))
    }
    pub(crate) fn ln(&self) -> B {
        B(with_consts(|cc| self.0.ln(PREC, RM, cc)))
    }
    pub(crate) fn atan(&self) -> B {
        B(with_consts(|cc| self.0.atan(PREC, RM, cc)))
    }
    pub(crate) fn is_zero(&self) -> bool {
        self.0.is_zero()
    }
    pub(crate) fn is_positive(&self) -> bool {
        !self.0.is_zero() && self.0.is_positive()
    }
    pub(crate) fn is_negative(&self) -> bool {
        !self.0.is_zero() && self.0.is_negative()
    }
    pub(crate) fn abs(&self) -> B {
        B(self.0.abs())
    }
    pub(crate) fn signum(&self) -> f64 {
        if self.is_positive() {
            1.0
        } else if self.is_negative() {
            -1.0
        } else {
            0.0
        }
    }
    pub(crate) fn gt(&self, o: &B) -> bool {
        (self - o).is_positive()
    }
    /// atan2(y, x) ∈ (−π, π], the angle of (x, y).
    pub(crate) fn atan2(y: &B, x: &B) -> B {
        if x.is_zero() {
            let half = B::pi() * B::from(0.5);
            return if y.is_negative() {
                -half
            } else if y.is_zero() {
                B::zero()
            } else {
                half
            };
        }
        let base = (y / x).atan();
        if x.is_positive() {
            base
        } else if y.is_negative() {
            base - B::pi()
        } else {
            base + B::pi()
        }
    }
    /// The nearest f64 (to within one unit in the last place; enough for
    /// reporting relative errors and comparing with f64 results).
    pub(crate) fn to_f64(&self) -> f64 {
        if self.0.is_zero() {
            return 0.0;
        }
        let (words, _, sign, exp, _) = self.0.as_raw_parts().expect("finite");
        let top = *words.last().expect("mantissa") as f64; // in [2^63, 2^64)
                                                           // value = top/2^64 · 2^exp
        let mut v = top / 18_446_744_073_709_551_616.0;
        let mut e = exp as i64;
        while e > 0 {
            let s = e.min(1000);
            v *= 2f64.powi(s as i32);
            e -= s;
        }
        while e < 0 {
            let s = (-e).min(1000);
            v /= 2f64.powi(s as i32);
            e += s;
        }
        if sign == Sign::Neg {
            -v
        } else {
            v
        }
    }
    /// The relative error of the double-double hi + lo (taken as exact)
    /// against self, or |hi| if self is 0.
    pub(crate) fn rel_err_dd(&self, hi: f64, lo: f64) -> f64 {
        if self.is_zero() {
            return hi.abs();
        }
        ((&B::from(hi) + &B::from(lo) - self) / self).abs().to_f64()
    }

    /// |f − self|/|self| as an f64 (f taken as exact), or |f| if self is 0.
    pub(crate) fn rel_err(&self, f: f64) -> f64 {
        if !f.is_finite() {
            return f64::INFINITY;
        }
        if self.is_zero() {
            return f.abs();
        }
        ((&B::from(f) - self) / self).abs().to_f64()
    }
}

macro_rules! binop {
    ($tr:ident, $f:ident) => {
        impl $tr<&B> for &B {
            type Output = B;
            fn $f(self, o: &B) -> B {
                B(self.0.$f(&o.0, PREC, RM))
            }
        }
        impl $tr<B> for B {
            type Output = B;
            fn $f(self, o: B) -> B {
                (&self).$f(&o)
            }
        }
        impl $tr<&B> for B {
            type Output = B;
            fn $f(self, o: &B) -> B {
                (&self).$f(o)
            }
        }
        impl $tr<B> for &B {
            type Output = B;
            fn $f(self, o: B) -> B {
                self.$f(&o)
            }
        }
    };
}
binop!(Add, add);
binop!(Sub, sub);
binop!(Mul, mul);
binop!(Div, div);

impl Neg for B {
    type Output = B;
    fn neg(self) -> B {
        B(self.0.neg())
    }
}

/// A 3-vector of 1024-bit floats.
#[derive(Clone, Debug)]
pub(crate) struct V(pub B, pub B, pub B);

impl V {
    pub(crate) fn from(v: DVec3) -> V {
        V(B::from(v.x), B::from(v.y), B::from(v.z))
    }
    pub(crate) fn dot(&self, o: &V) -> B {
        &self.0 * &o.0 + &self.1 * &o.1 + &self.2 * &o.2
    }
    pub(crate) fn cross(&self, o: &V) -> V {
        V(
            &self.1 * &o.2 - &self.2 * &o.1,
            &self.2 * &o.0 - &self.0 * &o.2,
            &self.0 * &o.1 - &self.1 * &o.0,
        )
    }
    pub(crate) fn sub(&self, o: &V) -> V {
        V(&self.0 - &o.0, &self.1 - &o.1, &self.2 - &o.2)
    }
    pub(crate) fn add(&self, o: &V) -> V {
        V(&self.0 + &o.0, &self.1 + &o.1, &self.2 + &o.2)
    }
    pub(crate) fn scale(&self, s: &B) -> V {
        V(&self.0 * s, &self.1 * s, &self.2 * s)
    }
    pub(crate) fn length(&self) -> B {
        self.dot(self).sqrt()
    }
    pub(crate) fn normalized(&self) -> V {
        let l = self.length();
        self.scale(&(B::from(1.0) / l))
    }
}

/// The angle between two vectors, atan2(|a × b|, a·b) ∈ [0, π].
fn angle(a: &V, b: &V) -> B {
    B::atan2(&a.cross(b).length(), &a.dot(b))
}

/// Lambert's formula after Sutherland–Hodgman clipping, all in 1024 bits:
/// E = (L/2)|Σ θᵢ n·unit(Rᵢ × Rᵢ₊₁)| over the part with n·(x − p) > 0.
/// The normal is taken as n/|n| exactly; the emitting side from Newell's
/// normal of the exact vertices.
pub(crate) fn polygon(radiance: f64, p: DVec3, n: DVec3, verts: &[DVec3], two_sided: bool) -> B {
    let pb = V::from(p);
    let nb = V::from(n).normalized();
    let vs: Vec<V> = verts.iter().map(|&v| V::from(v)).collect();
    let k = vs.len();
    let mut newell = V(B::zero(), B::zero(), B::zero());
    for i in 0..k {
        newell = newell.add(&vs[i].sub(&vs[0]).cross(&vs[(i + 1) % k].sub(&vs[0])));
    }
    let side = newell.dot(&pb.sub(&vs[0]));
    if side.is_zero() || (!two_sided && side.is_negative()) {
        return B::zero();
    }
    // Clip, relative to p.
    let rs: Vec<V> = vs.iter().map(|v| v.sub(&pb)).collect();
    let mut clipped = vec![];
    for i in 0..k {
        let (a, b) = (&rs[i], &rs[(i + 1) % k]);
        let (da, db) = (nb.dot(a), nb.dot(b));
        if !da.is_negative() {
            clipped.push(a.clone());
        }
        if (da.is_positive() && db.is_negative()) || (da.is_negative() && db.is_positive()) {
            let t = &da / (&da - &db);
            clipped.push(a.add(&b.sub(a).scale(&t)));
        }
    }
    let k = clipped.len();
    if k < 3 {
        return B::zero();
    }
    let mut sum = B::zero();
    for i in 0..k {
        let (a, b) = (&clipped[i], &clipped[(i + 1) % k]);
        let cr = a.cross(b);
        let len = cr.length();
        if len.is_zero() {
            continue;
        }
        sum = sum + angle(a, b) * nb.dot(&cr) / len;
    }
    B::from(radiance) * sum.abs() * B::from(0.5)
}

/// Snyder's (1996) projected solid angle of a cap of directions (axis at
/// angle β from n, half-angle γ) clipped to the hemisphere, as printed:
/// P = φ₀ + sin²γ cos β τ − W cos γ when the rim crosses the horizon,
/// with W = √(sin²β − cos²γ), φ₀ = atan2(W, cos γ), τ = atan2(W, −cos γ cos β);
/// π sin²γ cos β above, 0 below; γ > π/2 by the complement cap.
pub(crate) fn cap(cb: &B, sg: &B, cg: &B) -> B {
    if cg.is_negative() {
        return B::pi() - cap(&-cb.clone(), sg, &-cg.clone());
    }
    if !sg.gt(cb) {
        return B::pi() * sg * sg * cb;
    }
    if !cb.gt(&-sg.clone()) {
        return B::zero();
    }
    let sb2 = B::from(1.0) - cb * cb;
    let w = (sb2 - cg * cg).sqrt();
    let phi0 = B::atan2(&w, cg);
    let tau = B::atan2(&w, &-(cg * cb));
    phi0 + sg * sg * cb * tau - w * cg
}

/// A sky cap: n and the axis normalised exactly, sin γ and cos γ of the
/// f64 half-angle in 1024 bits.
pub(crate) fn sky_cap(radiance: f64, n: DVec3, axis: DVec3, half_angle: f64) -> B {
    let g = B::from(half_angle);
    let cb = V::from(n).normalized().dot(&V::from(axis).normalized());
    B::from(radiance) * cap(&cb, &g.sin(), &g.cos())
}

/// A sphere seen from outside: the cap with sin γ = r/d, cos β = n·(c − p)/d.
/// `None` when p is inside or on the sphere.
pub(crate) fn sphere(radiance: f64, p: DVec3, n: DVec3, c: DVec3, r: f64) -> Option<B> {
    let v = V::from(c).sub(&V::from(p));
    let d = v.length();
    let rb = B::from(r);
    if !d.gt(&rb) {
        return None;
    }
    let sg = &rb / &d;
    let cg = (B::from(1.0) - &sg * &sg).sqrt();
    let cb = V::from(n).normalized().dot(&v) / &d;
    Some(B::from(radiance) * cap(&cb, &sg, &cg))
}

/// A disk by Lambert's contour integral, E = (L/2)|∮ n·(R × dR)/|R|²|,
/// around the visible part's boundary (the rim's visible arc and, when the
/// receiver's plane cuts the disk, the chord in that plane). Along the rim
/// X(t) = c + r(cos t e₁ + sin t e₂) the integrand is
/// (A + B cos t + C sin t)/(a + b cos t + c sin t), integrated in closed
/// form as λt + μ ln(den) + ν ∫dt/den (the numerator split into multiples of
/// the denominator, its derivative and a constant); the last integral is
/// 2/√(a² − ρ²) times the growth of atan2(√(a−ρ) sin(x/2), √(a+ρ) cos(x/2)),
/// x = t − δ, ρ e^{iδ} = b + ic. The chord contributes ±its subtended angle.
pub(crate) fn disk(
    radiance: f64,
    p: DVec3,
    n: DVec3,
    c: DVec3,
    m: DVec3,
    r: f64,
    two_sided: bool,
) -> B {
    let nb = V::from(n).normalized();
    let mb = V::from(m).normalized();
    let v = V::from(c).sub(&V::from(p));
    let hv = v.dot(&mb);
    if hv.is_zero() || (!two_sided && hv.is_positive()) {
        return B::zero();
    }
    let rb = B::from(r);
    let f0 = nb.dot(&v);
    let n_par = nb.sub(&mb.scale(&nb.dot(&mb)));
    let g = n_par.length();
    // Frame: e₁ along n's projection on the disk's plane (any if none).
    let e1 = if g.is_zero() {
        // n ∥ m: any unit vector ⊥ m.
        let t = if mb.0.abs().gt(&B::from(0.5)) {
            V(B::zero(), B::from(1.0), B::zero())
        } else {
            V(B::from(1.0), B::zero(), B::zero())
        };
        t.sub(&mb.scale(&t.dot(&mb))).normalized()
    } else {
        n_par.scale(&(B::from(1.0) / &g))
    };
    let e2 = mb.cross(&e1);
    let rg = &rb * &g;
    if !(&f0 + &rg).is_positive() {
        return B::zero();
    }
    let whole = !(&f0 - &rg).is_negative();
    let pi = B::pi();
    let (t_lo, t_hi) = if whole {
        (-pi.clone(), pi.clone())
    } else {
        let cos_t1 = -(&f0 / &rg);
        let sin_t1 = (B::from(1.0) - &cos_t1 * &cos_t1).sqrt();
        let t1 = B::atan2(&sin_t1, &cos_t1);
        (-t1.clone(), t1)
    };
    let w = nb.cross(&v);
    let ca = &rb * &rb * nb.dot(&mb);
    let cb = &rb * w.dot(&e2);
    let cc = -(&rb * w.dot(&e1));
    let a = v.dot(&v) + &rb * &rb;
    let b = B::from(2.0) * &rb * v.dot(&e1);
    let c2 = B::from(2.0) * &rb * v.dot(&e2);
    let rho2 = &b * &b + &c2 * &c2;
    let arc = if rho2.is_zero() {
        let (s_hi, c_hi, s_lo, c_lo) = (t_hi.sin(), t_hi.cos(), t_lo.sin(), t_lo.cos());
        (&ca * (&t_hi - &t_lo) + &cb * (s_hi - s_lo) - &cc * (c_hi - c_lo)) / &a
    } else {
        let lambda = (&cb * &b + &cc * &c2) / &rho2;
        let mu = (&cb * &c2 - &cc * &b) / &rho2;
        let nu = &ca - &lambda * &a;
        let rho = rho2.sqrt();
        let den = |t: &B| &a + &b * t.cos() + &c2 * t.sin();
        let log_part = if whole {
            B::zero()
        } else {
            &mu * (den(&t_hi) / den(&t_lo)).ln()
        };
        let delta = B::atan2(&c2, &b);
        let (sp, sm) = ((&a + &rho).sqrt(), (&a - &rho).sqrt());
        let half = B::from(0.5);
        let point = |t: &B| {
            let x = (t - &delta) * &half;
            (&sp * x.cos(), &sm * x.sin())
        };
        let (x0, y0) = point(&t_lo);
        let (x1, y1) = point(&t_hi);
        // Growth of the angle of (√(a+ρ) cos(x/2), √(a−ρ) sin(x/2)) as x
        // runs over an interval of length ≤ 2π: in [0, π].
        let grow = if whole {
            pi.clone()
        } else {
            B::atan2(&(&x0 * &y1 - &y0 * &x1), &(&x0 * &x1 + &y0 * &y1))
        };
        let s = (&a * &a - &rho2).sqrt();
        &lambda * (&t_hi - &t_lo) + log_part + &nu * B::from(2.0) * grow / s
    };
    let chord = if whole {
        B::zero()
    } else {
        let at = |t: &B| v.add(&e1.scale(&(&rb * t.cos())).add(&e2.scale(&(&rb * t.sin()))));
        let (ra, rb2) = (at(&t_hi), at(&t_lo));
        let cr = ra.cross(&rb2);
        angle(&ra, &rb2) * B::from(nb.dot(&cr).signum())
    };
    B::from(radiance) * (arc + chord).abs() * B::from(0.5)
}

/// A disk parallel to the receiver at height h, offset s (Howell B-13 as
/// printed): E = (Lπ/2)(1 − (h² + s² − R²)/√((h² + R² + s²)² − 4R²s²)).
pub(crate) fn disk_parallel(radiance: f64, h: f64, s: f64, r: f64) -> B {
    let (h, s, r) = (B::from(h), B::from(s), B::from(r));
    let (h2, s2, r2) = (&h * &h, &s * &s, &r * &r);
    let t = &h2 + &s2 - &r2;
    let u = &h2 + &r2 + &s2;
    let q = (&u * &u - B::from(4.0) * &r2 * &s2).sqrt();
    B::from(radiance) * B::pi() * B::from(0.5) * (B::from(1.0) - t / q)
}
