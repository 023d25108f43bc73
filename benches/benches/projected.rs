//! ns/sample of the projected-solid-angle samplers (caps, spheres,
//! polygons) and of solid-angle sampling of disks, each next to the sampler
//! it replaces, in f32 and f64, RNG included (as in `warps`): uniform cone
//! vs projected cap; sphere solid angle vs projected sphere; spherical
//! triangle and rectangle vs projected polygon; disk area vs disk solid
//! angle, plain, tabulated and tabulated in batches (`TabulatedDiskSolidAngle`, and
//! `TabulatedProjectedPolygon` for the non-central square; the projected
//! cap across the horizon in batches too); and, next to
//! the projected polygon, a prototype of Arvo's 2001 method
//! (`lambert_benches::arvo`), the alternative to Peters' that the sampling
//! crate measured and did not choose. Group `projected` samples from a
//! prepared sampler; group `projected-setup` times preparing one sampler
//! for a shading point, which a path tracer pays once per light per shading
//! point.
//!
//! Medians: `python3 benches/scripts/medians.py projected`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DVec3, Vec3};
use lambert_benches::arvo::Arvo;
use lambert_benches::{config, next_u32x2, next_u64x2, rng, BATCH};
use lambert_geometry::{f32 as g32, f64 as g64};
use lambert_sampling::{f32 as s32, f64 as s64};

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

/// The scenes: a sphere 30° off the normal (radius 1 at distance 10, the
/// estimator bench's), the same cap straddling the horizon, the triangle and
/// rectangle of `warps`, and a tilted disk.
struct Scenes {
    sphere_center: DVec3,
    straddling_center: DVec3,
    triangle: [DVec3; 3],
    rectangle: [DVec3; 4],
    offset_square: [DVec3; 4],
    disk: (DVec3, DVec3, f64),
}

fn scenes() -> Scenes {
    let tilt = 30f64.to_radians();
    Scenes {
        sphere_center: DVec3::new(10.0 * tilt.sin(), 0.0, 10.0 * tilt.cos()),
        straddling_center: DVec3::new(10.0, 0.0, 0.3),
        triangle: [
            DVec3::new(-1.0, -1.0, 3.0),
            DVec3::new(2.0, -0.5, 3.5),
            DVec3::new(0.0, 1.5, 2.5),
        ],
        rectangle: [
            DVec3::new(-0.5, -0.3, 2.0),
            DVec3::new(0.5, -0.3, 2.0),
            DVec3::new(0.5, 0.5, 2.0),
            DVec3::new(-0.5, 0.5, 2.0),
        ],
        offset_square: [
            DVec3::new(0.5, -0.5, 1.0),
            DVec3::new(1.5, -0.5, 1.0),
            DVec3::new(1.5, 0.5, 1.0),
            DVec3::new(0.5, 0.5, 1.0),
        ],
        disk: (DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 0.4), 0.7),
    }
}

fn poly64(v: &[DVec3]) -> g64::ConvexPolygon {
    g64::ConvexPolygon::new(v.to_vec()).unwrap()
}

fn poly32(v: &[DVec3]) -> g32::ConvexPolygon {
    g32::ConvexPolygon::new(v.iter().map(|x| x.as_vec3()).collect()).unwrap()
}

/// The vertices counter-clockwise seen from the origin looking out (the
/// order the Arvo prototype's fan needs).
fn ccw(v: &[DVec3]) -> Vec<DVec3> {
    let mut v = v.to_vec();
    if (v[1] - v[0]).cross(v[2] - v[0]).dot(v[0]) < 0.0 {
        v.reverse();
    }
    v
}

