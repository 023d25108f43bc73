//! The equal-time comparison's machinery (`lambert_tracer::compare`), at
//! fixed samples per pixel (timing is not reproducible, so no test depends
//! on it):
//!
//! 1. the per-pixel RMSE and the reference's RMS standard error against
//!    hand-computed values (exact assertions: every operation below is
//!    exact in f64 or correctly rounded);
//! 2. a scene built so that the control variate must win: a square light
//!    over a floor, and an opaque wall as tall as the light whose plane
//!    separates the light from half the floor. From a floor point at
//!    x < 0 every segment to the light (x ≥ 0.5, z = 2) crosses the wall's
//!    plane x = 0 at height 2|x|/(x_l + |x|) < 2, inside the wall: the
//!    light is wholly hidden (umbra). From x > 0 no segment reaches x = 0:
//!    wholly seen. No pixel is in a penumbra, so every control-variate
//!    sample is E_u·V with V constant per pixel: each pixel's estimate is
//!    E_u or 0, the same in the reference, and its error is at most the
//!    f32 rounding of the stored layer (2⁻²³ relative, twice). Light
//!    sampling's values L Ω cos θ vary continuously over the light, so its
//!    lit pixels' errors are not 0 (their relative spread at 16 spp is a
//!    few percent). Hence RMSE(light)/RMSE(control variate) > 1 with
//!    certainty; the test asserts it through `rmse_ratio` (∞, reported as
//!    `None`, where the control variate's corrected RMSE is 0, or a finite
//!    ratio above 1e3 otherwise: the light's RMSE is above 1e-3 of the
//!    mean irradiance and the control variate's below 2·2⁻²³ of it);
//! 3. a penumbra scene (a disk occluder): the ratio is what the errors say,
//!    and every image is finite;
//! 4. bad configurations name their option.

use glam::DVec3;
use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;
use lambert_geometry::f64::{ConvexPolygon, Disk, Plane};
use lambert_light::emitter::{Emitter, PolygonLight};
use lambert_tracer::compare::{compare, pixel_error, rms_std_error, Budget, CompareConfig};
use lambert_tracer::{Camera, Image, Material, Rgb, Scene, SceneBuilder, Shape};

fn image(irradiance: Vec<f32>, std_error: Option<Vec<f32>>) -> Image {
    Image::from_layers(2, 2, vec![[0.0; 3]; 4], irradiance, std_error).unwrap()
}

#[test]
fn rmse_against_a_hand_case() {
    let reference = image(vec![1.0, 2.0, 3.0, 4.0], Some(vec![3.0, 4.0, 0.0, 0.0]));
    // √((9 + 16)/4) = 2.5.
    assert_eq!(rms_std_error(&reference), 2.5);
    let estimate = image(vec![1.0, 2.0, 3.0, 6.0], None);
    // Squared differences 0, 0, 0, 4: MSE 1, RMSE 1; with a reference
    // RMS error of 0.5 removed: √(1 − 0.25).
    let e = pixel_error(&estimate, &reference, 0.5).unwrap();
    assert_eq!(e.rmse, 1.0);
    assert_eq!(e.corrected_rmse, 0.75f64.sqrt());
    assert_eq!(e.mean_reference, 2.5);
    assert_eq!(e.pixels, 4);
    // A reference error larger than the difference: clamped to 0.
    assert_eq!(
        pixel_error(&estimate, &reference, 2.0)
            .unwrap()
            .corrected_rmse,
        0.0
    );
    // Sizes must agree.
    let small = Image::from_layers(1, 1, vec![[0.0; 3]], vec![0.0], None).unwrap();
    let err = pixel_error(&small, &reference, 0.0).unwrap_err();
    assert_eq!(err.field, "reference");
}

fn floor(camera: Camera, extra: impl FnOnce(&mut SceneBuilder)) -> Scene {
    let mut b = SceneBuilder::new(camera);
    let grey = b.add_material(Material::diffuse(Rgb::grey(0.5)));
    b.add_shape(
        Shape::Plane(Plane::new(DVec3::ZERO, DVec3::Z).unwrap()),
        grey,
    );
    extra(&mut b);
    // A square light x ∈ [0.5, 1.5], y ∈ [−0.5, 0.5] at z = 2, facing −z.
    let light = PolygonLight::new(
        vec![
            DVec3::new(0.5, -0.5, 2.0),
            DVec3::new(0.5, 0.5, 2.0),
            DVec3::new(1.5, 0.5, 2.0),
            DVec3::new(1.5, -0.5, 2.0),
        ],
        1.0,
        false,
    )
    .unwrap();
    b.add_emitter(Emitter::Polygon(light));
    b.build().unwrap()
}

