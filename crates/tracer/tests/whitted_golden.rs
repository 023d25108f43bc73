//! The `whitted` scene against a committed 64×64 golden image, with no NaN
//! or infinity in any mode; a sphere resting on a plane neither leaks
//! light at the contact nor shadows the plane with acne; the same image,
//! to the bit, on one thread and on two.
//!
//! Regenerate the golden image (after a deliberate change of the scene or
//! the shading) with `LAMBERT_BLESS=1 cargo test -p lambert-tracer --test
//! whitted_golden`.

use std::path::PathBuf;

use glam::DVec3;
use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;
use lambert_geometry::f64::{Plane, Ray, Sphere};
use lambert_light::emitter::{DirectionalLight, Emitter};
use lambert_tracer::output::{read_exr, write_exr};
use lambert_tracer::{
    builtin, render, render_with_threads, Camera, Material, Mode, RenderConfig, Rgb, SceneBuilder,
    Shape,
};

fn golden_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/whitted-64.exr")
}

#[test]
fn whitted_matches_the_golden_image() {
    let scene = builtin::whitted().with_size(64, 64).unwrap();
    let image = render(&scene, &RenderConfig::default(), &|_, _| {})
        .unwrap()
        .image;
    assert!(image.is_finite());
    if std::env::var_os("LAMBERT_BLESS").is_some() {
        write_exr(&image, &golden_path()).unwrap();
    }
    let golden = read_exr(&golden_path()).unwrap();
    // The tolerance, derived. Every value is a composition of IEEE-754
    // operations that are correctly rounded on every platform (+, −, ×, ÷,
    // √, floor, powi's multiplications) and of libm's tan (the camera's
    // field of view) and atan2/acos (sphere parameters, unused by these
    // materials), which implementations may round differently by ≤ 1 ulp.
    // A 1-ulp change of the camera's tan(fov/2) moves each ray by ~1e-16
    // relative, which moves a smooth radiance by ~1e-16 relative: below
    // half an f32 ulp (2⁻²⁴ ≈ 6e-8), so the stored f32 changes by at most
    // one ulp where the f64 value sits on a rounding boundary. A pixel
    // could change more only if its centre ray passed within ~1e-16 of an
    // edge (silhouette, shadow or checker boundary): for the ~10³ edge
    // pixels here the chance is ~1e-13, i.e. never. So: every channel of
    // every layer within one f32 ulp of the golden value.
    let close = |a: f32, b: f32| a == b || (a.to_bits() as i64 - b.to_bits() as i64).abs() <= 1;
    let mut worst = 0;
    for (a, b) in image
        .rgb_layer()
        .as_flattened()
        .iter()
        .zip(golden.rgb_layer().as_flattened())
    {
        assert!(close(*a, *b), "radiance {a} vs golden {b}");
        worst = worst.max((a.to_bits() as i64 - b.to_bits() as i64).abs());
    }
    for (a, b) in image
        .irradiance_layer()
        .iter()
        .zip(golden.irradiance_layer())
    {
        assert!(close(*a, *b), "irradiance {a} vs golden {b}");
    }
    assert!(worst <= 1);
}

#[test]
fn no_nan_or_infinity_in_any_mode() {
    for scene in [builtin::whitted(), builtin::cornell()] {
        let scene = scene.with_size(48, 48).unwrap();
        for mode in [Mode::Raycast, Mode::Whitted, Mode::Irradiance] {
            let config = RenderConfig {
                mode,
                estimate: PointConfig {
                    strategy: Strategy::Auto,
                    sequence: SequenceKind::Independent,
                    samples: 4,
                    seed: 3,
                },
                ..RenderConfig::default()
            };
            let image = render(&scene, &config, &|_, _| {}).unwrap().image;
            assert!(image.is_finite(), "{mode}");
        }
    }
}