fn sampling(c: &mut Criterion) {
    let s = scenes();
    let mut g = c.benchmark_group("projected");
    g.throughput(Throughput::Elements(BATCH));
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

    // Caps: the uniform cone about the sphere's axis (what light sampling
    // of a sphere uses) against the projected cap, above and straddling.
    let d = s.sphere_center.length();
    let h = {
        let s2 = (1.0 / d) * (1.0 / d);
        s2 / (1.0 + (1.0 - s2).sqrt())
    };
    let cone64 = s64::UniformCone::from_one_minus_cos(h).unwrap();
    let cone32 = s32::UniformCone::from_one_minus_cos(h as f32).unwrap();
    both!("uniform cone", |u| cone32.sample(u), cone64.sample(u));
    let axis = s.sphere_center / d;
    let cap64 = s64::ProjectedCap::new(axis, h).unwrap();
    let cap32 = s32::ProjectedCap::new(axis.as_vec3(), h as f32).unwrap();
    both!(
        "projected cap above",
        |u| cap32.sample(u).direction,
        cap64.sample(u).direction
    );
    let straddling = s.straddling_center.normalize();
    let scap64 = s64::ProjectedCap::new(straddling, h).unwrap();
    let scap32 = s32::ProjectedCap::new(straddling.as_vec3(), h as f32).unwrap();
    both!(
        "projected cap straddling",
        |u| scap32.sample(u).direction,
        scap64.sample(u).direction
    );

    // Spheres, world space with point and distance.
    let sphere64 = g64::Sphere::new(s.sphere_center, 1.0).unwrap();
    let sphere32 = g32::Sphere::new(s.sphere_center.as_vec3(), 1.0).unwrap();
    let sph64 = s64::SphereSolidAngle::new(DVec3::ZERO, &sphere64).unwrap();
    let sph32 = s32::SphereSolidAngle::new(Vec3::ZERO, &sphere32).unwrap();
    both!(
        "sphere solid angle",
        |u| sph32.sample(u).direction,
        sph64.sample(u).direction
    );
    let psph64 = s64::ProjectedSphere::new(DVec3::ZERO, DVec3::Z, &sphere64).unwrap();
    let psph32 = s32::ProjectedSphere::new(Vec3::ZERO, Vec3::Z, &sphere32).unwrap();
    both!(
        "projected sphere",
        |u| psph32.sample(u).direction,
        psph64.sample(u).direction
    );

    // Polygons.
    let [a, b, cc] = s.triangle;
    let tri64 = s64::SphericalTriangle::new(DVec3::ZERO, a, b, cc).unwrap();
    let tri32 =
        s32::SphericalTriangle::new(Vec3::ZERO, a.as_vec3(), b.as_vec3(), cc.as_vec3()).unwrap();
    both!(
        "spherical triangle",
        |u| tri32.sample(u).direction,
        tri64.sample(u).direction
    );
    let ptri64 = s64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &poly64(&s.triangle)).unwrap();
    let ptri32 = s32::ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &poly32(&s.triangle)).unwrap();
    both!(
        "projected triangle (central)",
        |u| ptri32.sample(u).direction,
        ptri64.sample(u).direction
    );
    let [r0, r1, _, r3] = s.rectangle;
    let rect64 = s64::SphericalRectangle::new(DVec3::ZERO, r0, r1 - r0, r3 - r0).unwrap();
    let rect32 = s32::SphericalRectangle::new(
        Vec3::ZERO,
        r0.as_vec3(),
        (r1 - r0).as_vec3(),
        (r3 - r0).as_vec3(),
    )
    .unwrap();
    both!(
        "spherical rectangle",
        |u| rect32.sample(u).direction,
        rect64.sample(u).direction
    );
    let prect64 = s64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &poly64(&s.rectangle)).unwrap();
    let prect32 = s32::ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &poly32(&s.rectangle)).unwrap();
    both!(
        "projected rectangle (central)",
        |u| prect32.sample(u).direction,
        prect64.sample(u).direction
    );
    // Arvo's method (2001), the alternative the sampling crate did not
    // choose: a prototype in f64 (`lambert_benches::arvo`).
    let arvo_triangle = Arvo::new(&ccw(&s.triangle));
    bench_warp!(
        g,
        "arvo 2001 prototype, triangle f64",
        next_u64x2,
        DVec3::ZERO,
        |u| arvo_triangle.sample(u).0
    );
    let arvo_square = Arvo::new(&ccw(&s.offset_square));
    bench_warp!(
        g,
        "arvo 2001 prototype, square (non-central) f64",
        next_u64x2,
        DVec3::ZERO,
        |u| arvo_square.sample(u).0
    );
    let poff64 =
        s64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &poly64(&s.offset_square)).unwrap();
    let poff32 =
        s32::ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &poly32(&s.offset_square)).unwrap();
    both!(
        "projected square (non-central)",
        |u| poff32.sample(u).direction,
        poff64.sample(u).direction
    );
    // The same with its sectors' inverses tabulated (an estimate's many
    // samples at one point).
    let toff64 = s64::TabulatedProjectedPolygon::new(poff64);
    let toff32 = s32::TabulatedProjectedPolygon::new(poff32);
    both!(
        "projected square (non-central) tabulated",
        |u| toff32.sample(u).direction,
        toff64.sample(u).direction
    );

    // Disks.
    let (dc, dn, dr) = s.disk;
    let d64 = g64::Disk::new(dc, dn, dr).unwrap();
    let d32 = g32::Disk::new(dc.as_vec3(), dn.as_vec3(), dr as f32).unwrap();
    let area64 = s64::UniformDiskArea::new(&d64);
    let area32 = s32::UniformDiskArea::new(&d32);
    // Area sampling as a direction sampler: the point, its direction and the
    // density converted to solid angle (what a light sampler pays).
    both!(
        "disk area",
        |u| {
            let p = area32.sample(u);
            let w = p.point.normalize();
            w * s32::pdf_area_to_solid_angle(p.pdf_area, Vec3::ZERO, p.point, p.normal)
        },
        {
            let p = area64.sample(u);
            let w = p.point.normalize();
            w * s64::pdf_area_to_solid_angle(p.pdf_area, DVec3::ZERO, p.point, p.normal)
        }
    );
    let disk64 = s64::DiskSolidAngle::new(DVec3::ZERO, &d64).unwrap();
    let disk32 = s32::DiskSolidAngle::new(Vec3::ZERO, &d32).unwrap();
    both!(
        "disk solid angle",
        |u| disk32.sample(u).direction,
        disk64.sample(u).direction
    );
    // The same map with its inverse tabulated (an estimate's many samples
    // at one point).
    let table64 = s64::TabulatedDiskSolidAngle::new(disk64);
    let table32 = s32::TabulatedDiskSolidAngle::new(disk32);
    both!(
        "disk solid angle tabulated",
        |u| table32.sample(u).direction,
        table64.sample(u).direction
    );
    // The same directions BATCH at a time by the samplers' batches, in the
    // process's instruction set (what the estimator's light and MIS loops
    // use for the disk, and its projected loops for the square and for
    // caps across the horizon); the random numbers are drawn into arrays
    // first.
    macro_rules! table_batch {
        ($name:expr, $table:expr, $next:ident, $zero:expr) => {
            g.bench_function($name, |b| {
                let (mut r, n) = (rng(), BATCH as usize);
                let (mut ux, mut uy) = (vec![$zero; n], vec![$zero; n]);
                let mut d = [vec![$zero; n], vec![$zero; n], vec![$zero; n]];
                let isa = lambert_sampling::isa::Isa::selected();
                b.iter(|| {
                    for (x, y) in ux.iter_mut().zip(uy.iter_mut()) {
                        let u = $next(&mut r);
                        (*x, *y) = (u.x, u.y);
                    }
                    let [dx, dy, dz] = &mut d;
                    isa.run(
                        #[inline(always)]
                        || $table.sample_directions(&ux, &uy, dx, dy, dz),
                    );
                    black_box(dx[0] + dy[n / 2] + dz[n - 1])
                })
            });
        };
    }
    table_batch!(
        "projected square (non-central) tabulated batch f32",
        toff32,
        next_u32x2,
        0.0f32
    );
    table_batch!(
        "projected square (non-central) tabulated batch f64",
        toff64,
        next_u64x2,
        0.0f64
    );
    table_batch!(
        "projected cap straddling batch f32",
        scap32,
        next_u32x2,
        0.0f32
    );
    table_batch!(
        "projected cap straddling batch f64",
        scap64,
        next_u64x2,
        0.0f64
    );
    table_batch!(
        "disk solid angle tabulated batch f32",
        table32,
        next_u32x2,
        0.0f32
    );
    table_batch!(
        "disk solid angle tabulated batch f64",
        table64,
        next_u64x2,
        0.0f64
    );
    g.finish();
}

