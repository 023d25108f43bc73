//! ns/sample of the estimator in f64 and in f32 (`--precision`), side by
//! side in one run: the sphere light of radius 1 at distance 10, 30° from
//! the normal, every strategy, independent samples, one thread; and light
//! sampling with the randomized-QMC sequences. The ratio f32/f64 per
//! strategy is the figure to quote (the README's estimate section does).
//!
//! Group `estimate precision shapes`: the other light shapes whose f32
//! kernels have loops of their own (a close tilted disk, a triangle, a
//! square and a pentagon seen from below), under the strategies that
//! hit-test or sample them, 2¹⁶ samples, and a sky cap (tilted 17°) and
//! the uniform sky.
//! Without these rows the f32 path ran 3–11 times slower than f64 on them
//! unnoticed (hit tests called per sample, fields loaded by masked
//! gathers, disk directions drawn one at a time); with them in f64 only
//! for the disk and the polygons, f64 light sampling of caps and skies
//! (a sampler called out of line per sample, 6× slower than inline) and
//! f32 MIS on the square (its density's containment test out of line,
//! 10×) went unnoticed too, and without the pentagon light sampling and
//! MIS of polygons of five or more vertices (a spherical fan's triangle
//! looked up per sample, out of line).

use std::hint::black_box;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use glam::DVec3;
use lambert_benches::config;
use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind};
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::{Heuristic, Strategy};
use lambert_light::emitter::{DiskLight, PolygonLight, Sky, SkyCap, SphereLight};
use lambert_light::{Emitter, Receiver, Scene};

const SAMPLES: u64 = 1 << 20;

/// Samples per estimate of the shapes group (its slowest rows take tens of
/// ns per sample).
const SHAPE_SAMPLES: u64 = 1 << 16;

fn precision(c: &mut Criterion) {
    let tilt = 30f64.to_radians();
    let scene = Scene::new(
        Receiver::new(DVec3::ZERO, DVec3::Z).unwrap(),
        vec![Emitter::Sphere(
            SphereLight::new(
                DVec3::new(10.0 * tilt.sin(), 0.0, 10.0 * tilt.cos()),
                1.0,
                1.0,
            )
            .unwrap(),
        )],
    )
    .unwrap();
    let mut g = c.benchmark_group("estimate precision");
    g.throughput(Throughput::Elements(SAMPLES));
    let cases = Strategy::ALL
        .into_iter()
        .map(|s| (s, SequenceKind::Independent))
        .chain([
            (Strategy::Light, SequenceKind::Sobol),
            (Strategy::Light, SequenceKind::Stratified),
        ]);
    for (strategy, sequence) in cases {
        let label = format!("sphere {strategy} {sequence}");
        both_precisions(&mut g, &label, &scene, strategy, sequence, SAMPLES);
    }
    g.finish();
}

/// One row per precision, `"{label} {precision}"`: a one-thread estimate
/// of `samples` samples of `scene` (seed 1).
fn both_precisions(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    scene: &Scene,
    strategy: Strategy,
    sequence: SequenceKind,
    samples: u64,
) {
    for precision in Precision::ALL {
        let cfg = EstimateConfig {
            strategy,
            sequence,
            samples,
            seed: 1,
            threads: 1,
            precision,
        };
        g.bench_function(format!("{label} {precision}"), |b| {
            b.iter(|| black_box(estimate(scene, &cfg).unwrap().mean))
        });
    }
}

/// The shapes group (module docs): one scene per light shape, the receiver
/// at the origin facing +z.
fn shapes(c: &mut Criterion) {
    let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
    let disk = DiskLight::new(
        DVec3::new(1.0, 0.5, 3.0),
        DVec3::new(0.0, 0.2, -1.0),
        1.0,
        1.0,
        false,
    )
    .unwrap();
    let triangle = PolygonLight::new(
        vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(0.0, 1.0, 2.5),
        ],
        1.0,
        true,
    )
    .unwrap();
    let square = PolygonLight::new(
        vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ],
        1.0,
        true,
    )
    .unwrap();
    // A regular pentagon: seen as a fan of three spherical triangles.
    let pentagon = PolygonLight::new(
        (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * f64::from(k) / 5.0;
                DVec3::new(1.2 * a.cos(), 1.2 * a.sin(), 2.0)
            })
            .collect(),
        1.0,
        true,
    )
    .unwrap();
    let cap = SkyCap::new(DVec3::new(0.3, 0.0, 1.0), 20f64.to_radians(), 1.0).unwrap();
    let scenes = [
        ("disk", Emitter::Disk(disk)),
        ("triangle", Emitter::Polygon(triangle)),
        ("square", Emitter::Polygon(square)),
        ("pentagon", Emitter::Polygon(pentagon)),
        ("sky cap", Emitter::SkyCap(cap)),
        ("sky", Emitter::Sky(Sky::new(1.0).unwrap())),
    ];
    let mut g = c.benchmark_group("estimate precision shapes");
    g.throughput(Throughput::Elements(SHAPE_SAMPLES));
    for (name, emitter) in scenes {
        let scene = Scene::new(receiver, vec![emitter]).unwrap();
        for strategy in [
            Strategy::UniformHemisphere,
            Strategy::CosineHemisphere,
            Strategy::Light,
            Strategy::Area,
            Strategy::Mis(Heuristic::Power),
        ] {
            let label = format!("{name} {strategy}");
            let independent = SequenceKind::Independent;
            both_precisions(&mut g, &label, &scene, strategy, independent, SHAPE_SAMPLES);
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
        targets = precision, shapes
    }
}
criterion_main!(group::benches);
