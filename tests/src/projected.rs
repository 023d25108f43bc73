//! The hard cases of the projected-solid-angle samplers (caps, spheres,
//! polygons) and of solid-angle sampling of disks, each buildable in either
//! precision behind [`DirectionWarp`], with densities written independently
//! of the samplers for the chi-square tests: cos θ/Ω⊥ with Ω⊥ from the
//! estimator crate's closed forms (Snyder's cap formula, Lambert's polygon
//! formula), 1/Ω for disks with Ω from a quadrature written here, and
//! supports tested by plain geometry (angle to the axis, ray–plane hits).

use glam::{DVec2, DVec3};
use lambert_geometry::f64::{ConvexPolygon, Sphere};
use lambert_light::analytic::{
    cap_projected_solid_angle, polygon_irradiance, sphere_irradiance, Emission,
};
use lambert_light::Receiver;
use lambert_sampling::f64::DirectionSample;
use lambert_validate::catalog::{DirectionWarp, Precision};

/// A light as the samplers take it.
#[derive(Clone, Debug)]
pub enum Shape {
    /// A cap of directions about a unit `axis` in the receiver's local frame
    /// (+z the normal), with 1 − cos θmax = `h`.
    Cap {
        /// Unit axis.
        axis: DVec3,
        /// 1 − cos θmax.
        h: f64,
    },
    /// A sphere seen from `p` with unit normal `n`.
    Sphere {
        /// Receiver point.
        p: DVec3,
        /// Receiver normal (unit).
        n: DVec3,
        /// Center.
        c: DVec3,
        /// Radius.
        r: f64,
    },
    /// A convex planar polygon seen from `p` with unit normal `n`.
    Polygon {
        /// Receiver point.
        p: DVec3,
        /// Receiver normal (unit).
        n: DVec3,
        /// Vertices in order.
        vertices: Vec<DVec3>,
    },
    /// A disk seen from `p` (uniform in solid angle: no normal needed).
    Disk {
        /// Receiver point.
        p: DVec3,
        /// Center.
        c: DVec3,
        /// Disk normal.
        normal: DVec3,
        /// Radius.
        r: f64,
    },
}

/// A named hard case.
#[derive(Clone, Debug)]
pub struct Case {
    /// Label for messages.
    pub label: String,
    /// The light.
    pub shape: Shape,
    /// Whether f32 resolves the light (angular size ≳ 1e-4 rad off the
    /// axes); f32 must still give finite samples of positive pdf elsewhere.
    pub f32_resolvable: bool,
}

/// 1 − cos θ for half-angle θ, without cancellation.
pub fn one_minus_cos(theta: f64) -> f64 {
    let s = (0.5 * theta).sin();
    2.0 * s * s
}

fn cap(label: &str, theta_m: f64, gamma: f64) -> Case {
    Case {
        label: label.into(),
        shape: Shape::Cap {
            axis: DVec3::new(gamma.sin(), 0.0, gamma.cos()),
            h: one_minus_cos(theta_m),
        },
        f32_resolvable: theta_m >= 1e-3,
    }
}

fn polygon(label: &str, p: DVec3, n: DVec3, vertices: Vec<DVec3>, resolvable: bool) -> Case {
    Case {
        label: label.into(),
        shape: Shape::Polygon {
            p,
            n: n.normalize(),
            vertices,
        },
        f32_resolvable: resolvable,
    }
}

fn disk(label: &str, p: DVec3, c: DVec3, normal: DVec3, r: f64, resolvable: bool) -> Case {
    Case {
        label: label.into(),
        shape: Shape::Disk { p, c, normal, r },
        f32_resolvable: resolvable,
    }
}

