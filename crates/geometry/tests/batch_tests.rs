//! The batch tests (`Intersect::nearest_in_batch`, `occludes_in_batch`)
//! give every ray exactly what `hit_distance` gives it, for every shape, in
//! both precisions: rays that hit, miss, graze, start inside or on the
//! surface, run parallel to planes, with limits before, at and after the
//! hit.

macro_rules! batch_test {
    ($name:ident, $p:ident, $v3:ident) => {
        #[test]
        fn $name() {
            use glam::$v3 as V3;
            use lambert_geometry::$p::{
                ConvexPolygon, Disk, Intersect, Parallelogram, Plane, Ray, RayBatch, Sphere,
                Triangle,
            };
            let shapes: Vec<(&str, Box<dyn Intersect>)> = vec![
                (
                    "sphere",
                    Box::new(Sphere::new(V3::new(0.2, -0.1, 4.0), 1.3).unwrap()),
                ),
                (
                    "sphere at origin",
                    Box::new(Sphere::new(V3::ZERO, 0.5).unwrap()),
                ),
                (
                    "plane",
                    Box::new(Plane::new(V3::new(0.0, 0.0, 5.0), V3::new(0.1, 0.2, -1.0)).unwrap()),
                ),
                ("plane z=0", Box::new(Plane::new(V3::ZERO, V3::Z).unwrap())),
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
            // A fan from two origins (outside everything, and inside the
            // sphere at the origin), plus axis-parallel rays.
            let mut rays = RayBatch::new();
            let mut list = Vec::new();
            for (k, origin) in [V3::new(0.01, -0.02, 0.0), V3::new(0.1, 0.05, 0.2)]
                .iter()
                .enumerate()
            {
                for i in 0..300 {
                    let a = i as $p * 0.0713;
                    let r = (i % 25) as $p * 0.04;
                    let z = if k == 1 && i % 3 == 0 { -1.0 } else { 1.0 };
                    list.push(Ray::new(
                        *origin,
                        V3::new(r * a.cos(), r * a.sin(), z).normalize(),
                    ));
                }
            }
            for d in [V3::X, V3::Y, V3::Z, -V3::Z] {
                list.push(Ray::new(V3::new(0.3, 0.2, 0.0), d));
            }
            for ray in &list {
                rays.push(ray);
            }
            assert_eq!(rays.len(), list.len());
            for (name, shape) in &shapes {
                let reference: Vec<Option<$p>> = list
                    .iter()
                    .map(|r| shape.hit_distance(r, $p::INFINITY))
                    .collect();
                let hits = reference.iter().flatten().count();
                assert!(hits > 20, "{name}: only {hits} hits");
                // Limits: none, before the hit, at it, after it.
                for scale in [$p::INFINITY, 0.5, 1.0, 2.0] {
                    let limit: Vec<$p> = reference
                        .iter()
                        .map(|t| {
                            if scale.is_finite() {
                                t.unwrap_or(3.0) * scale
                            } else {
                                scale
                            }
                        })
                        .collect();
                    let mut nearest = limit.clone();
                    let mut ids = vec![u32::MAX; list.len()];
                    shape.nearest_in_batch(&rays, 3, &mut nearest, &mut ids);
                    let mut blocked = vec![false; list.len()];
                    shape.occludes_in_batch(&rays, &limit, &mut blocked);
                    for (i, ray) in list.iter().enumerate() {
                        assert_eq!(rays.get(i), *ray);
                        let want = shape.hit_distance(ray, limit[i]);
                        match want {
                            Some(t) => {
                                assert_eq!(ids[i], 3, "{name} ray {i} scale {scale}");
                                assert_eq!(nearest[i].to_bits(), t.to_bits(), "{name} ray {i}");
                            }
                            None => {
                                assert_eq!(ids[i], u32::MAX, "{name} ray {i} scale {scale}");
                                assert_eq!(nearest[i].to_bits(), limit[i].to_bits());
                            }
                        }
                        assert_eq!(blocked[i], want.is_some(), "{name} ray {i} scale {scale}");
                    }
                }
                // A ray already blocked stays blocked.
                let mut blocked = vec![true; list.len()];
                shape.occludes_in_batch(&rays, &vec![$p::INFINITY; list.len()], &mut blocked);
                assert!(blocked.iter().all(|&b| b), "{name}");
            }
            rays.clear();
            assert!(rays.is_empty());
        }
    };
}

batch_test!(batches_match_hit_distance_f64, f64, DVec3);
batch_test!(batches_match_hit_distance_f32, f32, Vec3);
