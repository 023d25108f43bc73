//! Instruction counts of the projected-solid-angle and disk samplers, for
//! `valgrind --tool=callgrind` (whose counts, unlike times, do not depend on
//! the load of a shared machine):
//!
//! ```text
//! cargo build --release -p lambert-benches --example instructions
//! valgrind --tool=callgrind --callgrind-out-file=/tmp/cg.out \
//!     target/release/examples/instructions disk-sample 100000
//! ```
//!
//! then divide the total `Ir` by the count (the program's fixed start-up
//! cost is measured with a count of 0). Cases: `<sampler>-sample` draws from
//! a sampler prepared once; `<sampler>-setup` prepares one per iteration.

use std::hint::black_box;

use glam::{DVec2, DVec3};
use lambert_geometry::f64::{ConvexPolygon, Disk, Sphere};
use lambert_sampling::f64::{
    DiskSolidAngle, ProjectedPolygon, ProjectedSphere, SphereSolidAngle, SphericalRectangle,
    SphericalTriangle, UniformDiskArea,
};

fn u(i: u64) -> DVec2 {
    // A low-discrepancy walk (golden-ratio increments): no RNG in the count.
    let a = (i as f64 * 0.618_033_988_749_894_9).fract();
    let b = (i as f64 * 0.754_877_666_246_692_7).fract();
    DVec2::new(a, b)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case = args.get(1).map(String::as_str).unwrap_or("");
    let n: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(100_000);
    let o = DVec3::ZERO;
    let z = DVec3::Z;
    let square = ConvexPolygon::new(vec![
        DVec3::new(0.5, -0.5, 1.0),
        DVec3::new(1.5, -0.5, 1.0),
        DVec3::new(1.5, 0.5, 1.0),
        DVec3::new(0.5, 0.5, 1.0),
    ])
    .unwrap();
    let triangle = ConvexPolygon::new(vec![
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    ])
    .unwrap();
    let disk = Disk::new(DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 0.4), 0.7).unwrap();
    let tilt = 30f64.to_radians();
    let sphere = Sphere::new(DVec3::new(10.0 * tilt.sin(), 0.0, 10.0 * tilt.cos()), 1.0).unwrap();
    let mut acc = DVec3::ZERO;
    match case {
        "disk-sample" => {
            let s = DiskSolidAngle::new(o, &disk).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        "disk-area-sample" => {
            let s = UniformDiskArea::new(&disk);
            (0..n).for_each(|i| acc += s.sample(u(i)).point);
        }
        "disk-setup" => (0..n).for_each(|i| {
            acc.x += DiskSolidAngle::new(black_box(o) + u(i).extend(0.0) * 1e-3, &disk)
                .unwrap()
                .solid_angle()
        }),
        "square-sample" => {
            let s = ProjectedPolygon::new(o, z, &square).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        "square-steps" => {
            let s = ProjectedPolygon::new(o, z, &square).unwrap();
            let mut hist = [0u64; 8];
            (0..n).for_each(|i| hist[s.newton_steps(u(i)).min(7)] += 1);
            println!("steps histogram {hist:?}");
        }
        "disk-steps" => {
            let s = DiskSolidAngle::new(o, &disk).unwrap();
            let mut hist = [0u64; 8];
            (0..n).for_each(|i| hist[s.newton_steps(u(i)).min(7)] += 1);
            println!("steps histogram {hist:?}");
        }
        "square-setup" => (0..n).for_each(|i| {
            acc.x += ProjectedPolygon::new(black_box(o) + u(i).extend(0.0) * 1e-3, z, &square)
                .unwrap()
                .projected_solid_angle()
        }),
        "triangle-sample" => {
            let s = ProjectedPolygon::new(o, z, &triangle).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        "triangle-setup" => (0..n).for_each(|i| {
            acc.x += ProjectedPolygon::new(black_box(o) + u(i).extend(0.0) * 1e-3, z, &triangle)
                .unwrap()
                .projected_solid_angle()
        }),
        "spherical-triangle-setup" => {
            let v = triangle.vertices();
            (0..n).for_each(|i| {
                acc.x +=
                    SphericalTriangle::new(black_box(o) + u(i).extend(0.0) * 1e-3, v[0], v[1], v[2])
                        .unwrap()
                        .solid_angle()
            })
        }
        "spherical-rectangle-sample" => {
            let v = square.vertices();
            let s = SphericalRectangle::new(o, v[0], v[1] - v[0], v[3] - v[0]).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        "sphere-sample" => {
            let s = ProjectedSphere::new(o, z, &sphere).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        "sphere-setup" => (0..n).for_each(|i| {
            acc.x += ProjectedSphere::new(black_box(o) + u(i).extend(0.0) * 1e-3, z, &sphere)
                .unwrap()
                .projected_solid_angle()
        }),
        "cone-sphere-sample" => {
            let s = SphereSolidAngle::new(o, &sphere).unwrap();
            (0..n).for_each(|i| acc += s.sample(u(i)).direction);
        }
        _ => {}
    }
    black_box(acc);
}
