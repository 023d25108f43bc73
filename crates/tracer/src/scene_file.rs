//! The tracer's TOML scene files: lambert's `[[emitters]]` format extended
//! with a `[camera]`, `[[shapes]]` with materials, meshes by path, and a
//! background.
//!
//! ```toml
//! background = [0.2, 0.3, 0.6]     # optional: radiance of rays that escape (lights nothing)
//!
//! [camera]
//! position = [0.0, 1.5, 6.0]
//! look_at = [0.0, 0.6, 0.0]
//! up = [0.0, 1.0, 0.0]             # optional, default +y
//! fov_deg = 45.0                   # vertical field of view
//! width = 512                      # optional, default 512
//! height = 512                     # optional, default 512
//!
//! [[shapes]]
//! kind = "sphere"                  # sphere | plane | disk | triangle | parallelogram | polygon | mesh
//! center = [-0.9, 0.8, 0.0]
//! radius = 0.8
//! material = { kind = "mirror", specular = [0.6, 0.6, 0.6], shininess = 400.0 }
//!
//! [[shapes]]
//! kind = "mesh"
//! path = "bunny.obj"               # relative to this file
//! scale = 1.0                      # optional: p ↦ translate + R(scale·p)
//! rotate_axis = [0.0, 1.0, 0.0]    # optional, with rotate_deg
//! rotate_deg = 30.0
//! translate = [0.0, 0.0, 0.0]
//! material = { kind = "diffuse", albedo = [0.7, 0.7, 0.7] }
//!
//! [[emitters]]                     # exactly as in `lambert estimate`'s scene files
//! kind = "point"
//! position = [2.0, 5.0, 4.0]
//! intensity = 60.0
//! ```
//!
//! Shapes: `sphere` (center, radius), `plane` (point, normal), `disk`
//! (center, normal, radius), `triangle` (vertices: three points),
//! `parallelogram` (corner, edge0, edge1), `polygon` (vertices: convex,
//! planar, counter-clockwise seen from the front), `mesh` (path, scale,
//! rotate_axis, rotate_deg, translate). Materials: `diffuse` (albedo
//! [r, g, b], or checker = { even = [..], odd = [..], scale = squares per
//! unit of the surface parameters }), `mirror` (reflectance, default
//! [1, 1, 1]), `dielectric` (ior, default 1.5); any of them may add
//! Blinn–Phong highlights with `specular` = [r, g, b] and `shininess`.
//! Emitters: every kind of lambert's scene files; sphere, disk and polygon
//! emitters are also shapes, seen and occluding.
//!
//! Errors name the field with its place (`shapes[2].material.albedo`,
//! `camera.fov_deg`, `emitters[0].radius`): unknown keys, keys of another
//! kind, wrong types, NaN, zero radii, degenerate or non-manifold mesh
//! faces, a missing mesh file, a camera inside a sphere.

use std::path::Path;

use glam::DVec3;
use lambert_geometry::f64::{ConvexPolygon, Disk, Parallelogram, Plane, Sphere, Triangle};
use lambert_light::scene::EmitterEntry;
use serde::Deserialize;