/// The wall scene of the module docs: umbra at x < 0, lit at x > 0.
fn wall_scene() -> Scene {
    let camera = Camera::new(
        DVec3::new(-1.0, -4.0, 4.0),
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::Z,
        40.0,
        16,
        16,
    )
    .unwrap();
    floor(camera, |b| {
        let black = b.add_material(Material::diffuse(Rgb::BLACK));
        let wall = ConvexPolygon::new(vec![
            DVec3::new(0.0, -1000.0, 0.0),
            DVec3::new(0.0, 1000.0, 0.0),
            DVec3::new(0.0, 1000.0, 2.0),
            DVec3::new(0.0, -1000.0, 2.0),
        ])
        .unwrap();
        b.add_shape(Shape::Polygon(Box::new(wall)), black);
    })
}

fn config(strategies: Vec<Strategy>, budget: Budget) -> CompareConfig {
    CompareConfig {
        strategies,
        budget,
        estimate: PointConfig {
            strategy: Strategy::Auto,
            sequence: SequenceKind::Independent,
            samples: 16,
            seed: 11,
        },
        reference_strategy: Strategy::ControlVariate,
        reference_spp: 256,
        pilot_spp: 2,
        tile: 8,
    }
}

#[test]
fn control_variate_wins_where_no_pixel_is_in_a_penumbra() {
    let scene = wall_scene();
    let c = config(
        vec![Strategy::Light, Strategy::ControlVariate],
        Budget::SamplesPerPixel(16),
    );
    let result = compare(&scene, &c, &|_| {}).unwrap();
    let (light, cv) = (&result.runs[0], &result.runs[1]);
    assert_eq!((light.spp, cv.spp), (16, 16));
    let mean = light.error.mean_reference;
    assert!(mean > 0.0);
    // The premise: some pixels lit, some in the umbra.
    let layer = result.reference.image.irradiance_layer();
    assert!(layer.iter().any(|&e| e > 0.0) && layer.contains(&0.0));
    // The control variate is exact to f32 rounding, light sampling is not.
    assert!(
        cv.error.rmse <= 2.0 * 2f64.powi(-23) * mean,
        "{:?}",
        cv.error
    );
    assert!(light.error.rmse > 1e-3 * mean, "{:?}", light.error);
    match result.rmse_ratio(1) {
        None => assert_eq!(cv.error.corrected_rmse, 0.0),
        Some(r) => assert!(r > 1e3, "ratio {r}"),
    }
    assert_eq!(result.rmse_ratio(0), Some(1.0));
}

#[test]
fn penumbra_scene_ratio_is_the_ratio_of_errors() {
    let camera = Camera::new(
        DVec3::new(1.0, -3.0, 1.5),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::Z,
        40.0,
        12,
        12,
    )
    .unwrap();
    let scene = floor(camera, |b| {
        let black = b.add_material(Material::diffuse(Rgb::BLACK));
        b.add_shape(
            Shape::Disk(Disk::new(DVec3::new(1.0, 0.0, 1.0), DVec3::Z, 0.3).unwrap()),
            black,
        );
    });
    let c = config(
        vec![
            Strategy::Light,
            Strategy::ControlVariate,
            Strategy::Projected,
        ],
        Budget::SamplesPerPixel(8),
    );
    let result = compare(&scene, &c, &|_| {}).unwrap();
    assert_eq!(result.runs.len(), 3);
    for (i, run) in result.runs.iter().enumerate() {
        assert!(run.rendered.image.is_finite());
        assert!(run.error.rmse.is_finite() && run.error.rmse >= run.error.corrected_rmse);
        let scaled = |k: usize| {
            let r = &result.runs[k];
            r.error.corrected_rmse * r.rendered.stats.seconds.sqrt()
        };
        if let Some(r) = result.time_normalized_ratio(i) {
            assert_eq!(r, scaled(0) / scaled(i));
        }
        if let Some(r) = result.rmse_ratio(i) {
            assert_eq!(
                r,
                result.runs[0].error.corrected_rmse / run.error.corrected_rmse
            );
        }
    }
    assert!(result.reference_rms_std_error > 0.0);
}

#[test]
fn bad_configurations_name_their_option() {
    let scene = wall_scene();
    let cases = [
        (config(vec![], Budget::SamplesPerPixel(4)), "--compare"),
        (
            config(vec![Strategy::Light], Budget::Seconds(0.0)),
            "--seconds",
        ),
        (
            config(vec![Strategy::Light], Budget::Seconds(-1.0)),
            "--seconds",
        ),
        (
            config(vec![Strategy::Light], Budget::Seconds(f64::NAN)),
            "--seconds",
        ),
        (
            config(vec![Strategy::Light], Budget::SamplesPerPixel(1)),
            "--spp",
        ),
        (
            CompareConfig {
                reference_spp: 0,
                ..config(vec![Strategy::Light], Budget::SamplesPerPixel(4))
            },
            "--reference-spp",
        ),
    ];
    for (c, field) in cases {
        let err = compare(&scene, &c, &|_| {}).unwrap_err();
        assert_eq!(err.field, field, "{err}");
    }
}