/// Every hard case: caps from 1e-8 rad to the whole sky, above, touching,
/// straddling and peeking above the horizon; spheres seen from tilted,
/// offset receivers; polygons central and not, clipped, grazing, huge,
/// tiny, far, with the zenith on an edge or a vertex; disks coaxial,
/// tilted, close, nearly edge-on, tiny, huge, seen from under the rim.
pub fn cases() -> Vec<Case> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let mut out = vec![
        cap("cap 1e-8 rad overhead", 1e-8, 0.0),
        cap("cap 1e-8 rad on the horizon", 1e-8, FRAC_PI_2),
        cap("cap 1e-3 rad tilted", 1e-3, 1.0),
        cap("cap 1e-3 rad straddling", 1e-3, FRAC_PI_2 - 2e-4),
        cap("cap 0.3 rad above", 0.3, 0.8),
        cap("cap 0.3 rad touching", 0.3, FRAC_PI_2 - 0.3),
        cap("cap 0.3 rad straddling above", 0.3, FRAC_PI_2 - 0.15),
        cap("cap 0.3 rad straddling below", 0.3, FRAC_PI_2 + 0.15),
        cap("cap 0.3 rad peeking", 0.3, FRAC_PI_2 + 0.25),
        cap("cap near a hemisphere", FRAC_PI_2 - 1e-4, 0.3),
        cap("sky cap 2 rad round the zenith", 2.0, 0.5),
        cap("sky cap 2.5 rad, complement above", 2.5, 3.0),
        cap("whole sky", PI, 0.7),
    ];
    let tilt = DVec3::new(0.3, -0.2, 1.0).normalize();
    let p = DVec3::new(0.2, 0.1, -0.3);
    for (label, c, r, resolvable) in [
        ("sphere overhead", p + tilt * 4.0, 1.0, true),
        (
            "sphere straddling",
            p + DVec3::new(3.0, 1.0, 0.1),
            1.0,
            true,
        ),
        // f32 cannot hold the 1e-9 gap: the point rounds onto the sphere.
        (
            "sphere nearly touching",
            p + tilt * (1.0 + 1e-9),
            1.0,
            false,
        ),
        (
            "sphere tilted 1 rad",
            p + (tilt * 1f64.cos() + DVec3::new(1.0, 0.0, -0.3).normalize() * 1f64.sin()) * 3.0,
            1.0,
            true,
        ),
        ("sphere 1e6 away", p + DVec3::new(1e6, 0.0, 5e5), 1.0, false),
    ] {
        out.push(Case {
            label: label.into(),
            shape: Shape::Sphere { p, n: tilt, c, r },
            f32_resolvable: resolvable,
        });
    }
    let z = DVec3::Z;
    let o = DVec3::ZERO;
    out.extend([
        polygon(
            "square overhead (central)",
            o,
            z,
            vec![
                DVec3::new(-0.5, -0.5, 1.0),
                DVec3::new(0.5, -0.5, 1.0),
                DVec3::new(0.5, 0.5, 1.0),
                DVec3::new(-0.5, 0.5, 1.0),
            ],
            true,
        ),
        polygon(
            "square offset",
            o,
            z,
            vec![
                DVec3::new(0.5, -0.5, 1.0),
                DVec3::new(1.5, -0.5, 1.0),
                DVec3::new(1.5, 0.5, 1.0),
                DVec3::new(0.5, 0.5, 1.0),
            ],
            true,
        ),
        polygon(
            "triangle tilted receiver",
            DVec3::new(0.1, 0.2, -0.1),
            DVec3::new(0.4, -0.3, 1.0),
            vec![
                DVec3::new(-1.0, -1.0, 3.0),
                DVec3::new(2.0, -0.5, 3.5),
                DVec3::new(0.0, 1.5, 2.5),
            ],
            true,
        ),
        polygon(
            "wall straddling the horizon",
            o,
            z,
            vec![
                DVec3::new(2.0, -1.0, -1.0),
                DVec3::new(2.0, 1.0, -1.0),
                DVec3::new(2.0, 1.0, 1.0),
                DVec3::new(2.0, -1.0, 1.0),
            ],
            true,
        ),
        polygon(
            "grazing triangle",
            o,
            z,
            vec![
                DVec3::new(1.0, 0.0, 0.05),
                DVec3::new(3.0, 0.0, 0.01),
                DVec3::new(2.0, 1.0, 0.2),
            ],
            true,
        ),
        polygon(
            "huge triangle",
            o,
            z,
            vec![
                DVec3::new(-100.0, -100.0, 0.5),
                DVec3::new(100.0, -100.0, 0.5),
                DVec3::new(0.0, 150.0, 0.5),
            ],
            true,
        ),
        polygon(
            "zenith on an edge",
            o,
            z,
            vec![
                DVec3::new(-1.0, 0.0, 1.0),
                DVec3::new(1.0, 0.0, 1.0),
                DVec3::new(0.0, 1.0, 1.0),
            ],
            true,
        ),
        polygon(
            "zenith at a vertex",
            o,
            z,
            vec![
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(1.0, 0.0, 1.0),
                DVec3::new(0.0, 1.0, 1.0),
            ],
            true,
        ),
        polygon(
            "pentagon tilted",
            o,
            z,
            (0..5)
                .map(|k| {
                    let a = k as f64 * 0.4 * PI;
                    DVec3::new(
                        0.8 + 0.5 * a.cos(),
                        0.3 + 0.5 * a.sin(),
                        1.0 + 0.2 * a.cos(),
                    )
                })
                .collect(),
            true,
        ),
        polygon(
            "sliver",
            o,
            z,
            vec![
                DVec3::new(-1.0, 0.3, 2.0),
                DVec3::new(1.0, 0.3, 2.0),
                DVec3::new(0.0, 0.301, 2.0),
            ],
            true,
        ),
        polygon(
            "small (3e-4 rad)",
            DVec3::new(0.1, -0.2, 0.05),
            DVec3::new(0.1, 0.2, 1.0),
            vec![
                DVec3::new(2.0, 0.75, 2.5),
                DVec3::new(2.001, 0.75, 2.5002),
                DVec3::new(2.0003, 0.751, 2.4999),
            ],
            true,
        ),
        polygon(
            "tiny (1e-6 rad)",
            o,
            DVec3::new(0.1, 0.2, 1.0),
            vec![
                DVec3::new(2.0, 0.75, 2.5),
                DVec3::new(2.000003, 0.75, 2.5000006),
                DVec3::new(2.000001, 0.750003, 2.4999997),
            ],
            false,
        ),
        polygon(
            "square 1e6 away",
            o,
            z,
            vec![
                DVec3::new(1e6, 0.0, 5e5),
                DVec3::new(1e6 + 1.0, 0.0, 5e5),
                DVec3::new(1e6 + 1.0, 1.0, 5e5),
                DVec3::new(1e6, 1.0, 5e5),
            ],
            false,
        ),
        disk("disk coaxial", o, DVec3::new(0.0, 0.0, 2.0), -z, 0.5, true),
        disk(
            "disk tilted",
            o,
            DVec3::new(1.0, 0.5, 2.0),
            DVec3::new(0.3, -1.0, 0.4),
            0.7,
            true,
        ),
        disk(
            "disk receiver close under it",
            o,
            DVec3::new(0.2, 0.1, 1e-3),
            z,
            1.0,
            true,
        ),
        disk(
            "disk receiver under its rim",
            o,
            DVec3::new(1.0, 0.0, 1e-2),
            z,
            1.0,
            true,
        ),
        disk(
            "disk nearly edge-on",
            o,
            DVec3::new(2.0, 0.0, 1e-4),
            z,
            1.0,
            true,
        ),
        disk("disk tiny", o, DVec3::new(1.0, 2.0, 2.0), z, 1e-6, false),
        disk("disk huge", o, DVec3::new(0.5, 0.0, 1.0), z, 1e3, true),
        disk(
            "disk crossing the receiver's plane",
            o,
            DVec3::new(2.0, 0.0, 0.2),
            DVec3::new(1.0, 0.0, 0.3),
            0.8,
            true,
        ),
    ]);
    out
}

