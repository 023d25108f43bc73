//! The error type of the analytic irradiance functions.

use glam::DVec3;
use lambert_geometry::f64::unit_vector;
use lambert_geometry::{validate, GeometryError};
use std::fmt;

/// Why an analytic irradiance function has no value to give: invalid
/// input (validated by `lambert_geometry`'s rules, the same as every shape
/// and emitter), a receiver inside the light, a result beyond the f64
/// range, or a bounded numerical step that did not converge.
#[derive(Clone, Debug, PartialEq)]
pub enum AnalyticError {
    /// A parameter is invalid: not finite, a zero direction, out of range.
    Input(GeometryError),
    /// The receiver is inside (or on) the light.
    ReceiverInsideLight {
        /// The light.
        light: &'static str,
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
            AnalyticError::Input(e) => write!(f, "{e}"),
            AnalyticError::ReceiverInsideLight { light } => {
                write!(f, "the receiver lies inside or on the {light}")
            }
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

impl From<GeometryError> for AnalyticError {
    fn from(e: GeometryError) -> Self {
        AnalyticError::Input(e)
    }
}

/// `x` if finite.
pub(crate) fn finite(field: &'static str, x: f64) -> Result<f64, AnalyticError> {
    validate::finite(field, x)?;
    Ok(x)
}

/// `v` if finite.
pub(crate) fn finite3(field: &'static str, v: DVec3) -> Result<DVec3, AnalyticError> {
    validate::finite3(field, v)?;
    Ok(v)
}

/// `v` normalised (any finite, non-zero length), by the one rule of
/// `lambert_geometry::validate`.
pub(crate) fn unit(field: &'static str, v: DVec3) -> Result<DVec3, AnalyticError> {
    Ok(unit_vector(field, v)?)
}