/// Preparing a sampler for one shading point (f64), next to the samplers
/// they replace; throughput 1 element = one preparation.
fn setup(c: &mut Criterion) {
    let s = scenes();
    let mut g = c.benchmark_group("projected-setup");
    g.throughput(Throughput::Elements(1));
    let [a, b, cc] = s.triangle;
    let [r0, r1, _, r3] = s.rectangle;
    let (dc, dn, dr) = s.disk;
    let sphere = g64::Sphere::new(s.sphere_center, 1.0).unwrap();
    let straddling = g64::Sphere::new(s.straddling_center, 1.0).unwrap();
    let (triangle, square) = (poly64(&s.triangle), poly64(&s.offset_square));
    let disk = g64::Disk::new(dc, dn, dr).unwrap();
    g.bench_function("sphere solid angle f64", |bch| {
        bch.iter(|| s64::SphereSolidAngle::new(black_box(DVec3::ZERO), &sphere))
    });
    g.bench_function("projected sphere f64", |bch| {
        bch.iter(|| s64::ProjectedSphere::new(black_box(DVec3::ZERO), DVec3::Z, &sphere))
    });
    g.bench_function("projected sphere straddling f64", |bch| {
        bch.iter(|| s64::ProjectedSphere::new(black_box(DVec3::ZERO), DVec3::Z, &straddling))
    });
    g.bench_function("spherical triangle f64", |bch| {
        bch.iter(|| s64::SphericalTriangle::new(DVec3::ZERO, black_box(a), b, cc))
    });
    g.bench_function("projected triangle f64", |bch| {
        bch.iter(|| s64::ProjectedPolygon::new(black_box(DVec3::ZERO), DVec3::Z, &triangle))
    });
    g.bench_function("spherical rectangle f64", |bch| {
        bch.iter(|| s64::SphericalRectangle::new(DVec3::ZERO, black_box(r0), r1 - r0, r3 - r0))
    });
    g.bench_function("projected square (non-central) f64", |bch| {
        bch.iter(|| s64::ProjectedPolygon::new(black_box(DVec3::ZERO), DVec3::Z, &square))
    });
    g.bench_function("projected square (non-central) tabulated f64", |bch| {
        bch.iter(|| {
            s64::TabulatedProjectedPolygon::new(
                s64::ProjectedPolygon::new(black_box(DVec3::ZERO), DVec3::Z, &square).unwrap(),
            )
        })
    });
    g.bench_function("disk solid angle f64", |bch| {
        bch.iter(|| s64::DiskSolidAngle::new(black_box(DVec3::ZERO), &disk))
    });
    g.bench_function("disk solid angle tabulated f64", |bch| {
        bch.iter(|| {
            s64::TabulatedDiskSolidAngle::new(
                s64::DiskSolidAngle::new(black_box(DVec3::ZERO), &disk).unwrap(),
            )
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
        targets = sampling, setup
    }
}
criterion_main!(group::benches);
