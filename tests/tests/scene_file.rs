//! The TOML scene format: every emitter kind parses, every malformed input
//! is an error naming the field and the problem, and nothing panics
//! (deterministic property tests over arbitrary and structured input).

use std::f64::consts::PI;

use glam::DVec3;
use lambert_estimator::estimation::{estimate, EstimateConfig, EstimateError, SequenceKind};
use lambert_estimator::strategy::Strategy as Sampling;
use lambert_light::{Emitter, Scene};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngAlgorithm, RngSeed};

const RECEIVER: &str = "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n";

/// A scene of the default receiver and one emitter given by its body.
fn one(body: &str) -> String {
    format!("{RECEIVER}\n[[emitters]]\n{body}\n")
}

fn parse_one(body: &str) -> Emitter {
    let scene = Scene::from_toml(&one(body)).unwrap_or_else(|e| panic!("{body}: {e}"));
    assert_eq!(scene.emitters.len(), 1);
    scene.emitters.into_iter().next().unwrap()
}

/// The error message of a scene that must not parse, checked to contain
/// every one of `needles`.
fn error_of(text: &str, needles: &[&str]) -> String {
    let message = match Scene::from_toml(text) {
        Ok(s) => panic!("expected an error, parsed {s:?} from\n{text}"),
        Err(e) => e.message,
    };
    for n in needles {
        assert!(
            message.contains(n),
            "message {message:?} should contain {n:?} (input:\n{text})"
        );
    }
    message
}

// ---------------------------------------------------------------- kinds

#[test]
fn sky_parses() {
    let Emitter::Sky(s) = parse_one("kind = \"sky\"\nradiance = 2.5") else {
        panic!("not a sky")
    };
    assert_eq!(s.radiance, 2.5);
}

#[test]
fn sky_cap_parses_in_radians_and_degrees() {
    let Emitter::SkyCap(c) =
        parse_one("kind = \"sky_cap\"\naxis = [0.0, 0.0, 2.0]\nhalf_angle = 0.5\nradiance = 3.0")
    else {
        panic!("not a sky cap")
    };
    assert_eq!(c.axis, DVec3::Z, "the axis is normalised");
    assert_eq!(c.half_angle, 0.5);
    assert_eq!(c.radiance, 3.0);

    let Emitter::SkyCap(c) = parse_one(
        "kind = \"sky_cap\"\naxis = [0.0, 1.0, 0.0]\nhalf_angle_deg = 30.0\nradiance = 1.0",
    ) else {
        panic!("not a sky cap")
    };
    assert_eq!(c.half_angle, 30f64.to_radians());
    assert_eq!(c.axis, DVec3::Y);

    // The whole sphere of directions, both ways: π is inside (0, π].
    for body in [
        "kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle_deg = 180.0\nradiance = 1.0",
        "kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle = 3.141592653589793\nradiance = 1.0",
    ] {
        let Emitter::SkyCap(c) = parse_one(body) else {
            panic!("not a sky cap")
        };
        assert!(c.half_angle == PI);
    }
}

#[test]
fn sphere_parses() {
    let Emitter::Sphere(s) =
        parse_one("kind = \"sphere\"\ncenter = [0.0, 5.0, 8.66]\nradius = 1.0\nradiance = 1.0")
    else {
        panic!("not a sphere")
    };
    assert_eq!(s.sphere.center(), DVec3::new(0.0, 5.0, 8.66));
    assert_eq!((s.sphere.radius(), s.radiance), (1.0, 1.0));
}

#[test]
fn disk_parses_one_and_two_sided() {
    let body = "kind = \"disk\"\ncenter = [0.0, 0.0, 3.0]\nnormal = [0.0, 0.0, -4.0]\nradius = 0.5\nradiance = 2.0";
    let Emitter::Disk(d) = parse_one(body) else {
        panic!("not a disk")
    };
    assert_eq!(d.disk.normal(), -DVec3::Z, "the normal is normalised");
    assert_eq!((d.disk.radius(), d.radiance), (0.5, 2.0));
    assert!(!d.two_sided, "one-sided by default");

    let Emitter::Disk(d) = parse_one(&format!("{body}\ntwo_sided = true")) else {
        panic!("not a disk")
    };
    assert!(d.two_sided);
    let Emitter::Disk(d) = parse_one(&format!("{body}\ntwo_sided = false")) else {
        panic!("not a disk")
    };
    assert!(!d.two_sided);
}

