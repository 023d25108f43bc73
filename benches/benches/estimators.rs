//! ns/sample of the sphere-light irradiance estimate: radius 1 at distance
//! 10, 30° from the normal, light (cone) sampling, with independent,
//! stratified and Owen-scrambled Sobol samples, on one and on two threads.
//! Reference figures on this machine class: pbrt-v4 23 ns; Mitsuba 3
//! vectorised 4.3 ns on one thread, 2.4 ns on two.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec3;
use lambert_benches::config;
use lambert_estimator::estimation::{estimate, EstimateConfig, SequenceKind};
use lambert_estimator::strategy::Strategy;
use lambert_light::emitter::SphereLight;
use lambert_light::{Emitter, Receiver, Scene};

const SAMPLES: u64 = 1 << 20;

fn sphere_light(c: &mut Criterion) {
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
    let mut g = c.benchmark_group("estimate");
    g.throughput(Throughput::Elements(SAMPLES));
    for threads in [1, 2] {
        for sequence in SequenceKind::ALL {
            let cfg = EstimateConfig {
                strategy: Strategy::Light,
                sequence,
                samples: SAMPLES,
                seed: 1,
                threads,
                precision: lambert_estimator::precision::Precision::F64,
            };
            g.bench_function(
                format!("sphere light {sequence} {threads} thread(s)"),
                |b| b.iter(|| black_box(estimate(&scene, &cfg).unwrap().mean)),
            );
        }
    }
    // The same estimate with its kernels forced to each instruction set
    // (the bits are the same; the time is not).
    for isa in lambert_sampling::isa::Isa::available() {
        let cfg = EstimateConfig {
            strategy: Strategy::Light,
            sequence: SequenceKind::Independent,
            samples: SAMPLES,
            seed: 1,
            threads: 1,
            precision: lambert_estimator::precision::Precision::F64,
        };
        g.bench_function(format!("sphere light independent {isa}"), |b| {
            b.iter(|| {
                black_box(
                    lambert_estimator::estimation::estimate_with_isa(&scene, &cfg, 0.99, isa)
                        .unwrap()
                        .mean,
                )
            })
        });
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
        targets = sphere_light
    }
}
criterion_main!(group::benches);