/// The unit normal that cos θ is measured from (the local +z for caps).
pub fn receiver_normal(shape: &Shape) -> Option<DVec3> {
    match shape {
        Shape::Cap { .. } => Some(DVec3::Z),
        Shape::Sphere { n, .. } | Shape::Polygon { n, .. } => Some(*n),
        Shape::Disk { .. } => None,
    }
}

/// The normaliser of the density, independently of the samplers: Ω⊥ from
/// the estimator crate's closed forms (caps, spheres: Snyder's formula;
/// polygons: Lambert's), Ω for disks from [`disk_solid_angle`].
pub fn normaliser(shape: &Shape) -> f64 {
    match shape {
        Shape::Cap { axis, h } => {
            cap_projected_solid_angle(axis.z, (h * (2.0 - h)).sqrt(), 1.0 - h)
        }
        Shape::Sphere { p, n, c, r } => sphere_irradiance(
            &Sphere::new(*c, *r).unwrap(),
            1.0,
            &Receiver::new(*p, *n).unwrap(),
        )
        .unwrap(),
        Shape::Polygon { p, n, vertices } => two_sided_projected_solid_angle(*p, *n, vertices),
        Shape::Disk { p, c, normal, r } => disk_solid_angle(*p, *c, *normal, *r),
    }
}