#[test]
fn polygons_parse_triangle_rectangle_pentagon() {
    let triangle = "kind = \"polygon\"\nvertices = [[-1.0, -1.0, 3.0], [-1.0, 1.0, 3.0], [1.0, 0.0, 3.0]]\nradiance = 1.0";
    let rectangle = "kind = \"polygon\"\nvertices = [[-0.5, -0.3, 2.0], [-0.5, 0.5, 2.0], [0.5, 0.5, 2.0], [0.5, -0.3, 2.0]]\nradiance = 4.0\ntwo_sided = true";
    let pentagon_vertices: Vec<String> = (0..5)
        .map(|k| {
            // Clockwise seen from the receiver below: the front faces down.
            let a = -2.0 * PI * f64::from(k) / 5.0;
            format!("[{:?}, {:?}, 2.0]", a.cos(), a.sin())
        })
        .collect();
    let pentagon = format!(
        "kind = \"polygon\"\nvertices = [{}]\nradiance = 1.5",
        pentagon_vertices.join(", ")
    );
    for (body, n, sides, area) in [
        (triangle, 3, false, 2.0),
        (rectangle, 4, true, 0.8),
        (pentagon.as_str(), 5, false, 2.5 * (2.0 * PI / 5.0).sin()),
    ] {
        let Emitter::Polygon(p) = parse_one(body) else {
            panic!("not a polygon")
        };
        assert_eq!(p.polygon.vertices().len(), n);
        assert_eq!(p.two_sided, sides);
        assert!(
            (p.polygon.normal() - (-DVec3::Z)).length() < 1e-15,
            "{body}"
        );
        assert!((p.polygon.area() - area).abs() < 1e-12 * area, "{body}");
    }
}

