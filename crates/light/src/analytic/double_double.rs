//! Double-double arithmetic: a value held as an unevaluated sum hi + lo of
//! two f64 with |lo| ≤ ulp(hi)/2, about 106 significant bits (relative
//! precision u² ≈ 1.2e-32, u = 2⁻⁵³), for the few intermediates of the
//! closed forms whose cancellation is inherent in the geometry (a sliver's
//! height n·(v − p) of 1e-24 against |v − p| ≈ 1, a cap's visible depth
//! sin γ − |cos β| of 1e-20 against sin γ).
//!
//! We write our own because what is needed is small (the four operations,
//! √, sin/cos, atan2 and v − sin v on values of ordinary size) and must be
//! exact in the error-free building blocks; a crate brings more and
//! documents less. Sources of the algorithms, not of any code:
//! - TwoSum (Knuth, TAOCP vol. 2, §4.2.2), FastTwoSum (Dekker 1971),
//!   TwoProd by FMA, or by Veltkamp's splitting and Dekker's product when
//!   the target has no FMA (T. J. Dekker, "A floating-point technique for
//!   extending the available precision", Numer. Math. 18, 1971);
//! - addition, multiplication and division of double-words as analysed by
//!   M. Joldes, J.-M. Muller and V. Popescu, "Tight and rigorous error
//!   bounds for basic building blocks of double-word arithmetic", ACM TOMS
//!   44(2), 2017 (AccurateDWPlusDW: ≤ 3u²; DWTimesDW1: ≤ 7u²), and the
//!   QD library's division and square root by one correction step
//!   (Y. Hida, X. S. Li and D. H. Bailey, "Algorithms for quad-double
//!   precision floating point arithmetic", ARITH 15, 2001);
//! - sin/cos by Cody–Waite reduction by π/2 in four parts and the Taylor
//!   series on [−π/4, π/4]; atan2 by one Newton step from the f64 atan2.
//!
//! Preconditions (checked in debug builds): operands of TwoProd below
//! 2⁹⁹⁵ in magnitude (callers scale lengths by a power of two into
//! [½, 1] first), arguments of sin/cos below 10⁶. Results that fall below
//! about 1e-290 lose the low word to underflow and keep f64 precision.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// s + e = a + b exactly, s = fl(a + b) (Knuth's TwoSum; no condition on
/// the operands' order; 6 flops).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// s + e = a + b exactly when |a| ≥ |b| or a = 0 (Dekker's FastTwoSum).
#[inline]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// Veltkamp's splitting: a = h + l with h and l of 26 significant bits;
/// above 2⁹⁹⁵ (where (2²⁷ + 1)·a would overflow) the split is done on
/// a·2⁻³⁰ and scaled back, exactly.
#[cfg(not(target_feature = "fma"))]
#[inline]
fn split(a: f64) -> (f64, f64) {
    const BIG: f64 = 3.348_464_397_457_085_4e299; // 2⁹⁹⁵
    let (scaled, back) = if a.abs() > BIG {
        (a * 9.313_225_746_154_785e-10, 1_073_741_824.0) // 2⁻³⁰, 2³⁰
    } else {
        (a, 1.0)
    };
    let c = 134_217_729.0 * scaled; // 2²⁷ + 1
    let h = c - (c - scaled);
    (h * back, (scaled - h) * back)
}

/// p + e = a·b exactly, p = fl(a·b) (by FMA when the target has it, else
/// Dekker's product; exact unless a·b underflows below 2⁻⁹⁶⁹).
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    #[cfg(target_feature = "fma")]
    {
        (p, a.mul_add(b, -p))
    }
    #[cfg(not(target_feature = "fma"))]
    {
        let (ah, al) = split(a);
        let (bh, bl) = split(b);
        (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
    }
}

/// A double-double number hi + lo, |lo| ≤ ulp(hi)/2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Dd {
    /// The leading f64: the value rounded to f64.
    pub(crate) hi: f64,
    /// The trailing correction.
    pub(crate) lo: f64,
}

/// π/2 in four parts for Cody–Waite reduction: P1 and P2 carry 33
/// significant bits (so k·P1 and k·P2 are exact for |k| < 2²⁰), P3 and P4
/// 53; P1 + P2 + P3 + P4 is π/2 to 4e-54.
const FRAC_PI_2_PARTS: [f64; 4] = [
    1.570_796_326_734_125_6,
    6.077_100_506_303_966e-11,
    2.022_266_248_795_950_6e-21,
    1.008_585_403_587_248_3e-37,
];

