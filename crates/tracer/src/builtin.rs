//! The built-in scenes: `whitted` and `cornell`.

use glam::DVec3;
use lambert_geometry::f64::{Parallelogram, Sphere, Triangle};
use lambert_light::emitter::{Emitter, PointLight, PolygonLight};

use crate::camera::Camera;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::{Material, Surface};
use crate::scene::{Scene, SceneBuilder};
use crate::shape::Shape;
use crate::texture::Texture;

/// The names of the built-in scenes.
pub const BUILTIN_SCENES: [&str; 2] = ["whitted", "cornell"];

/// The built-in scene called `name`, if there is one.
pub fn builtin(name: &str) -> Option<Scene> {
    match name {
        "whitted" => Some(whitted()),
        "cornell" => Some(cornell()),
        _ => None,
    }
}

/// The setup of Whitted's 1979 picture ("An improved illumination model
/// for shaded display", CACM 23(6), 1980): a mirror sphere and a glass
/// sphere (index 1.5) above a red-and-yellow checkerboard, lit by one point
/// light, against a blue background; y is up. Both spheres carry
/// Blinn–Phong highlights (the point light seen in them). The geometry,
/// camera and light are those of the Mitsuba 3 scene the benchmarks
/// compare against: camera at (0, 1.5, 6) looking at (0, 0.6, 0), 45°
/// field of view, 512 × 512; spheres of radius 0.8 at (−0.9, 0.8, 0)
/// (mirror) and (0.9, 0.8, 1) (glass); a 40 m square board of 1 m squares
/// on y = 0; a point light of 60 W/sr at (2, 5, 4); background radiance
/// (0.2, 0.3, 0.6).
pub fn whitted() -> Scene {
    let built = (|| -> Result<Scene, TracerError> {
        let camera = Camera::new(
            DVec3::new(0.0, 1.5, 6.0),
            DVec3::new(0.0, 0.6, 0.0),
            DVec3::Y,
            45.0,
            512,
            512,
        )?;
        let mut b = SceneBuilder::new(camera);
        let shine = Rgb::grey(0.6);
        let mirror = b.add_material(Material::mirror(Rgb::WHITE).with_highlight(shine, 400.0));
        let glass = b.add_material(Material::dielectric(1.5).with_highlight(shine, 400.0));
        let board = b.add_material(Material {
            surface: Surface::Diffuse(Texture::Checker {
                even: Rgb::new(0.9, 0.9, 0.1),
                odd: Rgb::new(0.9, 0.1, 0.1),
                scale: 40.0,
            }),
            highlight: None,
        });
        b.add_shape(
            Shape::Sphere(Sphere::new(DVec3::new(-0.9, 0.8, 0.0), 0.8)?),
            mirror,
        );
        b.add_shape(
            Shape::Sphere(Sphere::new(DVec3::new(0.9, 0.8, 1.0), 0.8)?),
            glass,
        );
        b.add_shape(
            Shape::Parallelogram(Parallelogram::new(
                DVec3::new(-20.0, 0.0, 20.0),
                DVec3::new(40.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, -40.0),
            )?),
            board,
        );
        b.add_emitter(Emitter::Point(PointLight::with_intensity(
            DVec3::new(2.0, 5.0, 4.0),
            60.0,
        )?));
        b.background(Rgb::new(0.2, 0.3, 0.6));
        b.build()
    })();
    built.expect("the built-in whitted scene is valid")
}

/// Millimetres of the Cornell data to metres.
fn mm(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z) * 1e-3
}

