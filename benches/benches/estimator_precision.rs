//! ns/sample of the estimator in f64 and in f32 (`--precision`), side by
//! side in one run: the sphere light of radius 1 at distance 10, 30° from
//! the normal, every strategy, independent samples, one thread; and light
//! sampling with the randomized-QMC sequences. The ratio f32/f64 per
//! strategy is the figure to quote (the README's estimate section does).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec3;
use lambert_benches::config;
use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind};
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::Strategy;
use lambert_light::emitter::SphereLight;
use lambert_light::{Emitter, Receiver, Scene};

const SAMPLES: u64 = 1 << 20;

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
        for precision in Precision::ALL {
            let cfg = EstimateConfig {
                strategy,
                sequence,
                samples: SAMPLES,
                seed: 1,
                threads: 1,
                precision,
            };
            g.bench_function(format!("sphere {strategy} {sequence} {precision}"), |b| {
                b.iter(|| black_box(estimate(&scene, &cfg).unwrap().mean))
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
        targets = precision
    }
}
criterion_main!(group::benches);
