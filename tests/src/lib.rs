//! Cross-crate validation suites for lambert; the suites live in `tests/`.
//! This library holds what they share: the catalogue of hard cases.

use glam::DVec3;
use lambert_estimator::goodness_of_fit::{Binning, ChiSquareOutcome, ChiSquareTest};
use lambert_sampling::catalog::{DirectionWarp, DirectionWarpSpec, Precision};
use lambert_sampling::{Independent, SampleSequence};

/// A named warp configuration that the suites exercise.
#[derive(Clone, Debug)]
pub struct Case {
    /// Short label for messages.
    pub label: &'static str,
    /// The warp and its parameters.
    pub spec: DirectionWarpSpec,
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
            label: "uniform hemisphere",
            spec: DirectionWarpSpec::UniformHemisphere,
        },
        Case {
            label: "cosine hemisphere",
            spec: DirectionWarpSpec::CosineHemisphere,
        },
        Case {
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
            label,
            spec: DirectionWarpSpec::SphereLight { center, radius },
        });
    }
    cases.extend([
        Case {
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
            label: "disk area coaxial",
            spec: DirectionWarpSpec::DiskArea {
                center: DVec3::new(0.0, 0.0, 2.0),
                normal: DVec3::new(0.0, 0.0, -1.0),
                radius: 0.5,
            },
        },
        Case {
            label: "disk area tilted",
            spec: DirectionWarpSpec::DiskArea {
                center: DVec3::new(1.0, 0.5, 2.0),
                normal: DVec3::new(0.3, -1.0, 0.4),
                radius: 0.7,
            },
        },
        Case {
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

/// Samples on and near the edges of the unit square: 0, tiny, interior,
/// 1 − ε (for f64 and for f32) and exactly 1.
pub fn edge_values() -> Vec<f64> {
    vec![
        0.0,
        1e-12,
        1e-7,
        0.25,
        0.5,
        0.75,
        1.0 - f32::EPSILON as f64 / 2.0,
        1.0 - f64::EPSILON / 2.0,
        1.0,
    ]
}

/// The README's Rust example, run as a doc test.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;

/// Samples per chi-square test in the warp suites (and in their negative
/// controls, which must be rejected at this same count).
pub const CHI_SQUARE_SAMPLES: u64 = 400_000;

/// The binning the suites use for a warp: 16 × 16 cells of equal solid angle
/// inside its bounding cap, or 20 × 40 over the sphere. Expected counts are
/// then ≳ 1500 per occupied cell, far above the pooling threshold of 5.
pub fn binning_for(spec: &DirectionWarpSpec) -> Binning {
    match spec.bounding_cap() {
        Some(cap) => Binning::Cap {
            axis: cap.axis,
            one_minus_cos_max: cap.one_minus_cos,
            theta_bins: 16,
            phi_bins: 16,
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
