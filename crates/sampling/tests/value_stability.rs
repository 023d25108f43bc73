//! Value stability: every warp and light sampler, in both precisions, maps a
//! fixed set of u to fixed bits. An optimisation (reordered arithmetic, a
//! vectorised path, a different polynomial) that changes any output by even
//! one ulp fails here, so it cannot change results unnoticed; a deliberate
//! change updates the table below and says why in its commit.
//!
//! Each warp is run on a 17 × 17 grid of u ∈ [0, 1]² (edges included) and
//! the bits of every output (direction, density, point, distance) are folded
//! into one FNV-1a hash per warp and precision. Run with
//! `LAMBERT_PRINT_HASHES=1 cargo test -p lambert-sampling --test
//! value_stability -- --nocapture` to print the table.

use std::collections::BTreeMap;

/// FNV-1a over 64-bit words.
#[derive(Clone, Copy)]
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// Folds the bits of f64 or f32 values into the hash.
trait Bits {
    fn bits(self) -> u64;
}
impl Bits for f64 {
    fn bits(self) -> u64 {
        self.to_bits()
    }
}
impl Bits for f32 {
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
}

/// The warps of one precision, hashed.
macro_rules! hashes {
    ($p:ident, $v2:ident, $v3:ident) => {{
        use glam::{$v2 as V2, $v3 as V3};
        use lambert_geometry::$p::{ConvexPolygon, Disk, Parallelogram, Sphere, Triangle};
        use lambert_sampling::$p::*;

        let grid: Vec<V2> = (0..=16)
            .flat_map(|i| (0..=16).map(move |j| V2::new(i as _, j as _) / 16.0))
            .collect();
        let mut out: BTreeMap<String, u64> = BTreeMap::new();
        let mut run = |name: &str, f: &mut dyn FnMut(V2, &mut Vec<u64>)| {
            let mut h = Fnv::new();
            let mut words = Vec::new();
            for &u in &grid {
                words.clear();
                f(u, &mut words);
                for &w in &words {
                    h.word(w);
                }
            }
            out.insert(format!("{}/{}", stringify!($p), name), h.0);
        };
        let v3 = |w: &mut Vec<u64>, v: V3| w.extend([v.x.bits(), v.y.bits(), v.z.bits()]);
        let v2 = |w: &mut Vec<u64>, v: V2| w.extend([v.x.bits(), v.y.bits()]);

        run("uniform_hemisphere", &mut |u, w| {
            v3(w, sample_uniform_hemisphere(u))
        });
        run("cosine_hemisphere", &mut |u, w| {
            v3(w, sample_cosine_hemisphere(u))
        });
        run("uniform_sphere", &mut |u, w| {
            v3(w, sample_uniform_sphere(u))
        });
        run("concentric_disk", &mut |u, w| {
            v2(w, sample_concentric_disk(u))
        });
        run("uniform_disk", &mut |u, w| v2(w, sample_uniform_disk(u)));
        run("sin_cos_2pi", &mut |u, w| {
            let (s, c) = sin_cos_2pi(u.x);
            w.extend([s.bits(), c.bits()]);
        });
        for theta in [1e-5, 0.3, 2.5] {
            let cone = UniformCone::from_theta_max(theta).unwrap();
            run(&format!("uniform_cone({theta})"), &mut |u, w| {
                let d = cone.sample(u);
                v3(w, d);
                w.push(cone.pdf(d).bits());
                v2(w, cone.invert(d));
            });
        }
        let sphere = Sphere::new(V3::new(5.0, 0.0, 8.660254), 1.0).unwrap();
        let cone = SphereSolidAngle::new(V3::ZERO, &sphere).unwrap();
        run("sphere_solid_angle", &mut |u, w| {
            let s = cone.sample(u);
            v3(w, s.direction);
            v3(w, s.point);
            w.extend([s.pdf.bits(), s.distance.bits()]);
        });
        let (a, b, c) = (
            V3::new(-1.0, -1.0, 2.0),
            V3::new(0.0, 1.5, 2.5),
            V3::new(2.0, -0.5, 2.2),
        );
        let spherical = SphericalTriangle::new(V3::ZERO, a, b, c).unwrap();
        run("spherical_triangle", &mut |u, w| {
            let d = spherical.sample(u);
            v3(w, d.direction);
            w.push(d.pdf.bits());
            v2(w, spherical.invert(d.direction));
        });
        let (corner, e0, e1) = (
            V3::new(3.0, -1.0, 0.05),
            V3::new(0.0, 0.0, 1.0),
            V3::new(0.0, 2.0, 0.0),
        );
        let rect = SphericalRectangle::new(V3::ZERO, corner, e0, e1).unwrap();
        run("spherical_rectangle", &mut |u, w| {
            let s = rect.sample_point(u);
            v3(w, s.direction);
            v3(w, s.point);
            w.extend([s.pdf.bits(), s.distance.bits()]);
            v2(w, rect.invert(s.direction));
        });
        let triangle = Triangle::new(a, b, c).unwrap();
        let area = UniformTriangle::new(&triangle);
        run("triangle_area", &mut |u, w| {
            let s = area.sample(u);
            v3(w, s.point);
            w.push(s.pdf_area.bits());
            v2(w, area.invert(s.point));
        });
        let disk = Disk::new(V3::new(0.6, 0.2, 0.3), V3::new(0.1, -0.2, -1.0), 0.5).unwrap();
        let disk_area = UniformDiskArea::new(&disk);
        run("disk_area", &mut |u, w| {
            let s = disk_area.sample(u);
            v3(w, s.point);
            w.push(s.pdf_area.bits());
            v2(w, disk_area.invert(s.point));
        });
        let quad = Parallelogram::new(corner, e0, e1 + V3::new(0.0, 0.0, 0.3)).unwrap();
        let quad_area = UniformParallelogram::new(&quad);
        run("parallelogram_area", &mut |u, w| {
            let s = quad_area.sample(u);
            v3(w, s.point);
            w.push(s.pdf_area.bits());
        });
        // Projected-solid-angle samplers: a cap above, straddling with its
        // axis above and with it below the horizon (the three regions).
        for (name, axis) in [
            ("projected_cap(above)", V3::new(0.6, 0.0, 0.8)),
            ("projected_cap(straddling above)", V3::new(0.8, 0.36, 0.1)),
            ("projected_cap(straddling below)", V3::new(0.9, 0.0, -0.1)),
        ] {
            let cap = ProjectedCap::new(axis, 0.1).unwrap();
            run(name, &mut |u, w| {
                let d = cap.sample(u);
                v3(w, d.direction);
                w.push(d.pdf.bits());
                v2(w, cap.invert(d.direction));
            });
        }
        let (pr, nr) = (V3::new(0.1, 0.2, 0.3), V3::new(0.2, -0.1, 1.0).normalize());
        let projected_sphere = ProjectedSphere::new(pr, nr, &sphere).unwrap();
        run("projected_sphere", &mut |u, w| {
            let s = projected_sphere.sample(u);
            v3(w, s.direction);
            v3(w, s.point);
            w.extend([s.pdf.bits(), s.distance.bits()]);
            v2(w, projected_sphere.invert(s.direction));
        });
        for (name, dx) in [("central", 0.0), ("non-central", 1.0)] {
            let square = ConvexPolygon::new(vec![
                V3::new(dx - 0.5, -0.5, 1.0),
                V3::new(dx + 0.5, -0.5, 1.0),
                V3::new(dx + 0.5, 0.5, 1.0),
                V3::new(dx - 0.5, 0.5, 1.0),
            ])
            .unwrap();
            let sampler = ProjectedPolygon::new(V3::ZERO, V3::Z, &square).unwrap();
            run(&format!("projected_polygon({name})"), &mut |u, w| {
                let s = sampler.sample(u);
                v3(w, s.direction);
                v3(w, s.point);
                w.extend([s.pdf.bits(), s.distance.bits()]);
                v2(w, sampler.invert(s.direction));
            });
        }
        let disk_solid_angle = DiskSolidAngle::new(V3::ZERO, &disk).unwrap();
        run("disk_solid_angle", &mut |u, w| {
            let s = disk_solid_angle.sample(u);
            v3(w, s.direction);
            v3(w, s.point);
            w.extend([s.pdf.bits(), s.distance.bits()]);
            v2(w, disk_solid_angle.invert(s.direction));
        });
        // Its tabulated form (whose batch form's own test compares the
        // batch with it, bit for bit).
        let table = TabulatedDiskSolidAngle::new(disk_solid_angle);
        run("disk_solid_angle_table", &mut |u, w| {
            let s = table.sample(u);
            v3(w, s.direction);
            w.push(s.pdf.bits());
        });
        let hexagon: Vec<V3> = (0..6)
            .map(|k| {
                let t = k as f64 * std::f64::consts::PI / 3.0;
                V3::new(t.cos() as _, t.sin() as _, 2.0)
            })
            .collect();
        let polygon = ConvexPolygon::new(hexagon).unwrap();
        let (p, n) = (V3::new(0.1, 0.2, 0.0), V3::Z);
        let lights: Vec<(&str, Box<dyn LightSampler>)> = vec![
            ("sphere_light", Box::new(SphereLightSampler::new(sphere))),
            (
                "triangle_light",
                Box::new(TriangleLightSampler::new(triangle)),
            ),
            (
                "polygon_light",
                Box::new(PolygonLightSampler::new(polygon.clone()).unwrap()),
            ),
            ("sphere_area", Box::new(SphereAreaSampler::new(sphere))),
            (
                "projected_sphere_light",
                Box::new(ProjectedSphereSampler::new(sphere)),
            ),
            (
                "projected_polygon_light",
                Box::new(ProjectedPolygonSampler::new(polygon.clone())),
            ),
            ("disk_light", Box::new(DiskLightSampler::new(disk))),
            ("disk_area_light", Box::new(DiskAreaSampler::new(disk))),
            (
                "triangle_area_light",
                Box::new(TriangleAreaSampler::new(triangle)),
            ),
            (
                "polygon_area_light",
                Box::new(PolygonAreaSampler::new(polygon)),
            ),
        ];
        for (name, light) in &lights {
            run(name, &mut |u, w| match light.sample(p, n, u) {
                Some(s) => {
                    v3(w, s.direction);
                    v3(w, s.point);
                    w.extend([s.pdf.bits(), s.distance.bits()]);
                    w.push(light.pdf(p, n, s.direction).bits());
                }
                None => w.push(0xdead),
            });
        }
        out
    }};
}