#[test]
fn point_parses_with_intensity_and_with_flux() {
    let Emitter::Point(p) =
        parse_one("kind = \"point\"\nposition = [1.0, 2.0, 3.0]\nintensity = 60.0")
    else {
        panic!("not a point")
    };
    assert_eq!(p.position, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(p.intensity, 60.0);

    // An 815 lm (60 W-equivalent) bulb: I = Φ/4π.
    let Emitter::Point(p) = parse_one("kind = \"point\"\nposition = [0.0, 0.0, 2.0]\nflux = 815.0")
    else {
        panic!("not a point")
    };
    assert_eq!(p.intensity, 815.0 / (4.0 * PI));
}

#[test]
fn directional_parses() {
    let Emitter::Directional(d) =
        parse_one("kind = \"directional\"\ndirection = [0.0, 3.0, 4.0]\nirradiance = 1000.0")
    else {
        panic!("not directional")
    };
    assert!((d.direction - DVec3::new(0.0, 0.6, 0.8)).length() < 1e-15);
    assert_eq!(d.irradiance, 1000.0);
}

#[test]
fn several_emitters_keep_file_order() {
    let text = format!(
        "{RECEIVER}\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n\n[[emitters]]\nkind = \"point\"\nposition = [0.0, 0.0, 2.0]\nintensity = 1.0\n"
    );
    let scene = Scene::from_toml(&text).unwrap();
    let kinds: Vec<_> = scene.emitters.iter().map(Emitter::kind).collect();
    assert_eq!(kinds, ["sky", "point"]);
}

// ---------------------------------------------------------------- errors

const SPHERE: &str = "kind = \"sphere\"\ncenter = [0.0, 0.0, 5.0]\nradiance = 1.0";

#[test]
fn unknown_keys_are_named() {
    error_of(
        &format!("colour = 1\n{}", one("kind = \"sky\"\nradiance = 1.0")),
        &["colour", "unknown field", "line 1"],
    );
    error_of(
        &format!("{RECEIVER}up = [0.0, 0.0, 1.0]\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n"),
        &["up", "unknown field", "line 4"],
    );
    error_of(
        &one("kind = \"sky\"\nradiance = 1.0\ncolour = 2"),
        &["colour", "unknown field", "line 8"],
    );
}

#[test]
fn keys_of_another_kind_are_named() {
    error_of(
        &one("kind = \"sky\"\nradiance = 1.0\nradius = 2.0"),
        &["emitters[0].radius", "is not a field of a sky emitter"],
    );
    error_of(
        &one(&format!("{SPHERE}\nradius = 1.0\ntwo_sided = true")),
        &["emitters[0].two_sided", "sphere"],
    );
    error_of(
        &one("kind = \"point\"\nposition = [0.0, 0.0, 1.0]\nintensity = 1.0\nradiance = 1.0"),
        &["emitters[0].radiance", "point"],
    );
}

#[test]
fn wrong_types_are_named() {
    // serde's messages point at the offending line, which shows the key.
    error_of(
        &one(&format!("{SPHERE}\nradius = \"1\"")),
        &[
            "radius = \"1\"",
            "invalid type: string",
            "expected f64",
            "line 9",
        ],
    );
    error_of(
        &one("kind = \"sphere\"\ncenter = [0.0, 5.0]\nradius = 1.0\nradiance = 1.0"),
        &["center = [0.0, 5.0]", "invalid length 2", "line 7"],
    );
    error_of(
        "[receiver]\npoint = [0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n",
        &["point = [0.0, 0.0]", "invalid length 2", "line 2"],
    );
    error_of(
        &one("kind = \"disk\"\ncenter = [0.0, 0.0, 3.0]\nnormal = [0.0, 0.0, -1.0]\nradius = 1.0\nradiance = 1.0\ntwo_sided = 1"),
        &["two_sided = 1", "invalid type", "line 11"],
    );
    error_of(
        &one("kind = 3\nradiance = 1.0"),
        &["kind = 3", "invalid type", "expected a string"],
    );
}

#[test]
fn zero_normals_are_named() {
    error_of(
        "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 0.0]\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n",
        &["receiver.normal", "non-zero"],
    );
    error_of(
        &one("kind = \"disk\"\ncenter = [0.0, 0.0, 3.0]\nnormal = [0.0, 0.0, 0.0]\nradius = 1.0\nradiance = 1.0"),
        &["emitters[0].normal", "non-zero"],
    );
    error_of(
        &one("kind = \"directional\"\ndirection = [0.0, 0.0, 0.0]\nirradiance = 1.0"),
        &["emitters[0].direction", "non-zero"],
    );
    error_of(
        &one("kind = \"sky_cap\"\naxis = [0.0, 0.0, 0.0]\nhalf_angle = 1.0\nradiance = 1.0"),
        &["emitters[0].axis", "non-zero"],
    );
}

#[test]
fn non_positive_radii_are_named() {
    for r in ["-1.0", "0.0", "-0.0"] {
        error_of(
            &one(&format!("{SPHERE}\nradius = {r}")),
            &["emitters[0].radius", "must be positive"],
        );
        error_of(
            &one(&format!("kind = \"disk\"\ncenter = [0.0, 0.0, 3.0]\nnormal = [0.0, 0.0, -1.0]\nradius = {r}\nradiance = 1.0")),
            &["emitters[0].radius", "must be positive"],
        );
    }
}

#[test]
fn negative_radiance_and_intensity_are_named() {
    error_of(
        &one("kind = \"sky\"\nradiance = -1.0"),
        &["emitters[0].radiance", "must not be negative"],
    );
    error_of(
        &one("kind = \"point\"\nposition = [0.0, 0.0, 1.0]\nflux = -1.0"),
        &["emitters[0].flux", "must not be negative"],
    );
}

#[test]
fn nan_and_infinities_are_named() {
    error_of(
        &one("kind = \"sphere\"\ncenter = [0.0, nan, 5.0]\nradius = 1.0\nradiance = 1.0"),
        &["emitters[0].center", "must be finite", "NaN"],
    );
    error_of(
        &one("kind = \"sky\"\nradiance = nan"),
        &["emitters[0].radiance", "must be finite", "NaN"],
    );
    error_of(
        &one("kind = \"sky\"\nradiance = inf"),
        &["emitters[0].radiance", "must be finite", "inf"],
    );
    error_of(
        &one(&format!("{SPHERE}\nradius = +inf")),
        &["emitters[0].radius", "must be finite", "inf"],
    );
    error_of(
        &one("kind = \"point\"\nposition = [0.0, -inf, 1.0]\nintensity = 1.0"),
        &["emitters[0].position", "must be finite"],
    );
    error_of(
        "[receiver]\npoint = [0.0, 0.0, nan]\nnormal = [0.0, 0.0, 1.0]\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n",
        &["receiver.point", "must be finite"],
    );
    error_of(
        &one("kind = \"polygon\"\nvertices = [[0.0, 0.0, 1.0], [1.0, nan, 1.0], [0.0, 1.0, 1.0]]\nradiance = 1.0"),
        &["emitters[0].vertices", "vertex 1 must be finite"],
    );
    error_of(
        &one("kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle_deg = nan\nradiance = 1.0"),
        &["emitters[0].half_angle_deg", "must be finite"],
    );
    error_of(
        &one("kind = \"directional\"\ndirection = [0.0, 0.0, 1.0]\nirradiance = -inf"),
        &["emitters[0].irradiance", "must be finite"],
    );
}

#[test]
fn bad_polygons_are_named() {
    error_of(
        &one("kind = \"polygon\"\nvertices = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.5], [0.0, 1.0, 1.0]]\nradiance = 1.0"),
        &["emitters[0].vertices", "not planar", "vertex"],
    );
    error_of(
        &one("kind = \"polygon\"\nvertices = [[0.0, 0.0, 1.0], [2.0, 0.0, 1.0], [1.0, 0.3, 1.0], [1.0, 2.0, 1.0]]\nradiance = 1.0"),
        &["emitters[0].vertices", "not strictly convex"],
    );
    error_of(
        &one("kind = \"polygon\"\nvertices = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0]]\nradiance = 1.0"),
        &["emitters[0].vertices", "at least 3 vertices, got 2"],
    );
    error_of(
        &one("kind = \"polygon\"\nvertices = []\nradiance = 1.0"),
        &["emitters[0].vertices", "at least 3 vertices, got 0"],
    );
    error_of(
        &one("kind = \"polygon\"\nvertices = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [2.0, 0.0, 1.0]]\nradiance = 1.0"),
        &["emitters[0].vertices", "zero area"],
    );
    // 65 vertices: more than the polygon light sampler clips in its fixed
    // buffer.
    let ring: Vec<String> = (0..65)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 65.0;
            format!("[{:?}, {:?}, 1.0]", a.cos(), a.sin())
        })
        .collect();
    error_of(
        &one(&format!(
            "kind = \"polygon\"\nvertices = [{}]\nradiance = 1.0",
            ring.join(", ")
        )),
        &["emitters[0].vertices", "at most 64 vertices", "got 65"],
    );
}

