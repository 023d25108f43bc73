//! Scenes: one receiver and its emitters, built in code or read from TOML.
//!
//! The file format (kept exactly so; see the crate's README):
//!
//! ```toml
//! [receiver]
//! point = [0.0, 0.0, 0.0]
//! normal = [0.0, 0.0, 1.0]
//!
//! [[emitters]]
//! kind = "sphere"            # sky | sky_cap | sphere | disk | polygon | point | directional
//! center = [0.0, 5.0, 8.66]
//! radius = 1.0
//! radiance = 1.0             # point: intensity = … or flux = …; directional: irradiance = …
//! ```
//!
//! Per kind: `sky` (radiance); `sky_cap` (axis, half_angle in radians or
//! half_angle_deg, radiance); `sphere` (center, radius, radiance); `disk`
//! (center, normal, radius, radiance, two_sided); `polygon` (vertices, front
//! face by the right-hand rule, radiance, two_sided); `point` (position, and
//! intensity or flux); `directional` (direction toward the light,
//! irradiance). `two_sided` defaults to false; a one-sided emitter is dark
//! seen from behind. Unknown keys, keys of another kind, wrong types, zero
//! normals, negative radii, NaN, non-planar or non-convex polygons and a
//! receiver inside a sphere light are errors that name the field.

#[cfg(feature = "scene-file")]
mod file;

#[cfg(feature = "scene-file")]
pub use file::{EmitterEntry, SceneError};

use crate::emitter::{Emitter, EmitterError};
use crate::receiver::Receiver;

/// A receiver and the emitters that light it (additive; see
/// [`crate::emitter`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The receiver.
    pub receiver: Receiver,
    /// The emitters.
    pub emitters: Vec<Emitter>,
}

impl Scene {
    /// A scene, checked as a whole (a receiver inside a sphere light is an
    /// error naming that emitter).
    pub fn new(receiver: Receiver, emitters: Vec<Emitter>) -> Result<Self, EmitterError> {
        for (i, e) in emitters.iter().enumerate() {
            e.check_receiver(&receiver).map_err(|err| {
                EmitterError::new(
                    err.field,
                    format!("{} (emitters[{i}], a {})", err.problem, e.kind()),
                )
            })?;
        }
        Ok(Scene { receiver, emitters })
    }

    /// Parses a scene from TOML text (feature `scene-file`).
    #[cfg(feature = "scene-file")]
    pub fn from_toml(text: &str) -> Result<Self, SceneError> {
        file::parse(text)
    }

    /// Reads and parses a scene file (feature `scene-file`).
    #[cfg(feature = "scene-file")]
    pub fn load(path: &std::path::Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SceneError::new(format!("cannot read {}: {e}", path.display())))?;
        file::parse(&text)
    }
}
