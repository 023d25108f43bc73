//! `lambert render`: the JSON summary, both built-in scenes in every mode,
//! and bad input — a clear message naming the field, exit code 2, and no
//! EXR or PNG left behind.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn lambert(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lambert"))
        .args(args)
        .output()
        .expect("the lambert binary runs")
}

/// A directory under the temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "lambert-render-command-{name}-{}",
            std::process::id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn file(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Every file in the directory.
    fn files(&self) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
            .collect();
        v.sort();
        v
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn path(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 temp path")
}

#[test]
fn json_summary_and_files() {
    let dir = TempDir::new("json");
    let out = dir.file("c.exr");
    let o = lambert(&[
        "render",
        "cornell",
        "--mode",
        "irradiance",
        "--width",
        "24",
        "--height",
        "20",
        "--spp",
        "32",
        "--strategy",
        "light",
        "--sequence",
        "sobol",
        "--threads",
        "2",
        "--out",
        path(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    for key in [
        "seconds",
        "rays",
        "rays_per_second",
        "mean_relative_std_error",
        "camera_rays",
        "shadow_rays",
    ] {
        assert!(v[key].as_f64().is_some(), "{key} in {v}");
    }
    assert_eq!(v["camera_rays"].as_u64(), Some(24 * 20));
    assert!(v["mean_relative_std_error"].as_f64().unwrap() > 0.0);
    assert_eq!(dir.files(), ["c.exr", "c.png"]);
    // The other modes, and the closed form.
    for args in [
        &["--mode", "raycast"][..],
        &["--mode", "whitted", "--depth", "3"],
        &["--mode", "irradiance", "--analytic"],
    ] {
        let w = dir.file("w.exr");
        let mut all = vec![
            "render",
            "whitted",
            "--width",
            "16",
            "--height",
            "12",
            "--out",
            path(&w),
            "--json",
        ];
        all.extend_from_slice(args);
        let o = lambert(&all);
        assert!(
            o.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

/// The irradiance mode accepts the projected and control-variate
/// strategies (the Cornell box's light is a polygon, partly hidden by its
/// blocks from much of the floor: projected sampling with visibility, and
/// the closed form minus the hidden part).
#[test]
fn irradiance_mode_takes_projected_and_control_variate() {
    let dir = TempDir::new("strategies");
    for strategy in ["projected", "control-variate"] {
        let out = dir.file(&format!("{strategy}.exr"));
        let o = lambert(&[
            "render",
            "cornell",
            "--mode",
            "irradiance",
            "--width",
            "16",
            "--height",
            "12",
            "--spp",
            "32",
            "--strategy",
            strategy,
            "--out",
            path(&out),
            "--json",
        ]);
        assert!(
            o.status.success(),
            "{strategy}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let v: Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
        let e = v["mean_relative_std_error"].as_f64().unwrap();
        assert!(e.is_finite() && e >= 0.0, "{strategy}: {v}");
    }
}

/// Runs a render expected to fail: exit code 2, the message on stderr
/// containing `expected`, nothing on stdout, and no file written.
fn fails(dir: &TempDir, args: &[&str], expected: &str) {
    let out = dir.file("bad.exr");
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", path(&out)]);
    let o = lambert(&all);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(
        stderr.contains(expected),
        "{args:?}: expected {expected:?} in {stderr}"
    );
    assert!(o.stdout.is_empty(), "{args:?}");
    let left: Vec<String> = dir
        .files()
        .into_iter()
        .filter(|f| f.starts_with("bad"))
        .collect();
    assert!(left.is_empty(), "{args:?} left {left:?}");
}

#[test]
fn bad_input_exits_2_naming_the_field_and_writes_nothing() {
    let dir = TempDir::new("bad");
    let camera = "[camera]\nposition = [0.0, 1.0, 6.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 40\nwidth = 8\nheight = 8\n";
    let scene = |name: &str, body: &str| {
        let p = dir.file(name);
        std::fs::write(&p, format!("{camera}\n{body}")).unwrap();
        p
    };
    std::fs::write(dir.file("flat.obj"), "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n").unwrap();
    std::fs::write(
        dir.file("fin.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 0 -1 0\nf 1 2 3\nf 1 2 4\nf 1 2 5\n",
    )
    .unwrap();
    std::fs::write(
        dir.file("tet.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n",
    )
    .unwrap();
    let mesh = |p: &str, extra: &str| {
        format!("[[shapes]]\nkind = \"mesh\"\npath = \"{p}\"\n{extra}\nmaterial = {{ kind = \"diffuse\", albedo = [0.5, 0.5, 0.5] }}\n")
    };
    let inside = scene(
        "inside.toml",
        "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 1.0, 5.5]\nradius = 1.0\nmaterial = { kind = \"mirror\" }\n",
    );
    let missing = scene("missing.toml", &mesh("nowhere.obj", ""));
    let flat = scene("flat.toml", &mesh("flat.obj", ""));
    let fin = scene("fin.toml", &mesh("fin.obj", ""));
    let nan = scene("nan.toml", &mesh("tet.obj", "translate = [0.0, nan, 0.0]"));
    let unknown = scene("unknown.toml", "[[shapes]]\nkind = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nradius2 = 3.0\nmaterial = { kind = \"mirror\" }\n");
    fails(&dir, &[path(&inside)], "camera.position");
    fails(
        &dir,
        &[path(&missing), "--mode", "raycast"],
        "shapes[0].path: cannot read mesh",
    );
    fails(&dir, &[path(&flat)], "shapes[0].path:");
    fails(&dir, &[path(&flat)], "degenerate");
    fails(&dir, &[path(&fin)], "not manifold");
    fails(&dir, &[path(&nan)], "shapes[0].translate: must be finite");
    fails(&dir, &[path(&unknown)], "radius2");
    fails(&dir, &["whitted", "--width", "0"], "--width: must be 1");
    fails(
        &dir,
        &["whitted", "--mode", "pathtrace"],
        "--mode: unknown mode",
    );
    fails(
        &dir,
        &[
            "cornell",
            "--mode",
            "irradiance",
            "--sequence",
            "sobol",
            "--spp",
            "8",
        ],
        "--spp",
    );
    fails(&dir, &["cornell", "--strategy", "best"], "--strategy");
    fails(&dir, &["no-such-scene"], "neither a built-in scene");
    fails(&dir, &["whitted", "--analytic"], "--analytic");
    // The equal-time comparison (--compare).
    let irr = [
        "cornell",
        "--mode",
        "irradiance",
        "--width",
        "4",
        "--height",
        "4",
    ];
    let with = |extra: &[&'static str]| -> Vec<&'static str> {
        irr.iter().chain(extra).copied().collect()
    };
    fails(
        &dir,
        &with(&["--compare", "light,best"]),
        "--compare: unknown strategy \"best\"",
    );
    fails(
        &dir,
        &with(&["--compare", "light", "--seconds", "0"]),
        "--seconds: must be a positive",
    );
    fails(
        &dir,
        &with(&["--compare", "light", "--seconds=-2"]),
        "--seconds: must be a positive",
    );
    fails(
        &dir,
        &with(&["--seconds", "2"]),
        "--seconds: only with --compare",
    );
    fails(
        &dir,
        &with(&["--compare", "light", "--reference-spp", "1"]),
        "--reference-spp",
    );
    fails(
        &dir,
        &with(&["--compare", "light", "--reference-strategy", "best"]),
        "--reference-strategy",
    );
    fails(
        &dir,
        &["cornell", "--mode", "whitted", "--compare", "light"],
        "--compare: compares irradiance strategies, so it needs --mode irradiance, got whitted",
    );
}

/// `--compare` at equal samples on a tiny image: the table's rows, the
/// JSON's keys, and an EXR per strategy and one for the reference.
#[test]
fn compare_writes_every_image_and_a_ratio() {
    let dir = TempDir::new("compare");
    let out = dir.file("cmp.exr");
    let o = lambert(&[
        "render",
        "cornell",
        "--mode",
        "irradiance",
        "--width",
        "8",
        "--height",
        "8",
        "--compare",
        "light,control-variate",
        "--spp",
        "4",
        "--reference-spp",
        "16",
        "--json",
        "--out",
        path(&out),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["budget"]["spp"].as_u64(), Some(4));
    assert_eq!(v["reference"]["spp"].as_u64(), Some(16));
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[0]["rmse_ratio"].as_f64(), Some(1.0));
    assert!(runs[1]["rmse"].as_f64().unwrap() > 0.0);
    for f in [
        "cmp.reference.exr",
        "cmp.light.exr",
        "cmp.control-variate.exr",
    ] {
        assert!(
            dir.files().contains(&f.to_owned()),
            "{f}: {:?}",
            dir.files()
        );
    }
}

#[test]
fn help_describes_the_command() {
    let o = lambert(&["render", "--help"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "--mode",
        "raycast",
        "irradiance",
        "--spp",
        "--analytic",
        "irradiance.Y",
        "std_error.Y",
    ] {
        assert!(text.contains(needle), "{needle} missing from --help");
    }
}