/// Found by the fuzzer: an overflowing area once gave a NaN normal that
/// slipped past the planarity and convexity checks. Polygons are now
/// validated in coordinates divided by a power of two, so this huge
/// triangle gets its exact normal, ±y, whatever its (overflowing) area.
#[test]
fn huge_polygons_get_their_exact_normal() {
    let scene = Scene::from_toml(&one(
        "kind = \"polygon\"\nvertices = [[0.0, 0.0, 1e154], [1e200, 0.0, 0.0], [0.0, 0.0, 0.0]]\nradiance = 1.0",
    ))
    .unwrap();
    let Emitter::Polygon(p) = &scene.emitters[0] else {
        unreachable!()
    };
    assert_eq!(p.polygon.normal().abs(), DVec3::Y);
    assert_eq!(p.polygon.area(), f64::INFINITY);
}

#[test]
fn huge_and_tiny_normals_are_normalised_exactly() {
    for (n, expected) in [
        ("[1e300, 1e300, 0.0]", DVec3::new(1.0, 1.0, 0.0).normalize()),
        ("[0.0, 1e-160, 0.0]", DVec3::Y),
        ("[0.0, 0.0, 5e-324]", DVec3::Z),
    ] {
        let text = format!(
            "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = {n}\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n"
        );
        let scene = Scene::from_toml(&text).unwrap_or_else(|e| panic!("{n}: {e}"));
        assert!((scene.receiver.normal - expected).length() < 1e-15, "{n}");
    }
}

#[test]
fn a_receiver_inside_or_on_a_sphere_light_is_named() {
    for radius in ["6.0", "5.0"] {
        error_of(
            &one(&format!("{SPHERE}\nradius = {radius}")),
            &[
                "receiver.point",
                "inside or on the sphere light",
                "emitters[0]",
            ],
        );
    }
    // The second emitter is the culprit.
    let text = format!(
        "{}\n[[emitters]]\n{SPHERE}\nradius = 5.5\n",
        one("kind = \"sky\"\nradiance = 1.0")
    );
    error_of(&text, &["receiver.point", "emitters[1]"]);
}

