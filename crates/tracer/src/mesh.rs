//! Triangle meshes: Wavefront OBJ files (read by the `tobj` crate),
//! placed by a similarity transform, checked for degenerate faces and
//! non-manifold edges.

use std::collections::HashMap;
use std::path::Path;

use glam::{DQuat, DVec3};
use lambert_geometry::f64::Triangle;

use crate::error::TracerError;

/// A similarity transform p ↦ t + R(s·p): a uniform scale s > 0, a
/// rotation by `rotate_deg` degrees about `rotate_axis` (right-hand rule),
/// then a translation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    scale: f64,
    rotation: DQuat,
    translate: DVec3,
}

impl Default for Transform {
    /// The identity.
    fn default() -> Self {
        Transform {
            scale: 1.0,
            rotation: DQuat::IDENTITY,
            translate: DVec3::ZERO,
        }
    }
}

impl Transform {
    /// The transform; errors name the field (`scale`, `rotate_axis`,
    /// `rotate_deg`, `translate`): every value finite, the scale positive,
    /// the axis non-zero when there is a rotation.
    pub fn new(
        scale: f64,
        rotate_axis: DVec3,
        rotate_deg: f64,
        translate: DVec3,
    ) -> Result<Self, TracerError> {
        lambert_geometry::validate::positive("scale", scale)?;
        lambert_geometry::validate::finite3("rotate_axis", rotate_axis)?;
        lambert_geometry::validate::finite("rotate_deg", rotate_deg)?;
        lambert_geometry::validate::finite3("translate", translate)?;
        let rotation = if rotate_deg == 0.0 {
            DQuat::IDENTITY
        } else {
            let axis = lambert_geometry::f64::unit_vector("rotate_axis", rotate_axis)?;
            DQuat::from_axis_angle(axis, rotate_deg.to_radians())
        };
        Ok(Transform {
            scale,
            rotation,
            translate,
        })
    }

    /// The image of `p`.
    #[inline]
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.translate + self.rotation * (p * self.scale)
    }
}

/// A triangle mesh: its triangles, ready to be a scene's shapes.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// The triangles (front faces by the right-hand rule of each face's
    /// vertex order).
    pub triangles: Vec<Triangle>,
}

