//! ns/sample of every warp, RNG included, in f32 and f64, with
//! `rand_distr::UnitSphere` in the same run as an in-run reference.
//! Reference figures (one thread, this machine class): pbrt-v4 cosine hemisphere
//! 14.2 ns, uniform cone 17.5 ns, spherical triangle 139 ns, spherical
//! rectangle 182 ns; Mitsuba 3 vectorised cosine hemisphere 2.7 ns.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DVec3, Vec3};
use lambert_benches::{config, next_u32x2, next_u64x2, rng, BATCH};
use lambert_geometry::{f32 as g32, f64 as g64};
use lambert_sampling::{f32 as s32, f64 as s64};
use rand_distr::{Distribution, UnitSphere};

macro_rules! bench_warp {
    ($group:expr, $name:expr, $next:ident, $zero:expr, |$u:ident| $body:expr) => {
        $group.bench_function($name, |b| {
            let mut r = rng();
            b.iter(|| {
                let mut acc = $zero;
                for _ in 0..BATCH {
                    let $u = $next(&mut r);
                    acc += $body;
                }
                black_box(acc)
            })
        });
    };
}

fn warps(c: &mut Criterion) {
    let mut g = c.benchmark_group("warp");
    g.throughput(Throughput::Elements(BATCH));

    // In-run reference: rand_distr's rejection-free UnitSphere (f64).
    g.bench_function("rand_distr UnitSphere f64", |b| {
        let mut r = rng();
        b.iter(|| {
            let mut acc = DVec3::ZERO;
            for _ in 0..BATCH {
                let v: [f64; 3] = UnitSphere.sample(&mut r);
                acc += DVec3::from_array(v);
            }
            black_box(acc)
        })
    });
    bench_warp!(g, "rng only f32", next_u32x2, Vec3::ZERO, |u| u.extend(0.0));
    bench_warp!(g, "rng only f64", next_u64x2, DVec3::ZERO, |u| u
        .extend(0.0));

    // Every warp in both precisions, one sample per step, RNG included.
    macro_rules! both {
        ($name:expr, |$u:ident| $f32body:expr, $f64body:expr) => {
            bench_warp!(g, concat!($name, " f32"), next_u32x2, Vec3::ZERO, |$u| {
                $f32body
            });
            bench_warp!(g, concat!($name, " f64"), next_u64x2, DVec3::ZERO, |$u| {
                $f64body
            });
        };
    }
    both!(
        "uniform hemisphere",
        |u| s32::sample_uniform_hemisphere(u),
        s64::sample_uniform_hemisphere(u)
    );
    both!(
        "cosine hemisphere",
        |u| s32::sample_cosine_hemisphere(u),
        s64::sample_cosine_hemisphere(u)
    );
    both!(
        "uniform sphere",
        |u| s32::sample_uniform_sphere(u),
        s64::sample_uniform_sphere(u)
    );
    both!(
        "concentric disk",
        |u| s32::sample_concentric_disk(u).extend(0.0),
        s64::sample_concentric_disk(u).extend(0.0)
    );
    both!(
        "uniform disk",
        |u| s32::sample_uniform_disk(u).extend(0.0),
        s64::sample_uniform_disk(u).extend(0.0)
    );
    let cone32 = s32::UniformCone::from_theta_max(0.3).unwrap();
    let cone64 = s64::UniformCone::from_theta_max(0.3).unwrap();
    both!("uniform cone", |u| cone32.sample(u), cone64.sample(u));
    // n·ω for a tilted n: by the cone's direction, and by `ConeCosine`
    // (one cosine polynomial, no direction), as the light kernels take it.
    let (n32, n64) = (
        Vec3::new(0.3, -0.5, 0.81).normalize(),
        DVec3::new(0.3, -0.5, 0.81).normalize(),
    );
    let (cosine32, cosine64) = (
        s32::ConeCosine::new(&cone32, n32),
        s64::ConeCosine::new(&cone64, n64),
    );
    both!(
        "cone cosine by the direction",
        |u| Vec3::X * n32.dot(cone32.sample(u)),
        DVec3::X * n64.dot(cone64.sample(u))
    );
    both!(
        "cone cosine by ConeCosine",
        |u| Vec3::X * cosine32.sample(u),
        DVec3::X * cosine64.sample(u)
    );
    let sph32 = s32::SphereSolidAngle::new(
        Vec3::ZERO,
        &g32::Sphere::new(Vec3::new(5.0, 0.0, 8.66), 1.0).unwrap(),
    )
    .unwrap();
    let sph64 = s64::SphereSolidAngle::new(
        DVec3::ZERO,
        &g64::Sphere::new(DVec3::new(5.0, 0.0, 8.66), 1.0).unwrap(),
    )
    .unwrap();
    both!(
        "sphere light",
        |u| sph32.sample(u).direction,
        sph64.sample(u).direction
    );
    let (a, b, c) = (
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    );
    let tri32 =
        s32::SphericalTriangle::new(Vec3::ZERO, a.as_vec3(), b.as_vec3(), c.as_vec3()).unwrap();
    let tri64 = s64::SphericalTriangle::new(DVec3::ZERO, a, b, c).unwrap();
    both!(
        "spherical triangle",
        |u| tri32.sample(u).direction,
        tri64.sample(u).direction
    );
    let (corner, e0, e1) = (
        DVec3::new(-0.5, -0.3, 2.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 0.8, 0.0),
    );
    let rect32 =
        s32::SphericalRectangle::new(Vec3::ZERO, corner.as_vec3(), e0.as_vec3(), e1.as_vec3())
            .unwrap();
    let rect64 = s64::SphericalRectangle::new(DVec3::ZERO, corner, e0, e1).unwrap();
    both!(
        "spherical rectangle",
        |u| rect32.sample(u).direction,
        rect64.sample(u).direction
    );
    let area_tri32 = s32::UniformTriangle::new(
        &g32::Triangle::new(a.as_vec3(), b.as_vec3(), c.as_vec3()).unwrap(),
    );
    let area_tri64 = s64::UniformTriangle::new(&g64::Triangle::new(a, b, c).unwrap());
    both!(
        "triangle area",
        |u| area_tri32.sample(u).point,
        area_tri64.sample(u).point
    );
    let disk32 = s32::UniformDiskArea::new(&g32::Disk::new(Vec3::Z, Vec3::NEG_Z, 0.5).unwrap());
    let disk64 = s64::UniformDiskArea::new(&g64::Disk::new(DVec3::Z, DVec3::NEG_Z, 0.5).unwrap());
    both!(
        "disk area",
        |u| disk32.sample(u).point,
        disk64.sample(u).point
    );
    let par32 = s32::UniformParallelogram::new(
        &g32::Parallelogram::new(corner.as_vec3(), e0.as_vec3(), e1.as_vec3()).unwrap(),
    );
    let par64 = s64::UniformParallelogram::new(&g64::Parallelogram::new(corner, e0, e1).unwrap());
    both!(
        "parallelogram area",
        |u| par32.sample(u).point,
        par64.sample(u).point
    );
    g.finish();
}

