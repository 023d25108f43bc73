//! The tracer's speed: the `whitted` frame (512×512, depth 5, 1 sample per
//! pixel) on one and two threads; the `cornell` irradiance image (256×256,
//! 64 samples per pixel) per strategy; primary and shadow rays per second
//! on a procedurally generated 100k-triangle mesh under the BVH; and the
//! brute-force/BVH crossover behind `BVH_THRESHOLD`. Throughputs are in
//! rays (criterion's elements/s are rays/s).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec3;
use lambert_benches::config;
use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::{Heuristic, Strategy};
use lambert_geometry::f64::{Ray, Triangle};
use lambert_light::emitter::{Emitter, PointLight};
use lambert_tracer::{
    builtin, render, Acceleration, Aggregate, Camera, Material, Mesh, Mode, Primitive,
    RenderConfig, Rgb, SceneBuilder, Shape,
};

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// One `whitted` frame, 512×512, depth 5.
fn whitted_frame(c: &mut Criterion) {
    let scene = builtin::whitted();
    let config = RenderConfig {
        mode: Mode::Whitted,
        max_depth: 5,
        ..RenderConfig::default()
    };
    let rays = render(&scene, &config, &|_, _| {})
        .unwrap()
        .stats
        .rays
        .total();
    let mut g = c.benchmark_group("tracer_whitted");
    g.throughput(Throughput::Elements(rays));
    for threads in [1, 2] {
        let pool = pool(threads);
        g.bench_function(format!("512x512 depth 5, {threads} thread(s)"), |b| {
            b.iter(|| pool.install(|| black_box(render(&scene, &config, &|_, _| {}).unwrap())))
        });
    }
    g.finish();
}

/// The strategies timed on the `cornell` irradiance image.
fn strategies() -> [Strategy; 5] {
    [
        Strategy::Light,
        Strategy::Area,
        Strategy::CosineHemisphere,
        Strategy::UniformHemisphere,
        Strategy::Mis(Heuristic::Power),
    ]
}

/// The `cornell` irradiance image, 256×256, 64 samples per pixel, two
/// threads, per strategy.
fn cornell_irradiance(c: &mut Criterion) {
    let scene = builtin::cornell().with_size(256, 256).unwrap();
    let pool = pool(2);
    let mut g = c.benchmark_group("tracer_cornell");
    g.sample_size(10);
    g.warm_up_time(std::time::Duration::from_millis(100));
    g.measurement_time(std::time::Duration::from_secs(5));
    for strategy in strategies() {
        let config = RenderConfig {
            mode: Mode::Irradiance,
            estimate: PointConfig {
                strategy,
                sequence: SequenceKind::Independent,
                samples: 64,
                seed: 1,
            },
            ..RenderConfig::default()
        };
        let rays = render(&scene, &config, &|_, _| {})
            .unwrap()
            .stats
            .rays
            .total();
        g.throughput(Throughput::Elements(rays));
        g.bench_function(format!("256x256 64spp {strategy}, 2 threads"), |b| {
            b.iter(|| pool.install(|| black_box(render(&scene, &config, &|_, _| {}).unwrap())))
        });
    }
    g.finish();
}

/// Primary and shadow rays on a 100,352-triangle terrain under the BVH,
/// one thread: 256×256 camera rays, then one shadow ray from each hit
/// toward a point light.
fn mesh_rays(c: &mut Criterion) {
    let camera = Camera::new(
        DVec3::new(0.0, 1.6, 2.4),
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::Y,
        50.0,
        256,
        256,
    )
    .unwrap();
    let mut b = SceneBuilder::new(camera);
    let grey = b.add_material(Material::diffuse(Rgb::grey(0.7)));
    for t in Mesh::terrain(224, 1).triangles {
        b.add_shape(Shape::Triangle(t), grey);
    }
    let light = DVec3::new(1.5, 2.0, 0.5);
    b.add_emitter(Emitter::Point(
        PointLight::with_intensity(light, 10.0).unwrap(),
    ));
    let scene = b.build().unwrap();
    assert!(scene.aggregate().has_bvh());
    let primary: Vec<Ray> = (0..256)
        .flat_map(|y| (0..256).map(move |x| (x, y)))
        .map(|(x, y)| camera.pixel_ray(x, y))
        .collect();
    let shadow: Vec<(Ray, f64)> = primary
        .iter()
        .filter_map(|r| scene.intersect(r, f64::INFINITY))
        .filter_map(|h| h.hit.spawn_ray_to(light))
        .collect();
    let mut g = c.benchmark_group("tracer_mesh");
    g.throughput(Throughput::Elements(primary.len() as u64));
    g.bench_function("100k triangles, primary rays, 1 thread", |b| {
        b.iter(|| {
            primary
                .iter()
                .filter(|r| scene.intersect(r, f64::INFINITY).is_some())
                .count()
        })
    });
    g.throughput(Throughput::Elements(shadow.len() as u64));
    g.bench_function("100k triangles, shadow rays, 1 thread", |b| {
        b.iter(|| shadow.iter().filter(|(r, t)| scene.occluded(r, *t)).count())
    });
    g.finish();
}

