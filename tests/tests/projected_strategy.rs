//! The `projected` and `control-variate` strategies against closed forms.
//!
//! - Unoccluded: every single projected sample of a uniform sphere, sky cap
//!   or polygon light equals the closed form to 1e-12 relative plus the
//!   sampler's own bound on its Ω⊥ rounding error, across the hard cases
//!   (θmax of 1e-7 rad, a sphere nearly touching the receiver, lights
//!   straddling the horizon, a polygon of more vertices than the sector
//!   sampler takes); the control variate without occluders is the closed
//!   form itself.
//! - Occluded: an opaque half-plane x < 0 at height 1 hides, from a
//!   receiver at the origin, exactly the directions with ω_x < 0 (the plane
//!   through the receiver and the half-plane's edge). Each light below is
//!   symmetric under x → −x, so the visible irradiance is exactly half the
//!   closed form. z-tests of both strategies × two sequences × four lights
//!   (a family of 16, family-wise α = 0.01, Šidák-corrected per test;
//!   Student t with the estimate's degrees of freedom).
//! - Negative controls: the same estimates judged against a truth 1 % off
//!   (equivalently, an estimator biased by 1 %) must all be rejected by the
//!   same test at the same sample count; and an estimator that ignores the
//!   occluder (the unoccluded closed form, the control variate's control
//!   alone) must be rejected.

use glam::{DVec2, DVec3};
use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::point::{estimate_at, PointConfig};
use lambert_estimator::statistics::rounding::mean_rounding_floor;
use lambert_estimator::strategy::{PreparedEmitter, Strategy};
use lambert_light::emitter::{DiskLight, Emitter, PolygonLight, SkyCap, SphereLight};
use lambert_light::Receiver;
use lambert_validate::sidak_level;
use statrs::distribution::{ContinuousCDF, StudentsT};

const FAMILY_ALPHA: f64 = 0.01;
const SAMPLES: u64 = 1 << 20;

fn up() -> Receiver {
    Receiver::new(DVec3::ZERO, DVec3::Z).unwrap()
}

fn polygon(vertices: &[[f64; 3]]) -> Emitter {
    let v = vertices.iter().map(|&p| DVec3::from(p)).collect();
    Emitter::Polygon(PolygonLight::new(v, 1.0, false).unwrap())
}

/// u on a 24 × 24 grid and on the square's edges.
fn us() -> Vec<DVec2> {
    let edges = [0.0, 1e-12, 0.5, 1.0 - f64::EPSILON / 2.0, 1.0];
    let mut out: Vec<DVec2> = edges
        .iter()
        .flat_map(|&a| edges.iter().map(move |&b| DVec2::new(a, b)))
        .collect();
    let n = 24;
    for i in 0..n {
        for j in 0..n {
            out.push(DVec2::new(
                (i as f64 + 0.5) / n as f64,
                (j as f64 + 0.5) / n as f64,
            ));
        }
    }
    out
}

/// Uniform lights of every kind projected sampling covers, on the hard
/// cases.
fn unoccluded_lights() -> Vec<(&'static str, Emitter)> {
    let ring = |n: usize, z: f64| {
        (0..n)
            .map(|k| {
                let a = -(k as f64) * std::f64::consts::TAU / n as f64;
                [a.cos(), a.sin(), z]
            })
            .collect::<Vec<_>>()
    };
    vec![
        (
            "sphere of 1e-7 rad overhead",
            Emitter::Sphere(SphereLight::new(DVec3::new(0.0, 0.0, 1e7), 1.0, 1.0).unwrap()),
        ),
        (
            "sphere nearly touching the receiver",
            Emitter::Sphere(SphereLight::new(DVec3::new(0.0, 0.0, 1.0 + 1e-9), 1.0, 1.0).unwrap()),
        ),
        (
            "sphere tilted 30°",
            Emitter::Sphere(
                SphereLight::new(DVec3::new(5.0, 0.0, 5.0 * 3f64.sqrt()), 1.0, 2.0).unwrap(),
            ),
        ),
        (
            "sphere straddling the horizon",
            Emitter::Sphere(SphereLight::new(DVec3::new(3.0, 0.0, 0.4), 1.0, 1.0).unwrap()),
        ),
        (
            "sky cap straddling the horizon",
            Emitter::SkyCap(
                SkyCap::new(
                    DVec3::new(70f64.to_radians().sin(), 0.0, 70f64.to_radians().cos()),
                    40f64.to_radians(),
                    1.0,
                )
                .unwrap(),
            ),
        ),
        (
            "triangle",
            polygon(&[[-1.0, -1.0, 2.0], [0.0, 1.5, 2.5], [2.0, -0.5, 2.2]]),
        ),
        (
            "wall straddling the horizon",
            polygon(&[
                [2.0, -1.0, 0.5],
                [2.0, 1.0, 0.5],
                [2.0, 1.0, -1.0],
                [2.0, -1.0, -1.0],
            ]),
        ),
        (
            "12-gon overhead (more vertices than the sector sampler's)",
            polygon(&ring(12, 2.0)),
        ),
    ]
}