/// The Cornell box as published by the Cornell University Program of
/// Computer Graphics ("Cornell Box Data", graphics.cornell.edu/online/box):
/// the measured corners of the floor, ceiling, back, left (red) and right
/// (green) walls and of the short and tall blocks, in metres; the camera at
/// (0.278, 0.273, −0.800) looking along +z with a 35 mm lens on a 25 mm
/// square film (vertical field of view 2 atan(12.5/35) = 39.3°), 512 × 512;
/// the ceiling light, a 130 × 105 mm rectangle at the ceiling's height,
/// as a one-sided polygon emitter of radiance 15 W·m⁻²·sr⁻¹ facing down,
/// with the ceiling cut around it (the data put both in one plane). Walls
/// are quads split into triangles (two of them are not quite planar in the
/// data); albedos are RGB approximations of the published reflectance
/// spectra (white 0.73, red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091)).
pub fn cornell() -> Scene {
    let built = (|| -> Result<Scene, TracerError> {
        let fov = 2.0 * (12.5f64 / 35.0).atan().to_degrees();
        let camera = Camera::new(
            mm(278.0, 273.0, -800.0),
            mm(278.0, 273.0, 0.0),
            DVec3::Y,
            fov,
            512,
            512,
        )?;
        let mut b = SceneBuilder::new(camera);
        let white = b.add_material(Material::diffuse(Rgb::grey(0.73)));
        let red = b.add_material(Material::diffuse(Rgb::new(0.63, 0.065, 0.05)));
        let green = b.add_material(Material::diffuse(Rgb::new(0.14, 0.45, 0.091)));
        let quad = |b: &mut SceneBuilder, q: [DVec3; 4], m| -> Result<(), TracerError> {
            b.add_shape(Shape::Triangle(Triangle::new(q[0], q[1], q[2])?), m);
            b.add_shape(Shape::Triangle(Triangle::new(q[0], q[2], q[3])?), m);
            Ok(())
        };
        // Floor, back wall, right (green) and left (red) walls.
        quad(
            &mut b,
            [
                mm(552.8, 0.0, 0.0),
                mm(0.0, 0.0, 0.0),
                mm(0.0, 0.0, 559.2),
                mm(549.6, 0.0, 559.2),
            ],
            white,
        )?;
        quad(
            &mut b,
            [
                mm(549.6, 0.0, 559.2),
                mm(0.0, 0.0, 559.2),
                mm(0.0, 548.8, 559.2),
                mm(556.0, 548.8, 559.2),
            ],
            white,
        )?;
        quad(
            &mut b,
            [
                mm(0.0, 0.0, 559.2),
                mm(0.0, 0.0, 0.0),
                mm(0.0, 548.8, 0.0),
                mm(0.0, 548.8, 559.2),
            ],
            green,
        )?;
        quad(
            &mut b,
            [
                mm(552.8, 0.0, 0.0),
                mm(549.6, 0.0, 559.2),
                mm(556.0, 548.8, 559.2),
                mm(556.0, 548.8, 0.0),
            ],
            red,
        )?;
        // The ceiling (x 0…556, z 0…559.2 at y = 548.8) around the light
        // (x 213…343, z 227…332): four rectangles.
        let y = 548.8;
        for (x0, x1, z0, z1) in [
            (0.0, 556.0, 0.0, 227.0),
            (0.0, 556.0, 332.0, 559.2),
            (0.0, 213.0, 227.0, 332.0),
            (343.0, 556.0, 227.0, 332.0),
        ] {
            b.add_shape(
                Shape::Parallelogram(Parallelogram::new(
                    mm(x0, y, z0),
                    mm(0.0, 0.0, z1 - z0),
                    mm(x1 - x0, 0.0, 0.0),
                )?),
                white,
            );
        }
        // The blocks: top, then four sides each.
        let short = [
            [
                mm(130.0, 165.0, 65.0),
                mm(82.0, 165.0, 225.0),
                mm(240.0, 165.0, 272.0),
                mm(290.0, 165.0, 114.0),
            ],
            [
                mm(290.0, 0.0, 114.0),
                mm(290.0, 165.0, 114.0),
                mm(240.0, 165.0, 272.0),
                mm(240.0, 0.0, 272.0),
            ],
            [
                mm(130.0, 0.0, 65.0),
                mm(130.0, 165.0, 65.0),
                mm(290.0, 165.0, 114.0),
                mm(290.0, 0.0, 114.0),
            ],
            [
                mm(82.0, 0.0, 225.0),
                mm(82.0, 165.0, 225.0),
                mm(130.0, 165.0, 65.0),
                mm(130.0, 0.0, 65.0),
            ],
            [
                mm(240.0, 0.0, 272.0),
                mm(240.0, 165.0, 272.0),
                mm(82.0, 165.0, 225.0),
                mm(82.0, 0.0, 225.0),
            ],
        ];
        let tall = [
            [
                mm(423.0, 330.0, 247.0),
                mm(265.0, 330.0, 296.0),
                mm(314.0, 330.0, 456.0),
                mm(472.0, 330.0, 406.0),
            ],
            [
                mm(423.0, 0.0, 247.0),
                mm(423.0, 330.0, 247.0),
                mm(472.0, 330.0, 406.0),
                mm(472.0, 0.0, 406.0),
            ],
            [
                mm(472.0, 0.0, 406.0),
                mm(472.0, 330.0, 406.0),
                mm(314.0, 330.0, 456.0),
                mm(314.0, 0.0, 456.0),
            ],
            [
                mm(314.0, 0.0, 456.0),
                mm(314.0, 330.0, 456.0),
                mm(265.0, 330.0, 296.0),
                mm(265.0, 0.0, 296.0),
            ],
            [
                mm(265.0, 0.0, 296.0),
                mm(265.0, 330.0, 296.0),
                mm(423.0, 330.0, 247.0),
                mm(423.0, 0.0, 247.0),
            ],
        ];
        for q in short.into_iter().chain(tall) {
            quad(&mut b, q, white)?;
        }
        b.add_emitter(Emitter::Polygon(PolygonLight::new(
            vec![
                mm(343.0, y, 227.0),
                mm(343.0, y, 332.0),
                mm(213.0, y, 332.0),
                mm(213.0, y, 227.0),
            ],
            15.0,
            false,
        )?));
        b.build()
    })();
    built.expect("the built-in cornell scene is valid")
}