/// Nearest hits of 4096 rays against n random triangles in a unit cube,
/// brute force against the BVH: where the BVH starts to pay.
fn bvh_threshold(c: &mut Criterion) {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut triangles = Vec::new();
    while triangles.len() < 64 {
        let c = DVec3::new(next(), next(), next());
        let mut corner = || c + 0.3 * (DVec3::new(next(), next(), next()) - 0.5);
        if let Ok(t) = Triangle::new(corner(), corner(), corner()) {
            triangles.push(t);
        }
    }
    let rays: Vec<Ray> = (0..4096)
        .map(|i| {
            let (x, y) = ((i % 64) as f64 / 64.0, (i / 64) as f64 / 64.0);
            let target = DVec3::new(x, y, 0.5);
            let origin = DVec3::new(0.5, 0.5, -2.0);
            Ray::new(origin, (target - origin).normalize())
        })
        .collect();
    let mut g = c.benchmark_group("tracer_bvh_threshold");
    g.throughput(Throughput::Elements(rays.len() as u64));
    for n in [1, 2, 4, 6, 8, 12, 16, 32, 64] {
        for (name, acceleration) in [
            ("brute force", Acceleration::BruteForce),
            ("bvh", Acceleration::Bvh),
        ] {
            let prims = triangles[..n]
                .iter()
                .map(|t| Primitive {
                    shape: Shape::Triangle(*t),
                    material: 0,
                })
                .collect();
            let aggregate = Aggregate::with_acceleration(prims, acceleration);
            g.bench_function(format!("n={n:02} {name}"), |b| {
                b.iter(|| {
                    rays.iter()
                        .filter(|r| aggregate.intersect(r, f64::INFINITY).is_some())
                        .count()
                })
            });
        }
    }
    g.finish();
}

/// The switch on whole scenes: the `whitted` frame (3 bounded
/// primitives: spheres and a parallelogram) and a `cornell` ray-cast frame
/// (41: triangles, parallelograms, the light) at 256×256, one thread, by
/// brute force and with the BVH.
fn bvh_scenes(c: &mut Criterion) {
    let mut g = c.benchmark_group("tracer_bvh_scenes");
    let config = RenderConfig {
        mode: Mode::Raycast,
        ..RenderConfig::default()
    };
    let pool = pool(1);
    for (name, scene) in [
        ("whitted", builtin::whitted()),
        ("cornell", builtin::cornell()),
    ] {
        for (how, acceleration) in [
            ("brute force", Acceleration::BruteForce),
            ("bvh", Acceleration::Bvh),
        ] {
            let scene = scene
                .clone()
                .with_acceleration(acceleration)
                .with_size(256, 256)
                .unwrap();
            g.bench_function(format!("{name} raycast 256x256 {how}"), |b| {
                b.iter(|| pool.install(|| black_box(render(&scene, &config, &|_, _| {}).unwrap())))
            });
        }
    }
    g.finish();
}

// criterion_group! generates an undocumented pub fn.
#[allow(missing_docs)]
mod group {
    use super::*;
    criterion_group! {
        name = benches;
        config = config();
        targets = whitted_frame, mesh_rays, bvh_threshold, bvh_scenes, cornell_irradiance
    }
}
criterion_main!(group::benches);
