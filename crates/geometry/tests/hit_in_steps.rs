//! `Intersect::intersect` is, to the bit, `hit_distance`, then `hit_at`,
//! then `surface_parameters`: for every shape, in both precisions, over a
//! fan of rays that hit, miss and graze.

macro_rules! steps_test {
    ($name:ident, $p:ident, $v2:ident, $v3:ident) => {
        #[test]
        fn $name() {
            use glam::$v3 as V3;
            use lambert_geometry::$p::{
                ConvexPolygon, Disk, Intersect, Parallelogram, Plane, Ray, Sphere, Triangle,
            };
            let shapes: Vec<(&str, Box<dyn Intersect>)> = vec![
                (
                    "sphere",
                    Box::new(Sphere::new(V3::new(0.2, -0.1, 4.0), 1.3).unwrap()),
                ),
                (
                    "plane",
                    Box::new(Plane::new(V3::new(0.0, 0.0, 5.0), V3::new(0.1, 0.2, -1.0)).unwrap()),
                ),
                (
                    "disk",
                    Box::new(
                        Disk::new(V3::new(0.0, 0.3, 3.0), V3::new(0.0, 0.4, 1.0), 1.1).unwrap(),
                    ),
                ),
                (
                    "triangle",
                    Box::new(
                        Triangle::new(
                            V3::new(-1.0, -1.0, 3.0),
                            V3::new(1.5, -0.5, 3.5),
                            V3::new(0.0, 1.5, 2.5),
                        )
                        .unwrap(),
                    ),
                ),
                (
                    "parallelogram",
                    Box::new(
                        Parallelogram::new(
                            V3::new(-1.0, -1.0, 3.0),
                            V3::new(2.0, 0.3, 0.0),
                            V3::new(0.2, 1.8, 0.5),
                        )
                        .unwrap(),
                    ),
                ),
                (
                    "polygon",
                    Box::new(
                        ConvexPolygon::new(vec![
                            V3::new(-1.0, -1.0, 3.0),
                            V3::new(1.0, -1.0, 3.0),
                            V3::new(1.3, 0.5, 3.0),
                            V3::new(0.0, 1.2, 3.0),
                            V3::new(-1.2, 0.4, 3.0),
                        ])
                        .unwrap(),
                    ),
                ),
            ];
            for (name, shape) in &shapes {
                let mut hits = 0;
                for i in 0..400 {
                    let a = i as $p * 0.0713;
                    let r = (i % 20) as $p * 0.03;
                    let d = V3::new(r * a.cos(), r * a.sin(), 1.0).normalize();
                    let ray = Ray::new(V3::new(0.01, -0.02, 0.0), d);
                    let full = shape.intersect(&ray, $p::INFINITY);
                    let t = shape.hit_distance(&ray, $p::INFINITY);
                    assert_eq!(full.map(|h| h.distance), t, "{name} {i}");
                    let (Some(full), Some(t)) = (full, t) else {
                        continue;
                    };
                    hits += 1;
                    let record = shape.hit_at(&ray, t);
                    assert_eq!(record.uv, glam::$v2::ZERO, "{name} {i}");
                    let uv = shape.surface_parameters(&ray, t);
                    let bits = |v: V3| v.to_array().map(|x| x.to_bits());
                    assert_eq!(record.distance.to_bits(), full.distance.to_bits());
                    assert_eq!(bits(record.point), bits(full.point), "{name} {i}");
                    assert_eq!(bits(record.normal), bits(full.normal), "{name} {i}");
                    assert_eq!(bits(record.error), bits(full.error), "{name} {i}");
                    assert_eq!(
                        uv.to_array().map(|x| x.to_bits()),
                        full.uv.to_array().map(|x| x.to_bits()),
                        "{name} {i}"
                    );
                }
                assert!(hits > 40, "{name}: only {hits} hits");
            }
        }
    };
}

steps_test!(intersect_is_its_three_steps_f64, f64, DVec2, DVec3);
steps_test!(intersect_is_its_three_steps_f32, f32, Vec2, Vec3);
