//! Products of factors spanning the whole f64 range, without intermediate
//! overflow or underflow: E = L · q · s² with L up to 1.8e308 and s down
//! to 1e-300 is an ordinary f64 whenever its true value is one (a disk of
//! radius 1e-300 and radiance 1e300 seen from distance 1 gives π·1e-300,
//! where L·s² evaluated left to right underflows to 0).
//!
//! Each factor is split into a mantissa in [1/2, 1) and a power of two
//! (C's `frexp`); the mantissas are multiplied (the product stays in
//! [2⁻ᵏ, 1) for k factors, no overflow, no underflow) and the exponents
//! added as integers; the result is scaled back once (C's `ldexp`), so it
//! is correctly rounded up to the one final rounding (plus one in the
//! subnormal range). A true result beyond f64::MAX is an
//! [`AnalyticError::Overflow`] naming the quantity, never ∞.

use super::error::AnalyticError;

/// x = m·2^e with m ∈ [1/2, 1) (x finite and non-zero).
fn frexp(x: f64) -> (f64, i32) {
    let (x, bias) = if x.abs() < f64::MIN_POSITIVE {
        (x * 2f64.powi(64), -64)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32 - 1022;
    let m = f64::from_bits((bits & !(0x7ff << 52)) | (1022 << 52));
    (m, e + bias)
}

/// m·2^e, rounding once (m ∈ [1/2, 1)): every scaling but the last is
/// exact.
fn ldexp(m: f64, e: i32) -> f64 {
    if e > 1000 {
        let mut v = m;
        let mut e = e;
        while e > 1000 {
            v *= 2f64.powi(1000);
            e -= 1000;
        }
        return v * 2f64.powi(e);
    }
    if e >= -1000 {
        return m * 2f64.powi(e);
    }
    if e < -1200 {
        return 0.0 * m;
    }
    // m·2^-1000 is normal and exact; the second factor rounds once.
    m * 2f64.powi(-1000) * 2f64.powi(e + 1000)
}

/// The product of `factors` (finite), without intermediate overflow or
/// underflow; errors if its magnitude exceeds f64::MAX.
pub(crate) fn product(quantity: &'static str, factors: &[f64]) -> Result<f64, AnalyticError> {
    let mut m = 1.0f64;
    let mut e = 0i32;
    for &x in factors {
        if x == 0.0 {
            return Ok(0.0 * factors.iter().map(|f| f.signum()).product::<f64>());
        }
        let (fm, fe) = frexp(x);
        m *= fm;
        e += fe;
        // Renormalise so that m stays in [1/2, 1).
        let (mm, me) = frexp(m);
        m = mm;
        e += me;
    }
    let v = ldexp(m, e);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(AnalyticError::Overflow { quantity })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_across_the_range_are_correctly_rounded() {
        // π·1e300·1e-300·1e-300 = π·1e-300 (the naive order gives 0).
        let pi = std::f64::consts::PI;
        let v = product("irradiance", &[1e300, pi, 1e-300, 1e-300]).unwrap();
        assert!((v / (pi * 1e-300) - 1.0).abs() < 4.0 * f64::EPSILON);
        assert_eq!(product("x", &[3.0, 0.5]).unwrap(), 1.5);
        assert_eq!(product("x", &[-3.0, 0.5]).unwrap(), -1.5);
        assert_eq!(product("x", &[1e308, 0.0]).unwrap(), 0.0);
        // Subnormal results.
        assert_eq!(product("x", &[1e-300, 1e-20]).unwrap(), 1e-300 * 1e-20);
        assert_eq!(product("x", &[5e-324, 1.0]).unwrap(), 5e-324);
        assert_eq!(product("x", &[1e-200, 1e-200]).unwrap(), 0.0);
        // Overflow is an error naming the quantity.
        assert_eq!(
            product("irradiance", &[1e308, 4.0]),
            Err(AnalyticError::Overflow {
                quantity: "irradiance"
            })
        );
        assert_eq!(product("x", &[1e308, 1.5, 0.5]).unwrap(), 1e308 * 0.75);
    }
}
