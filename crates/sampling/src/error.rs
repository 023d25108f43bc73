//! The error every validating constructor of this crate returns.

use core::fmt;

/// Why a sampler could not be built from the parameters it was given.
///
/// Each variant names the parameter (`field`) and the offending value, so a
/// message can be shown to a user as it is. Values are widened to f64 for
/// both precisions.
#[derive(Clone, Debug, PartialEq)]
pub enum SamplingError {
    /// A parameter is NaN or infinite.
    NotFinite {
        /// The parameter's name.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A parameter lies outside the range the warp is defined on.
    OutOfRange {
        /// The parameter's name.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The accepted range, in words (e.g. `"(0, 2]"`).
        range: &'static str,
    },
    /// A vector that must have a direction (a normal, an edge) has length 0.
    ZeroVector {
        /// The parameter's name.
        field: &'static str,
    },
    /// The geometry is degenerate: zero area or zero solid angle.
    Degenerate {
        /// What is degenerate, in words.
        what: &'static str,
    },
    /// A shape the sampler is built from is invalid.
    Geometry(lambert_geometry::GeometryError),
    /// A polygon light has more vertices than the sampler's fixed buffer
    /// holds ([`MAX_POLYGON_VERTICES`](crate::MAX_POLYGON_VERTICES)).
    TooManyVertices {
        /// The polygon's vertex count.
        count: usize,
        /// The limit.
        limit: usize,
    },
    /// The reference point is inside, or on, the light it should sample.
    InsideLight {
        /// Distance from the point to the light's center.
        distance: f64,
        /// The light's radius.
        radius: f64,
    },
}

impl fmt::Display for SamplingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SamplingError::NotFinite { field, value } => {
                write!(f, "`{field}` must be finite, got {value}")
            }
            SamplingError::OutOfRange {
                field,
                value,
                range,
            } => write!(f, "`{field}` must lie in {range}, got {value}"),
            SamplingError::ZeroVector { field } => {
                write!(f, "`{field}` must be a non-zero vector")
            }
            SamplingError::Degenerate { what } => write!(f, "degenerate geometry: {what}"),
            SamplingError::Geometry(e) => write!(f, "{e}"),
            SamplingError::TooManyVertices { count, limit } => write!(
                f,
                "`vertices`: a polygon light has at most {limit} vertices (the sampler clips it \
                 to the horizon in a fixed buffer), got {count}"
            ),
            SamplingError::InsideLight { distance, radius } => write!(
                f,
                "the reference point is inside or on the sphere light \
                 (distance to center {distance} <= radius {radius})"
            ),
        }
    }
}

impl std::error::Error for SamplingError {}

impl From<lambert_geometry::GeometryError> for SamplingError {
    fn from(e: lambert_geometry::GeometryError) -> Self {
        SamplingError::Geometry(e)
    }
}

/// Checks that a scalar parameter is finite.
pub(crate) fn finite(field: &'static str, value: f64) -> Result<(), SamplingError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SamplingError::NotFinite { field, value })
    }
}

/// Checks that every component of a vector parameter (widened to f64) is
/// finite.
pub(crate) fn finite3(field: &'static str, v: glam::DVec3) -> Result<(), SamplingError> {
    for c in v.to_array() {
        finite(field, c)?;
    }
    Ok(())
}