/// Ω⊥ of a two-sided convex polygon above the horizon of (`p`, `n`), by
/// Lambert's formula after clipping (the light crate's closed form).
pub fn two_sided_projected_solid_angle(p: DVec3, n: DVec3, vertices: &[DVec3]) -> f64 {
    polygon_irradiance(
        &ConvexPolygon::new(vertices.to_vec()).unwrap(),
        Emission::TwoSided,
        1.0,
        &Receiver::new(p, n).unwrap(),
    )
    .unwrap()
}

/// The solid angle of a disk seen from `p`, by the trapezoidal rule in the
/// disk's polar angle ψ (exponentially convergent for this smooth periodic
/// integrand) of the closed-form radial integral. For a receiver at height
/// h and offset ρ, with b = ρ cos ψ, c = h² + ρ², Δ = c − b² and
/// Q = R² + 2bR + c, Ω = h ∫₀^{2π} [√c − (bR + c)/√Q]/Δ dψ, whose integrand
/// is rewritten without cancellation (cQ − (bR + c)² = R²Δ) as
/// R²/(√Q (√(cQ) + bR + c)), or (√(cQ) − bR − c)/(√Q Δ) when bR + c < 0.
/// Q is formed as (R + b)² + Δ. Checked against mpmath at 40 digits:
/// 5.4173184501234460686e-5 ("nearly edge-on"), 0.18760020439596728171
/// (coaxial), 3.0747468915964972703 ("under its rim").
pub fn disk_solid_angle(p: DVec3, center: DVec3, normal: DVec3, r: f64) -> f64 {
    let n = normal.normalize();
    let v = center - p;
    let h = n.dot(v).abs();
    let rho = (v - n * n.dot(v)).length();
    let steps = 1 << 16;
    // Neumaier-compensated sum (65536 terms would otherwise lose ~1e-12).
    let (mut sum, mut carry) = (0.0f64, 0.0f64);
    for i in 0..steps {
        let psi = std::f64::consts::TAU * (i as f64 + 0.5) / steps as f64;
        let b = rho * psi.cos();
        let c = h * h + rho * rho;
        let delta = h * h + (rho * psi.sin()).powi(2);
        // Q = (R + b)² + Δ: no cancellation when the rim passes over p.
        let q = (r + b) * (r + b) + delta;
        let (sq, scq) = (q.sqrt(), (c * q).sqrt());
        let near = b * r + c;
        let term = if near >= 0.0 {
            r * r / (sq * (scq + near))
        } else {
            (scq - near) / (sq * delta)
        };
        let t = sum + term;
        carry += if sum.abs() >= term.abs() {
            (sum - t) + term
        } else {
            (term - t) + sum
        };
        sum = t;
    }
    h * (sum + carry) * std::f64::consts::TAU / steps as f64
}

/// Whether the unit direction `w` (world, or local for caps) lies in the
/// light's support, by plain geometry (no sampler code): the angle to the
/// cap's axis, the ray from p hitting the polygon or disk; plus cos θ > 0
/// for the projected densities.
pub fn in_support(shape: &Shape, w: DVec3) -> bool {
    match shape {
        Shape::Cap { axis, h } => w.z > 0.0 && 0.5 * (w - *axis).length_squared() <= *h,
        Shape::Sphere { p, n, c, r } => {
            let d = (*c - *p).length();
            let a = (*c - *p) / d;
            let s2 = (r / d) * (r / d);
            let h = s2 / (1.0 + (1.0 - s2).sqrt());
            n.dot(w) > 0.0 && 0.5 * (w - a).length_squared() <= h
        }
        Shape::Polygon { p, n, vertices } => {
            if n.dot(w) <= 0.0 {
                return false;
            }
            let e = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
            let t = e.dot(vertices[0] - *p) / e.dot(w);
            if !(t > 0.0) {
                return false;
            }
            let x = *p + w * t;
            let k = vertices.len();
            let side = (0..k).map(|i| {
                let (a, b) = (vertices[i], vertices[(i + 1) % k]);
                (b - a).cross(x - a).dot(e)
            });
            let signs: Vec<f64> = side.collect();
            signs.iter().all(|&s| s >= 0.0) || signs.iter().all(|&s| s <= 0.0)
        }
        Shape::Disk { p, c, normal, r } => {
            let n = normal.normalize();
            let t = n.dot(*c - *p) / n.dot(w);
            t > 0.0 && ((*p + w * t) - *c).length() <= *r
        }
    }
}