#[test]
fn unknown_kind_and_missing_fields_are_named() {
    error_of(
        &one("kind = \"spotlight\"\nradiance = 1.0"),
        &["emitters[0].kind", "unknown emitter kind \"spotlight\""],
    );
    error_of(&one("radiance = 1.0"), &["missing field `kind`"]);
    error_of(
        &one(SPHERE),
        &["emitters[0].radius", "is required for a sphere emitter"],
    );
    error_of(
        &one("kind = \"sky\""),
        &["emitters[0].radiance", "is required"],
    );
    error_of(
        &one("kind = \"polygon\"\nradiance = 1.0"),
        &["emitters[0].vertices", "is required"],
    );
    error_of(
        &one("kind = \"point\"\nposition = [0.0, 0.0, 1.0]"),
        &["emitters[0].intensity", "is required", "flux"],
    );
    error_of(
        &one("kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nradiance = 1.0"),
        &["emitters[0].half_angle", "is required", "half_angle_deg"],
    );
    error_of(
        "[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n",
        &["missing field `receiver`"],
    );
    error_of(
        "[receiver]\npoint = [0.0, 0.0, 0.0]\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0\n",
        &["missing field `normal`"],
    );
}

#[test]
fn alternatives_given_twice_are_named() {
    error_of(
        &one("kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle = 1.0\nhalf_angle_deg = 57.0\nradiance = 1.0"),
        &["emitters[0].half_angle", "not both"],
    );
    error_of(
        &one("kind = \"point\"\nposition = [0.0, 0.0, 1.0]\nintensity = 1.0\nflux = 1.0"),
        &["emitters[0].intensity", "not both"],
    );
}

#[test]
fn half_angles_out_of_range_are_named() {
    for a in ["0.0", "-0.5", "3.1416", "7.0"] {
        error_of(
            &one(&format!(
                "kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle = {a}\nradiance = 1.0"
            )),
            &["emitters[0].half_angle", "must lie in (0, π]"],
        );
    }
    for d in ["0.0", "-10.0", "180.001", "200.0"] {
        error_of(
            &one(&format!(
                "kind = \"sky_cap\"\naxis = [0.0, 0.0, 1.0]\nhalf_angle_deg = {d}\nradiance = 1.0"
            )),
            &["emitters[0].half_angle_deg", "must lie in (0, 180]"],
        );
    }
}

#[test]
fn a_scene_needs_emitters() {
    error_of(
        &format!("emitters = []\n{RECEIVER}"),
        &["emitters", "at least one"],
    );
    error_of(RECEIVER, &["emitters", "at least one"]);
}

#[test]
fn syntax_errors_give_the_line() {
    error_of(
        &format!("{RECEIVER}\n[[emitters]]\nkind = \"sky\"\nradiance = 1.0 2.0\n"),
        &["line 7"],
    );
    error_of(
        &format!("{RECEIVER}\n[[emitters]\nkind = \"sky\"\n"),
        &["line 5"],
    );
    error_of("[receiver\n", &["line 1"]);
}

#[test]
fn load_names_a_missing_file() {
    let path = std::env::temp_dir().join(format!(
        "lambert-scene-file-missing-{}.toml",
        std::process::id()
    ));
    let e = Scene::load(&path).unwrap_err();
    assert!(e.message.contains("cannot read"), "{e}");
    assert!(e.message.contains(&path.display().to_string()), "{e}");
}

#[test]
fn load_reads_a_file() {
    let path = std::env::temp_dir().join(format!(
        "lambert-scene-file-load-{}.toml",
        std::process::id()
    ));
    std::fs::write(&path, one("kind = \"sky\"\nradiance = 1.0")).unwrap();
    let scene = Scene::load(&path);
    std::fs::remove_file(&path).unwrap();
    assert_eq!(scene.unwrap().emitters.len(), 1);
}

// ---------------------------------------------------------------- fuzzing

/// Deterministic: a fixed ChaCha seed, no persistence files.
fn fuzz_config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(0x5ce9_ef11),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A number as TOML spells it.
fn toml_number(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x:?}")
    }
}

/// Mostly sensible numbers, with extremes and arbitrary bit patterns.
fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -10.0..10.0f64,
        8 => 0.01..5.0f64,
        1 => prop::sample::select(vec![
            0.0, -0.0, 1.0, -1.0, PI, 180.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY,
            f64::MAX, f64::MIN, f64::MIN_POSITIVE, 5e-324, 1e-300, 1e-160, -1e-200, 1e154,
            1e200, 1e300, -1e300, 1e-9, 1e9,
        ]),
        1 => any::<f64>(),
    ]
}

