//! The tracer's TOML scene files: every shape kind, meshes by path
//! relative to the file, and errors that name the field with its place.

use std::path::{Path, PathBuf};

use lambert_tracer::scene_file::{load, parse};

/// A directory under the temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("lambert-scene-files-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const CAMERA: &str = r#"
[camera]
position = [0.0, 1.0, 6.0]
look_at = [0.0, 0.5, 0.0]
fov_deg = 40
width = 32
height = 24
"#;

const TETRAHEDRON: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

fn scene(body: &str) -> String {
    format!("background = [0.1, 0.2, 0.3]\n{CAMERA}\n{body}")
}

#[test]
fn every_shape_kind_and_a_mesh() {
    let dir = TempDir::new("every");
    std::fs::create_dir_all(dir.0.join("meshes")).unwrap();
    std::fs::write(dir.0.join("meshes/tet.obj"), TETRAHEDRON).unwrap();
    let text = scene(
        r#"
[[shapes]]
kind = "sphere"
center = [-1.0, 0.5, 0.0]
radius = 0.5
material = { kind = "mirror", specular = [0.5, 0.5, 0.5], shininess = 100 }

[[shapes]]
kind = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = { kind = "diffuse", checker = { even = [0.9, 0.9, 0.1], odd = [0.9, 0.1, 0.1], scale = 1.0 } }

[[shapes]]
kind = "disk"
center = [1.0, 0.01, 1.0]
normal = [0.0, 1.0, 0.0]
radius = 0.3
material = { kind = "dielectric", ior = 1.33 }

[[shapes]]
kind = "triangle"
vertices = [[0.0, 0.0, -1.0], [1.0, 0.0, -1.0], [0.0, 1.0, -1.0]]
material = { kind = "diffuse", albedo = [0.5, 0.5, 0.5] }

[[shapes]]
kind = "parallelogram"
corner = [-2.0, 0.0, -2.0]
edge0 = [1.0, 0.0, 0.0]
edge1 = [0.0, 1.0, 0.0]
material = { kind = "diffuse", albedo = [0.5, 0.5, 0.5] }

[[shapes]]
kind = "polygon"
vertices = [[2.0, 0.0, -2.0], [3.0, 0.0, -2.0], [3.0, 1.0, -2.0], [2.0, 1.0, -2.0]]
material = { kind = "diffuse", albedo = [0.5, 0.5, 0.5] }

[[shapes]]
kind = "mesh"
path = "meshes/tet.obj"
scale = 0.5
rotate_axis = [0.0, 1.0, 0.0]
rotate_deg = 30.0
translate = [0.5, 0.0, 0.5]
material = { kind = "diffuse", albedo = [0.7, 0.7, 0.7] }

[[emitters]]
kind = "point"
position = [2.0, 5.0, 4.0]
intensity = 60.0

[[emitters]]
kind = "disk"
center = [0.0, 3.0, 0.0]
normal = [0.0, -1.0, 0.0]
radius = 0.5
radiance = 4.0
"#,
    );
    let path = dir.0.join("scene.toml");
    std::fs::write(&path, &text).unwrap();
    let s = load(&path).unwrap();
    // 6 shapes, 4 mesh triangles, the disk emitter's own disk.
    assert_eq!(s.aggregate().len(), 6 + 4 + 1);
    assert_eq!(s.emitters().len(), 2);
    assert_eq!((s.camera().width(), s.camera().height()), (32, 24));
}

fn error(body: &str, base: &Path) -> String {
    parse(&scene(body), base).unwrap_err().to_string()
}

#[test]
fn errors_name_the_field_and_its_place() {
    let dir = TempDir::new("errors");
    let base = dir.0.as_path();
    std::fs::write(dir.0.join("tet.obj"), TETRAHEDRON).unwrap();
    std::fs::write(
        dir.0.join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        dir.0.join("fin.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 1 2 5\n",
    )
    .unwrap();
    let sphere = |extra: &str| {
        format!("[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = {{ kind = \"diffuse\", albedo = [0.5, 0.5, 0.5] }}\n{extra}")
    };
    let mesh = |path: &str, extra: &str| {
        format!("[[shapes]]\nkind = \"mesh\"\npath = \"{path}\"\n{extra}\nmaterial = {{ kind = \"diffuse\", albedo = [0.5, 0.5, 0.5] }}\n")
    };
    let cases: Vec<(String, &str)> = vec![
        (sphere("colour = 3"), "unknown field `colour`"),
        (
            "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.0\nmaterial = { kind = \"mirror\" }\n".into(),
            "shapes[0].radius: must be positive, got 0",
        ),
        (
            "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nnormal = [0.0, 1.0, 0.0]\nmaterial = { kind = \"mirror\" }\n".into(),
            "shapes[0].normal: is not a field of a sphere shape",
        ),
        (
            "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = { kind = \"diffuse\", albedo = [1.5, 0.5, 0.5] }\n".into(),
            "shapes[0].material.albedo: every channel must lie in [0, 1]",
        ),
        (
            "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n".into(),
            "shapes[0].material: is required for a sphere shape",
        ),
        (
            "[[shapes]]\nkind = \"cube\"\nmaterial = { kind = \"mirror\" }\n".into(),
            "shapes[0].kind: unknown shape kind \"cube\"",
        ),
        (mesh("missing.obj", ""), "shapes[0].path: cannot read mesh"),
        (mesh("flat.obj", ""), "shapes[0].path: "),
        (mesh("fin.obj", ""), "not manifold"),
        (mesh("tet.obj", "translate = [nan, 0.0, 0.0]"), "shapes[0].translate: must be finite"),
        (mesh("tet.obj", "scale = -1.0"), "shapes[0].scale: must be positive"),
        (
            "[[emitters]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = -1.0\nradiance = 1.0\n".into(),
            "emitters[0].radius: must be positive",
        ),
    ];
    for (body, expected) in cases {
        let e = error(&body, base);
        assert!(e.contains(expected), "expected {expected:?} in {e:?}");
    }
    let flat = error(&mesh("flat.obj", ""), base);
    assert!(
        flat.contains("face 0") && flat.contains("degenerate"),
        "{flat}"
    );
    // The camera inside a sphere, NaN in the camera, a zero-size image.
    let inside = format!(
        "{}\n[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 1.0, 6.0]\nradius = 2.0\nmaterial = {{ kind = \"mirror\" }}\n",
        CAMERA
    );
    let e = parse(&inside, base).unwrap_err();
    assert_eq!(e.field, "camera.position");
    assert!(e.problem.contains("inside the sphere"), "{e}");
    let e = parse(&CAMERA.replace("fov_deg = 40", "fov_deg = nan"), base).unwrap_err();
    assert_eq!(e.to_string(), "camera.fov_deg: must be finite, got NaN");
    let e = parse(&CAMERA.replace("width = 32", "width = 0"), base).unwrap_err();
    assert_eq!(e.field, "camera.width");
}