/// The density each sampler must have, written independently: cos θ/Ω⊥ on
/// the support for the projected samplers, 1/Ω for disks.
pub fn reference_density(shape: &Shape) -> impl Fn(DVec3) -> f64 + '_ {
    let norm = normaliser(shape);
    let normal = receiver_normal(shape);
    move |w| {
        if !in_support(shape, w) {
            return 0.0;
        }
        match normal {
            Some(n) => n.dot(w) / norm,
            None => 1.0 / norm,
        }
    }
}

/// A bounding cap of the support (axis, 1 − cos), for binning: the cap
/// itself widened 2 % for caps and spheres, the smallest cap about the mean vertex or
/// rim direction for polygons and disks (widened 2 %), or `None` when that
/// exceeds a hemisphere.
pub fn bounding_cap(shape: &Shape) -> Option<(DVec3, f64)> {
    let cap_of = |dirs: &[DVec3]| {
        let axis = dirs.iter().copied().sum::<DVec3>().normalize();
        let h = dirs
            .iter()
            .map(|d| 0.5 * (*d - axis).length_squared())
            .fold(0.0, f64::max)
            * 1.02;
        (h < 1.0).then_some((axis, h))
    };
    match shape {
        // Widened 2 % so that samples in the samplers' rounding band beyond
        // the rim (a few ε rad: 2e-6 rad in f32) fall in the last row.
        Shape::Cap { axis, h } => (*h <= 1.0).then_some((*axis, *h * 1.02)),
        Shape::Sphere { p, c, r, .. } => {
            let d = (*c - *p).length();
            let s2 = (r / d) * (r / d);
            Some(((*c - *p) / d, 1.02 * s2 / (1.0 + (1.0 - s2).sqrt())))
        }
        Shape::Polygon { p, vertices, .. } => {
            let dirs: Vec<DVec3> = vertices.iter().map(|v| (*v - *p).normalize()).collect();
            cap_of(&dirs)
        }
        Shape::Disk { p, c, normal, r } => {
            let (x, y) = normal.normalize().any_orthonormal_pair();
            let dirs: Vec<DVec3> = (0..256)
                .map(|k| {
                    let phi = std::f64::consts::TAU * k as f64 / 256.0;
                    (*c + (x * phi.cos() + y * phi.sin()) * *r - *p).normalize()
                })
                .collect();
            cap_of(&dirs)
        }
    }
}

/// A partition of a polygon's or a disk's support into cells of exactly
/// known probability, for `ChiSquareTest::run_partition`: the cell
/// probabilities, and the cell a unit direction falls in (`None` outside the
/// light by more than 1e-9 of its size).
pub struct Partition {
    /// Probability of each cell.
    pub probabilities: Vec<f64>,
    /// The cell of a direction from the receiver.
    pub locate: Box<dyn Fn(DVec3) -> Option<usize>>,
}

/// Cells per side: each fan triangle of a polygon is cut into K² barycentric
/// sub-triangles, a disk into K rings of equal area × 2K sectors.
pub const PARTITION_SIDE: usize = 8;

