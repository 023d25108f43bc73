//! The error of emitter and receiver construction.

use glam::DVec3;
use std::fmt;

/// What was wrong with an emitter's or receiver's parameters: the field
/// (with its place, e.g. `emitters[2].radius`, once a scene has added it)
/// and the problem, with the offending value.
#[derive(Clone, Debug, PartialEq)]
pub struct EmitterError {
    /// The field, e.g. `radius` or `emitters[2].radius`.
    pub field: String,
    /// What is wrong with it.
    pub problem: String,
}

impl EmitterError {
    /// An error about `field`.
    pub fn new(field: impl Into<String>, problem: impl Into<String>) -> Self {
        EmitterError {
            field: field.into(),
            problem: problem.into(),
        }
    }

    /// The same error, its field prefixed by `place` (e.g. `emitters[2]`).
    pub fn within(mut self, place: &str) -> Self {
        self.field = format!("{place}.{}", self.field);
        self
    }

    /// Errors unless `value` is finite.
    pub fn check_finite(field: &str, value: f64) -> Result<(), EmitterError> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(EmitterError::new(
                field,
                format!("must be finite, got {value}"),
            ))
        }
    }

    /// Errors unless `value` is finite and > 0.
    pub fn check_positive(field: &str, value: f64) -> Result<(), EmitterError> {
        Self::check_finite(field, value)?;
        if value > 0.0 {
            Ok(())
        } else {
            Err(EmitterError::new(
                field,
                format!("must be positive, got {value}"),
            ))
        }
    }

    /// Errors unless `value` is finite and ≥ 0.
    pub fn check_non_negative(field: &str, value: f64) -> Result<(), EmitterError> {
        Self::check_finite(field, value)?;
        if value >= 0.0 {
            Ok(())
        } else {
            Err(EmitterError::new(
                field,
                format!("must not be negative, got {value}"),
            ))
        }
    }

    /// Errors unless every component of `v` is finite.
    pub fn check_vector(field: &str, v: DVec3) -> Result<(), EmitterError> {
        if v.is_finite() {
            Ok(())
        } else {
            Err(EmitterError::new(field, format!("must be finite, got {v}")))
        }
    }

    /// `v` normalised; errors if it is zero or not finite.
    pub fn unit(field: &str, v: DVec3) -> Result<DVec3, EmitterError> {
        Self::check_vector(field, v)?;
        // Scaled by the largest component first, so that neither a huge
        // vector (|v|² overflows) nor a tiny one (|v|² underflows, losing
        // precision) is mistaken for zero or normalised inexactly.
        let largest = v.abs().max_element();
        if !(largest > 0.0) {
            return Err(EmitterError::new(field, "must be a non-zero vector"));
        }
        let scaled = v / largest;
        Ok(scaled / scaled.length())
    }
}

impl fmt::Display for EmitterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.problem)
    }
}

impl std::error::Error for EmitterError {}