/// Every projected sample of an unoccluded uniform light is the closed
/// form: 1e-12 relative (the sampling crate's per-sampler bound, measured
/// there at a few ulps) plus the sampler's stated Ω⊥ rounding bound, which
/// is where an error of Ω⊥ itself would show.
#[test]
fn every_projected_sample_is_the_closed_form() {
    let receiver = up();
    let mut worst: f64 = 0.0;
    for (label, emitter) in unoccluded_lights() {
        let truth = emitter.closed_form_irradiance(&receiver).unwrap();
        let prepared = PreparedEmitter::new(&emitter, &receiver, Strategy::Projected);
        let tolerance = 1e-12 * truth + prepared.systematic_error();
        for u in us() {
            let v = prepared.evaluate_u(&receiver, u, DVec2::ZERO);
            worst = worst.max((v - truth).abs() / truth);
            assert!(
                (v - truth).abs() <= tolerance,
                "{label} u={u}: {v} vs {truth} ({:e} relative)",
                (v - truth).abs() / truth
            );
        }
        // Without occluders the control variate is the closed form, exactly.
        let control = PreparedEmitter::new(&emitter, &receiver, Strategy::ControlVariate);
        assert_eq!(
            control.evaluate_u(&receiver, DVec2::new(0.3, 0.7), DVec2::ZERO),
            truth,
            "{label}"
        );
    }
    eprintln!("projected samples vs closed form: worst {worst:.1e} relative");
}

/// Whether the ray from `p` along `w` reaches distance `far` without
/// crossing the opaque half-plane {z = 1, x < 0}.
fn past_the_half_plane(p: DVec3, w: DVec3, far: f64) -> bool {
    if w.z <= 0.0 {
        return true;
    }
    let t = (1.0 - p.z) / w.z;
    !(t > 0.0 && t < far && p.x + t * w.x < 0.0)
}

/// Lights above the half-plane's height, symmetric under x → −x.
fn symmetric_lights() -> Vec<(&'static str, Emitter)> {
    vec![
        (
            "coaxial disk",
            Emitter::Disk(
                DiskLight::new(DVec3::new(0.0, 0.0, 2.0), -DVec3::Z, 1.0, 1.0, false).unwrap(),
            ),
        ),
        (
            "sphere overhead",
            Emitter::Sphere(SphereLight::new(DVec3::new(0.0, 0.0, 3.0), 1.0, 1.0).unwrap()),
        ),
        (
            "square overhead",
            polygon(&[
                [-1.0, -1.0, 2.0],
                [-1.0, 1.0, 2.0],
                [1.0, 1.0, 2.0],
                [1.0, -1.0, 2.0],
            ]),
        ),
        (
            "sky cap around the zenith",
            Emitter::SkyCap(SkyCap::new(DVec3::Z, 30f64.to_radians(), 1.0).unwrap()),
        ),
    ]
}

/// The two-sided critical |t| of one of `tests` tests with `dof` degrees of
/// freedom at the Šidák-corrected level.
fn critical(tests: usize, dof: u64) -> f64 {
    let alpha = sidak_level(FAMILY_ALPHA, tests);
    StudentsT::new(0.0, 1.0, dof as f64)
        .unwrap()
        .inverse_cdf(1.0 - alpha / 2.0)
}

#[test]
fn occluded_estimates_match_the_visible_half_and_a_biased_one_is_rejected() {
    let receiver = up();
    let strategies = [Strategy::Projected, Strategy::ControlVariate];
    let sequences = [SequenceKind::Independent, SequenceKind::Sobol];
    let tests = symmetric_lights().len() * strategies.len() * sequences.len();
    let mut failures = Vec::new();
    for (label, emitter) in symmetric_lights() {
        let unoccluded = emitter.closed_form_irradiance(&receiver).unwrap();
        let truth = 0.5 * unoccluded;
        for strategy in strategies {
            for sequence in sequences {
                let config = PointConfig {
                    strategy,
                    sequence,
                    samples: SAMPLES,
                    seed: 17,
                };
                let e = estimate_at(
                    &receiver,
                    std::slice::from_ref(&emitter),
                    &past_the_half_plane,
                    &config,
                )
                .unwrap();
                let q = critical(tests, e.degrees_of_freedom);
                // Point estimates report σ = 0 when every sample (or every
                // replicate: Sobol points split by the half-plane exactly in
                // half) is equal; they are then judged, as `estimate`
                // judges its own, with the rounding floor of the mean plus
                // the projected sampler's bound on its Ω⊥ error.
                let floor = mean_rounding_floor(e.mean, SAMPLES)
                    + PreparedEmitter::new(&emitter, &receiver, strategy).systematic_error();
                let se = e.std_error.max(floor);
                let z = (e.mean - truth) / se;
                eprintln!(
                    "{label} / {strategy} / {sequence}: z {z:.2} (critical {q:.2}), \
                     relative σ {:.2e}",
                    se / truth
                );
                if z.abs() > q {
                    failures.push(format!("{label} / {strategy} / {sequence}: z {z:.2}"));
                }
                // Negative controls, same estimate, same test: a truth 1 %
                // off, and the occluder ignored (the control alone).
                for (what, wrong) in [("1 % off", 1.01 * truth), ("unoccluded", unoccluded)] {
                    let z = (e.mean - wrong) / se;
                    if z.abs() <= q {
                        failures.push(format!(
                            "negative control ({what}) accepted: {label} / {strategy} / \
                             {sequence}: z {z:.2}"
                        ));
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
