//! Honest uncertainty on the cases where the samples cannot see: lights no
//! sample reaches, samples that are all equal, estimates below the rounding
//! floor, heavy tails, and polygons cut by the horizon. Every strategy ×
//! sequence, not only `auto`, either agrees with the closed form within its
//! stated interval, or says (a warning, an interval from rare-event bounds)
//! that the central limit theorem does not hold there — and its interval
//! still contains the truth.
//!
//! Calibration: one family of K = scenes × 9 strategies (auto and the eight) × 3 sequences
//! intervals, each computed at level 1 − α_K with α_K the Šidák level for a
//! family-wise α = 0.01, so that the family passes with probability ≥ 0.99
//! when every interval is honest; fixed seeds make it deterministic.
//!
//! Negative controls: on the cases the issue names, the interval that
//! ignores them — `m ± q·s/√N` from the sample standard error alone (with
//! no hit: [0, 0]) — must exclude the truth at the same level.

use glam::DVec3;
use lambert_estimator::estimation::{
    estimate_at_level, EstimateConfig, SequenceKind, RQMC_REPLICATES,
};
use lambert_estimator::interval::{IntervalKind, RareCause};
use lambert_estimator::statistics::rounding::mean_rounding_floor;
use lambert_estimator::statistics::ConfidenceInterval;
use lambert_estimator::strategy::{PartShape, PreparedEmitter, Strategy};
use lambert_light::emitter::{DiskLight, Emitter, PolygonLight, SkyCap, SphereLight};
use lambert_light::receiver::Receiver;
use lambert_light::Scene;
use lambert_validate::sidak_level;

const SAMPLES: u64 = 1 << 14;

fn up() -> Receiver {
    Receiver::new(DVec3::ZERO, DVec3::Z).expect("a valid receiver")
}

fn one(emitter: Emitter) -> Scene {
    Scene::new(up(), vec![emitter]).expect("a valid scene")
}

fn polygon(vertices: &[[f64; 3]]) -> Emitter {
    let v = vertices.iter().map(|&p| DVec3::from(p)).collect();
    Emitter::Polygon(PolygonLight::new(v, 1.0, false).expect("a valid polygon"))
}

/// What a case must show, beyond covering the truth.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Expect {
    /// No sample hits the light: 0 hits, a one-sided interval from 0, a
    /// warning; the naive interval [0, 0] excludes the truth.
    NoHits,
    /// Every sample equal, or all but a few (cosine sampling under a disk
    /// that covers all but a sliver of probability cos²α ≈ 10⁻⁶: a run of
    /// 16 384 samples misses it with probability 1.6 %, and the stratified
    /// points of seed 41 do, once): a few-misses warning; when every sample
    /// is equal, the naive interval (of width 0) excludes the truth.
    AllEqual,
    /// Heavy tail (area sampling close to a large disk) whose core no
    /// sample is expected to reach (N·q < 1): a warning. Its negative
    /// control is a test of its own over many seeds
    /// ([`naive_interval_is_miscalibrated_on_a_heavy_tail`]): one run's naive
    /// interval covers the truth whenever a sample lands near the core,
    /// which happens in a quarter to two fifths of runs, so no single run
    /// can serve as the control.
    HeavyTail,
    /// Heavy tail whose core a few samples may reach (N·q ≈ 5): a warning
    /// (the naive interval may or may not cover, depending on whether a
    /// sample reached the core).
    HeavyTailWarned,
    /// Every sample sees the light (a polygon clipped to the horizon):
    /// hits = N, a central-limit interval.
    AllHit,
    /// Values equal to ~1e-15: the standard error is the rounding floor.
    Floor,
    /// As `Floor`, and the mean is off by more than the sample standard
    /// error can explain (here over 200 of them, ~4u relative): the naive
    /// interval excludes the truth.
    FloorMatters,
}

struct Case {
    name: &'static str,
    scene: Scene,
    expect: &'static [(Strategy, Expect)],
}