/// The hashes of this commit's warps (see the module docs).
///
/// Changed on purpose: the spherical triangle and rectangle warps (and the
/// triangle and polygon light samplers built on them) take their sines from
/// `sin_cos` (a Cody–Waite reduction and the warps' own polynomials) rather
/// than libm, so that the estimator's batch kernels inline and vectorise
/// them; the outputs moved by an ulp or so, and no longer depend on the
/// platform's libm. Changed on purpose again: the concentric map (the
/// concentric disk, the cosine hemisphere, disk area sampling, and the
/// projected cap and sphere, which draw their disk points through it) takes
/// the sine and cosine of its angle (π/4)t from polynomials in t
/// (`sin_cos_eighth`) instead of Taylor series at the rounded (π/4)t: the
/// outputs moved by an ulp or two, closer to the exact ones (see
/// `trig.rs`).
const EXPECTED: &[(&str, u64)] = &[
    ("f32/concentric_disk", 0x2b88e2359060800d),
    ("f32/cosine_hemisphere", 0xde9a8a901d92ba30),
    ("f32/disk_area", 0x3f3f942eb0952f46),
    ("f32/disk_area_light", 0x928309affd0c062e),
    ("f32/disk_light", 0x970fac7a65b8bdc8),
    ("f32/disk_solid_angle", 0x2e1aa6f557314583),
    ("f32/disk_solid_angle_table", 0x391071356261e023),
    ("f32/parallelogram_area", 0xd1417b47dc5947d0),
    ("f32/polygon_area_light", 0xd3be571cbd23d44c),
    ("f32/polygon_light", 0x14c93da074557b43),
    ("f32/projected_cap(above)", 0x029f0e848246e4c7),
    ("f32/projected_cap(straddling above)", 0xce490bf65fb116a6),
    ("f32/projected_cap(straddling below)", 0x79e025ecfd016f81),
    ("f32/projected_polygon(central)", 0x45b548d411e8c3c3),
    ("f32/projected_polygon(non-central)", 0x2718818938b86104),
    ("f32/projected_polygon_light", 0x72109ef584a615d7),
    ("f32/projected_sphere", 0x766b955384874f5e),
    ("f32/projected_sphere_light", 0x47bf669b578cc9dc),
    ("f32/sin_cos_2pi", 0x5c30d5d8051ab590),
    ("f32/sphere_area", 0x6b7293e577c36fca),
    ("f32/sphere_light", 0x1484d807b6224230),
    ("f32/sphere_solid_angle", 0x04f1663058e6e67c),
    ("f32/spherical_rectangle", 0xc348fb630da3807b),
    ("f32/spherical_triangle", 0xb8164c8314b5e8f7),
    ("f32/triangle_area", 0xd690981ef772c0fe),
    ("f32/triangle_area_light", 0xeab2e3e3d7a0cfef),
    ("f32/triangle_light", 0x00e438952e6c1c84),
    ("f32/uniform_cone(0.00001)", 0x1743da2db5f888d1),
    ("f32/uniform_cone(0.3)", 0xff7a3a8768805694),
    ("f32/uniform_cone(2.5)", 0xf4bfe47c6aae1f59),
    ("f32/uniform_disk", 0x32177c1edd765354),
    ("f32/uniform_hemisphere", 0x31e0f985e4a40e95),
    ("f32/uniform_sphere", 0x0b9019dc15d289dc),
    ("f64/concentric_disk", 0xe4455669b5752d2d),
    ("f64/cosine_hemisphere", 0x14325446afe0d8c8),
    ("f64/disk_area", 0x062be151cbc57ad2),
    ("f64/disk_area_light", 0x6d03c308ae4b5448),
    ("f64/disk_light", 0x11ced86573913df9),
    ("f64/disk_solid_angle", 0xd95e2f3c60193ff3),
    ("f64/disk_solid_angle_table", 0x09ccbbaf24100c24),
    ("f64/parallelogram_area", 0x12c9cfd2eec84658),
    ("f64/polygon_area_light", 0x060b0c4dce5847eb),
    ("f64/polygon_light", 0x748d46b113ee480f),
    ("f64/projected_cap(above)", 0xc1c90068398ecfdc),
    ("f64/projected_cap(straddling above)", 0x38488fa7f49d85d8),
    ("f64/projected_cap(straddling below)", 0xd4a745c0f2e32669),
    ("f64/projected_polygon(central)", 0x50421265095f4198),
    // Changed when the sectors' arc corrections moved from libm's atan2 to
    // `atan2` (branch-free, within 3 ulps; the same bits on every machine).
    ("f64/projected_polygon(non-central)", 0x5ef5441b68228bc0),
    ("f64/projected_polygon_light", 0xd653b3aef3109106),
    ("f64/projected_sphere", 0xd81a32a440afbab2),
    ("f64/projected_sphere_light", 0xf666d431704cd54c),
    ("f64/sin_cos_2pi", 0x170b059a0fe54d38),
    ("f64/sphere_area", 0x89c5846079f59c9a),
    ("f64/sphere_light", 0x877dc3da59aa59a1),
    ("f64/sphere_solid_angle", 0x5e8e0cd8ede21cfc),
    ("f64/spherical_rectangle", 0xe7863cdd054d175d),
    ("f64/spherical_triangle", 0x0cc8887ae16eefdc),
    ("f64/triangle_area", 0xa0b5c186e6c500d0),
    ("f64/triangle_area_light", 0xf85f772c07755598),
    ("f64/triangle_light", 0xe44413ded7977dc4),
    ("f64/uniform_cone(0.00001)", 0x4afd16783e340c48),
    ("f64/uniform_cone(0.3)", 0xee011e1b51f29771),
    ("f64/uniform_cone(2.5)", 0x3f13a2af371233c3),
    ("f64/uniform_disk", 0xf9e432666a0d86cd),
    ("f64/uniform_hemisphere", 0xdb9e51f566f630bf),
    ("f64/uniform_sphere", 0x25f474cd7b16b884),
];

#[test]
fn every_warp_gives_the_same_bits() {
    let mut actual = hashes!(f64, DVec2, DVec3);
    actual.extend(hashes!(f32, Vec2, Vec3));
    if std::env::var_os("LAMBERT_PRINT_HASHES").is_some() {
        for (name, h) in &actual {
            println!("    (\"{name}\", 0x{h:016x}),");
        }
    }
    let expected: BTreeMap<String, u64> = EXPECTED
        .iter()
        .map(|&(name, h)| (name.to_string(), h))
        .collect();
    let changed: Vec<&String> = actual
        .iter()
        .filter(|(name, h)| expected.get(*name) != Some(h))
        .map(|(name, _)| name)
        .collect();
    assert!(
        changed.is_empty() && expected.len() == actual.len(),
        "values changed for {changed:?} ({} expected, {} computed)",
        expected.len(),
        actual.len()
    );
}
