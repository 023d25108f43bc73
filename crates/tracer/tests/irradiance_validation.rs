//! Irradiance images against closed forms and against each other, each
//! statistical test with a stated significance level, Šidák-corrected over
//! its family, and a negative control that the same test at the same
//! sample count rejects.
//!
//! - Unoccluded floor under a disk, a sphere and a polygon light: every
//!   pixel's estimate matches the closed form at its hit point (z-test on
//!   the per-pixel standard error, Student t with the estimate's degrees of
//!   freedom); control: the light's radiance off by 1 %.
//! - Occluded: light sampling and cosine sampling agree per pixel within
//!   their joint error; control: cosine sampling that ignores occluders.
//! - A point whose whole light is hidden gets exactly 0.
//! - A polygon light partly hidden by a polygon occluder, the visible part
//!   itself a polygon, matches Lambert's formula on the visible polygon;
//!   controls: the whole light, and the visible part at 1.01 × L.

use glam::DVec3;
use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;
use lambert_geometry::f64::{ConvexPolygon, Disk, Plane};
use lambert_light::analytic::{polygon_irradiance, Emission};
use lambert_light::emitter::{DiskLight, Emitter, PolygonLight, SphereLight};
use lambert_light::Receiver;
use lambert_tracer::{
    render, Camera, Image, Material, Mode, RenderConfig, Rgb, Scene, SceneBuilder, Shape,
};
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Lambert's formula for the one-sided polygon `vertices` of radiance `l`
/// at the upward-facing receiver at `p`.
fn lambert_polygon(l: f64, p: DVec3, vertices: &[DVec3]) -> f64 {
    let polygon = ConvexPolygon::new(vertices.to_vec()).unwrap();
    let receiver = Receiver::new(p, DVec3::Z).unwrap();
    polygon_irradiance(&polygon, Emission::OneSided, l, &receiver).unwrap()
}

/// Family-wise significance of every test here.
const ALPHA: f64 = 0.01;

/// The two-sided critical |z| of one of `tests` Student-t tests with `dof`
/// degrees of freedom at the Šidák-corrected level 1 − (1 − α)^(1/tests).
fn critical(tests: usize, dof: u64) -> f64 {
    let per_test = 1.0 - (1.0 - ALPHA).powf(1.0 / tests as f64);
    StudentsT::new(0.0, 1.0, dof as f64)
        .unwrap()
        .inverse_cdf(1.0 - per_test / 2.0)
}

fn square(z: f64, half: f64, radiance: f64) -> PolygonLight {
    // Counter-clockwise seen from below: facing −z.
    PolygonLight::new(
        vec![
            DVec3::new(-half, -half, z),
            DVec3::new(-half, half, z),
            DVec3::new(half, half, z),
            DVec3::new(half, -half, z),
        ],
        radiance,
        false,
    )
    .unwrap()
}

/// A camera low over the floor z = 0, looking at the region around the
/// origin from the side (lights at z ≥ 1.5 stay out of view).
fn floor_camera() -> Camera {
    Camera::new(
        DVec3::new(0.2, -3.0, 0.6),
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::Z,
        30.0,
        16,
        16,
    )
    .unwrap()
}

fn floor_scene(emitter: Emitter, extra: impl FnOnce(&mut SceneBuilder)) -> Scene {
    let mut b = SceneBuilder::new(floor_camera());
    let grey = b.add_material(Material::diffuse(Rgb::grey(0.5)));
    b.add_shape(
        Shape::Plane(Plane::new(DVec3::ZERO, DVec3::Z).unwrap()),
        grey,
    );
    extra(&mut b);
    b.add_emitter(emitter);
    b.build().unwrap()
}

fn irradiance_image(
    scene: &Scene,
    strategy: Strategy,
    sequence: SequenceKind,
    samples: u64,
) -> Image {
    let config = RenderConfig {
        mode: Mode::Irradiance,
        estimate: PointConfig {
            strategy,
            sequence,
            samples,
            seed: 2024,
        },
        ..RenderConfig::default()
    };
    render(scene, &config, &|_, _| {}).unwrap().image
}

/// The floor points seen by the camera's pixels (where a pixel sees it).
fn floor_points(camera: &Camera) -> Vec<(u32, u32, DVec3)> {
    let mut out = Vec::new();
    for y in 0..camera.height() {
        for x in 0..camera.width() {
            let r = camera.pixel_ray(x, y);
            if r.direction.z < 0.0 {
                let t = -r.origin.z / r.direction.z;
                out.push((x, y, r.at(t)));
            }
        }
    }
    out
}

/// The largest |z| over the floor pixels of `image` against the closed
/// form of `truth`, and the number of pixels.
fn worst_z(image: &Image, truth: &Emitter) -> (f64, usize) {
    let points = floor_points(&floor_camera());
    let mut worst: f64 = 0.0;
    for &(x, y, p) in &points {
        let e = image.irradiance(x, y) as f64;
        let se = image.std_error(x, y).unwrap() as f64;
        let exact = truth
            .closed_form_irradiance(&Receiver::new(p, DVec3::Z).unwrap())
            .unwrap();
        assert!(se > 0.0, "pixel ({x}, {y}): no error reported");
        // The image stores f32: its rounding (≤ 2⁻²⁴ relative) is far below
        // the standard errors here (> 1e-6 relative), so it does not bias z.
        worst = worst.max((e - exact).abs() / se);
    }
    (worst, points.len())
}

