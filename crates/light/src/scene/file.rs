//! The TOML scene format: parsing and validation with messages that name
//! the field.

use glam::DVec3;
use serde::Deserialize;
use std::fmt;

use super::Scene;
use crate::emitter::{
    DirectionalLight, DiskLight, Emitter, EmitterError, PointLight, PolygonLight, Sky, SkyCap,
    SphereLight,
};
use crate::receiver::Receiver;

/// Why a scene file could not be used: a message naming the field (and,
/// for syntax errors, the line and column).
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// The message.
    pub message: String,
}

impl SceneError {
    /// An error with this message.
    pub fn new(message: impl Into<String>) -> Self {
        SceneError {
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}

impl From<EmitterError> for SceneError {
    fn from(e: EmitterError) -> Self {
        SceneError::new(e.to_string())
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    receiver: RawReceiver,
    #[serde(default)]
    emitters: Vec<RawEmitter>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawReceiver {
    point: [f64; 3],
    normal: [f64; 3],
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawEmitter {
    kind: String,
    radiance: Option<f64>,
    center: Option<[f64; 3]>,
    radius: Option<f64>,
    normal: Option<[f64; 3]>,
    two_sided: Option<bool>,
    vertices: Option<Vec<[f64; 3]>>,
    axis: Option<[f64; 3]>,
    half_angle: Option<f64>,
    half_angle_deg: Option<f64>,
    position: Option<[f64; 3]>,
    intensity: Option<f64>,
    flux: Option<f64>,
    direction: Option<[f64; 3]>,
    irradiance: Option<f64>,
}

/// One `[[emitters]]` entry of a scene file as written, checked against its
/// kind only when built: for file formats that embed this one's emitters
/// (the tracer's scene files), so that both read emitters by one set of
/// rules and report errors alike.
///
/// ```
/// use lambert_light::scene::EmitterEntry;
/// let entry: EmitterEntry = toml::from_str("kind = \"point\"\nposition = [0.0, 0.0, 1.0]\nflux = 4.0").unwrap();
/// assert_eq!(entry.build()?.kind(), "point");
/// let bad: EmitterEntry = toml::from_str("kind = \"sky\"\nradius = 1.0").unwrap();
/// assert_eq!(bad.build().unwrap_err().field, "radius");
/// # Ok::<(), lambert_light::EmitterError>(())
/// ```
#[derive(Deserialize)]
#[serde(transparent)]
pub struct EmitterEntry(RawEmitter);

impl EmitterEntry {
    /// The emitter, validated. Errors name the field without its place
    /// (`radius`); add the place with [`EmitterError::within`].
    pub fn build(&self) -> Result<Emitter, EmitterError> {
        build(&self.0)
    }
}

/// The fields each kind accepts (besides `kind`).
fn allowed(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "sky" => &["radiance"],
        "sky_cap" => &["axis", "half_angle", "half_angle_deg", "radiance"],
        "sphere" => &["center", "radius", "radiance"],
        "disk" => &["center", "normal", "radius", "radiance", "two_sided"],
        "polygon" => &["vertices", "radiance", "two_sided"],
        "point" => &["position", "intensity", "flux"],
        "directional" => &["direction", "irradiance"],
        _ => return None,
    })
}

impl RawEmitter {
    /// The names of the fields that are present.
    fn present(&self) -> Vec<&'static str> {
        let mut p = Vec::new();
        macro_rules! check {
            ($($f:ident),*) => { $( if self.$f.is_some() { p.push(stringify!($f)); } )* };
        }
        check!(
            radiance,
            center,
            radius,
            normal,
            two_sided,
            vertices,
            axis,
            half_angle,
            half_angle_deg,
            position,
            intensity,
            flux,
            direction,
            irradiance
        );
        p
    }
}

fn need<T: Copy>(value: Option<T>, field: &str, kind: &str) -> Result<T, EmitterError> {
    value.ok_or_else(|| EmitterError::new(field, format!("is required for a {kind} emitter")))
}

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

fn build(raw: &RawEmitter) -> Result<Emitter, EmitterError> {
    let kind = raw.kind.as_str();
    let Some(fields) = allowed(kind) else {
        return Err(EmitterError::new(
            "kind",
            format!(
                "unknown emitter kind {kind:?} (expected sky, sky_cap, sphere, disk, polygon, point or directional)"
            ),
        ));
    };
    for f in raw.present() {
        if !fields.contains(&f) {
            return Err(EmitterError::new(
                f,
                format!(
                    "is not a field of a {kind} emitter (its fields: kind, {})",
                    fields.join(", ")
                ),
            ));
        }
    }
    Ok(match kind {
        "sky" => Emitter::Sky(Sky::new(need(raw.radiance, "radiance", kind)?)?),
        "sky_cap" => {
            let half_angle = match (raw.half_angle, raw.half_angle_deg) {
                (Some(r), None) => r,
                (None, Some(d)) => {
                    lambert_geometry::validate::finite("half_angle_deg", d)?;
                    if !(d > 0.0 && d <= 180.0) {
                        return Err(EmitterError::new(
                            "half_angle_deg",
                            format!("must lie in (0, 180] degrees, got {d}"),
                        ));
                    }
                    // 180° is π exactly (to_radians may round just above).
                    d.to_radians().min(std::f64::consts::PI)
                }
                (Some(_), Some(_)) => {
                    return Err(EmitterError::new(
                        "half_angle",
                        "give half_angle (radians) or half_angle_deg, not both",
                    ))
                }
                (None, None) => {
                    return Err(EmitterError::new(
                        "half_angle",
                        "is required for a sky_cap emitter (or half_angle_deg)",
                    ))
                }
            };
            Emitter::SkyCap(SkyCap::new(
                v3(need(raw.axis, "axis", kind)?),
                half_angle,
                need(raw.radiance, "radiance", kind)?,
            )?)
        }
        "sphere" => Emitter::Sphere(SphereLight::new(
            v3(need(raw.center, "center", kind)?),
            need(raw.radius, "radius", kind)?,
            need(raw.radiance, "radiance", kind)?,
        )?),
        "disk" => Emitter::Disk(DiskLight::new(
            v3(need(raw.center, "center", kind)?),
            v3(need(raw.normal, "normal", kind)?),
            need(raw.radius, "radius", kind)?,
            need(raw.radiance, "radiance", kind)?,
            raw.two_sided.unwrap_or(false),
        )?),
        "polygon" => {
            let vertices = raw.vertices.as_ref().ok_or_else(|| {
                EmitterError::new("vertices", "is required for a polygon emitter")
            })?;
            Emitter::Polygon(PolygonLight::new(
                vertices.iter().copied().map(v3).collect(),
                need(raw.radiance, "radiance", kind)?,
                raw.two_sided.unwrap_or(false),
            )?)
        }
        "point" => {
            let position = v3(need(raw.position, "position", kind)?);
            Emitter::Point(match (raw.intensity, raw.flux) {
                (Some(i), None) => PointLight::with_intensity(position, i)?,
                (None, Some(f)) => PointLight::with_flux(position, f)?,
                (Some(_), Some(_)) => {
                    return Err(EmitterError::new(
                        "intensity",
                        "give intensity or flux, not both",
                    ))
                }
                (None, None) => {
                    return Err(EmitterError::new(
                        "intensity",
                        "is required for a point emitter (or flux)",
                    ))
                }
            })
        }
        "directional" => Emitter::Directional(DirectionalLight::new(
            v3(need(raw.direction, "direction", kind)?),
            need(raw.irradiance, "irradiance", kind)?,
        )?),
        _ => unreachable!("kinds were checked by `allowed`"),
    })
}

/// Parses and validates a scene.
pub(super) fn parse(text: &str) -> Result<Scene, SceneError> {
    let raw: RawScene =
        toml::from_str(text).map_err(|e| SceneError::new(format!("scene file: {e}")))?;
    let receiver = Receiver::new(v3(raw.receiver.point), v3(raw.receiver.normal))
        .map_err(EmitterError::from)?;
    let mut emitters = Vec::with_capacity(raw.emitters.len());
    for (i, e) in raw.emitters.iter().enumerate() {
        emitters.push(build(e).map_err(|err| err.within(&format!("emitters[{i}]")))?);
    }
    if emitters.is_empty() {
        return Err(SceneError::new(
            "emitters: a scene needs at least one [[emitters]] entry",
        ));
    }
    Ok(Scene::new(receiver, emitters)?)
}
