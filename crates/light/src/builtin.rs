//! The built-in scenes: the closed-form cases that break naive code, used by
//! the test suites and by `lambert study`.
//!
//! Every scene has a closed form ([`crate::analytic`]); together they cover
//! every emitter kind, both delta lights, a cap crossing the horizon, a
//! sphere straddling it, tiny and large disks, a grazing rectangle, and a
//! receiver close under a disk, where area sampling is heavy-tailed (listed
//! last, so the rows of studies made before it keep their indices).

use glam::DVec3;

use crate::emitter::{
    DirectionalLight, DiskLight, Emitter, PointLight, PolygonLight, Sky, SkyCap, SphereLight,
};
use crate::receiver::Receiver;
use crate::scene::Scene;

/// A named scene.
#[derive(Clone, Debug)]
pub struct NamedScene {
    /// Short name (file- and column-friendly).
    pub name: &'static str,
    /// The scene.
    pub scene: Scene,
}

fn up() -> Receiver {
    Receiver::new(DVec3::ZERO, DVec3::Z).expect("a valid receiver")
}

fn scene(name: &'static str, receiver: Receiver, emitters: Vec<Emitter>) -> NamedScene {
    NamedScene {
        name,
        scene: Scene::new(receiver, emitters).expect("built-in scenes are valid"),
    }
}

/// A disk of angular radius `alpha` straight overhead at height 1.
fn coaxial_disk(alpha: f64) -> Emitter {
    Emitter::Disk(
        DiskLight::new(DVec3::Z, -DVec3::Z, alpha.tan(), 1.0, false).expect("a valid disk"),
    )
}

/// The built-in scenes, in a fixed order.
pub fn builtin_scenes() -> Vec<NamedScene> {
    let tilt = 30f64.to_radians();
    vec![
        scene(
            "uniform-sky",
            up(),
            vec![Emitter::Sky(Sky::new(1.0).expect("valid"))],
        ),
        scene(
            "sky-cap-horizon",
            // A 40° cap whose axis is 70° from the normal: it crosses the
            // horizon.
            up(),
            vec![Emitter::SkyCap(
                SkyCap::new(
                    DVec3::new(70f64.to_radians().sin(), 0.0, 70f64.to_radians().cos()),
                    40f64.to_radians(),
                    1.0,
                )
                .expect("valid"),
            )],
        ),
        scene("disk-coaxial-small", up(), vec![coaxial_disk(0.01)]),
        scene("disk-coaxial-large", up(), vec![coaxial_disk(1.2)]),
        scene(
            "disk-close-offset",
            up(),
            vec![Emitter::Disk(
                DiskLight::new(DVec3::new(0.6, 0.2, 0.3), -DVec3::Z, 0.5, 1.0, false)
                    .expect("valid"),
            )],
        ),
        scene(
            "sphere-overhead",
            up(),
            vec![Emitter::Sphere(
                SphereLight::new(DVec3::new(0.0, 0.0, 10.0), 1.0, 1.0).expect("valid"),
            )],
        ),
        scene(
            "sphere-tilted-30",
            up(),
            vec![Emitter::Sphere(
                SphereLight::new(
                    DVec3::new(10.0 * tilt.sin(), 0.0, 10.0 * tilt.cos()),
                    1.0,
                    1.0,
                )
                .expect("valid"),
            )],
        ),
        scene(
            "sphere-straddling",
            up(),
            vec![Emitter::Sphere(
                SphereLight::new(DVec3::new(3.0, 0.0, 0.4), 1.0, 1.0).expect("valid"),
            )],
        ),
        scene(
            "triangle",
            up(),
            vec![Emitter::Polygon(
                PolygonLight::new(
                    vec![
                        DVec3::new(-1.0, -1.0, 2.0),
                        DVec3::new(0.0, 1.5, 2.5),
                        DVec3::new(2.0, -0.5, 2.2),
                    ],
                    1.0,
                    false,
                )
                .expect("valid"),
            )],
        ),
        scene(
            "rectangle-grazing",
            // A wall 2 × 1 standing 3 away, seen at grazing elevation.
            up(),
            vec![Emitter::Polygon(
                PolygonLight::new(
                    vec![
                        DVec3::new(3.0, -1.0, 0.05),
                        DVec3::new(3.0, -1.0, 1.05),
                        DVec3::new(3.0, 1.0, 1.05),
                        DVec3::new(3.0, 1.0, 0.05),
                    ],
                    1.0,
                    false,
                )
                .expect("valid"),
            )],
        ),
        scene(
            "several-lights",
            up(),
            vec![
                Emitter::Sphere(
                    SphereLight::new(DVec3::new(2.0, 1.0, 6.0), 0.8, 3.0).expect("valid"),
                ),
                Emitter::Polygon(
                    PolygonLight::new(
                        vec![
                            DVec3::new(-2.0, -1.0, 3.0),
                            DVec3::new(-2.0, 1.0, 3.0),
                            DVec3::new(-1.0, 1.0, 3.0),
                            DVec3::new(-1.0, -1.0, 3.0),
                        ],
                        2.0,
                        true,
                    )
                    .expect("valid"),
                ),
                Emitter::Point(
                    PointLight::with_intensity(DVec3::new(0.5, -0.5, 2.0), 4.0).expect("valid"),
                ),
                Emitter::Sky(Sky::new(0.1).expect("valid")),
            ],
        ),
        scene(
            "directional-and-sky",
            Receiver::new(DVec3::ZERO, DVec3::new(0.2, -0.1, 1.0)).expect("valid"),
            vec![
                Emitter::Directional(
                    DirectionalLight::new(DVec3::new(1.0, 0.0, 1.0), 100.0).expect("valid"),
                ),
                Emitter::Sky(Sky::new(0.5).expect("valid")),
            ],
        ),
        scene(
            "disk-close-under",
            // A unit disk 0.01 above the receiver, off-centre by 0.3: area
            // sampling's values reach L·A/h², carried by a core of the
            // disk that a sample reaches with probability ~3e-4 (heavy
            // tail, infinite variance in the limit h → 0).
            up(),
            vec![Emitter::Disk(
                DiskLight::new(DVec3::new(0.3, 0.0, 0.01), -DVec3::Z, 1.0, 1.0, false)
                    .expect("valid"),
            )],
        ),
    ]
}
