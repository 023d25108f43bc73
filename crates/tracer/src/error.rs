//! The tracer's error: the field (with its place) and what is wrong.

use std::fmt;

use lambert_estimator::estimation::EstimateError;
use lambert_geometry::GeometryError;
use lambert_light::EmitterError;

/// Why a scene, a render or an output could not be made: the field, with
/// its place (`shapes[2].radius`, `camera.position`, `--width`), and what
/// is wrong with it, with the offending value. `Display` writes
/// `field: problem`.
#[derive(Clone, Debug, PartialEq)]
pub struct TracerError {
    /// The field, e.g. `shapes[2].radius`.
    pub field: String,
    /// What is wrong with it.
    pub problem: String,
}

impl TracerError {
    /// An error about `field`.
    pub fn new(field: impl Into<String>, problem: impl Into<String>) -> Self {
        TracerError {
            field: field.into(),
            problem: problem.into(),
        }
    }

    /// The same error, its field prefixed by `place` (`shapes[2]`).
    pub fn within(mut self, place: &str) -> Self {
        self.field = if self.field.is_empty() {
            place.to_string()
        } else {
            format!("{place}.{}", self.field)
        };
        self
    }
}

impl fmt::Display for TracerError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.field, self.problem)
    }
}

impl std::error::Error for TracerError {}

impl From<GeometryError> for TracerError {
    fn from(e: GeometryError) -> Self {
        TracerError::new(e.field(), e.problem())
    }
}

impl From<EmitterError> for TracerError {
    fn from(e: EmitterError) -> Self {
        TracerError::new(e.field, e.problem)
    }
}

impl From<EstimateError> for TracerError {
    fn from(e: EstimateError) -> Self {
        match e {
            EstimateError::Config { field, problem } => TracerError::new(field, problem),
            EstimateError::NonFiniteSample { emitter, .. } => {
                TracerError::new(format!("emitters[{emitter}]"), e.to_string())
            }
            other => TracerError::new("estimate", other.to_string()),
        }
    }
}