#[test]
fn a_sphere_resting_on_a_plane_neither_leaks_nor_acnes() {
    // A unit sphere resting on z = 0 at the origin, a directional light
    // from (1, 0, 1)/√2 (irradiance 2 W/m² normal to it), a camera looking
    // down at the contact from the lit side.
    let light = DVec3::new(1.0, 0.0, 1.0).normalize();
    let sphere = Sphere::new(DVec3::new(0.0, 0.0, 1.0), 1.0).unwrap();
    let camera = Camera::new(
        DVec3::new(3.0, -2.0, 2.5),
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::Z,
        35.0,
        48,
        48,
    )
    .unwrap();
    let mut b = SceneBuilder::new(camera);
    let grey = b.add_material(Material::diffuse(Rgb::grey(0.5)));
    b.add_shape(Shape::Sphere(sphere), grey);
    b.add_shape(
        Shape::Plane(Plane::new(DVec3::ZERO, DVec3::Z).unwrap()),
        grey,
    );
    b.add_emitter(Emitter::Directional(
        DirectionalLight::new(light, 2.0).unwrap(),
    ));
    let scene = b.build().unwrap();
    let config = RenderConfig {
        mode: Mode::Raycast,
        ..RenderConfig::default()
    };
    let image = render(&scene, &config, &|_, _| {}).unwrap().image;
    // Whether a floor point sees the light, decided in exact terms with a
    // margin: the line p + s·l misses the sphere iff its distance from the
    // centre exceeds the radius.
    let lit = |p: DVec3| -> Option<bool> {
        let v = p - sphere.center();
        let b = v.dot(light);
        let d2 = v.length_squared() - b * b;
        if (d2 - 1.0).abs() < 1e-9 {
            return None; // on the shadow's edge: either answer is right
        }
        Some(d2 > 1.0 || b > 0.0 && v.length_squared() > 1.0 + 1e-9)
    };
    let full = (2.0 * light.z) as f32;
    let (mut lit_count, mut dark_count) = (0, 0);
    for y in 0..48 {
        for x in 0..48 {
            let ray: Ray = camera.pixel_ray(x, y);
            let Some(hit) = scene.intersect(&ray, f64::INFINITY) else {
                continue;
            };
            if hit.hit.normal != DVec3::Z {
                continue; // the sphere itself
            }
            let Some(is_lit) = lit(hit.hit.point) else {
                continue;
            };
            let e = image.irradiance(x, y);
            if is_lit {
                lit_count += 1;
                assert_eq!(e, full, "acne at {}", hit.hit.point);
            } else {
                dark_count += 1;
                assert_eq!(e, 0.0, "light leaks at {}", hit.hit.point);
            }
        }
    }
    assert!(
        lit_count > 200 && dark_count > 50,
        "{lit_count} lit, {dark_count} dark"
    );
    // Floor points approaching the contact point from every side, down to
    // 1e-9 of the radius: all in the sphere's shadow (the sphere fills the
    // sky toward the light there), none leaking through the contact; and
    // points far on the lit side get the whole light.
    let probe = PointConfig {
        strategy: Strategy::Light,
        sequence: SequenceKind::Independent,
        samples: 2,
        seed: 0,
    };
    for k in 1..=9 {
        let d = 10f64.powi(-k);
        for dir in [DVec3::X, -DVec3::X, DVec3::Y, DVec3::new(0.6, 0.8, 0.0)] {
            let e = scene.irradiance_at(dir * d, DVec3::Z, &probe).unwrap();
            assert_eq!(e.mean, 0.0, "leak at {}", dir * d);
        }
    }
    for p in [
        DVec3::new(1.5, 0.0, 0.0),
        DVec3::new(3.0, 1.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
    ] {
        let e = scene.irradiance_at(p, DVec3::Z, &probe).unwrap();
        assert_eq!(e.mean, 2.0 * light.z, "acne at {p}");
    }
}

#[test]
fn images_do_not_depend_on_the_thread_count() {
    let whitted = builtin::whitted().with_size(40, 30).unwrap();
    let cornell = builtin::cornell().with_size(24, 24).unwrap();
    for (scene, mode, sequence) in [
        (&whitted, Mode::Whitted, SequenceKind::Independent),
        (&cornell, Mode::Irradiance, SequenceKind::Independent),
        (&cornell, Mode::Irradiance, SequenceKind::Sobol),
        (&cornell, Mode::Whitted, SequenceKind::Stratified),
    ] {
        let config = RenderConfig {
            mode,
            estimate: PointConfig {
                strategy: Strategy::Mis(lambert_estimator::strategy::Heuristic::Power),
                sequence,
                samples: 32,
                seed: 11,
            },
            tile: 7,
            ..RenderConfig::default()
        };
        let one = render_with_threads(scene, &config, 1, &|_, _| {}).unwrap();
        let two = render_with_threads(scene, &config, 2, &|_, _| {}).unwrap();
        let three = render_with_threads(scene, &config, 3, &|_, _| {}).unwrap();
        let bits = |i: &lambert_tracer::Image| {
            i.rgb_layer()
                .as_flattened()
                .iter()
                .chain(i.irradiance_layer())
                .chain(i.std_error_layer().unwrap_or(&[]))
                .map(|v| v.to_bits())
                .collect::<Vec<u32>>()
        };
        assert_eq!(bits(&one.image), bits(&two.image), "{mode} {sequence}");
        assert_eq!(bits(&one.image), bits(&three.image), "{mode} {sequence}");
        assert_eq!(one.stats.rays, two.stats.rays);
    }
}