#[test]
fn unoccluded_floor_matches_the_closed_forms_per_pixel() {
    let lights = [
        Emitter::Disk(
            DiskLight::new(DVec3::new(0.3, 0.2, 1.5), -DVec3::Z, 0.8, 2.0, false).unwrap(),
        ),
        Emitter::Sphere(SphereLight::new(DVec3::new(-0.2, 0.4, 2.0), 0.5, 3.0).unwrap()),
        Emitter::Polygon(square(1.8, 0.7, 1.5)),
    ];
    // 16 replicates of 16 Owen-scrambled Sobol points per pixel: the
    // standard error has 15 degrees of freedom.
    let tests: usize = 3 * floor_points(&floor_camera()).len();
    let limit = critical(tests, 15);
    for light in &lights {
        let scene = floor_scene(light.clone(), |_| {});
        let image = irradiance_image(&scene, Strategy::Light, SequenceKind::Sobol, 256);
        let (z, n) = worst_z(&image, light);
        assert!(n > 100, "{n} floor pixels");
        assert!(
            z < limit,
            "{}: worst |z| = {z:.2} ≥ {limit:.2}",
            light.kind()
        );
        // Negative control: the same test, the light 1 % too bright.
        let brighter = match light {
            Emitter::Disk(d) => Emitter::Disk(DiskLight {
                radiance: d.radiance * 1.01,
                ..*d
            }),
            Emitter::Sphere(s) => Emitter::Sphere(SphereLight {
                radiance: s.radiance * 1.01,
                ..*s
            }),
            Emitter::Polygon(p) => Emitter::Polygon(PolygonLight {
                radiance: p.radiance * 1.01,
                ..p.clone()
            }),
            _ => unreachable!(),
        };
        let wrong = irradiance_image(
            &floor_scene(brighter, |_| {}),
            Strategy::Light,
            SequenceKind::Sobol,
            256,
        );
        let (z, _) = worst_z(&wrong, light);
        assert!(
            z > limit,
            "{}: the 1 % control was not rejected (|z| = {z:.2})",
            light.kind()
        );
    }
}

/// A big square light over the floor and an opaque disk between them:
/// umbra, penumbra and lit floor in view.
fn occluded_scene() -> Scene {
    floor_scene(Emitter::Polygon(square(2.0, 1.2, 1.0)), |b| {
        let black = b.add_material(Material::diffuse(Rgb::BLACK));
        b.add_shape(
            Shape::Disk(Disk::new(DVec3::new(0.1, 0.0, 0.8), DVec3::Z, 0.45).unwrap()),
            black,
        );
    })
}

#[test]
fn light_and_cosine_sampling_agree_under_occlusion() {
    let scene = occluded_scene();
    let n = 2048;
    let light = irradiance_image(&scene, Strategy::Light, SequenceKind::Independent, n);
    let cosine = irradiance_image(
        &scene,
        Strategy::CosineHemisphere,
        SequenceKind::Independent,
        n,
    );
    // Negative control: cosine sampling of the same light with nothing in
    // the way (the occluder removed).
    let open = floor_scene(Emitter::Polygon(square(2.0, 1.2, 1.0)), |_| {});
    let ignoring = irradiance_image(
        &open,
        Strategy::CosineHemisphere,
        SequenceKind::Independent,
        n,
    );
    // Cosine sampling finds a light of solid angle Ω with probability
    // P = E⊥/(πL) (the projected solid angle over π) per sample: the normal
    // approximation of the test needs many hits, so only pixels whose
    // floor point has n·P ≥ 200 unoccluded hits expected are compared
    // (far pixels, where the light is a speck, are the rare-event case
    // the CLT does not cover).
    let open_light = Emitter::Polygon(square(2.0, 1.2, 1.0));
    let pixels: Vec<(u32, u32)> = floor_points(&floor_camera())
        .into_iter()
        .filter(|&(_, _, p)| {
            let e = open_light
                .closed_form_irradiance(&Receiver::new(p, DVec3::Z).unwrap())
                .unwrap();
            n as f64 * e / std::f64::consts::PI >= 200.0
        })
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(pixels.len() > 100, "{} pixels compared", pixels.len());
    // Joint error of two independent estimates of n samples each: the
    // difference over √(se₁² + se₂²) is t-distributed with ≥ n − 1 dof.
    let limit = critical(pixels.len(), n - 1);
    let z = |a: &Image, b: &Image, x, y| {
        let (ea, eb) = (a.irradiance(x, y) as f64, b.irradiance(x, y) as f64);
        let (sa, sb) = (
            a.std_error(x, y).unwrap() as f64,
            b.std_error(x, y).unwrap() as f64,
        );
        (ea - eb).abs() / (sa * sa + sb * sb).sqrt()
    };
    let (mut worst, mut worst_control, mut shadowed) = (0.0f64, 0.0f64, 0);
    for &(x, y) in &pixels {
        worst = worst.max(z(&light, &cosine, x, y));
        worst_control = worst_control.max(z(&light, &ignoring, x, y));
        let open_e = ignoring.irradiance(x, y);
        if light.irradiance(x, y) < 0.9 * open_e {
            shadowed += 1;
        }
    }
    assert!(
        shadowed > 20,
        "only {shadowed} pixels in shadow: the test sees no occlusion"
    );
    assert!(
        worst < limit,
        "worst |z| = {worst:.2} ≥ {limit:.2} over {} pixels",
        pixels.len()
    );
    assert!(
        worst_control > limit,
        "the occluder-blind control was not rejected (|z| = {worst_control:.2})"
    );
}

