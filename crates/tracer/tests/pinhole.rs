//! A pinhole pixel measures radiance: a camera looking at a uniform
//! emitter of radiance L reads exactly L in every pixel the emitter covers,
//! whatever the distance, the angle and the mode (see the `camera` module
//! docs for why).

use glam::DVec3;
use lambert_light::emitter::{Emitter, PolygonLight, SphereLight};
use lambert_tracer::{render, Camera, Mode, RenderConfig, SceneBuilder};

const L: f64 = 3.25; // exactly representable in f32: the image stores L itself

fn covered_pixels_read_l(emitter: Emitter, camera: Camera) -> usize {
    let mut b = SceneBuilder::new(camera);
    b.add_emitter(emitter);
    let scene = b.build().unwrap();
    let mut covered = 0;
    for mode in [Mode::Raycast, Mode::Whitted, Mode::Irradiance] {
        let config = RenderConfig {
            mode,
            ..RenderConfig::default()
        };
        let image = render(&scene, &config, &|_, _| {}).unwrap().image;
        covered = 0;
        for y in 0..camera.height() {
            for x in 0..camera.width() {
                let seen = scene
                    .intersect(&camera.pixel_ray(x, y), f64::INFINITY)
                    .is_some();
                let rgb = image.rgb(x, y);
                if seen {
                    covered += 1;
                    assert_eq!(rgb, [L as f32; 3], "{mode} pixel ({x}, {y})");
                } else {
                    assert_eq!(rgb, [0.0; 3], "{mode} pixel ({x}, {y})");
                }
            }
        }
    }
    covered
}

#[test]
fn pinhole_pixels_read_radiance() {
    // A square emitter facing the camera, seen obliquely, from 1 m to 1 km:
    // the covered pixels shrink with distance, the reading does not.
    for distance in [1.0, 10.0, 1000.0] {
        let half = 0.2 * distance; // about 22° across at every distance
        let square = PolygonLight::new(
            vec![
                DVec3::new(-half, -half, 0.0),
                DVec3::new(half, -half, 0.0),
                DVec3::new(half, half, 0.0),
                DVec3::new(-half, half, 0.0),
            ],
            L,
            false,
        )
        .unwrap();
        let eye = DVec3::new(0.3, -0.4, 1.0).normalize() * distance;
        let camera = Camera::new(eye, DVec3::ZERO, DVec3::Z, 40.0, 24, 24).unwrap();
        let covered = covered_pixels_read_l(Emitter::Polygon(square), camera);
        assert!(
            covered > 50,
            "distance {distance}: {covered} pixels covered"
        );
    }
    // A sphere light, which the camera sees at every angle of its surface
    // (from grazing at the limb to head-on): still L everywhere.
    let sphere = SphereLight::new(DVec3::ZERO, 1.0, L).unwrap();
    let camera = Camera::new(
        DVec3::new(0.0, -7.0, 2.0),
        DVec3::ZERO,
        DVec3::Z,
        25.0,
        24,
        24,
    )
    .unwrap();
    assert!(covered_pixels_read_l(Emitter::Sphere(sphere), camera) > 100);
}