/// The partition of a polygon (fan triangles from vertex 0, each cut into
/// K² sub-triangles) or a disk (K rings × 2K sectors), with probabilities
/// from closed forms that share no code with the samplers: Lambert's
/// formula (`polygon_irradiance`, which clips each cell at the horizon) for
/// the projected density; for the disk's uniform density, each cell's solid
/// angle by the radial closed form of [`disk_solid_angle`] integrated over
/// the cell's polar angle by 16-point Gauss–Legendre on 16 sub-intervals.
/// `None` for caps and spheres (binned within their cap instead).
///
/// Samples outside the light by less than `slack` (relative to its size:
/// the precision's rounding, 16ε over the light's narrowest angular width —
/// a fan triangle's height over its distance, a disk's foreshortened
/// radius — plus 1e-9 for the f64 ray intersection) are put in the nearest
/// cell.
pub fn partition(shape: &Shape, precision: Precision) -> Option<Partition> {
    let k = PARTITION_SIDE;
    let eps = match precision {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let width = match shape {
        Shape::Polygon { p, vertices, .. } => (1..vertices.len() - 1)
            .map(|t| {
                let (a, b, c) = (vertices[0], vertices[t], vertices[t + 1]);
                let longest = (b - a).length().max((c - b).length()).max((a - c).length());
                let height = (b - a).cross(c - a).length() / longest;
                height / ((a + b + c) / 3.0 - *p).length()
            })
            .fold(f64::INFINITY, f64::min),
        _ => angular_size(shape),
    };
    let slack = 16.0 * eps / width + 1e-9;
    match shape {
        Shape::Polygon { p, n, vertices } => {
            let (p, n) = (*p, *n);
            let mut cells: Vec<[DVec3; 3]> = Vec::new();
            for t in 1..vertices.len() - 1 {
                let (a, b, c) = (vertices[0], vertices[t], vertices[t + 1]);
                let point = |i: usize, j: usize| {
                    a + (b - a) * (i as f64 / k as f64) + (c - a) * (j as f64 / k as f64)
                };
                for i in 0..k {
                    for j in 0..k - i {
                        cells.push([point(i, j), point(i + 1, j), point(i, j + 1)]);
                        if i + j + 2 <= k {
                            cells.push([point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)]);
                        }
                    }
                }
            }
            let weights: Vec<f64> = cells
                .iter()
                .map(|t| two_sided_projected_solid_angle(p, n, t))
                .collect();
            let total: f64 = weights.iter().sum();
            let vertices = vertices.clone();
            let locate = move |w: DVec3| {
                let e = (vertices[1] - vertices[0]).cross(vertices[2] - vertices[0]);
                let t = e.dot(vertices[0] - p) / e.dot(w);
                if !(t > 0.0) {
                    return None;
                }
                let x = p + w * t;
                let mut base = 0;
                let per = k * k;
                for f in 1..vertices.len() - 1 {
                    let (a, b, c) = (vertices[0], vertices[f], vertices[f + 1]);
                    // Barycentric (s, t) of x in (a, b, c), least squares.
                    let (e0, e1, d) = (b - a, c - a, x - a);
                    let (aa, ab, bb) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
                    let (r0, r1) = (d.dot(e0), d.dot(e1));
                    let det = aa * bb - ab * ab;
                    let s = (bb * r0 - ab * r1) / det;
                    let u = (aa * r1 - ab * r0) / det;
                    if s >= -slack && u >= -slack && s + u <= 1.0 + slack {
                        let (mut s, mut u) = (s.max(0.0) * k as f64, u.max(0.0) * k as f64);
                        if s + u > k as f64 {
                            let scale = k as f64 / (s + u);
                            s *= scale;
                            u *= scale;
                        }
                        let i = (s as usize).min(k - 1);
                        let j = (u as usize).min(k - 1 - i);
                        let upper = i + j + 1 < k && (s - i as f64) + (u - j as f64) >= 1.0;
                        // Index in the order the cells were pushed.
                        let mut index = 0;
                        for ii in 0..i {
                            index += 2 * (k - ii) - 1;
                        }
                        index += 2 * j + usize::from(upper);
                        return Some(base + index);
                    }
                    base += per;
                }
                None
            };
            Some(Partition {
                probabilities: weights.iter().map(|w| w / total).collect(),
                locate: Box::new(locate),
            })
        }
        Shape::Disk { p, c, normal, r } => {
            let (p, c, r) = (*p, *c, *r);
            let n = normal.normalize();
            let (x, y) = n.any_orthonormal_pair();
            let v = c - p;
            let h = n.dot(v).abs();
            // The disk's center is `offset` (in the plane) from the foot of
            // p's perpendicular, so a point at polar angle ψ and radius R′
            // about the center is at distance² ρ² + R′² + 2ρR′ cos(ψ − ψ_ρ)
            // from the foot, ψ_ρ the offset's polar angle.
            let offset = v - n * n.dot(v);
            let rho = offset.length();
            let psi_rho = offset.dot(y).atan2(offset.dot(x));
            let sectors = 2 * k;
            // ∫ over ψ ∈ [ψ0, ψ1] of the radial integral from R0 to R1.
            let radial = |radius: f64, psi: f64| {
                let b = rho * (psi - psi_rho).cos();
                let cc = h * h + rho * rho;
                let delta = h * h + (rho * (psi - psi_rho).sin()).powi(2);
                let q = (radius + b) * (radius + b) + delta;
                let (sq, scq) = (q.sqrt(), (cc * q).sqrt());
                let near = b * radius + cc;
                if near >= 0.0 {
                    radius * radius / (sq * (scq + near))
                } else {
                    (scq - near) / (sq * delta)
                }
            };
            let (nodes, gl_weights) = gauss_legendre_16();
            let mut probabilities = Vec::with_capacity(k * sectors);
            for ring in 0..k {
                let (r0, r1) = (
                    r * (ring as f64 / k as f64).sqrt(),
                    r * ((ring + 1) as f64 / k as f64).sqrt(),
                );
                for sector in 0..sectors {
                    let (a0, a1) = (
                        std::f64::consts::TAU * sector as f64 / sectors as f64,
                        std::f64::consts::TAU * (sector + 1) as f64 / sectors as f64,
                    );
                    let mut sum = 0.0;
                    let pieces = 16;
                    for piece in 0..pieces {
                        let lo = a0 + (a1 - a0) * piece as f64 / pieces as f64;
                        let hi = a0 + (a1 - a0) * (piece + 1) as f64 / pieces as f64;
                        for (t, wgt) in nodes.iter().zip(&gl_weights) {
                            let psi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * t;
                            let inner = if r0 > 0.0 { radial(r0, psi) } else { 0.0 };
                            sum += 0.5 * (hi - lo) * wgt * (radial(r1, psi) - inner);
                        }
                    }
                    probabilities.push(h * sum);
                }
            }
            let total: f64 = probabilities.iter().sum();
            for q in probabilities.iter_mut() {
                *q /= total;
            }
            let locate = move |w: DVec3| {
                let t = n.dot(c - p) / n.dot(w);
                if !(t > 0.0) {
                    return None;
                }
                let d = p + w * t - c;
                let rr = (d.dot(x).powi(2) + d.dot(y).powi(2)) / (r * r);
                if rr > 1.0 + 2.0 * slack {
                    return None;
                }
                let ring = ((rr.min(1.0) * k as f64) as usize).min(k - 1);
                let phi = d.dot(y).atan2(d.dot(x)).rem_euclid(std::f64::consts::TAU);
                let sector =
                    ((phi / std::f64::consts::TAU * sectors as f64) as usize).min(sectors - 1);
                Some(ring * sectors + sector)
            };
            Some(Partition {
                probabilities,
                locate: Box::new(locate),
            })
        }
        _ => None,
    }
}