macro_rules! bench_batch {
    ($group:expr, $name:expr, $next:ident, $u0:expr, $w0:expr, |$us:ident, $out:ident| $call:expr) => {
        $group.bench_function($name, |b| {
            let mut r = rng();
            let mut $us = vec![$u0; BATCH as usize];
            let mut $out = vec![$w0; BATCH as usize];
            b.iter(|| {
                for u in $us.iter_mut() {
                    *u = $next(&mut r);
                }
                $call;
                black_box(&$out);
            })
        });
    };
}

/// The slice forms: the RNG fills a buffer, then the warp runs over it.
fn batches(c: &mut Criterion) {
    let mut g = c.benchmark_group("batch");
    g.throughput(Throughput::Elements(BATCH));
    let (u32z, u64z) = (glam::Vec2::ZERO, glam::DVec2::ZERO);
    bench_batch!(
        g,
        "cosine hemisphere f32",
        next_u32x2,
        u32z,
        Vec3::ZERO,
        |us, out| { s32::sample_cosine_hemisphere_batch(&us, &mut out) }
    );
    bench_batch!(
        g,
        "cosine hemisphere f64",
        next_u64x2,
        u64z,
        DVec3::ZERO,
        |us, out| { s64::sample_cosine_hemisphere_batch(&us, &mut out) }
    );
    bench_batch!(
        g,
        "uniform hemisphere f32",
        next_u32x2,
        u32z,
        Vec3::ZERO,
        |us, out| { s32::sample_uniform_hemisphere_batch(&us, &mut out) }
    );
    bench_batch!(
        g,
        "uniform sphere f32",
        next_u32x2,
        u32z,
        Vec3::ZERO,
        |us, out| { s32::sample_uniform_sphere_batch(&us, &mut out) }
    );
    let cone32 = s32::UniformCone::from_theta_max(0.3).unwrap();
    let cone64 = s64::UniformCone::from_theta_max(0.3).unwrap();
    bench_batch!(
        g,
        "uniform cone f32",
        next_u32x2,
        u32z,
        Vec3::ZERO,
        |us, out| { cone32.sample_batch(&us, &mut out) }
    );
    bench_batch!(
        g,
        "uniform cone f64",
        next_u64x2,
        u64z,
        DVec3::ZERO,
        |us, out| { cone64.sample_batch(&us, &mut out) }
    );
    g.finish();
}

