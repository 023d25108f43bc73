//! The error of emitter and receiver construction.

use lambert_geometry::GeometryError;
use std::fmt;

/// What was wrong with an emitter's or receiver's parameters: the field
/// (with its place, e.g. `emitters[2].radius`, once a scene has added it)
/// and the problem, with the offending value. Shapes are validated by
/// `lambert_geometry` (one set of rules); their errors convert into this
/// one unchanged.
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
}

impl From<GeometryError> for EmitterError {
    fn from(e: GeometryError) -> Self {
        EmitterError::new(e.field(), e.problem())
    }
}

impl fmt::Display for EmitterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.problem)
    }
}

impl std::error::Error for EmitterError {}