fn cases() -> Vec<Case> {
    use Expect::*;
    use Strategy::{Area, CosineHemisphere as Cos, Light, UniformHemisphere as Uni};
    // A triangle of ~1e-9 sr straight overhead at height 1 (front face
    // down, toward the receiver).
    let t = 1e-9f64.sqrt() * 1.5;
    vec![
        Case {
            name: "tiny sphere (1e-4 rad)",
            scene: one(Emitter::Sphere(
                SphereLight::new(DVec3::new(0.0, 0.0, 10.0), 1e-3, 1.0).unwrap(),
            )),
            expect: &[(Uni, NoHits), (Cos, NoHits)],
        },
        Case {
            name: "micro-radian disk",
            scene: one(Emitter::Disk(
                DiskLight::new(DVec3::Z, -DVec3::Z, 1e-6, 1.0, false).unwrap(),
            )),
            expect: &[(Uni, NoHits), (Cos, NoHits)],
        },
        Case {
            name: "far rectangle (1 m at 1e4 m)",
            scene: one(polygon(&[
                [-0.5, -0.5, 1e4],
                [-0.5, 0.5, 1e4],
                [0.5, 0.5, 1e4],
                [0.5, -0.5, 1e4],
            ])),
            expect: &[(Uni, NoHits), (Cos, NoHits)],
        },
        Case {
            name: "wall clipped by the horizon to a 1e-4 sliver",
            scene: one(polygon(&[
                [2.0, -1.0, 1e-4],
                [2.0, 1.0, 1e-4],
                [2.0, 1.0, -1.0],
                [2.0, -1.0, -1.0],
            ])),
            // Projected sampling's Ω⊥ is here the small difference of sectors
            // of ≈ 0.1 sr (about 1e-7 of it from rounding): its interval must
            // still cover, through the sampler's error bound.
            expect: &[
                (Light, AllHit),
                (Strategy::Auto, AllHit),
                (Strategy::Projected, AllHit),
            ],
        },
        Case {
            name: "disk 1000 wide at height 1",
            scene: one(Emitter::Disk(
                DiskLight::new(DVec3::Z, -DVec3::Z, 1000.0, 1.0, false).unwrap(),
            )),
            // Light (and projected, which samples disks by solid angle) draws
            // the disk's spherical ellipse: values LΩ cos θ ≤ LΩ, no tail.
            expect: &[
                (Cos, AllEqual),
                (Area, HeavyTail),
                (Light, AllHit),
                (Strategy::Projected, AllHit),
            ],
        },
        Case {
            // The receiver on the disk's axis, 30° off its own normal: the
            // disk's solid-angle sampler once built a skewed frame here
            // from the rounding of its lateral offset, and its density
            // rejected directions that hit the disk, so MIS counted those
            // cosine samples at full weight (about twice the irradiance).
            name: "disk seen from its axis, 30° off the normal",
            scene: one(Emitter::Disk(
                DiskLight::new(
                    DVec3::new(0.5, 0.0, 0.866_025_403_784_438_6),
                    DVec3::new(-0.5, 0.0, -0.866_025_403_784_438_6),
                    0.1,
                    1.0,
                    false,
                )
                .unwrap(),
            )),
            expect: &[],
        },
        Case {
            name: "receiver 0.01 under a unit disk",
            scene: one(Emitter::Disk(
                DiskLight::new(DVec3::new(0.3, 0.0, 0.01), -DVec3::Z, 1.0, 1.0, false).unwrap(),
            )),
            expect: &[
                (Area, HeavyTailWarned),
                (Light, AllHit),
                (Strategy::Projected, AllHit),
            ],
        },
        Case {
            name: "sphere of 1e-7 rad overhead",
            scene: one(Emitter::Sphere(
                SphereLight::new(DVec3::new(0.0, 0.0, 1e7), 1.0, 1.0).unwrap(),
            )),
            expect: &[(Light, Floor), (Uni, NoHits), (Cos, NoHits)],
        },
        Case {
            name: "sky cap of 1e-7 rad at the zenith",
            scene: one(Emitter::SkyCap(SkyCap::new(DVec3::Z, 1e-7, 1.0).unwrap())),
            expect: &[(Light, Floor), (Uni, NoHits), (Cos, NoHits)],
        },
        Case {
            name: "triangle of 1e-15 sr overhead",
            scene: one(polygon(&[
                [0.0, 0.0, 1.0],
                [0.0, 4.5e-8, 1.0],
                [4.5e-8, 0.0, 1.0],
            ])),
            expect: &[(Light, FloorMatters)],
        },
        Case {
            name: "triangle of 1e-9 sr overhead",
            scene: one(polygon(&[[0.0, 0.0, 1.0], [0.0, t, 1.0], [t, 0.0, 1.0]])),
            expect: &[(Uni, NoHits), (Cos, NoHits)],
        },
    ]
}

