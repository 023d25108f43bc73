//! The built-in validation suite of direction warps: every warp of the
//! sampling crate's catalogue at ordinary and hard parameters, with the
//! binning or exact partition each is tested on. Used by `lambert validate`
//! and by the `lambert-tests` suites.
//!
//! Smooth densities (hemispheres, spheres, cones, sphere lights) are binned
//! in equal-solid-angle cells ([`binning_for`]) with the pdf integrated per
//! cell; densities uniform on a sharp-edged support (spherical polygons,
//! area-sampled shapes) are tested on an exact partition of the support
//! ([`partition_for`]), whose cell probabilities are closed-form solid
//! angles or areas, because equal-solid-angle cells cut such supports and
//! leave the quadrature an indicator function to integrate (measured: on a
//! sliver triangle that bias alone failed the test).

use crate::catalog::{DirectionWarp, DirectionWarpSpec, Precision};
use glam::DVec3;
use lambert_sampling::sequence::{Independent, SampleSequence};

use crate::{Binning, ChiSquareOutcome, ChiSquareTest, Integral};

/// A named warp configuration that the suite exercises.
#[derive(Clone, Debug)]
pub struct Case {
    /// Short label for messages.
    pub label: &'static str,
    /// The warp and its parameters.
    pub spec: DirectionWarpSpec,
    /// Whether the case is within f32's reach: an f32 unit vector off the
    /// coordinate axes is located only to ~1.6e-7 rad, so lights smaller
    /// than ~1e-5 rad off-axis are tested in f64 alone (f32 still must give
    /// finite unit samples of positive pdf there).
    pub f32_resolvable: bool,
}

/// 1 − cos θ for a cone of half-angle `theta`, without cancellation.
pub fn one_minus_cos(theta: f64) -> f64 {
    let s = (0.5 * theta).sin();
    2.0 * s * s
}