/// Nodes and weights of 16-point Gauss–Legendre quadrature on [−1, 1]
/// (Golub–Welsch values, symmetric pairs).
fn gauss_legendre_16() -> ([f64; 16], [f64; 16]) {
    let half = [
        (0.095_012_509_837_637_44, 0.189_450_610_455_068_5),
        (0.281_603_550_779_258_9, 0.182_603_415_044_923_6),
        (0.458_016_777_657_227_4, 0.169_156_519_395_002_5),
        (0.617_876_244_402_643_7, 0.149_595_988_816_576_7),
        (0.755_404_408_355_003, 0.124_628_971_255_533_9),
        (0.865_631_202_387_831_7, 0.095_158_511_682_492_78),
        (0.944_575_023_073_232_6, 0.062_253_523_938_647_89),
        (0.989_400_934_991_649_9, 0.027_152_459_411_754_09),
    ];
    let (mut nodes, mut weights) = ([0.0; 16], [0.0; 16]);
    for (i, &(x, w)) in half.iter().enumerate() {
        nodes[2 * i] = x;
        nodes[2 * i + 1] = -x;
        weights[2 * i] = w;
        weights[2 * i + 1] = w;
    }
    (nodes, weights)
}

/// The angular size of the support (rad, roughly), which bounds how
/// precisely a direction can be placed in it: sin θmax for caps and
/// spheres, √Ω-like for polygons and disks.
pub fn angular_size(shape: &Shape) -> f64 {
    match shape {
        Shape::Cap { h, .. } if *h >= 1.0 => 1.0,
        Shape::Cap { h, .. } => (h * (2.0 - h)).sqrt(),
        Shape::Sphere { p, c, r, .. } => r / (*c - *p).length(),
        Shape::Polygon { p, vertices, .. } => {
            let dirs: Vec<DVec3> = vertices.iter().map(|v| (*v - *p).normalize()).collect();
            let mut size: f64 = 0.0;
            for a in &dirs {
                for b in &dirs {
                    size = size.max((*a - *b).length());
                }
            }
            size
        }
        Shape::Disk { p, c, normal, r } => {
            let v = *c - *p;
            let cos = normal.normalize().dot(v).abs() / v.length();
            r * cos.max(1e-300) / v.length()
        }
    }
}