fn truth(scene: &Scene) -> f64 {
    scene
        .emitters
        .iter()
        .map(|e| {
            e.closed_form_irradiance(&scene.receiver)
                .expect("a closed form")
        })
        .sum()
}

fn strategies() -> Vec<Strategy> {
    std::iter::once(Strategy::Auto)
        .chain(Strategy::ALL)
        .collect()
}

#[test]
fn every_strategy_and_sequence_covers_the_truth_or_says_it_cannot() {
    let cases = cases();
    let family = cases.len() * strategies().len() * SequenceKind::ALL.len();
    let level = 1.0 - sidak_level(0.01, family);
    let mut failures = Vec::new();
    for case in &cases {
        let e = truth(&case.scene);
        for strategy in strategies() {
            for sequence in SequenceKind::ALL {
                let config = EstimateConfig {
                    strategy,
                    sequence,
                    samples: SAMPLES,
                    seed: 41,
                    threads: 1,
                    precision: lambert_estimator::precision::Precision::F64,
                };
                let r = estimate_at_level(&case.scene, &config, level).unwrap();
                let what =
                    format!(
                    "{} / {strategy} / {sequence}: E = {e:e}, mean {:e} ± {:e}, ci [{:e}, {:e}], \
                     {} hits, {} {:?}",
                    case.name, r.mean, r.std_error, r.ci99.0, r.ci99.1, r.hits, r.interval,
                    r.warning
                );
                let mut fail = |why: &str| failures.push(format!("{why}: {what}"));
                if !(r.ci99.0 <= e && e <= r.ci99.1) {
                    fail("interval misses the truth");
                }
                if (r.interval == IntervalKind::CentralLimit) != r.warning.is_none() {
                    fail("a warning must come with every interval but the CLT one");
                }
                // The naive interval: the sample standard error alone.
                let raw_se = (r.sample_variance / SAMPLES as f64).sqrt();
                let dof = match sequence {
                    SequenceKind::Independent => SAMPLES,
                    _ => RQMC_REPLICATES,
                };
                let naive = ConfidenceInterval::new(r.mean, raw_se, dof, level);
                let expect = case.expect.iter().find(|(s, _)| *s == strategy);
                match expect.map(|&(_, x)| x) {
                    None => {}
                    Some(Expect::AllHit)
                        if r.hits != SAMPLES || r.interval != IntervalKind::CentralLimit =>
                    {
                        fail("every sample should hit the light");
                    }
                    Some(Expect::AllHit) => {}
                    Some(x @ (Expect::Floor | Expect::FloorMatters)) => {
                        let floor = mean_rounding_floor(r.mean, SAMPLES);
                        if r.std_error != floor || raw_se >= floor {
                            fail("the rounding floor should bind");
                        }
                        if x == Expect::FloorMatters && naive.contains(e) {
                            fail("negative control: the naive interval covers the truth");
                        }
                    }
                    Some(Expect::HeavyTailWarned) => {
                        let cause = r.warning.map(|w| w.cause);
                        if !matches!(cause, Some(RareCause::HeavyTail { .. })) {
                            fail("the heavy-tail warning is missing");
                        }
                    }
                    Some(x) => {
                        let cause = r.warning.map(|w| w.cause);
                        let (right, naive_must_exclude) = match x {
                            Expect::NoHits => {
                                let none = r.hits == 0;
                                (
                                    none && r.ci99.0 == 0.0 && cause == Some(RareCause::NoHits),
                                    true,
                                )
                            }
                            Expect::AllEqual => match cause {
                                Some(RareCause::FewMisses { misses }) => (true, misses == 0),
                                _ => (false, true),
                            },
                            _ => {
                                let warned = matches!(cause, Some(RareCause::HeavyTail { .. }));
                                (warned, false)
                            }
                        };
                        if !right {
                            fail("the expected warning is missing");
                        }
                        // With a few misses the naive interval has width and
                        // may cover; a heavy tail's control is its own test
                        // (the variants' docs).
                        if naive_must_exclude && naive.contains(e) {
                            fail("negative control: the naive interval covers the truth");
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Negative control for [`Expect::HeavyTail`]: area sampling of the
/// 1000-wide disk at height 1, N = 2¹⁴, seeds 1 … 64, every sequence. The
/// naive interval `m ± q·s/√N` at the level of the family above (a miss
/// probability α_K of about 3·10⁻⁵ if it were honest) misses the truth in
/// most runs, since without a sample in the core the mean falls short:
/// measured, it covers in 10, 17 and 15 of 40 runs (independent,
/// stratified, Sobol). The test asserts at least 16 misses of 64 per
/// sequence; an honest interval would give as many with probability below
/// C(64, 16)·α_K¹⁶ < 10⁻⁵⁸. lambert's own interval (rare-event bound)
/// covers the truth in every run, as its level promises for the family.
#[test]
fn naive_interval_is_miscalibrated_on_a_heavy_tail() {
    let cases = cases();
    let case = cases
        .iter()
        .find(|c| c.name == "disk 1000 wide at height 1")
        .expect("the heavy-tail case");
    let e = truth(&case.scene);
    let family = cases.len() * strategies().len() * SequenceKind::ALL.len();
    let level = 1.0 - sidak_level(0.01, family);
    for sequence in SequenceKind::ALL {
        let mut naive_misses = 0;
        for seed in 1..=64 {
            let config = EstimateConfig {
                strategy: Strategy::Area,
                sequence,
                samples: SAMPLES,
                seed,
                threads: 1,
                precision: lambert_estimator::precision::Precision::F64,
            };
            let r = estimate_at_level(&case.scene, &config, level).unwrap();
            assert!(
                r.ci99.0 <= e && e <= r.ci99.1,
                "{sequence} seed {seed}: {r:?}"
            );
            let raw_se = (r.sample_variance / SAMPLES as f64).sqrt();
            let dof = match sequence {
                SequenceKind::Independent => SAMPLES,
                _ => RQMC_REPLICATES,
            };
            if !ConfidenceInterval::new(r.mean, raw_se, dof, level).contains(e) {
                naive_misses += 1;
            }
        }
        assert!(
            naive_misses >= 16,
            "{sequence}: the naive interval missed only {naive_misses} of 64"
        );
    }
}

/// `auto` never picks a heavy-tailed (area-sampling) part: on the hard
/// cases and the built-in scenes, none of its parts is heavy-tailed, while
/// `area` on a disk is (the control).
#[test]
fn auto_never_uses_a_heavy_tailed_part() {
    let mut scenes: Vec<Scene> = cases().into_iter().map(|c| c.scene).collect();
    scenes.extend(
        lambert_light::builtin::builtin_scenes()
            .into_iter()
            .map(|s| s.scene),
    );
    let heavy = |scene: &Scene, strategy: Strategy| {
        scene.emitters.iter().filter(|e| !e.is_delta()).any(|e| {
            PreparedEmitter::new(e, &scene.receiver, strategy)
                .parts()
                .iter()
                .any(|p| matches!(p.shape, PartShape::HeavyTailed { .. }))
        })
    };
    for scene in &scenes {
        assert!(!heavy(scene, Strategy::Auto), "{scene:?}");
    }
    assert!(heavy(&cases()[4].scene, Strategy::Area));
}

/// The per-call samplers a path tracer uses (`LightSampler::sample`, no
/// allocation), on a rectangle and a triangle that straddle the horizon:
/// the estimate L·cos θ/p of 2^16 independent samples agrees with the closed
/// form (z-test at α = 0.01 / 2, Šidák over the two). Negative control: the
/// same samples weighted with the density of the whole, unclipped light
/// (1/Ω_whole instead of 1/Ω_visible) must be rejected.
#[test]
fn clipped_light_samplers_are_unbiased_and_the_unclipped_density_is_rejected() {
    use lambert_estimator::Estimate;
    use lambert_geometry::f64::{ConvexPolygon, Triangle};
    use lambert_sampling::f64::{LightSampler, PolygonLightSampler, TriangleLightSampler};
    use rand::{Rng, SeedableRng};
    let (p, n) = (DVec3::ZERO, DVec3::Z);
    // Front faces toward the receiver at the origin (normal −x).
    let rectangle = [
        [2.0, -1.0, 0.4],
        [2.0, 1.0, 0.4],
        [2.0, 1.0, -0.6],
        [2.0, -1.0, -0.6],
    ];
    let triangle = [[2.0, 0.0, 1.0], [2.0, 1.0, -0.5], [2.0, -1.0, -0.5]];
    let corners = |v: &[[f64; 3]]| v.iter().map(|&c| DVec3::from(c)).collect::<Vec<_>>();
    let polygon_sampler =
        PolygonLightSampler::new(ConvexPolygon::new(corners(&rectangle)).unwrap()).unwrap();
    let t = corners(&triangle);
    let triangle_sampler = TriangleLightSampler::new(Triangle::new(t[0], t[1], t[2]).unwrap());
    let samplers: [(&[[f64; 3]], &dyn LightSampler); 2] = [
        (&rectangle, &polygon_sampler),
        (&triangle, &triangle_sampler),
    ];
    let z_crit = {
        use statrs::distribution::{ContinuousCDF, Normal};
        Normal::standard().inverse_cdf(1.0 - sidak_level(0.01, 2) / 2.0)
    };
    for (vertices, sampler) in samplers {
        let truth = truth(&one(polygon(vertices)));
        let whole = lambert_geometry::f64::convex_polygon_solid_angle(p, &corners(vertices));
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(5);
        let (mut right, mut wrong) = (Estimate::new(), Estimate::new());
        for _ in 0..1 << 16 {
            let u = glam::DVec2::new(rng.random(), rng.random());
            let s = sampler.sample(p, n, u).expect("the light is visible");
            let cos = s.direction.dot(n).max(0.0);
            right.push(cos / s.pdf);
            wrong.push(cos * whole);
        }
        let z = right.z(truth).unwrap();
        assert!(z.abs() <= z_crit, "{vertices:?}: z {z}");
        let z = wrong.z(truth).unwrap();
        assert!(z.abs() > z_crit, "negative control accepted: z {z}");
    }
}

/// Stratification that fixes a count: a sphere of 0.1 rad straight overhead
/// is, for uniform-hemisphere sampling, the strip u₀ ∈ [0.995, 1) of the
/// unit square, and each stratified or Sobol replicate of 8192 points hits
/// it 41 times (40.96 expected). Seeds where all 16 replicates agree report
/// a standard error ~1000× too small (z ≈ −1200 on the plain t interval):
/// the estimate must warn and cover the truth (level 1 − 0.01/6, Šidák over
/// the 3 seeds × 2 sequences); negative control: the plain t interval
/// misses it on at least one of them.
#[test]
fn counts_fixed_by_stratification_are_declared_and_covered() {
    use lambert_estimator::estimation::RQMC_REPLICATES;
    let scene = one(Emitter::Sphere(
        SphereLight::new(DVec3::new(0.0, 0.0, 10.0), 1.0, 1.0).unwrap(),
    ));
    let e = truth(&scene);
    let level = 1.0 - sidak_level(0.01, 6);
    let mut naive_misses = 0;
    for sequence in [SequenceKind::Stratified, SequenceKind::Sobol] {
        for seed in 1..=3 {
            let config = EstimateConfig {
                strategy: Strategy::UniformHemisphere,
                sequence,
                samples: 1 << 17,
                seed,
                threads: 1,
                precision: lambert_estimator::precision::Precision::F64,
            };
            let r = estimate_at_level(&scene, &config, level).unwrap();
            assert!(
                r.ci99.0 <= e && e <= r.ci99.1,
                "{sequence} {seed}: {:?} misses {e}",
                r.ci99
            );
            let raw_se = (r.sample_variance / (1u64 << 17) as f64).sqrt();
            let plain = ConfidenceInterval::new(r.mean, raw_se, RQMC_REPLICATES, level);
            if !plain.contains(e) {
                naive_misses += 1;
                assert!(
                    matches!(
                        r.warning.map(|w| w.cause),
                        Some(RareCause::FixedCount { per_replicate: 41 })
                    ),
                    "{sequence} {seed}: {:?}",
                    r.warning
                );
            }
        }
    }
    assert!(
        naive_misses > 0,
        "negative control: the t interval never missed"
    );
}
