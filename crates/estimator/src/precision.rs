//! The arithmetic precision of an estimate's per-sample work.
//!
//! - [`Precision::F64`] (the default): every sample's direction, density
//!   and value in f64.
//! - [`Precision::F32`]: each emitter's per-sample arithmetic — the uniform
//!   coordinates, the warp, the frame, the hit test, the density and the
//!   geometric factor cos θ/p — in f32, twice as many lanes per vector as
//!   f64 (16 in an AVX-512 register); the emitter's radiance is applied and
//!   every value accumulated in f64 (compensated sums, as in f64 mode).
//!   An emitter for which f32 is not accurate enough runs in f64 instead,
//!   and the estimate says so ([`crate::strategy::F32Fallback`]); the
//!   f32 rounding bound of the others is added to the standard error's
//!   floor. docs/NUMERICS.md ("The f32 estimator") gives the error bound,
//!   the fallback rules and the random numbers of the f32 path.

use std::fmt;
use std::str::FromStr;

/// The precision of an estimate's per-sample arithmetic (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Precision {
    /// Per-sample arithmetic in f64 (the default).
    #[default]
    F64,
    /// Per-sample arithmetic in f32, accumulation in f64.
    F32,
}

impl Precision {
    /// Both, f64 first.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// The name used on the command line, in study files and reports.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Precision {
    type Err = String;

    /// `f64` or `f32`.
    ///
    /// ```
    /// use lambert_estimator::precision::Precision;
    /// assert_eq!("f32".parse::<Precision>(), Ok(Precision::F32));
    /// assert!("half".parse::<Precision>().unwrap_err().contains("\"half\""));
    /// ```
    fn from_str(s: &str) -> Result<Self, String> {
        Precision::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| format!("unknown precision {s:?} (expected f64 or f32)"))
    }
}