use crate::camera::Camera;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::{Highlight, Material, Surface};
use crate::mesh::{Mesh, Transform};
use crate::scene::{Scene, SceneBuilder};
use crate::shape::Shape;
use crate::texture::Texture;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    background: Option<[f64; 3]>,
    camera: RawCamera,
    #[serde(default)]
    shapes: Vec<RawShape>,
    #[serde(default)]
    emitters: Vec<EmitterEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    position: [f64; 3],
    look_at: [f64; 3],
    up: Option<[f64; 3]>,
    fov_deg: f64,
    width: Option<u32>,
    height: Option<u32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawShape {
    kind: String,
    material: Option<RawMaterial>,
    center: Option<[f64; 3]>,
    radius: Option<f64>,
    point: Option<[f64; 3]>,
    normal: Option<[f64; 3]>,
    vertices: Option<Vec<[f64; 3]>>,
    corner: Option<[f64; 3]>,
    edge0: Option<[f64; 3]>,
    edge1: Option<[f64; 3]>,
    path: Option<String>,
    scale: Option<f64>,
    rotate_axis: Option<[f64; 3]>,
    rotate_deg: Option<f64>,
    translate: Option<[f64; 3]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    kind: String,
    albedo: Option<[f64; 3]>,
    checker: Option<RawChecker>,
    reflectance: Option<[f64; 3]>,
    ior: Option<f64>,
    specular: Option<[f64; 3]>,
    shininess: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawChecker {
    even: [f64; 3],
    odd: [f64; 3],
    scale: f64,
}

/// The names of the fields present among `fields`.
fn present(fields: &[(&'static str, bool)]) -> Vec<&'static str> {
    fields.iter().filter(|f| f.1).map(|f| f.0).collect()
}

/// Errors on a present field that `kind` does not take.
fn only(
    what: &str,
    kind: &str,
    present: &[&'static str],
    allowed: &[&str],
) -> Result<(), TracerError> {
    for f in present {
        if !allowed.contains(f) {
            return Err(TracerError::new(
                *f,
                format!(
                    "is not a field of a {kind} {what} (its fields: kind, {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

fn need<T: Clone>(
    value: &Option<T>,
    field: &str,
    kind: &str,
    what: &str,
) -> Result<T, TracerError> {
    value
        .clone()
        .ok_or_else(|| TracerError::new(field, format!("is required for a {kind} {what}")))
}

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

impl RawMaterial {
    fn build(&self) -> Result<Material, TracerError> {
        let kind = self.kind.as_str();
        let fields = present(&[
            ("albedo", self.albedo.is_some()),
            ("checker", self.checker.is_some()),
            ("reflectance", self.reflectance.is_some()),
            ("ior", self.ior.is_some()),
            ("specular", self.specular.is_some()),
            ("shininess", self.shininess.is_some()),
        ]);
        let allowed: &[&str] = match kind {
            "diffuse" => &["albedo", "checker", "specular", "shininess"],
            "mirror" => &["reflectance", "specular", "shininess"],
            "dielectric" => &["ior", "specular", "shininess"],
            other => {
                return Err(TracerError::new(
                    "kind",
                    format!(
                        "unknown material kind {other:?} (expected diffuse, mirror or dielectric)"
                    ),
                ))
            }
        };
        only("material", kind, &fields, allowed)?;
        let surface = match kind {
            "diffuse" => Surface::Diffuse(match (&self.albedo, &self.checker) {
                (Some(a), None) => Texture::Constant(Rgb::from_array(*a)),
                (None, Some(c)) => Texture::Checker {
                    even: Rgb::from_array(c.even),
                    odd: Rgb::from_array(c.odd),
                    scale: c.scale,
                },
                (Some(_), Some(_)) => {
                    return Err(TracerError::new(
                        "albedo",
                        "give albedo or checker, not both",
                    ))
                }
                (None, None) => {
                    return Err(TracerError::new(
                        "albedo",
                        "is required for a diffuse material (or checker)",
                    ))
                }
            }),
            "mirror" => Surface::Mirror(Rgb::from_array(self.reflectance.unwrap_or([1.0; 3]))),
            _ => Surface::Dielectric {
                ior: self.ior.unwrap_or(1.5),
            },
        };
        let highlight = match (self.specular, self.shininess) {
            (Some(s), Some(e)) => Some(Highlight {
                specular: Rgb::from_array(s),
                exponent: e,
            }),
            (None, None) => None,
            (Some(_), None) => {
                return Err(TracerError::new("shininess", "is required with specular"))
            }
            (None, Some(_)) => {
                return Err(TracerError::new("specular", "is required with shininess"))
            }
        };
        let material = Material { surface, highlight };
        material.validate().map_err(|e| {
            // The checker's fields live in their own table.
            if matches!(
                e.field.as_str(),
                "albedo.even" | "albedo.odd" | "albedo.scale"
            ) {
                TracerError::new(e.field.replacen("albedo", "checker", 1), e.problem)
            } else {
                e
            }
        })?;
        Ok(material)
    }
}

impl RawShape {
    /// The shapes (one, or a mesh's triangles); mesh paths are relative to
    /// `base`.
    fn build(&self, base: &Path) -> Result<Vec<Shape>, TracerError> {
        let kind = self.kind.as_str();
        let fields = present(&[
            ("center", self.center.is_some()),
            ("radius", self.radius.is_some()),
            ("point", self.point.is_some()),
            ("normal", self.normal.is_some()),
            ("vertices", self.vertices.is_some()),
            ("corner", self.corner.is_some()),
            ("edge0", self.edge0.is_some()),
            ("edge1", self.edge1.is_some()),
            ("path", self.path.is_some()),
            ("scale", self.scale.is_some()),
            ("rotate_axis", self.rotate_axis.is_some()),
            ("rotate_deg", self.rotate_deg.is_some()),
            ("translate", self.translate.is_some()),
        ]);
        let allowed: &[&str] = match kind {
            "sphere" => &["center", "radius", "material"],
            "plane" => &["point", "normal", "material"],
            "disk" => &["center", "normal", "radius", "material"],
            "triangle" | "polygon" => &["vertices", "material"],
            "parallelogram" => &["corner", "edge0", "edge1", "material"],
            "mesh" => &["path", "scale", "rotate_axis", "rotate_deg", "translate", "material"],
            other => {
                return Err(TracerError::new(
                    "kind",
                    format!(
                        "unknown shape kind {other:?} (expected sphere, plane, disk, triangle, parallelogram, polygon or mesh)"
                    ),
                ))
            }
        };
        only("shape", kind, &fields, allowed)?;
        let n = |f: &Option<[f64; 3]>, name| need(f, name, kind, "shape").map(v3);
        let vertices = || -> Result<Vec<DVec3>, TracerError> {
            Ok(need(&self.vertices, "vertices", kind, "shape")?
                .into_iter()
                .map(v3)
                .collect())
        };
        Ok(vec![match kind {
            "sphere" => Shape::Sphere(Sphere::new(
                n(&self.center, "center")?,
                need(&self.radius, "radius", kind, "shape")?,
            )?),
            "plane" => Shape::Plane(Plane::new(
                n(&self.point, "point")?,
                n(&self.normal, "normal")?,
            )?),
            "disk" => Shape::Disk(Disk::new(
                n(&self.center, "center")?,
                n(&self.normal, "normal")?,
                need(&self.radius, "radius", kind, "shape")?,
            )?),
            "triangle" => {
                let v = vertices()?;
                if v.len() != 3 {
                    return Err(TracerError::new(
                        "vertices",
                        format!("a triangle needs exactly 3 vertices, got {}", v.len()),
                    ));
                }
                Shape::Triangle(Triangle::new(v[0], v[1], v[2])?)
            }
            "polygon" => Shape::Polygon(Box::new(ConvexPolygon::new(vertices()?)?)),
            "parallelogram" => Shape::Parallelogram(Parallelogram::new(
                n(&self.corner, "corner")?,
                n(&self.edge0, "edge0")?,
                n(&self.edge1, "edge1")?,
            )?),
            _ => {
                let transform = Transform::new(
                    self.scale.unwrap_or(1.0),
                    v3(self.rotate_axis.unwrap_or([0.0, 1.0, 0.0])),
                    self.rotate_deg.unwrap_or(0.0),
                    v3(self.translate.unwrap_or([0.0; 3])),
                )?;
                if self.rotate_axis.is_some() && self.rotate_deg.is_none() {
                    return Err(TracerError::new(
                        "rotate_deg",
                        "is required with rotate_axis",
                    ));
                }
                let path = base.join(need(&self.path, "path", kind, "shape")?);
                let mesh = Mesh::load_obj(&path, &transform, "path")?;
                return Ok(mesh.triangles.into_iter().map(Shape::Triangle).collect());
            }
        }])
    }
}

/// Parses a scene from TOML `text`; mesh paths are relative to `base`.
pub fn parse(text: &str, base: &Path) -> Result<Scene, TracerError> {
    let raw: RawScene = toml::from_str(text)
        .map_err(|e| TracerError::new("scene file", e.to_string().trim_end().to_string()))?;
    let c = &raw.camera;
    let camera = Camera::new(
        v3(c.position),
        v3(c.look_at),
        v3(c.up.unwrap_or([0.0, 1.0, 0.0])),
        c.fov_deg,
        c.width.unwrap_or(512),
        c.height.unwrap_or(512),
    )
    .map_err(|e| e.within("camera"))?;
    let mut b = SceneBuilder::new(camera);
    if let Some(bg) = raw.background {
        b.background(Rgb::from_array(bg));
    }
    for (i, s) in raw.shapes.iter().enumerate() {
        let place = format!("shapes[{i}]");
        let shapes = s.build(base).map_err(|e| e.within(&place))?;
        let material = s
            .material
            .as_ref()
            .ok_or_else(|| {
                TracerError::new("material", format!("is required for a {} shape", s.kind))
            })
            .and_then(RawMaterial::build)
            .map_err(|e| {
                let e = if e.field == "material" {
                    e
                } else {
                    e.within("material")
                };
                e.within(&place)
            })?;
        let id = b.add_material(material);
        for shape in shapes {
            b.add_shape(shape, id);
        }
    }
    for (i, e) in raw.emitters.iter().enumerate() {
        let emitter = e
            .build()
            .map_err(|err| TracerError::from(err).within(&format!("emitters[{i}]")))?;
        b.add_emitter(emitter);
    }
    b.build()
}

/// Reads and parses a scene file (mesh paths relative to its directory).
/// Errors name the file when it cannot be read.
pub fn load(path: &Path) -> Result<Scene, TracerError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| TracerError::new(path.display().to_string(), format!("cannot read: {e}")))?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse(&text, base)
}
