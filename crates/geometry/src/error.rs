//! The error of every validating constructor of this crate.

use core::fmt;

/// Why a shape (or another piece of geometry) could not be built from the
/// values it was given: the parameter, and what is wrong with it, with the
/// offending value.
///
/// `Display` writes `field: problem`, e.g. `radius: must be positive, got
/// -1`; [`GeometryError::problem`] gives the part after the field, so a
/// caller can put the field in its own context (`emitters[2].radius`).
/// Values are widened to f64 in both precisions.
#[derive(Clone, Debug, PartialEq)]
pub enum GeometryError {
    /// A scalar or a vector component is NaN or infinite.
    NotFinite {
        /// The parameter.
        field: &'static str,
        /// Its value, as written (a scalar or `[x, y, z]`).
        value: String,
    },
    /// A length that must be positive is zero or negative.
    NotPositive {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A quantity that must not be negative is.
    Negative {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A vector that must have a direction (a normal, an axis) is zero.
    ZeroVector {
        /// The parameter.
        field: &'static str,
    },
    /// A value outside the range it is defined on.
    OutOfRange {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The accepted range, in words.
        range: &'static str,
    },
    /// The shape is degenerate, not planar, not convex or too large.
    Shape {
        /// The parameter (e.g. `vertices`).
        field: &'static str,
        /// What is wrong, in words, with the values involved.
        problem: String,
    },
}

impl GeometryError {
    /// The parameter the error is about.
    pub fn field(&self) -> &'static str {
        match self {
            GeometryError::NotFinite { field, .. }
            | GeometryError::NotPositive { field, .. }
            | GeometryError::Negative { field, .. }
            | GeometryError::ZeroVector { field }
            | GeometryError::OutOfRange { field, .. }
            | GeometryError::Shape { field, .. } => field,
        }
    }

    /// What is wrong with the parameter, without its name (e.g. `must be
    /// positive, got -1`).
    pub fn problem(&self) -> String {
        match self {
            GeometryError::NotFinite { value, .. } => format!("must be finite, got {value}"),
            GeometryError::NotPositive { value, .. } => format!("must be positive, got {value}"),
            GeometryError::Negative { value, .. } => format!("must not be negative, got {value}"),
            GeometryError::ZeroVector { .. } => "must be a non-zero vector".into(),
            GeometryError::OutOfRange { value, range, .. } => {
                format!("must lie in {range}, got {value}")
            }
            GeometryError::Shape { problem, .. } => problem.clone(),
        }
    }
}

impl fmt::Display for GeometryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field(), self.problem())
    }
}

impl std::error::Error for GeometryError {}