impl Mesh {
    /// The mesh of `positions` and triangular `faces` (indices into
    /// `positions`), checked: every index in range, every face of non-zero
    /// area, and every edge shared by at most two faces (a 2-manifold,
    /// possibly with boundary: an edge of three faces has no inside and
    /// outside). Errors are about `field`, and say which face or edge.
    pub fn from_indexed(
        positions: &[DVec3],
        faces: &[[u32; 3]],
        field: &str,
    ) -> Result<Mesh, TracerError> {
        let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(faces.len() * 3 / 2);
        let mut triangles = Vec::with_capacity(faces.len());
        for (f, face) in faces.iter().enumerate() {
            let mut v = [DVec3::ZERO; 3];
            for (slot, &i) in v.iter_mut().zip(face) {
                *slot = *positions.get(i as usize).ok_or_else(|| {
                    TracerError::new(
                        field,
                        format!(
                            "face {f} refers to vertex {i}, but there are {} vertices",
                            positions.len()
                        ),
                    )
                })?;
            }
            let t = Triangle::new(v[0], v[1], v[2]).map_err(|e| {
                TracerError::new(
                    field,
                    format!(
                        "face {f} (vertices {}, {}, {}) is degenerate: {}",
                        face[0],
                        face[1],
                        face[2],
                        e.problem()
                    ),
                )
            })?;
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                let count = edges.entry((a.min(b), a.max(b))).or_insert(0);
                *count += 1;
                if *count > 2 {
                    return Err(TracerError::new(
                        field,
                        format!(
                            "the edge between vertices {} and {} is shared by more than two faces (face {f} is the third): the mesh is not manifold",
                            a.min(b),
                            a.max(b)
                        ),
                    ));
                }
            }
            triangles.push(t);
        }
        if triangles.is_empty() {
            return Err(TracerError::new(field, "has no faces"));
        }
        Ok(Mesh { triangles })
    }

    /// The mesh of a Wavefront OBJ file (every object in it; polygons are
    /// triangulated as fans), each vertex mapped by `transform`. Errors
    /// are about `field` and name the file.
    pub fn load_obj(path: &Path, transform: &Transform, field: &str) -> Result<Mesh, TracerError> {
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: false,
            ..Default::default()
        };
        let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| {
            let why = match e {
                tobj::LoadError::OpenFileFailed => match std::fs::metadata(path) {
                    Err(io) => io.to_string(),
                    Ok(_) => e.to_string(),
                },
                other => other.to_string(),
            };
            TracerError::new(field, format!("cannot read mesh {}: {why}", path.display()))
        })?;
        let mut triangles = Vec::new();
        for model in &models {
            let positions: Vec<DVec3> = model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| transform.apply(DVec3::new(p[0], p[1], p[2])))
                .collect();
            let faces: Vec<[u32; 3]> = model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|f| [f[0], f[1], f[2]])
                .collect();
            let mesh = Mesh::from_indexed(&positions, &faces, field).map_err(|e| {
                TracerError::new(
                    e.field,
                    format!(
                        "{} (object {:?}): {}",
                        path.display(),
                        model.name,
                        e.problem
                    ),
                )
            })?;
            triangles.extend(mesh.triangles);
        }
        if triangles.is_empty() {
            return Err(TracerError::new(
                field,
                format!("{} has no faces", path.display()),
            ));
        }
        Ok(Mesh { triangles })
    }

    /// A procedural test mesh: a height field over [−1, 1]² (y up) of
    /// `n` × `n` quads, two triangles each (2n² triangles), with heights
    /// 0.15 sin(5x) cos(4z) + 0.05 sin(17x + 11z + seed) — a rolling,
    /// rippled terrain for benchmarks (n = 224 gives 100,352 triangles).
    pub fn terrain(n: u32, seed: u32) -> Mesh {
        let n = n.max(1);
        let phase = seed as f64 * 0.618;
        let height = |x: f64, z: f64| {
            0.15 * (5.0 * x).sin() * (4.0 * z).cos() + 0.05 * (17.0 * x + 11.0 * z + phase).sin()
        };
        let at = |i: u32, j: u32| {
            let x = -1.0 + 2.0 * i as f64 / n as f64;
            let z = -1.0 + 2.0 * j as f64 / n as f64;
            DVec3::new(x, height(x, z), z)
        };
        let mut triangles = Vec::with_capacity(2 * (n * n) as usize);
        for j in 0..n {
            for i in 0..n {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                // Counter-clockwise seen from above (+y).
                triangles
                    .push(Triangle::new(a, c, b).expect("a height field has no degenerate quads"));
                triangles
                    .push(Triangle::new(a, d, c).expect("a height field has no degenerate quads"));
            }
        }
        Mesh { triangles }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn manifold_checks_and_degenerate_faces() {
        let p = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(0.0, -1.0, 0.5),
            DVec3::new(2.0, 0.0, 0.0),
        ];
        // A tetrahedron's faces: each edge in two faces.
        let tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        assert_eq!(
            Mesh::from_indexed(&p, &tet, "path")
                .unwrap()
                .triangles
                .len(),
            4
        );
        // A third face on edge (0, 1).
        let fin = [[0, 2, 1], [0, 1, 3], [0, 1, 4]];
        let e = Mesh::from_indexed(&p, &fin, "path").unwrap_err();
        assert!(
            e.problem.contains("not manifold") && e.problem.contains("vertices 0 and 1"),
            "{e}"
        );
        let flat = [[0, 1, 5]];
        let e = Mesh::from_indexed(&p, &flat, "path").unwrap_err();
        assert!(
            e.problem.contains("face 0") && e.problem.contains("degenerate"),
            "{e}"
        );
        let out = [[0, 1, 9]];
        assert!(Mesh::from_indexed(&p, &out, "path")
            .unwrap_err()
            .problem
            .contains("vertex 9"));
    }

    #[test]
    fn transforms_scale_rotate_translate_and_reject_nan() {
        let t = Transform::new(2.0, DVec3::Z, 90.0, DVec3::new(1.0, 0.0, 0.0)).unwrap();
        let p = t.apply(DVec3::X);
        assert!((p - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-15, "{p}");
        let e = Transform::new(1.0, DVec3::Z, 0.0, DVec3::new(f64::NAN, 0.0, 0.0)).unwrap_err();
        assert_eq!(e.field, "translate");
        assert_eq!(
            Transform::new(0.0, DVec3::Z, 0.0, DVec3::ZERO)
                .unwrap_err()
                .field,
            "scale"
        );
        assert_eq!(
            Transform::new(1.0, DVec3::ZERO, 10.0, DVec3::ZERO)
                .unwrap_err()
                .field,
            "rotate_axis"
        );
    }

    #[test]
    fn terrain_has_the_stated_size() {
        assert_eq!(Mesh::terrain(224, 0).triangles.len(), 100_352);
    }
}