/// Every direction warp at ordinary and hard parameters: cones from 1e-8 rad
/// to π, spheres overhead, tilted, tiny and far, nearly touching, grazing.
pub fn direction_cases() -> Vec<Case> {
    let mut cases = vec![
        Case {
            f32_resolvable: true,
            label: "uniform hemisphere",
            spec: DirectionWarpSpec::UniformHemisphere,
        },
        Case {
            f32_resolvable: true,
            label: "cosine hemisphere",
            spec: DirectionWarpSpec::CosineHemisphere,
        },
        Case {
            f32_resolvable: true,
            label: "uniform sphere",
            spec: DirectionWarpSpec::UniformSphere,
        },
    ];
    for (label, theta) in [
        ("cone 1e-8 rad", 1e-8),
        ("cone 1e-6 rad", 1e-6),
        ("cone 1e-3 rad", 1e-3),
        ("cone 1 rad", 1.0),
        ("cone 3 rad", 3.0),
        ("cone pi rad", std::f64::consts::PI),
    ] {
        cases.push(Case {
            f32_resolvable: true,
            label,
            spec: DirectionWarpSpec::UniformCone {
                one_minus_cos_theta_max: one_minus_cos(theta),
            },
        });
    }
    let tilt = 30f64.to_radians();
    for (label, center, radius) in [
        ("sphere overhead", DVec3::new(0.0, 0.0, 10.0), 1.0),
        (
            "sphere tilted 30 deg",
            DVec3::new(10.0 * tilt.sin(), 0.0, 10.0 * tilt.cos()),
            1.0,
        ),
        ("sphere tiny and far", DVec3::new(0.0, 0.0, 1e6), 1.0),
        (
            "sphere nearly touching",
            DVec3::new(0.3, -0.2, 1.0 + 1e-9),
            1.0,
        ),
        ("sphere grazing", DVec3::new(5.0, 3.0, 0.01), 0.5),
    ] {
        cases.push(Case {
            f32_resolvable: true,
            label,
            spec: DirectionWarpSpec::SphereLight { center, radius },
        });
    }
    let tri = [
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(2.0, -0.5, 3.5),
        DVec3::new(0.0, 1.5, 2.5),
    ];
    cases.extend([
        Case {
            f32_resolvable: true,
            label: "sph. triangle",
            spec: DirectionWarpSpec::SphericalTriangle { vertices: tri },
        },
        Case {
            f32_resolvable: false,
            label: "sph. triangle tiny",
            // ~1e-4 × 1e-4 at distance 3: Ω ≈ 6e-10 sr.
            spec: DirectionWarpSpec::SphericalTriangle {
                vertices: [
                    DVec3::new(0.5, 0.2, 3.0),
                    DVec3::new(0.5001, 0.2, 3.0),
                    DVec3::new(0.5, 0.2001, 3.00005),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. triangle small",
            // ~2e-3 across at distance 3 (≈ 7e-4 rad): Ω ≈ 2e-7 sr, small
            // but within f32's reach.
            spec: DirectionWarpSpec::SphericalTriangle {
                vertices: [
                    DVec3::new(0.5, 0.2, 3.0),
                    DVec3::new(0.502, 0.2, 3.0),
                    DVec3::new(0.5, 0.202, 3.001),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. triangle sliver",
            spec: DirectionWarpSpec::SphericalTriangle {
                vertices: [
                    DVec3::new(-1.0, 0.0, 2.0),
                    DVec3::new(1.0, 0.0, 2.0),
                    DVec3::new(0.0, 0.001, 2.0),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. triangle huge",
            // Nearly a hemisphere: a large triangle just above the origin.
            spec: DirectionWarpSpec::SphericalTriangle {
                vertices: [
                    DVec3::new(-100.0, -100.0, 0.5),
                    DVec3::new(100.0, -100.0, 0.5),
                    DVec3::new(0.0, 150.0, 0.5),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. triangle grazing",
            spec: DirectionWarpSpec::SphericalTriangle {
                vertices: [
                    DVec3::new(1.0, 0.0, 0.05),
                    DVec3::new(3.0, 0.0, 0.01),
                    DVec3::new(2.0, 1.0, 0.2),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. rectangle",
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(-0.5, -0.3, 2.0),
                edge0: DVec3::new(1.0, 0.0, 0.0),
                edge1: DVec3::new(0.0, 0.8, 0.0),
            },
        },
        Case {
            f32_resolvable: false,
            label: "sph. rectangle tiny",
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(0.3, -0.2, 2.0),
                edge0: DVec3::new(1e-4, 0.0, 0.0),
                edge1: DVec3::new(0.0, 2e-4, 0.0),
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. rectangle small",
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(0.3, -0.2, 2.0),
                edge0: DVec3::new(2e-3, 0.0, 0.0),
                edge1: DVec3::new(0.0, 3e-3, 0.0),
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. rectangle sliver",
            // 2 × 0.001 at distance 2: aspect 2000.
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(-1.0, 0.3, 2.0),
                edge0: DVec3::new(2.0, 0.0, 0.0),
                edge1: DVec3::new(0.0, 0.001, 0.0),
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. rectangle huge",
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(-50.0, -50.0, 0.5),
                edge0: DVec3::new(100.0, 0.0, 0.0),
                edge1: DVec3::new(0.0, 100.0, 0.0),
            },
        },
        Case {
            f32_resolvable: true,
            label: "sph. rectangle grazing",
            // A wall-like rectangle seen almost edge-on, tilted.
            spec: DirectionWarpSpec::SphericalRectangle {
                corner: DVec3::new(1.0, -1.0, 0.02),
                edge0: DVec3::new(0.0, 2.0, 0.0),
                edge1: DVec3::new(3.0, 0.0, 0.3).normalize() * 0.5,
            },
        },
        Case {
            f32_resolvable: true,
            label: "triangle area",
            spec: DirectionWarpSpec::TriangleArea {
                vertices: [
                    DVec3::new(-1.0, -1.0, 3.0),
                    DVec3::new(2.0, -0.5, 3.5),
                    DVec3::new(0.0, 1.5, 2.5),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "triangle area grazing",
            spec: DirectionWarpSpec::TriangleArea {
                vertices: [
                    DVec3::new(1.0, 0.0, 0.05),
                    DVec3::new(3.0, 0.0, 0.01),
                    DVec3::new(2.0, 1.0, 0.2),
                ],
            },
        },
        Case {
            f32_resolvable: true,
            label: "disk area coaxial",
            spec: DirectionWarpSpec::DiskArea {
                center: DVec3::new(0.0, 0.0, 2.0),
                normal: DVec3::new(0.0, 0.0, -1.0),
                radius: 0.5,
            },
        },
        Case {
            f32_resolvable: true,
            label: "disk area tilted",
            spec: DirectionWarpSpec::DiskArea {
                center: DVec3::new(1.0, 0.5, 2.0),
                normal: DVec3::new(0.3, -1.0, 0.4),
                radius: 0.7,
            },
        },
        Case {
            f32_resolvable: true,
            label: "parallelogram area",
            spec: DirectionWarpSpec::ParallelogramArea {
                corner: DVec3::new(-0.5, -0.5, 1.0),
                edge0: DVec3::new(1.0, 0.0, 0.2),
                edge1: DVec3::new(0.3, 1.0, 0.0),
            },
        },
    ]);
    cases
}

/// Samples per chi-square test in the warp suites (and in their negative
/// controls, which must be rejected at this same count).
pub const CHI_SQUARE_SAMPLES: u64 = 1_000_000;

/// The binning the suites use for a warp: 64 rows × 4 sectors of equal
/// solid angle inside its bounding cap, or 20 × 40 over the sphere.
///
/// Many rows because the errors that matter most for caps and lights are
/// radial (a wrong cos θmax): moving a cap's rim by a fraction δ of its
/// solid angle raises X² by λ ≈ n δ² (R + 1) for R rows, so with n = 1e6
/// and R = 64 a 0.25 % error gives λ ≈ 406, against a 1 % critical excess
/// of about 2.33·√(2·255) ≈ 53. Expected counts are ≳ 3900 per fully
/// occupied cell, far above the pooling threshold of 5.
pub fn binning_for(spec: &DirectionWarpSpec) -> Binning {
    match spec.bounding_cap() {
        Some(cap) => Binning::Cap {
            axis: cap.axis,
            one_minus_cos_max: cap.one_minus_cos,
            theta_bins: 64,
            phi_bins: 4,
        },
        None => Binning::Sphere {
            theta_bins: 20,
            phi_bins: 40,
        },
    }
}

/// Draws `samples` directions from `warp` (sample i from the independent
/// sequence's stream i for `seed`; 24-bit uniforms for f32) and runs the
/// chi-square test against `pdf` at level `alpha`.
pub fn chi_square(
    warp: &dyn DirectionWarp,
    precision: Precision,
    binning: Binning,
    pdf: impl FnMut(DVec3) -> f64,
    samples: u64,
    seed: u64,
    alpha: f64,
) -> ChiSquareOutcome {
    let mut sequence = Independent::new(seed);
    let sample = |i: u64| {
        sequence.start_sample(i);
        let u = match precision {
            Precision::F32 => sequence.next_2d_f32().as_dvec2(),
            Precision::F64 => sequence.next_2d(),
        };
        warp.sample(u).direction
    };
    ChiSquareTest::new(binning)
        .samples(samples)
        .significance(alpha)
        .run(sample, pdf)
        .expect("the suite's chi-square configuration is valid")
}

/// A partition of a warp's support into cells of exactly known probability,
/// for [`ChiSquareTest::run_partition`](super::ChiSquareTest::run_partition).
pub struct Partition {
    /// Probability of each cell under the warp's density.
    pub probabilities: Vec<f64>,
    /// The cell a unit direction (seen from the origin) falls in; `None`
    /// when it is outside the support by more than rounding (see
    /// [`partition_for`]).
    pub locate: Box<dyn Fn(DVec3) -> Option<usize> + Sync>,
    /// The shape of each cell on the light's plane (same order as
    /// `probabilities`), to integrate a density over it
    /// ([`PartitionCell::integrate_solid_angle`]).
    pub cells: Vec<PartitionCell>,
}

/// The planar shape of one partition cell; the cell of directions is the
/// shape seen from the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PartitionCell {
    /// The triangle with these vertices.
    Triangle([DVec3; 3]),
    /// The parallelogram `corner + a·edge0 + b·edge1`, a, b ∈ [0, 1].
    Parallelogram {
        /// A corner.
        corner: DVec3,
        /// The first edge from it.
        edge0: DVec3,
        /// The second edge from it.
        edge1: DVec3,
    },
    /// The part of a disk with (r/R)² ∈ [s₀, s₁] and polar angle φ ∈ [φ₀, φ₁]
    /// about `center` in the orthonormal in-plane axes `x`, `y`.
    RingSector {
        /// The disk's center.
        center: DVec3,
        /// In-plane axis at φ = 0.
        x: DVec3,
        /// In-plane axis at φ = π/2.
        y: DVec3,
        /// The disk's radius R.
        radius: f64,
        /// The range of (r/R)².
        rho2: (f64, f64),
        /// The range of φ, radians.
        phi: (f64, f64),
    },
}

impl PartitionCell {
    /// The point at parameters (a, b) ∈ [0, 1]², and the area element
    /// dA/(da db) there: a Duffy map for triangles (p = A + a(B − A) +
    /// ab(C − B), dA = a·|(B − A) × (C − B)| da db, smooth on the square),
    /// the affine map for parallelograms, and (r/R)², φ linear in a, b for
    /// ring sectors (dA = ½R² ds dφ).
    fn point(&self, a: f64, b: f64) -> (DVec3, f64) {
        match *self {
            PartitionCell::Triangle([p0, p1, p2]) => {
                let e = p1 - p0;
                let f = p2 - p1;
                (p0 + e * a + f * (a * b), a * e.cross(f).length())
            }
            PartitionCell::Parallelogram {
                corner,
                edge0,
                edge1,
            } => (corner + edge0 * a + edge1 * b, edge0.cross(edge1).length()),
            PartitionCell::RingSector {
                center,
                x,
                y,
                radius,
                rho2: (s0, s1),
                phi: (f0, f1),
            } => {
                let s = s0 + (s1 - s0) * a;
                let phi = f0 + (f1 - f0) * b;
                let r = radius * s.sqrt();
                let (sin, cos) = phi.sin_cos();
                (
                    center + (x * cos + y * sin) * r,
                    0.5 * radius * radius * (s1 - s0) * (f1 - f0),
                )
            }
        }
    }

    /// The unit normal of the cell's plane (either orientation).
    fn normal(&self) -> DVec3 {
        match *self {
            PartitionCell::Triangle([p0, p1, p2]) => (p1 - p0).cross(p2 - p0).normalize(),
            PartitionCell::Parallelogram { edge0, edge1, .. } => edge0.cross(edge1).normalize(),
            PartitionCell::RingSector { x, y, .. } => x.cross(y).normalize(),
        }
    }

    /// ∫ f(ω) dω over the directions in which the origin sees the cell,
    /// computed on the plane as ∫ f(p/|p|) |n·p|/|p|³ dA (dω = cos θₗ dA/d²)
    /// by the adaptive Gauss quadrature of [`crate::quadrature`] for smooth
    /// integrands, to the relative error `relative_tolerance`, with at most
    /// `max_splits` splits. `f` is evaluated only at interior points of the
    /// cell, so a density smooth on the support (uniform, or uniform in area
    /// converted to solid angle) is integrated without meeting its edges.
    pub fn integrate_solid_angle(
        &self,
        mut f: impl FnMut(DVec3) -> f64,
        relative_tolerance: f64,
        max_splits: usize,
    ) -> Integral {
        let n = self.normal();
        let integrand = |a: f64, b: f64| {
            let (p, jacobian) = self.point(a, b);
            let d2 = p.length_squared();
            let d = d2.sqrt();
            f(p / d) * n.dot(p).abs() / (d2 * d) * jacobian
        };
        crate::quadrature::integrate_smooth(
            integrand,
            (0.0, 1.0),
            (0.0, 1.0),
            |value| relative_tolerance * value.abs() + f64::MIN_POSITIVE,
            max_splits,
        )
    }
}

/// Subdivisions per side of the partitions (16² = 256 cells, ≈ 3900
/// expected samples per cell at [`CHI_SQUARE_SAMPLES`]).
pub const PARTITION_SIDE: usize = 16;

/// Parameters (s, t) of `p` in the plane through `origin` spanned by
/// `e0`, `e1`: p − origin = s e0 + t e1 (least squares, exact in-plane).
fn plane_parameters(p: DVec3, origin: DVec3, e0: DVec3, e1: DVec3) -> (f64, f64) {
    let d = p - origin;
    let (a, b, c) = (e0.dot(e0), e0.dot(e1), e1.dot(e1));
    let (r0, r1) = (d.dot(e0), d.dot(e1));
    let det = a * c - b * b;
    ((c * r0 - b * r1) / det, (a * r1 - b * r0) / det)
}

/// Where the ray from the origin along `w` meets the plane through `on`
/// with normal `n`, if in front.
fn hit(w: DVec3, on: DVec3, n: DVec3) -> Option<DVec3> {
    let t = n.dot(on) / n.dot(w);
    (t > 0.0 && t.is_finite()).then(|| w * t)
}

/// The partition of a triangle (a, b, c) into K² sub-triangles of its
/// barycentric grid; `weight` gives each sub-triangle's unnormalised
/// probability from its three vertices.
fn triangle_partition(
    a: DVec3,
    b: DVec3,
    c: DVec3,
    slack: f64,
    weight: impl Fn(DVec3, DVec3, DVec3) -> f64,
) -> Partition {
    let k = PARTITION_SIDE;
    let point =
        |i: usize, j: usize| a + (b - a) * (i as f64 / k as f64) + (c - a) * (j as f64 / k as f64);
    // lower(i, j) for i + j ≤ k − 1 and upper(i, j) for i + j ≤ k − 2.
    let mut index = vec![[usize::MAX; 2]; k * k];
    let mut weights = Vec::new();
    let mut cells = Vec::new();
    for i in 0..k {
        for j in 0..k - i {
            index[i * k + j][0] = weights.len();
            let lower = [point(i, j), point(i + 1, j), point(i, j + 1)];
            weights.push(weight(lower[0], lower[1], lower[2]));
            cells.push(PartitionCell::Triangle(lower));
            if i + j + 2 <= k {
                index[i * k + j][1] = weights.len();
                let upper = [point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)];
                weights.push(weight(upper[0], upper[1], upper[2]));
                cells.push(PartitionCell::Triangle(upper));
            }
        }
    }
    let total: f64 = weights.iter().sum();
    let n = (b - a).cross(c - a);
    let locate = move |w: DVec3| {
        let p = hit(w, a, n)?;
        let (s, t) = plane_parameters(p, a, b - a, c - a);
        if s < -slack || t < -slack || s + t > 1.0 + slack {
            return None;
        }
        let (mut s, mut t) = (s.max(0.0) * k as f64, t.max(0.0) * k as f64);
        if s + t > k as f64 {
            let scale = k as f64 / (s + t);
            s *= scale;
            t *= scale;
        }
        let i = (s as usize).min(k - 1);
        let j = (t as usize).min(k - 1 - i);
        let upper = i + j + 1 < k && (s - i as f64) + (t - j as f64) >= 1.0;
        Some(index[i * k + j][usize::from(upper)])
    };
    Partition {
        probabilities: weights.iter().map(|w| w / total).collect(),
        locate: Box::new(locate),
        cells,
    }
}

/// The partition of a parallelogram (corner, e0, e1) into K × K
/// sub-parallelograms; `weight` gives each one's unnormalised probability
/// from its four corners (in order around it).
fn parallelogram_partition(
    corner: DVec3,
    e0: DVec3,
    e1: DVec3,
    slack: f64,
    weight: impl Fn([DVec3; 4]) -> f64,
) -> Partition {
    let k = PARTITION_SIDE;
    let point =
        |i: usize, j: usize| corner + e0 * (i as f64 / k as f64) + e1 * (j as f64 / k as f64);
    let mut weights = Vec::with_capacity(k * k);
    let mut cells = Vec::with_capacity(k * k);
    for i in 0..k {
        for j in 0..k {
            weights.push(weight([
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ]));
            cells.push(PartitionCell::Parallelogram {
                corner: point(i, j),
                edge0: e0 / k as f64,
                edge1: e1 / k as f64,
            });
        }
    }
    let total: f64 = weights.iter().sum();
    let n = e0.cross(e1);
    let locate = move |w: DVec3| {
        let p = hit(w, corner, n)?;
        let (s, t) = plane_parameters(p, corner, e0, e1);
        let inside = |x: f64| (-slack..=1.0 + slack).contains(&x);
        if !inside(s) || !inside(t) {
            return None;
        }
        let cell = |x: f64| ((x.clamp(0.0, 1.0) * k as f64) as usize).min(k - 1);
        Some(cell(s) * k + cell(t))
    };
    Partition {
        probabilities: weights.iter().map(|w| w / total).collect(),
        locate: Box::new(locate),
        cells,
    }
}

/// Solid angle of the planar triangle (a, b, c) seen from the origin.
fn solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    lambert_geometry::f64::triangle_solid_angle(DVec3::ZERO, a, b, c)
}

/// The exact partition of the warp's support, for the warps whose density
/// is uniform on a sharp-edged support (spherical polygons by solid angle;
/// area-sampled shapes by area); `None` for the others, which are binned in
/// equal-solid-angle cells.
///
/// Samples outside the shape by less than the rounding of `precision` are
/// binned in the edge cell: a unit vector carries ~8ε of absolute angular
/// error, which is 8ε/√Ω of the shape's parameters (√Ω its angular size);
/// we allow twice that, plus 1e-9 for the f64 ray intersection.
pub fn partition_for(spec: &DirectionWarpSpec, precision: Precision) -> Option<Partition> {
    let half_area = |a: DVec3, b: DVec3, c: DVec3| (b - a).cross(c - a).length();
    let eps = match precision {
        Precision::F32 => f32::EPSILON as f64,
        Precision::F64 => f64::EPSILON,
    };
    let slack_for = |omega: f64| 16.0 * eps / omega.sqrt() + 1e-9;
    let parallelogram_omega = |c: DVec3, e0: DVec3, e1: DVec3| {
        solid_angle(c, c + e0, c + e0 + e1) + solid_angle(c, c + e0 + e1, c + e1)
    };
    match spec {
        DirectionWarpSpec::SphericalTriangle {
            vertices: [a, b, c],
        } => {
            let slack = slack_for(solid_angle(*a, *b, *c));
            Some(triangle_partition(*a, *b, *c, slack, solid_angle))
        }
        DirectionWarpSpec::TriangleArea {
            vertices: [a, b, c],
        } => {
            let slack = slack_for(solid_angle(*a, *b, *c));
            Some(triangle_partition(*a, *b, *c, slack, half_area))
        }
        DirectionWarpSpec::SphericalRectangle {
            corner,
            edge0,
            edge1,
        } => Some(parallelogram_partition(
            *corner,
            *edge0,
            *edge1,
            slack_for(parallelogram_omega(*corner, *edge0, *edge1)),
            |[p0, p1, p2, p3]| solid_angle(p0, p1, p2) + solid_angle(p0, p2, p3),
        )),
        DirectionWarpSpec::ParallelogramArea {
            corner,
            edge0,
            edge1,
        } => Some(parallelogram_partition(
            *corner,
            *edge0,
            *edge1,
            slack_for(parallelogram_omega(*corner, *edge0, *edge1)),
            |[p0, p1, p2, p3]| half_area(p0, p1, p2) + half_area(p0, p2, p3),
        )),
        DirectionWarpSpec::DiskArea {
            center,
            normal,
            radius,
        } => {
            // Rings of equal area (uniform in r²) × sectors of equal angle.
            let k = PARTITION_SIDE;
            let (c, n, r) = (*center, normal.normalize(), *radius);
            // A disk's solid angle is at least its projected area over the
            // farthest rim distance squared.
            let far = c.length() + r;
            let omega = std::f64::consts::PI * r * r * (n.dot(c).abs() / c.length()) / (far * far);
            let slack = slack_for(omega);
            let (x, y) = n.any_orthonormal_pair();
            let locate = move |w: DVec3| {
                let p = hit(w, c, n)? - c;
                let rho2 = (p.dot(x).powi(2) + p.dot(y).powi(2)) / (r * r);
                if rho2 > 1.0 + 2.0 * slack {
                    return None;
                }
                let ring = ((rho2.min(1.0) * k as f64) as usize).min(k - 1);
                let phi = p.dot(y).atan2(p.dot(x)).rem_euclid(std::f64::consts::TAU);
                let sector = ((phi / std::f64::consts::TAU * k as f64) as usize).min(k - 1);
                Some(ring * k + sector)
            };
            let cells = (0..k * k)
                .map(|cell| {
                    let (ring, sector) = (cell / k, cell % k);
                    let step = std::f64::consts::TAU / k as f64;
                    PartitionCell::RingSector {
                        center: c,
                        x,
                        y,
                        radius: r,
                        rho2: (ring as f64 / k as f64, (ring + 1) as f64 / k as f64),
                        phi: (sector as f64 * step, (sector + 1) as f64 * step),
                    }
                })
                .collect();
            Some(Partition {
                probabilities: vec![1.0 / (k * k) as f64; k * k],
                locate: Box::new(locate),
                cells,
            })
        }
        _ => None,
    }
}

/// Runs one case of the suite in one precision: the exact partition where
/// there is one, else the pdf-integrated cells; sample i comes from the
/// independent sequence's stream i for `seed` (24-bit uniforms for f32).
pub fn run_case(
    case: &Case,
    precision: Precision,
    samples: u64,
    seed: u64,
    alpha: f64,
) -> ChiSquareOutcome {
    let warp = case
        .spec
        .build(precision)
        .expect("the suite's cases are valid");
    match partition_for(&case.spec, precision) {
        Some(partition) => {
            let mut sequence = Independent::new(seed);
            ChiSquareTest::new(binning_for(&case.spec))
                .samples(samples)
                .significance(alpha)
                .run_partition(&partition.probabilities, |i| {
                    sequence.start_sample(i);
                    let u = match precision {
                        Precision::F32 => sequence.next_2d_f32().as_dvec2(),
                        Precision::F64 => sequence.next_2d(),
                    };
                    (partition.locate)(warp.sample(u).direction)
                })
                .expect("the suite's partitions are valid")
        }
        None => chi_square(
            warp.as_ref(),
            precision,
            binning_for(&case.spec),
            |w| warp.pdf(w),
            samples,
            seed,
            alpha,
        ),
    }
}

/// Every (case, precision) pair the suite runs: f64 always, f32 where the
/// case is within f32's reach.
pub fn runs() -> Vec<(Case, Precision)> {
    direction_cases()
        .into_iter()
        .flat_map(|case| {
            let f32_too = case.f32_resolvable;
            Precision::ALL
                .into_iter()
                .filter(move |p| *p == Precision::F64 || f32_too)
                .map(move |p| (case.clone(), p))
        })
        .collect()
}
