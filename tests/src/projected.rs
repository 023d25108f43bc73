//! The hard cases of the projected-solid-angle samplers (caps, spheres,
//! polygons) and of solid-angle sampling of disks, each buildable in either
//! precision behind [`DirectionWarp`], with densities written independently
//! of the samplers for the chi-square tests: cos θ/Ω⊥ with Ω⊥ from the
//! estimator crate's closed forms (Snyder's cap formula, Lambert's polygon
//! formula), 1/Ω for disks with Ω from a quadrature written here, and
//! supports tested by plain geometry (angle to the axis, ray–plane hits).

use glam::{DVec2, DVec3};
use lambert_estimator::analytic::{
    cap_projected_solid_angle, polygon_irradiance, sphere_irradiance, Emission,
};
use lambert_sampling::catalog::{DirectionWarp, Precision};
use lambert_sampling::f64::DirectionSample;

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
        ("sphere nearly touching", p + tilt * (1.0 + 1e-9), 1.0, true),
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
        Shape::Sphere { p, n, c, r } => sphere_irradiance(1.0, *p, *n, *c, *r).unwrap(),
        Shape::Polygon { p, n, vertices } => {
            polygon_irradiance(1.0, *p, *n, vertices, Emission::TwoSided).unwrap()
        }
        Shape::Disk { p, c, normal, r } => disk_solid_angle(*p, *c, *normal, *r),
    }
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
/// itself for caps and spheres, the smallest cap about the mean vertex or
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
        Shape::Cap { axis, h } => (*h <= 1.0).then_some((*axis, *h)),
        Shape::Sphere { p, c, r, .. } => {
            let d = (*c - *p).length();
            let s2 = (r / d) * (r / d);
            Some(((*c - *p) / d, s2 / (1.0 + (1.0 - s2).sqrt())))
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
                Sphere(s::ProjectedSphere),
                Polygon(Box<s::ProjectedPolygon>),
                Disk(s::DiskSolidAngle),
            }

            fn narrow(v: DVec3) -> $v3 {
                <$v3>::new(v.x as $real, v.y as $real, v.z as $real)
            }

            pub fn build(shape: &Shape) -> Result<Warp, lambert_sampling::SamplingError> {
                Ok(match shape {
                    Shape::Cap { axis, h } => {
                        Warp::Cap(s::ProjectedCap::new(narrow(*axis), *h as $real)?)
                    }
                    Shape::Sphere { p, n, c, r } => Warp::Sphere(s::ProjectedSphere::new(
                        narrow(*p),
                        narrow(*n),
                        narrow(*c),
                        *r as $real,
                    )?),
                    Shape::Polygon { p, n, vertices } => {
                        let v: Vec<$v3> = vertices.iter().map(|v| narrow(*v)).collect();
                        Warp::Polygon(Box::new(s::ProjectedPolygon::new(
                            narrow(*p),
                            narrow(*n),
                            &v,
                        )?))
                    }
                    Shape::Disk { p, c, normal, r } => Warp::Disk(s::DiskSolidAngle::new(
                        narrow(*p),
                        narrow(*c),
                        narrow(*normal),
                        *r as $real,
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