/// π as a double-double.
pub(crate) const PI: Dd = Dd {
    hi: std::f64::consts::PI,
    lo: 1.224_646_799_147_353_2e-16,
};

impl Dd {
    /// 0.
    pub(crate) const ZERO: Dd = Dd { hi: 0.0, lo: 0.0 };
    /// 1.
    pub(crate) const ONE: Dd = Dd { hi: 1.0, lo: 0.0 };

    /// x exactly.
    #[inline]
    pub(crate) const fn from_f64(x: f64) -> Dd {
        Dd { hi: x, lo: 0.0 }
    }

    /// a + b exactly.
    #[inline]
    pub(crate) fn sum(a: f64, b: f64) -> Dd {
        let (hi, lo) = two_sum(a, b);
        Dd { hi, lo }
    }

    /// a · b exactly (barring underflow).
    #[inline]
    pub(crate) fn product(a: f64, b: f64) -> Dd {
        let (hi, lo) = two_prod(a, b);
        Dd { hi, lo }
    }

    /// The nearest f64 (hi, as the pair is normalised).
    #[inline]
    pub(crate) fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// self ≥ x, exactly.
    #[inline]
    pub(crate) fn at_least(self, x: f64) -> bool {
        self.hi > x || (self.hi == x && self.lo >= 0.0)
    }

    /// self ≤ x, exactly.
    #[inline]
    pub(crate) fn at_most(self, x: f64) -> bool {
        self.hi < x || (self.hi == x && self.lo <= 0.0)
    }

    /// |self|.
    #[inline]
    pub(crate) fn abs(self) -> Dd {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -self
        } else {
            self
        }
    }

    /// self + b for an f64 b (error ≤ 2u²|result|).
    #[inline]
    pub(crate) fn add_f64(self, b: f64) -> Dd {
        let (s, e) = two_sum(self.hi, b);
        let (hi, lo) = fast_two_sum(s, e + self.lo);
        Dd { hi, lo }
    }

    /// self · b for an f64 b.
    #[inline]
    pub(crate) fn mul_f64(self, b: f64) -> Dd {
        let (p, e) = two_prod(self.hi, b);
        let (hi, lo) = fast_two_sum(p, e + self.lo * b);
        Dd { hi, lo }
    }

    /// self / b for an f64 b ≠ 0 (one correction step).
    #[inline]
    pub(crate) fn div_f64(self, b: f64) -> Dd {
        let q = self.hi / b;
        let (p, e) = two_prod(q, b);
        let r = ((self.hi - p) - e + self.lo) / b;
        let (hi, lo) = fast_two_sum(q, r);
        Dd { hi, lo }
    }

    /// self² .
    #[inline]
    pub(crate) fn square(self) -> Dd {
        self * self
    }

    /// √self for self ≥ 0 (0 for self ≤ 0): the f64 root and one Newton
    /// correction, relative error a few u².
    pub(crate) fn sqrt(self) -> Dd {
        if !(self.hi > 0.0) {
            return Dd::ZERO;
        }
        let q = self.hi.sqrt();
        let (p, e) = two_prod(q, q);
        let r = ((self.hi - p) - e + self.lo) / (2.0 * q);
        let (hi, lo) = fast_two_sum(q, r);
        Dd { hi, lo }
    }

    /// (sin self, cos self) to a few u² (absolute for the sine near
    /// multiples of π, relative elsewhere), for |self| < 10⁶: Cody–Waite
    /// reduction by π/2 in four parts, then the Taylor series of the sine
    /// on |r| ≤ π/4 and cos r = √(1 − sin²r) (≥ 0.7 there, no
    /// cancellation).
    pub(crate) fn sin_cos(self) -> (Dd, Dd) {
        debug_assert!(self.hi.abs() < 1e6, "sin_cos argument {}", self.hi);
        let k = (self.hi / std::f64::consts::FRAC_PI_2).round();
        let [p1, p2, p3, p4] = FRAC_PI_2_PARTS;
        let r = if k == 0.0 {
            self
        } else {
            // k·P1 and k·P2 are exact; k·P3 is formed exactly.
            (self - Dd::from_f64(k * p1) - Dd::from_f64(k * p2) - Dd::product(k, p3))
                .add_f64(-k * p4)
        };
        let r2 = r.square();
        let mut s = r;
        let mut term = r;
        // |r| ≤ π/4 + tiny: r²ʲ⁺¹/(2j + 1)! < 1e-34 by j = 15; the bound
        // also ends the loop for a NaN argument.
        for j in 1..=16 {
            let j = j as f64;
            term = -(term * r2).div_f64((2.0 * j) * (2.0 * j + 1.0));
            s = s + term;
            if term.hi.abs() <= 1e-34 * s.hi.abs() || term.hi == 0.0 {
                break;
            }
        }
        let c = (Dd::ONE - s.square()).sqrt();
        match (k as i64).rem_euclid(4) {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }

    /// atan2(y, x) ∈ (−π, π]: the f64 atan2 θ₀ and one Newton step,
    /// θ = θ₀ + (y cos θ₀ − x sin θ₀)/(x cos θ₀ + y sin θ₀) (the tangent of
    /// the residual angle, ~1e-16, whose cube is negligible). Relative
    /// error a few u², also for tiny angles (the residual is formed from
    /// products of the size of y).
    pub(crate) fn atan2(y: Dd, x: Dd) -> Dd {
        let t0 = y.hi.atan2(x.hi);
        if y.hi == 0.0 && x.hi == 0.0 {
            return Dd::from_f64(t0);
        }
        let (s, c) = Dd::from_f64(t0).sin_cos();
        let num = y * c - x * s;
        let den = x * c + y * s;
        Dd::from_f64(t0) + num / den
    }
}