/// The samplers of one precision behind [`DirectionWarp`] (inputs rounded
/// to the precision once, outputs widened to f64).
macro_rules! wrappers {
    ($m:ident, $v2:ty, $v3:ty, $real:ty) => {
        mod $m {
            use super::*;
            use lambert_sampling::$m as s;

            pub enum Warp {
                Cap(s::ProjectedCap),
                Sphere(Box<s::ProjectedSphere>),
                Polygon(Box<s::ProjectedPolygon>),
                Disk(s::DiskSolidAngle),
            }

            fn narrow(v: DVec3) -> $v3 {
                <$v3>::new(v.x as $real, v.y as $real, v.z as $real)
            }

            pub fn build(shape: &Shape) -> Result<Warp, lambert_sampling::SamplingError> {
                use lambert_geometry::$m::{ConvexPolygon, Disk, Sphere};
                Ok(match shape {
                    Shape::Cap { axis, h } => {
                        Warp::Cap(s::ProjectedCap::new(narrow(*axis), *h as $real)?)
                    }
                    Shape::Sphere { p, n, c, r } => {
                        Warp::Sphere(Box::new(s::ProjectedSphere::new(
                            narrow(*p),
                            narrow(*n),
                            &Sphere::new(narrow(*c), *r as $real)?,
                        )?))
                    }
                    Shape::Polygon { p, n, vertices } => {
                        let v: Vec<$v3> = vertices.iter().map(|v| narrow(*v)).collect();
                        Warp::Polygon(Box::new(s::ProjectedPolygon::new(
                            narrow(*p),
                            narrow(*n),
                            &ConvexPolygon::new(v)?,
                        )?))
                    }
                    Shape::Disk { p, c, normal, r } => Warp::Disk(s::DiskSolidAngle::new(
                        narrow(*p),
                        &Disk::new(narrow(*c), narrow(*normal), *r as $real)?,
                    )?),
                })
            }

            #[allow(clippy::unnecessary_cast)]
            impl DirectionWarp for Warp {
                fn sample(&self, u: DVec2) -> DirectionSample {
                    let u = <$v2>::new(u.x as $real, u.y as $real);
                    let (w, pdf) = match self {
                        Warp::Cap(c) => {
                            let d = c.sample(u);
                            (d.direction, d.pdf)
                        }
                        Warp::Sphere(c) => {
                            let d = c.sample(u);
                            (d.direction, d.pdf)
                        }
                        Warp::Polygon(c) => {
                            let d = c.sample(u);
                            (d.direction, d.pdf)
                        }
                        Warp::Disk(c) => {
                            let d = c.sample(u);
                            (d.direction, d.pdf)
                        }
                    };
                    DirectionSample {
                        direction: DVec3::new(w.x as f64, w.y as f64, w.z as f64),
                        pdf: pdf as f64,
                    }
                }

                fn pdf(&self, w: DVec3) -> f64 {
                    let w = narrow(w);
                    (match self {
                        Warp::Cap(c) => c.pdf(w),
                        Warp::Sphere(c) => c.pdf(w),
                        Warp::Polygon(c) => c.pdf(w),
                        Warp::Disk(c) => c.pdf(w),
                    }) as f64
                }

                fn invert(&self, w: DVec3) -> DVec2 {
                    let w = narrow(w);
                    let u = match self {
                        Warp::Cap(c) => c.invert(w),
                        Warp::Sphere(c) => c.invert(w),
                        Warp::Polygon(c) => c.invert(w),
                        Warp::Disk(c) => c.invert(w),
                    };
                    DVec2::new(u.x as f64, u.y as f64)
                }
            }
        }
    };
}

wrappers!(f64, glam::DVec2, glam::DVec3, f64);
wrappers!(f32, glam::Vec2, glam::Vec3, f32);

/// The sampler for `shape` in `precision`, behind [`DirectionWarp`]
/// (world directions; local for caps).
pub fn build(
    shape: &Shape,
    precision: Precision,
) -> Result<Box<dyn DirectionWarp>, lambert_sampling::SamplingError> {
    Ok(match precision {
        Precision::F64 => Box::new(f64::build(shape)?),
        Precision::F32 => Box::new(f32::build(shape)?),
    })
}

#[cfg(test)]
mod tests {
    /// The 16-point Gauss–Legendre rule integrates polynomials of degree
    /// ≤ 31 exactly: its weights sum to 2 and ∫x³⁰ = 2/31.
    #[test]
    fn gauss_legendre_is_exact_to_degree_31() {
        let (x, w) = super::gauss_legendre_16();
        let sum: f64 = w.iter().sum();
        assert!((sum - 2.0).abs() < 1e-15);
        let m30: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(30)).sum();
        assert!((m30 - 2.0 / 31.0).abs() < 1e-15, "{m30}");
    }
}
