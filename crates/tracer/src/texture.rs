//! Reflectance textures: a constant, or a checkerboard over the surface
//! parameters.

use glam::DVec2;

use crate::color::Rgb;
use crate::error::TracerError;

/// A reflectance that may vary over a surface, looked up by the hit's
/// surface parameters (u, v) (for planes, metres along the plane's axes;
/// for parallelograms, the fractions along the edges; see
/// `lambert_geometry`'s shapes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Texture {
    /// The same everywhere.
    Constant(Rgb),
    /// Squares of side 1/`scale` in (u, v), alternating `even` (where
    /// ⌊u·scale⌋ + ⌊v·scale⌋ is even) and `odd` (Whitted's checkerboard).
    Checker {
        /// The colour of even squares.
        even: Rgb,
        /// The colour of odd squares.
        odd: Rgb,
        /// Squares per unit of u and v.
        scale: f64,
    },
}

/// `x.floor() as i64`, to the bit (saturating at the ends of the `i64`
/// range, 0 for NaN), without a call to `floor`: on the baseline x86-64
/// instruction set (no SSE4.1 rounding instruction) `f64::floor` is a
/// library call, which cost a checkerboard lookup more than the rest of
/// it. Truncation toward zero (`as`), minus one where it rounded a
/// negative non-integer up.
#[inline]
fn floor_to_int(x: f64) -> i64 {
    let truncated = x as i64;
    truncated.saturating_sub(i64::from(truncated as f64 > x))
}

impl Texture {
    /// The reflectance at surface parameters `uv`.
    #[inline]
    pub fn at(&self, uv: DVec2) -> Rgb {
        match *self {
            Texture::Constant(c) => c,
            Texture::Checker { even, odd, scale } => {
                // The parity of ⌊u·s⌋ + ⌊v·s⌋ (as integers: exact for
                // |u·s| < 2⁶³, saturating beyond, where squares are far
                // below a pixel anyway).
                let k = floor_to_int(uv.x * scale) ^ floor_to_int(uv.y * scale);
                if k & 1 == 0 {
                    even
                } else {
                    odd
                }
            }
        }
    }

    /// The reflectance at the surface parameters `uv()`, called only for a
    /// texture that varies (a tracer computes the parameters lazily).
    #[inline]
    pub fn at_lazy(&self, uv: impl FnOnce() -> DVec2) -> Rgb {
        match *self {
            Texture::Constant(c) => c,
            Texture::Checker { .. } => self.at(uv()),
        }
    }

    /// Checks every reflectance is in [0, 1] and the scale finite and
    /// positive (errors name the field: `albedo`, `even`, `odd`, `scale`).
    pub fn validate(&self, field: &str) -> Result<(), TracerError> {
        match *self {
            Texture::Constant(c) => reflectance(field, c),
            Texture::Checker { even, odd, scale } => {
                reflectance("even", even).map_err(|e| e.within(field))?;
                reflectance("odd", odd).map_err(|e| e.within(field))?;
                if !(scale.is_finite() && scale > 0.0) {
                    return Err(TracerError::new(
                        "scale",
                        format!("must be finite and positive, got {scale}"),
                    )
                    .within(field));
                }
                Ok(())
            }
        }
    }
}

/// Checks a reflectance: every channel finite and in [0, 1] (a surface
/// reflects at most what it receives).
pub fn reflectance(field: &str, c: Rgb) -> Result<(), TracerError> {
    for v in [c.r, c.g, c.b] {
        if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
            return Err(TracerError::new(
                field,
                format!(
                    "every channel must lie in [0, 1], got [{}, {}, {}]",
                    c.r, c.g, c.b
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::floor_to_int;

    #[test]
    fn floor_to_int_is_floor_as_i64_to_the_bit() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            -1.5,
            2.0f64.powi(52) + 0.5,
            -(2.0f64.powi(52) + 0.5),
            2.0f64.powi(63),
            -(2.0f64.powi(63)),
            2.0f64.powi(63) - 1024.0,
            -(2.0f64.powi(63)) - 2048.0,
            1e300,
            -1e300,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        // A walk over magnitudes and signs, integers and their neighbours.
        let mut x: f64 = 1e-3;
        while x < 1e20 {
            for y in [
                x,
                x.next_up(),
                x.next_down(),
                x.round(),
                x.round().next_down(),
            ] {
                xs.extend([y, -y]);
            }
            x *= 1.37;
        }
        for x in xs {
            assert_eq!(floor_to_int(x), x.floor() as i64, "{x:e}");
        }
    }
}
