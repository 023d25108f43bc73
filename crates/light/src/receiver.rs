//! The receiver: a point with a unit normal, one-sided (only the hemisphere
//! n·ω > 0 above it receives light).

use glam::DVec3;
use lambert_geometry::f64::{unit_vector, Frame};
use lambert_geometry::{validate, GeometryError};

/// A point receiving irradiance E = ∫_{n·ω>0} L(ω) (n·ω) dω, in W/m².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Receiver {
    /// The point, in metres.
    pub point: DVec3,
    /// The unit normal.
    pub normal: DVec3,
    /// The local frame whose z is the normal.
    pub frame: Frame,
}

impl Receiver {
    /// A receiver at `point` facing `normal` (any non-zero length; it is
    /// normalised). Errors name the field.
    pub fn new(point: DVec3, normal: DVec3) -> Result<Self, GeometryError> {
        validate::finite3("receiver.point", point)?;
        let normal = unit_vector("receiver.normal", normal)?;
        Ok(Receiver {
            point,
            normal,
            frame: Frame::from_normal(normal),
        })
    }
}
