//! Random numbers as a careless script writes them: ordinary values most of
//! the time, and every corner of the f64 range the rest of the time —
//! subnormals down to 5e-324, powers of ten up to 1e308, `f64::MAX`, signed
//! zeros — plus, on request, the values a validator must refuse (zero,
//! negative, NaN, ±∞).
//!
//! Every number is written to TOML by [`toml_float`], which round-trips
//! exactly (Rust's shortest representation, `nan`/`inf` spelled as TOML
//! spells them).

use rand::Rng;

/// Positive values at the edges of the f64 range and of precision: the
/// smallest subnormal, the largest subnormal, the smallest normal, the
/// machine epsilon, powers of ten out to the ends of the range, `f64::MAX`.
pub const EDGE_MAGNITUDES: [f64; 20] = [
    5e-324,
    1e-323,
    // The largest subnormal.
    f64::from_bits(0x000f_ffff_ffff_ffff),
    f64::MIN_POSITIVE,
    1e-300,
    1e-200,
    1e-100,
    1e-30,
    f64::EPSILON,
    1e-8,
    1e-3,
    1.0,
    1e3,
    1e8,
    1e16,
    1e30,
    1e100,
    1e200,
    1e300,
    1e308,
];

/// A positive finite magnitude: 45 % log-uniform in [1e-3, 1e3] (ordinary
/// scenes), 30 % log-uniform over the whole normal and subnormal range
/// [5e-324, 1.8e308], 20 % an edge value ([`EDGE_MAGNITUDES`] or
/// `f64::MAX`), 5 % exactly 1.
pub fn magnitude<R: Rng>(rng: &mut R) -> f64 {
    match rng.random_range(0..100) {
        0..=44 => log_uniform(rng, -3.0, 3.0),
        45..=74 => log_uniform(rng, -323.3, 308.25),
        75..=94 => {
            if rng.random_bool(0.1) {
                f64::MAX
            } else {
                EDGE_MAGNITUDES[rng.random_range(0..EDGE_MAGNITUDES.len())]
            }
        }
        _ => 1.0,
    }
}

/// 10^x for x uniform in [lo, hi], never 0 or ∞ (clamped to the smallest
/// subnormal and to `f64::MAX`).
pub fn log_uniform<R: Rng>(rng: &mut R, lo: f64, hi: f64) -> f64 {
    let x = 10f64.powf(rng.random_range(lo..=hi));
    if x == 0.0 {
        5e-324
    } else if x.is_infinite() {
        f64::MAX
    } else {
        x
    }
}

/// A value a validator must refuse where a positive finite number is
/// required: zero (either sign), a negative number, NaN or ±∞.
pub fn invalid_magnitude<R: Rng>(rng: &mut R) -> f64 {
    match rng.random_range(0..6) {
        0 => 0.0,
        1 => -0.0,
        2 => -magnitude(rng),
        3 => f64::NAN,
        4 => f64::INFINITY,
        _ => f64::NEG_INFINITY,
    }
}

/// A non-finite value (NaN, +∞ or −∞).
pub fn non_finite<R: Rng>(rng: &mut R) -> f64 {
    match rng.random_range(0..3) {
        0 => f64::NAN,
        1 => f64::INFINITY,
        _ => f64::NEG_INFINITY,
    }
}

/// A signed coordinate: a magnitude with a random sign, or exactly zero
/// (10 %, either sign).
pub fn coordinate<R: Rng>(rng: &mut R) -> f64 {
    if rng.random_bool(0.1) {
        if rng.random_bool(0.5) {
            0.0
        } else {
            -0.0
        }
    } else {
        let m = magnitude(rng);
        signed(rng, m)
    }
}

/// `x` with a random sign.
pub fn signed<R: Rng>(rng: &mut R, x: f64) -> f64 {
    if rng.random_bool(0.5) {
        x
    } else {
        -x
    }
}

/// The TOML spelling of `x` that parses back to the same bits: Rust's
/// shortest round-trip representation (always with a `.` or an exponent,
/// so TOML reads a float), and `nan`, `inf`, `-inf` for the non-finite
/// values.
pub fn toml_float(x: f64) -> String {
    if x.is_nan() {
        "nan".to_owned()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_owned()
    } else {
        format!("{x:?}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn toml_floats_round_trip() {
        for x in EDGE_MAGNITUDES.iter().copied().chain([
            0.0,
            -0.0,
            0.1,
            -2.5,
            f64::MAX,
            123_456_789.0,
            1e-7,
        ]) {
            let text = format!("x = {}", toml_float(x));
            let v: toml::Table = text.parse().expect("valid TOML");
            let back = v["x"].as_float().expect("a float");
            assert_eq!(back.to_bits(), x.to_bits(), "{text}");
        }
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let text = format!("x = {}", toml_float(x));
            let v: toml::Table = text.parse().expect("valid TOML");
            let back = v["x"].as_float().expect("a float");
            assert_eq!(back.is_nan(), x.is_nan(), "{text}");
            assert!(back.is_nan() || back == x, "{text}");
        }
    }

    #[test]
    fn magnitudes_are_positive_and_finite_and_reach_both_ends() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(1);
        let values: Vec<f64> = (0..10_000).map(|_| magnitude(&mut rng)).collect();
        assert!(values.iter().all(|x| x.is_finite() && *x > 0.0));
        assert!(values.iter().any(|x| *x < 1e-300));
        assert!(values.iter().any(|x| *x > 1e300));
    }
}