#[test]
fn a_wholly_hidden_light_gives_exactly_zero() {
    // Under the middle of a large opaque square: every direction to the
    // light (a square of half-width 1 at z = 2) crosses it.
    let scene = floor_scene(Emitter::Polygon(square(2.0, 1.0, 5.0)), |b| {
        let grey = b.add_material(Material::diffuse(Rgb::grey(0.5)));
        let blocker = ConvexPolygon::new(vec![
            DVec3::new(-1.5, -1.5, 1.0),
            DVec3::new(1.5, -1.5, 1.0),
            DVec3::new(1.5, 1.5, 1.0),
            DVec3::new(-1.5, 1.5, 1.0),
        ])
        .unwrap();
        b.add_shape(Shape::Polygon(Box::new(blocker)), grey);
    });
    for strategy in Strategy::ALL.into_iter().chain([Strategy::Auto]) {
        for sequence in SequenceKind::ALL {
            let config = PointConfig {
                strategy,
                sequence,
                samples: 64,
                seed: 9,
            };
            for p in [DVec3::ZERO, DVec3::new(0.2, -0.1, 0.0)] {
                let e = scene.irradiance_at(p, DVec3::Z, &config).unwrap();
                assert_eq!(
                    (e.mean, e.std_error),
                    (0.0, 0.0),
                    "{strategy} × {sequence} at {p}"
                );
            }
        }
    }
}

#[test]
fn a_partly_hidden_polygon_light_matches_lambert_on_its_visible_part() {
    // Light: the square |x|, |y| ≤ 1 at z = 2, facing down, radiance L.
    // Occluder: the half-plane x < 0.25 of z = 1 (a large square). From a
    // receiver at (px, py, 0) the ray to a light point q crosses z = 1 at
    // the midpoint, so q is hidden iff (px + qx)/2 < 0.25: the visible part
    // is the rectangle qx ≥ 0.5 − px, a polygon.
    let radiance = 2.0;
    let scene = floor_scene(Emitter::Polygon(square(2.0, 1.0, radiance)), |b| {
        let grey = b.add_material(Material::diffuse(Rgb::grey(0.5)));
        let half_plane = ConvexPolygon::new(vec![
            DVec3::new(-9.0, -9.0, 1.0),
            DVec3::new(0.25, -9.0, 1.0),
            DVec3::new(0.25, 9.0, 1.0),
            DVec3::new(-9.0, 9.0, 1.0),
        ])
        .unwrap();
        b.add_shape(Shape::Polygon(Box::new(half_plane)), grey);
    });
    let config = PointConfig {
        strategy: Strategy::Light,
        sequence: SequenceKind::Sobol,
        samples: 1 << 14,
        seed: 77,
    };
    let receivers = [
        DVec3::new(-0.3, 0.0, 0.0),
        DVec3::new(0.0, 0.4, 0.0),
        DVec3::new(0.2, -0.3, 0.0),
        DVec3::new(0.45, 0.1, 0.0),
    ];
    let limit = critical(receivers.len(), 15);
    let visible = |p: DVec3, l: f64| {
        let b = 0.5 - p.x;
        let v = [
            DVec3::new(b, -1.0, 2.0),
            DVec3::new(b, 1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
        ];
        lambert_polygon(l, p, &v)
    };
    for p in receivers {
        let e = scene.irradiance_at(p, DVec3::Z, &config).unwrap();
        let z = |exact: f64| (e.mean - exact).abs() / e.std_error;
        let exact = visible(p, radiance);
        assert!(
            z(exact) < limit,
            "at {p}: E = {} vs {exact}, |z| = {:.2}",
            e.mean,
            z(exact)
        );
        // Controls: the whole light (occluder ignored), and the visible
        // part 1 % too bright.
        let whole = lambert_polygon(
            radiance,
            p,
            &[
                DVec3::new(-1.0, -1.0, 2.0),
                DVec3::new(-1.0, 1.0, 2.0),
                DVec3::new(1.0, 1.0, 2.0),
                DVec3::new(1.0, -1.0, 2.0),
            ],
        );
        assert!(
            z(whole) > limit,
            "at {p}: the unoccluded control was not rejected"
        );
        assert!(
            z(visible(p, radiance * 1.01)) > limit,
            "at {p}: the 1 % control was not rejected"
        );
    }
}
