//! Checking your own direction sampler with lambert's chi-square tool.
//!
//! A path tracer's author has written a "cosine-weighted" sampler and wants
//! to know whether it really has the density cos θ/π. We test two of them:
//! Malley's method (right) and a tempting shortcut that draws cos θ
//! uniformly (wrong: that is the uniform hemisphere, density 1/2π). The
//! chi-square test accepts the first and rejects the second.
//!
//! Run with `cargo run --release -p lambert-estimator --example check_your_sampler`.

use glam::DVec3;
use lambert_validate::{Binning, ChiSquareTest};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use std::f64::consts::PI;

/// Malley's method: a uniform disk point lifted to the hemisphere.
fn malley(u0: f64, u1: f64) -> DVec3 {
    let r = u0.sqrt();
    let phi = 2.0 * PI * u1;
    DVec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u0).max(0.0).sqrt())
}

/// The shortcut: cos θ uniform in [0, 1) — not cosine-weighted at all.
fn shortcut(u0: f64, u1: f64) -> DVec3 {
    let z = u0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u1;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

fn main() {
    let cosine_pdf = |w: DVec3| w.z.max(0.0) / PI;
    let test = ChiSquareTest::new(Binning::Sphere {
        theta_bins: 20,
        phi_bins: 40,
    })
    .samples(200_000)
    .significance(0.01);
    for (name, sampler) in [
        ("Malley", malley as fn(f64, f64) -> DVec3),
        ("shortcut", shortcut),
    ] {
        let mut rng = Pcg64Mcg::seed_from_u64(1);
        let outcome = test
            .run(|_| sampler(rng.random(), rng.random()), cosine_pdf)
            .expect("a valid test configuration");
        println!("{name:>8}: {outcome}");
    }
}