fn vector() -> impl Strategy<Value = Vec<f64>> {
    prop_oneof![
        8 => prop::collection::vec(number(), 3),
        1 => prop::collection::vec(number(), 0..5),
    ]
}

/// A field's value in TOML: usually of the right type, sometimes not.
fn value_for(field: &'static str) -> BoxedStrategy<String> {
    let vec_text = |v: Vec<f64>| {
        format!(
            "[{}]",
            v.into_iter()
                .map(toml_number)
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let right: BoxedStrategy<String> = match field {
        "two_sided" => any::<bool>().prop_map(|b| b.to_string()).boxed(),
        "center" | "normal" | "axis" | "position" | "direction" => {
            vector().prop_map(vec_text).boxed()
        }
        "vertices" => prop_oneof![
            // A regular n-gon in a random plane: often valid.
            (vector(), vector(), number(), 3usize..7, any::<bool>()).prop_map(
                move |(c, n, r, k, flip)| {
                    let c = DVec3::new(
                        c.first().copied().unwrap_or(0.0),
                        c.get(1).copied().unwrap_or(0.0),
                        c.get(2).copied().unwrap_or(3.0),
                    );
                    let n = DVec3::new(
                        n.first().copied().unwrap_or(0.0),
                        n.get(1).copied().unwrap_or(0.0),
                        n.get(2).copied().unwrap_or(1.0),
                    );
                    let n = n.try_normalize().unwrap_or(DVec3::Z);
                    let (a, b) = n.any_orthonormal_pair();
                    let sign = if flip { -1.0 } else { 1.0 };
                    let vs: Vec<String> = (0..k)
                        .map(|i| {
                            let t = sign * 2.0 * PI * i as f64 / k as f64;
                            let v = c + r * (t.cos() * a + t.sin() * b);
                            format!(
                                "[{}, {}, {}]",
                                toml_number(v.x),
                                toml_number(v.y),
                                toml_number(v.z)
                            )
                        })
                        .collect();
                    format!("[{}]", vs.join(", "))
                }
            ),
            prop::collection::vec(vector().prop_map(vec_text), 0..6)
                .prop_map(|vs| format!("[{}]", vs.join(", "))),
        ]
        .boxed(),
        _ => number().prop_map(toml_number).boxed(),
    };
    prop_oneof![
        30 => right,
        1 => prop::sample::select(vec![
            "\"1.0\"".to_string(), "true".into(), "[]".into(), "{ x = 1 }".into(), "1".into(),
            "[1.0, 2.0, 3.0]".into(), "7".into(),
        ]),
    ]
    .boxed()
}

const KINDS: [&str; 8] = [
    "sky",
    "sky_cap",
    "sphere",
    "disk",
    "polygon",
    "point",
    "directional",
    "laser",
];

const FIELDS: [&str; 15] = [
    "radiance",
    "center",
    "radius",
    "normal",
    "two_sided",
    "vertices",
    "axis",
    "half_angle",
    "half_angle_deg",
    "position",
    "intensity",
    "flux",
    "direction",
    "irradiance",
    "colour",
];

fn fields_of(kind: &str) -> &'static [&'static str] {
    match kind {
        "sky" => &["radiance"],
        "sky_cap" => &["axis", "half_angle", "radiance"],
        "sphere" => &["center", "radius", "radiance"],
        "disk" => &["center", "normal", "radius", "radiance", "two_sided"],
        "polygon" => &["vertices", "radiance", "two_sided"],
        "point" => &["position", "intensity"],
        "directional" => &["direction", "irradiance"],
        _ => &["radiance"],
    }
}

/// One `[[emitters]]` table: a kind, its fields (each present with
/// probability 0.97, sometimes swapped for an alternative) and rare extra
/// keys, possibly of another kind.
fn emitter_table() -> impl Strategy<Value = String> {
    (
        prop_oneof![
            20 => prop::sample::select(KINDS[..7].to_vec()),
            1 => Just(KINDS[7]),
        ],
        prop::collection::vec(prop::bool::weighted(0.97), 5),
        any::<bool>(),
        prop::collection::vec(prop::sample::select(FIELDS.to_vec()), 0..3),
        prop::bool::weighted(0.08),
    )
        .prop_flat_map(|(kind, present, alternative, extras, with_extras)| {
            let mut fields: Vec<&'static str> = fields_of(kind)
                .iter()
                .zip(&present)
                .filter(|(_, p)| **p)
                .map(|(f, _)| match (*f, alternative) {
                    ("half_angle", true) => "half_angle_deg",
                    ("intensity", true) => "flux",
                    (f, _) => f,
                })
                .collect();
            if with_extras {
                fields.extend(extras);
            }
            fields.sort_unstable();
            fields.dedup();
            let values: Vec<BoxedStrategy<String>> = fields.iter().map(|f| value_for(f)).collect();
            values.prop_map(move |vals| {
                let mut t = format!("[[emitters]]\nkind = \"{kind}\"\n");
                for (f, v) in fields.iter().zip(vals) {
                    t.push_str(&format!("{f} = {v}\n"));
                }
                t
            })
        })
}

fn scene_text() -> impl Strategy<Value = String> {
    (
        prop_oneof![
            4 => Just(vec![0.0, 0.0, 0.0]),
            1 => vector(),
        ],
        prop_oneof![
            4 => Just(vec![0.0, 0.0, 1.0]),
            1 => vector(),
        ],
        prop_oneof![
            1 => Just(Vec::new()),
            20 => prop::collection::vec(emitter_table(), 1..4),
        ],
    )
        .prop_map(|(p, n, emitters)| {
            let v = |v: Vec<f64>| {
                v.into_iter()
                    .map(toml_number)
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            format!(
                "[receiver]\npoint = [{}]\nnormal = [{}]\n\n{}",
                v(p),
                v(n),
                emitters.join("\n")
            )
        })
}

fn unit(v: DVec3) -> bool {
    v.is_finite() && (v.length() - 1.0).abs() < 1e-12
}

/// What every parsed scene guarantees.
fn check_invariants(scene: &Scene) -> Result<(), String> {
    let r = &scene.receiver;
    if !r.point.is_finite() || !unit(r.normal) {
        return Err(format!("bad receiver {r:?}"));
    }
    if scene.emitters.is_empty() {
        return Err("no emitters".into());
    }
    let non_negative = |x: f64| x.is_finite() && x >= 0.0;
    let positive = |x: f64| x.is_finite() && x > 0.0;
    for e in &scene.emitters {
        let ok = match e {
            Emitter::Sky(s) => non_negative(s.radiance),
            Emitter::SkyCap(c) => {
                unit(c.axis) && c.half_angle > 0.0 && c.half_angle <= PI && non_negative(c.radiance)
            }
            Emitter::Sphere(s) => {
                s.sphere.center().is_finite()
                    && positive(s.sphere.radius())
                    && non_negative(s.radiance)
                    && (r.point - s.sphere.center()).length() > s.sphere.radius()
            }
            Emitter::Disk(d) => {
                d.disk.center().is_finite()
                    && unit(d.disk.normal())
                    && positive(d.disk.radius())
                    && non_negative(d.radiance)
            }
            Emitter::Polygon(p) => {
                p.polygon.vertices().len() >= 3
                    && p.polygon.vertices().iter().all(|v| v.is_finite())
                    && unit(p.polygon.normal())
                    // 0 or ∞ when the area is beyond f64 (a valid polygon 1e-160
                    // or 1e160 across), never negative or NaN.
                    && p.polygon.area() >= 0.0
                    && non_negative(p.radiance)
            }
            Emitter::Point(p) => p.position.is_finite() && non_negative(p.intensity),
            Emitter::Directional(d) => unit(d.direction) && non_negative(d.irradiance),
        };
        if !ok {
            return Err(format!("invariant broken by {e:?}"));
        }
    }
    Ok(())
}

/// The structured generator is worth its name: a good share of its scenes
/// parse, so the invariant and estimate properties are exercised.
#[test]
fn structured_scenes_often_parse() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::new(fuzz_config(1));
    let strategy = scene_text();
    let n = 500;
    let mut ok = 0;
    let mut moderate_count = 0;
    let mut kinds = std::collections::BTreeSet::new();
    for _ in 0..n {
        let text = strategy.new_tree(&mut runner).unwrap().current();
        if let Ok(scene) = Scene::from_toml(&text) {
            ok += 1;
            moderate_count += usize::from(moderate(&scene));
            kinds.extend(scene.emitters.iter().map(Emitter::kind));
        }
    }
    eprintln!("{ok} of {n} structured scenes parse, {moderate_count} of them moderate");
    assert!(ok * 10 >= n, "only {ok} of {n} structured scenes parse");
    // Most parsed scenes are moderate, so the estimate property's
    // "must succeed" is exercised on many scenes.
    assert!(moderate_count * 2 >= ok, "{moderate_count} of {ok}");
    assert_eq!(kinds.len(), 7, "every kind among the parsed: {kinds:?}");
}

proptest! {
    #![proptest_config(fuzz_config(2000))]

    #[test]
    fn arbitrary_text_never_panics(text in any::<String>()) {
        let _ = Scene::from_toml(&text);
    }

    #[test]
    fn toml_like_text_never_panics(text in "[a-z_\\[\\]=\" .,0-9\n-]{0,200}") {
        let _ = Scene::from_toml(&text);
    }

    #[test]
    fn structured_scenes_parse_to_valid_scenes_or_errors(text in scene_text()) {
        match Scene::from_toml(&text) {
            Ok(scene) => {
                if let Err(e) = check_invariants(&scene) {
                    return Err(TestCaseError::fail(format!("{e}\nfrom\n{text}")));
                }
            }
            Err(e) => prop_assert!(!e.message.is_empty()),
        }
    }
}

/// Whether every number of the scene is 0 or within [1e-12, 1e12] in
/// magnitude. Then no quantity the estimator forms can overflow or
/// underflow to a wrong 0 — the largest is an area sample's value
/// L·cos θ·cos θₗ·A/d² and its square, for the variance: at most
/// (1e12·1e24/d²)² — so every estimate of such a scene must succeed. Scenes
/// beyond it (radiance 1e300, a light 1e200 away) may have sample values or
/// sums beyond f64, which the estimator reports as errors that name the
/// emitter and the sample or the quantity.
fn moderate(scene: &Scene) -> bool {
    let ok = |x: f64| x == 0.0 || (1e-12..=1e12).contains(&x.abs());
    let ok3 = |v: DVec3| ok(v.x) && ok(v.y) && ok(v.z);
    ok3(scene.receiver.point)
        && scene.emitters.iter().all(|e| match e {
            Emitter::Sky(s) => ok(s.radiance),
            Emitter::SkyCap(c) => ok(c.radiance) && ok(c.half_angle),
            Emitter::Sphere(s) => ok3(s.sphere.center()) && ok(s.sphere.radius()) && ok(s.radiance),
            Emitter::Disk(d) => ok3(d.disk.center()) && ok(d.disk.radius()) && ok(d.radiance),
            Emitter::Polygon(p) => p.polygon.vertices().iter().all(|&v| ok3(v)) && ok(p.radiance),
            Emitter::Point(p) => ok3(p.position) && ok(p.intensity),
            Emitter::Directional(d) => ok(d.irradiance),
        })
}

proptest! {
    #![proptest_config(fuzz_config(1000))]

    /// Every strategy × sequence on every parsed scene: a finite estimate
    /// and standard error; on a scene of moderate numbers ([`moderate`])
    /// always that, beyond it that or an error saying which emitter and
    /// sample, or which sum, left f64's range (never a statistics or
    /// configuration error, which would mean the run itself went wrong).
    #[test]
    fn estimates_of_parsed_scenes_succeed_or_name_the_overflow(text in scene_text()) {
        let Ok(scene) = Scene::from_toml(&text) else {
            return Ok(());
        };
        let moderate = moderate(&scene);
        let mut strategies = vec![Sampling::Auto];
        strategies.extend(Sampling::ALL);
        for strategy in strategies {
            for sequence in SequenceKind::ALL {
                let config = EstimateConfig {
                    strategy,
                    sequence,
                    samples: 64,
                    seed: 1,
                    threads: 1,
                    precision: lambert_estimator::precision::Precision::F64,
                };
                match estimate(&scene, &config) {
                    Ok(report) => prop_assert!(
                        report.mean.is_finite() && report.std_error.is_finite(),
                        "{strategy} × {sequence}: {report:?}\nfrom\n{text}"
                    ),
                    Err(e) => {
                        prop_assert!(
                            !moderate,
                            "{strategy} × {sequence} on a moderate scene: {e}\nfrom\n{text}"
                        );
                        prop_assert!(
                            matches!(
                                e,
                                EstimateError::NonFiniteSample { .. } | EstimateError::Overflow { .. }
                            ),
                            "{strategy} × {sequence}: {e:?}\nfrom\n{text}"
                        );
                    }
                }
            }
        }
    }
}
