//! The error type of the analytic irradiance functions.

use glam::DVec3;
use std::fmt;

/// What was wrong with the input of an analytic irradiance function.
#[derive(Clone, Debug, PartialEq)]
pub enum AnalyticError {
    /// A parameter is NaN or infinite.
    NotFinite {
        /// The parameter.
        field: &'static str,
    },
    /// A direction that must be unit length is not (to 1e-6).
    NotUnit {
        /// The parameter.
        field: &'static str,
        /// Its length.
        length: f64,
    },
    /// A length that must be positive is not.
    NotPositive {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// The receiver is inside (or on) the light.
    ReceiverInsideLight {
        /// The light.
        light: &'static str,
    },
    /// A polygon is degenerate, non-planar or non-convex.
    BadPolygon {
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The true value of a quantity (the irradiance, or an intermediate
    /// that cannot be scaled away) exceeds the largest f64, 1.8e308: the
    /// answer is not representable, and no ∞ or NaN is returned instead.
    Overflow {
        /// The quantity, e.g. `irradiance`.
        quantity: &'static str,
    },
    /// A bounded numerical step (the quadrature over a disk's visible rim)
    /// used its whole work budget without reaching its error target.
    Unresolved {
        /// What could not be resolved.
        what: &'static str,
        /// The value reached.
        value: f64,
        /// The error bound it achieved (absolute, same unit as `value`).
        error_bound: f64,
    },
}

impl fmt::Display for AnalyticError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnalyticError::NotFinite { field } => write!(f, "`{field}` is not finite"),
            AnalyticError::NotUnit { field, length } => {
                write!(f, "`{field}` must be a unit vector, its length is {length}")
            }
            AnalyticError::NotPositive { field, value } => {
                write!(f, "`{field}` must be positive, got {value}")
            }
            AnalyticError::ReceiverInsideLight { light } => {
                write!(f, "the receiver lies inside or on the {light}")
            }
            AnalyticError::BadPolygon { reason } => write!(f, "bad polygon: {reason}"),
            AnalyticError::Overflow { quantity } => {
                write!(
                    f,
                    "the {quantity} overflows: its true value exceeds 1.8e308"
                )
            }
            AnalyticError::Unresolved {
                what,
                value,
                error_bound,
            } => write!(
                f,
                "{what} not resolved within its work bound: {value} ± {error_bound}"
            ),
        }
    }
}

impl std::error::Error for AnalyticError {}

pub(crate) fn finite(field: &'static str, x: f64) -> Result<f64, AnalyticError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(AnalyticError::NotFinite { field })
    }
}

pub(crate) fn finite3(field: &'static str, v: DVec3) -> Result<DVec3, AnalyticError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(AnalyticError::NotFinite { field })
    }
}

pub(crate) fn positive(field: &'static str, x: f64) -> Result<f64, AnalyticError> {
    finite(field, x)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(AnalyticError::NotPositive { field, value: x })
    }
}

/// Checks that `v` is finite and unit to 1e-6, and returns it renormalised.
pub(crate) fn unit(field: &'static str, v: DVec3) -> Result<DVec3, AnalyticError> {
    finite3(field, v)?;
    let length = v.length();
    if (length - 1.0).abs() <= 1e-6 {
        Ok(v / length)
    } else {
        Err(AnalyticError::NotUnit { field, length })
    }
}