/// The SplitMix64 fill of a precision, in the set the batch runs in.
trait Fill: Sized {
    fn fill(
        rng: &lambert_sampling::sequence::SplitMix64,
        isa: lambert_sampling::isa::Isa,
        first: u64,
        x: &mut [Self],
        y: &mut [Self],
    );
}

impl Fill for f32 {
    #[inline(always)]
    fn fill(
        rng: &lambert_sampling::sequence::SplitMix64,
        isa: lambert_sampling::isa::Isa,
        first: u64,
        x: &mut [f32],
        y: &mut [f32],
    ) {
        rng.fill_2d_f32_in(isa, first, x, y);
    }
}

impl Fill for f64 {
    #[inline(always)]
    fn fill(
        rng: &lambert_sampling::sequence::SplitMix64,
        isa: lambert_sampling::isa::Isa,
        first: u64,
        x: &mut [f64],
        y: &mut [f64],
    ) {
        rng.fill_2d_in(isa, first, x, y);
    }
}

/// Structure-of-arrays batches with their random numbers, as the estimator
/// runs them: SplitMix64 fills the coordinate arrays (one counter-based
/// output per point), the warp writes three direction arrays, all inside
/// `Isa::run` for each instruction set this processor has (the widest is
/// what `Isa::selected` picks).
fn soa_batches(c: &mut Criterion) {
    use lambert_sampling::isa::Isa;
    use lambert_sampling::sequence::SplitMix64;
    let mut g = c.benchmark_group("soa");
    g.throughput(Throughput::Elements(BATCH));
    let n = BATCH as usize;
    let rng = SplitMix64::new(1);
    macro_rules! soa {
        ($name:expr, $real:ty, |$ux:ident, $uy:ident, $wx:ident, $wy:ident, $wz:ident| $warp:expr) => {
            for isa in Isa::available() {
                g.bench_function(format!("{} {isa}", $name), |b| {
                    let (mut $ux, mut $uy) = (vec![0.0 as $real; n], vec![0.0 as $real; n]);
                    let (mut $wx, mut $wy, mut $wz) = (
                        vec![0.0 as $real; n],
                        vec![0.0 as $real; n],
                        vec![0.0 as $real; n],
                    );
                    let mut first = 0u64;
                    b.iter(|| {
                        // Inlined into `run`, so that the fill and the warp
                        // are compiled for `isa` (a closure left out of line
                        // is compiled for the baseline set).
                        isa.run(
                            #[inline(always)]
                            || {
                                <$real as Fill>::fill(&rng, isa, first, &mut $ux, &mut $uy);
                                $warp;
                            },
                        );
                        first = first.wrapping_add(BATCH);
                        black_box((&$wx, &$wy, &$wz));
                    })
                });
            }
        };
    }
    soa!("cosine hemisphere f32", f32, |ux, uy, wx, wy, wz| {
        s32::sample_cosine_hemisphere_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    soa!("cosine hemisphere f64", f64, |ux, uy, wx, wy, wz| {
        s64::sample_cosine_hemisphere_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    soa!("uniform hemisphere f32", f32, |ux, uy, wx, wy, wz| {
        s32::sample_uniform_hemisphere_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    soa!("uniform sphere f32", f32, |ux, uy, wx, wy, wz| {
        s32::sample_uniform_sphere_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    let cone32 = s32::UniformCone::from_theta_max(0.3).unwrap();
    let cone64 = s64::UniformCone::from_theta_max(0.3).unwrap();
    soa!("uniform cone f32", f32, |ux, uy, wx, wy, wz| {
        cone32.sample_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    soa!("uniform cone f64", f64, |ux, uy, wx, wy, wz| {
        cone64.sample_soa(&ux, &uy, &mut wx, &mut wy, &mut wz)
    });
    g.bench_function("splitmix64 rng only f32", |b| {
        let (mut ux, mut uy) = (vec![0.0f32; n], vec![0.0f32; n]);
        b.iter(|| {
            Isa::selected().run(
                #[inline(always)]
                || rng.fill_2d_f32_in(Isa::selected(), 0, &mut ux, &mut uy),
            );
            black_box((&ux, &uy));
        })
    });
    g.finish();
}

// criterion_group! generates an undocumented pub fn.
#[allow(missing_docs)]
mod group {
    use super::*;
    criterion_group! {
        name = benches;
        config = config();
        targets = warps, batches, soa_batches
    }
}
criterion_main!(group::benches);