impl Neg for Dd {
    type Output = Dd;
    #[inline]
    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Add for Dd {
    type Output = Dd;
    /// AccurateDWPlusDW (Joldes, Muller & Popescu 2017): ≤ 3u² relative.
    #[inline]
    fn add(self, b: Dd) -> Dd {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = fast_two_sum(s, e + t);
        let (hi, lo) = fast_two_sum(s, e + f);
        Dd { hi, lo }
    }
}

impl Sub for Dd {
    type Output = Dd;
    #[inline]
    fn sub(self, b: Dd) -> Dd {
        self + (-b)
    }
}

impl Mul for Dd {
    type Output = Dd;
    /// DWTimesDW1 (Joldes, Muller & Popescu 2017): ≤ 7u² relative.
    #[inline]
    fn mul(self, b: Dd) -> Dd {
        let (p, e) = two_prod(self.hi, b.hi);
        let (hi, lo) = fast_two_sum(p, e + (self.hi * b.lo + self.lo * b.hi));
        Dd { hi, lo }
    }
}

impl Div for Dd {
    type Output = Dd;
    /// Three quotient digits, each from the remainder so far (QD's
    /// accurate division), renormalised: a few u² relative.
    fn div(self, b: Dd) -> Dd {
        let q1 = self.hi / b.hi;
        let r = self - b.mul_f64(q1);
        let q2 = r.hi / b.hi;
        let r = r - b.mul_f64(q2);
        let q3 = r.hi / b.hi;
        let (hi, lo) = fast_two_sum(q1, q2);
        Dd { hi, lo }.add_f64(q3)
    }
}

impl From<f64> for Dd {
    #[inline]
    fn from(x: f64) -> Dd {
        Dd::from_f64(x)
    }
}

/// v − sin v without cancellation: the Taylor series v³/3! − v⁵/5! + …
/// for |v| < 1.5 (summed to u²), v − sin v directly above (where it is
/// ≥ v/3).
pub(crate) fn v_minus_sin(v: Dd) -> Dd {
    if v.hi.abs() >= 1.5 {
        return v - v.sin_cos().0;
    }
    v_minus_sin_over_cube(v) * v * v.square()
}

/// (v − sin v)/v³ for any v (1/6 at 0): the series
/// 1/3! − v²/5! + v⁴/7! − … for |v| < 1.5, the quotient above. Bounded
/// (between 1/(π²·…) and 1/6), so it neither underflows nor overflows for
/// tiny v, where v − sin v itself would underflow.
pub(crate) fn v_minus_sin_over_cube(v: Dd) -> Dd {
    if v.hi.abs() >= 1.5 {
        return (v - v.sin_cos().0) / (v * v.square());
    }
    let v2 = v.square();
    let mut term = Dd::ONE.div_f64(6.0);
    let mut sum = term;
    // |v| < 1.5: the k-th term is below 1.5²ᵏ/(2k + 3)! < 1e-34 by k = 14.
    for k in 1..=16 {
        let k = k as f64;
        term = -(term * v2).div_f64((2.0 * k + 2.0) * (2.0 * k + 3.0));
        sum = sum + term;
        if term.hi.abs() <= 1e-34 * sum.hi.abs() {
            break;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytic::oracle::B;

    fn rel(exact: &B, x: Dd) -> f64 {
        exact.rel_err_dd(x.hi, x.lo)
    }

    fn dd(b: &B) -> Dd {
        let hi = b.to_f64();
        let lo = (b - &B::from(hi)).to_f64();
        Dd::sum(hi, lo)
    }

    const U2: f64 = 1.232_595_164_407_831e-32; // 2⁻¹⁰⁶

    /// The error-free transformations are exact: checked in 1024 bits on
    /// operands whose sums and products are not representable.
    #[test]
    fn error_free_transformations_are_exact() {
        for &(a, b) in &[
            (1.0, 1e-30),
            (0.1, 0.2),
            (1e300, -3.7e283),
            (std::f64::consts::PI, std::f64::consts::E),
            (-1.3e-7, 9.1e-9),
        ] {
            let (s, e) = two_sum(a, b);
            assert!((&B::from(s) + &B::from(e) - (B::from(a) + B::from(b))).is_zero());
            if a.abs() < 1e200 {
                let (p, e) = two_prod(a, b);
                assert!((&B::from(p) + &B::from(e) - (B::from(a) * B::from(b))).is_zero());
            }
        }
    }

    /// Operations and functions against the 1024-bit oracle, on operands
    /// spread over magnitudes and signs: within the published bounds (add
    /// 3u², mul 7u², div and sqrt a few u²; sin, cos, atan2 a few u²
    /// after the exact reduction); tolerance 16u² (2e-31) for each.
    #[test]
    fn arithmetic_and_functions_agree_with_the_oracle() {
        let third = B::from(1.0) / B::from(3.0);
        let xs: Vec<B> = [
            0.7,
            -1.3,
            3.0e-9,
            2.5,
            1e-200,
            -0.999,
            std::f64::consts::FRAC_PI_2,
            3.1,
        ]
        .iter()
        // Each operand exactly a double-double, so that the oracle sees
        // the same input.
        .map(|&v| {
            let d = dd(&(B::from(v) + &third * B::from(v) * B::from(1e-17)));
            B::from(d.hi) + B::from(d.lo)
        })
        .collect();
        for a in &xs {
            let da = dd(a);
            assert!(rel(&a.abs().sqrt(), da.abs().sqrt()) < 16.0 * U2);
            if a.abs().to_f64() < 10.0 {
                let (s, c) = da.sin_cos();
                assert!(
                    rel(&a.sin(), s) < 16.0 * U2,
                    "sin {} {:e}",
                    a.to_f64(),
                    rel(&a.sin(), s)
                );
                assert!(
                    rel(&a.cos(), c) < 16.0 * U2,
                    "cos {} {:e}",
                    a.to_f64(),
                    rel(&a.cos(), c)
                );
                let v = v_minus_sin(da);
                let exact = a - &a.sin();
                assert!(rel(&exact, v) < 16.0 * U2, "v − sin v {}", a.to_f64());
            }
            for b in &xs {
                let db = dd(b);
                assert!(rel(&(a + b), da + db) < 16.0 * U2);
                assert!(rel(&(a - b), da - db) < 16.0 * U2);
                // Products and quotients in the range where the low word
                // does not underflow (module docs).
                let (prod, quot) = ((a * b).abs().to_f64(), (a / b).abs().to_f64());
                if prod > 1e-280 {
                    assert!(rel(&(a * b), da * db) < 16.0 * U2);
                }
                if quot > 1e-280 && quot < 1e280 {
                    assert!(rel(&(a / b), da / db) < 16.0 * U2);
                }
                let t = Dd::atan2(da, db);
                assert!(
                    rel(&B::atan2(a, b), t) < 16.0 * U2,
                    "atan2 {} {}",
                    a.to_f64(),
                    b.to_f64()
                );
            }
        }
        // Reduction near multiples of π/2: sin(π_f64) = 1.2246e-16 to full
        // relative precision, and an argument of 1000.
        let (s, _) = Dd::from_f64(std::f64::consts::PI).sin_cos();
        assert!(rel(&B::from(std::f64::consts::PI).sin(), s) < 1e-20);
        let (s, c) = Dd::from_f64(1000.0).sin_cos();
        assert!(rel(&B::from(1000.0).sin(), s) < 16.0 * U2);
        assert!(rel(&B::from(1000.0).cos(), c) < 16.0 * U2);
    }
}
