//! The f32 estimator (`Precision::F32`) against the closed forms: every
//! built-in scene (every emitter kind) × every strategy × every sequence,
//! z-tested at a Šidák-corrected level with a negative control (the truth
//! 1 % off) that the same test must reject; which emitters run in f32 and
//! which fall back to f64, and why; results bit-identical across thread
//! counts and instruction sets; and pinned values.

use glam::DVec3;
use lambert_estimator::estimation::{
    estimate, estimate_with_isa, f32_fallbacks, EstimateConfig, SequenceKind, RQMC_REPLICATES,
};
use lambert_estimator::interval::IntervalKind;
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::{FallbackReason, Strategy};
use lambert_light::builtin::builtin_scenes;
use lambert_light::emitter::{DiskLight, SkyCap, SphereLight};
use lambert_light::{Emitter, Receiver, Scene};
use lambert_validate::sidak_level;
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

const FAMILY_ALPHA: f64 = 0.01;
const SAMPLES: u64 = 1 << 18;

fn closed_form(scene: &Scene) -> f64 {
    scene
        .emitters
        .iter()
        .map(|e| e.closed_form_irradiance(&scene.receiver).unwrap())
        .sum()
}

/// Two-sided critical value: normal for independent samples (N = 2^18),
/// Student-t(R − 1) for randomized QMC.
fn critical(sequence: SequenceKind, alpha: f64) -> f64 {
    match sequence {
        SequenceKind::Independent => Normal::standard().inverse_cdf(1.0 - alpha / 2.0),
        _ => StudentsT::new(0.0, 1.0, (RQMC_REPLICATES - 1) as f64)
            .unwrap()
            .inverse_cdf(1.0 - alpha / 2.0),
    }
}

fn config(strategy: Strategy, sequence: SequenceKind, seed: u64) -> EstimateConfig {
    EstimateConfig {
        strategy,
        sequence,
        samples: SAMPLES,
        seed,
        threads: 2,
        precision: Precision::F32,
    }
}

fn strategies() -> Vec<Strategy> {
    std::iter::once(Strategy::Auto)
        .chain(Strategy::ALL)
        .collect()
}

/// The closed-form suite in f32. Every CLT interval is z-tested at the
/// family's Šidák level (α = 0.01 over scenes × strategies × sequences);
/// rare-event intervals must contain the truth. Negative control, at the
/// same level and sample count: the truth moved 1 % must be rejected by
/// every z-test whose power against a 1 % bias is ≥ 0.999 (|bias|/se ≥
/// z_crit + 3.09), and there must be such a test for every emitter kind.
/// Coverage: every (emitter kind, strategy) pair of the built-in scenes
/// runs in f32 somewhere (a fallback to f64 would leave it untested here).
#[test]
fn f32_agrees_with_the_closed_form_everywhere_and_a_1_percent_error_is_caught() {
    let scenes = builtin_scenes();
    let family = scenes.len() * strategies().len() * SequenceKind::ALL.len();
    let alpha = sidak_level(FAMILY_ALPHA, family);
    let mut failures = Vec::new();
    let mut controls = std::collections::BTreeSet::new();
    let mut ran_f32 = std::collections::BTreeSet::new();
    let mut all_pairs = std::collections::BTreeSet::new();
    for named in &scenes {
        let truth = closed_form(&named.scene);
        for strategy in strategies() {
            let fallbacks = f32_fallbacks(&named.scene, strategy);
            for (i, e) in named.scene.emitters.iter().enumerate() {
                if e.is_delta() {
                    continue;
                }
                all_pairs.insert((e.kind(), strategy.name()));
                if !fallbacks.iter().any(|f| f.emitter == i) {
                    ran_f32.insert((e.kind(), strategy.name()));
                }
            }
            for sequence in SequenceKind::ALL {
                let r = estimate(&named.scene, &config(strategy, sequence, 7)).unwrap();
                assert_eq!(r.precision, Precision::F32);
                assert_eq!(r.f64_fallbacks, fallbacks.len());
                assert!(r.mean.is_finite() && r.std_error > 0.0 || truth == 0.0);
                let crit = critical(sequence, alpha);
                let z = (r.mean - truth) / r.std_error;
                let pass = if r.interval == IntervalKind::CentralLimit {
                    z.abs() <= crit
                } else {
                    r.ci99.0 <= truth && truth <= r.ci99.1
                };
                if !pass {
                    failures.push(format!(
                        "{} {strategy} {sequence}: mean {} truth {truth} se {:e} z {z:.2} ({} in f64)",
                        named.name, r.mean, r.std_error, r.f64_fallbacks
                    ));
                }
                // The negative control: the truth 1 % off.
                let bias = 0.01 * truth;
                if r.interval == IntervalKind::CentralLimit
                    && bias.abs() / r.std_error >= crit + 3.09
                {
                    let z_wrong = (r.mean - 1.01 * truth) / r.std_error;
                    if z_wrong.abs() <= crit {
                        failures.push(format!(
                            "{} {strategy} {sequence}: the truth 1 % off was not rejected (z {z_wrong:.2})",
                            named.name
                        ));
                    }
                    if r.f64_fallbacks == 0 {
                        for e in &named.scene.emitters {
                            controls.insert(e.kind());
                        }
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    for kind in ["sky", "sky_cap", "sphere", "disk", "polygon"] {
        assert!(controls.contains(kind), "no negative control for {kind}");
    }
    let untested: Vec<_> = all_pairs.difference(&ran_f32).collect();
    assert!(untested.is_empty(), "never run in f32: {untested:?}");
}

/// The same f32 estimate on 1, 2 and 8 threads, and with its kernels
/// forced to every instruction set this processor has, gives the same
/// bits (mean, standard error, hits): every built-in scene × strategy ×
/// sequence, 20 003 samples (full and partial chunks).
#[test]
fn f32_results_are_bit_identical_across_threads_and_instruction_sets() {
    use lambert_sampling::isa::Isa;
    for named in builtin_scenes() {
        for strategy in strategies() {
            for sequence in SequenceKind::ALL {
                let mut c = config(strategy, sequence, 5);
                c.samples = 20_003;
                let run = |isa, threads| {
                    let c = EstimateConfig { threads, ..c };
                    let r = estimate_with_isa(&named.scene, &c, 0.99, isa).unwrap();
                    (r.mean.to_bits(), r.std_error.to_bits(), r.hits)
                };
                let want = run(Isa::Baseline, 1);
                for isa in Isa::available() {
                    for threads in [1, 2, 8] {
                        assert_eq!(
                            run(isa, threads),
                            want,
                            "{} {strategy} {sequence} {isa} {threads} thread(s)",
                            named.name
                        );
                    }
                }
            }
        }
    }
}

/// FNV-1a over 64-bit words.
fn digest(words: impl IntoIterator<Item = u64>) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325_u64;
    for w in words {
        for byte in w.to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// Value stability of the f32 path: the bits of the mean and standard
/// error of every built-in scene × strategy × sequence (10 007 samples,
/// seed 3) are pinned. A change to an f32 warp, sampler or kernel, to the
/// 24-bit coordinates or to the error bound moves the digest; re-pin only
/// with the reason written here. (Re-pinned once: when a chunk's values
/// were summed in 16 lanes instead of 4, which regroups the compensated
/// sums; with 4 lanes the digest was the earlier 0x7e93_2672_09e3_5b5d, so
/// nothing else moved. The f64 digests did not move: those sums round to
/// the same bits there. Re-pinned again when MIS took its weighted values
/// in one division each and spheres and sky caps their own MIS kernel
/// (`Heuristic::weighted_f32`, `ConeMisF32`): the only code that changed
/// runs for the `mis` and `mis-balance` strategies alone; the z-tests above
/// still pass for them. Re-pinned with the 2026-12 redefinition of the
/// stratified sequence (sub-strata spread by a golden-ratio multiplier,
/// `lambert_sampling`'s `stratified` module): its points changed by
/// design; the Sobol and independent values did not, as the f64 digests of
/// the estimator and the sampling crate's pinned Sobol values show. And
/// when the stratified shifts and jitters became 32-bit hashes, the
/// digest was 0xe0e0_a19a_4250_d10c; again only stratified points moved.
/// The f32 path's native fill of sequence points moved nothing: it gives
/// the f64 points rounded down to 24 bits, to the bit, as before. Re-pinned
/// when a disk seen from its axis (a circle) took its azimuth from the
/// linear guess without a Newton step (`DiskSolidAngle`): the digest was
/// 0x3e42_7f3e_63d6_7a54; compared with the CLI, only the rows of
/// the coaxial disk of half-angle 1.2 moved (means by at most 2e-11
/// relative, standard errors by at most 5e-8), those of half-angle 0.01
/// did not. Re-pinned when estimates took a disk's directions from its
/// `TabulatedDiskSolidAngle` (the same root by quadrature instead of
/// Carlson's integrals, a few ulps apart): the digest was
/// 0x5255_c32f_f4c6_09dc; compared with the CLI on the two close disks, f32
/// means moved by at most 1e-8 relative (f32 rounds at 6e-8) and standard
/// errors by at most 5e-6 relative, nothing else moved. Re-pinned when
/// projected sampling of a non-central polygon started its solve from its
/// `TabulatedProjectedPolygon` (the same root by fewer Halley steps): the
/// digest was 0xcbf2_e45c_c23f_e2e1; the f64 digests did not move (a
/// projected sample of a polygon scores L Ω⊥ whatever its direction),
/// compared with the CLI on the study's grazing rectangle and side
/// square (8 strategies × 3 sequences × 2 precisions), only the f32
/// `projected` and `auto` rows of the rectangle moved, means by at most
/// 1.3e-11 relative, no standard error. Re-pinned when the spherical
/// triangle and rectangle took their sines from `sin_cos` instead of libm
/// (so the kernels sample them inline): the digest was
/// 0xd76d_3022_8a56_0e7d; the f64 digests did not move; compared with the
/// CLI at 2^22 samples, the f32 light and MIS means of the triangle and of
/// the grazing rectangle moved by at most 1.4e-9 relative (f32 rounds at
/// 6e-8). Re-pinned when a circle's azimuth (a disk seen from its axis)
/// took its sines from `sin_cos` instead of libm, so that the tabulated
/// disk's batch draws it in one vectorised pass: the digest was
/// 0xc9e9_5620_e23a_0be2; compared with the CLI on the two coaxial disks
/// (8 strategies × 3 sequences × 2 precisions, 70 003 samples), f32 means
/// moved by at most 2.2e-9 relative and standard errors by at most 1.2e-6
/// relative, only in the light, MIS and projected rows. Re-pinned when
/// the projected samplers (polygon sectors, cap segments) took their sines
/// from `sin_cos` and v − sin v from a fixed polynomial instead of libm
/// and a summing loop: the digest was 0x3d65_09f9_51bf_2011; compared with
/// the CLI on the grazing rectangle, the straddling sphere, the sky cap
/// across the horizon, the triangle, the close disk and the tilted sphere
/// (9 strategies with `auto` × 3 sequences × 2 precisions, 70 003
/// samples), only `projected` and `auto` rows moved: in f32 the
/// rectangle's means by at most 1.1e-7 relative (its Ω⊥, which every
/// sample scores, moved by two f32 ulps) and standard errors by 5.8e-9,
/// the sphere's and cap's means by at most 1.2e-10; in f64 means by at
/// most 2.1e-16 relative. Re-pinned when f64 MIS on spheres and sky caps
/// took a division per half instead of one shared by both: the digest was
/// 0x725f_599e_438b_fcbd; compared row by row on every built-in scene (9
/// strategies with `auto` × 3 sequences, this test's configuration), only
/// the four MIS rows of the straddling sphere, which runs in f64 in an f32
/// estimate, moved: no mean, standard errors by at most 5.8e-15 relative.
/// Re-pinned when the circular-segment solve of the projected cap sampler
/// started from a fitted guess (one Halley step instead of three, the
/// same root to within 3 ulps of φ in f64): the digest was
/// 0x8c57_b299_3b51_8533; compared with the CLI on the sky cap across the
/// horizon, the straddling sphere and the tilted sphere (9 strategies with
/// `auto` × 3 sequences × 2 precisions, at 10 007 samples with seed 3 and
/// 70 003 with seed 11), only the f32 `projected` and `auto` rows of the
/// cap and of the straddling sphere moved, means by at most 2.5e-10
/// relative (f32 rounds at 6e-8), no standard error, no f64 row.
/// Re-pinned when `Estimate::from_values` summed M₂'s non-negative terms
/// with plain adds in windows of 4096 values instead of a Neumaier step
/// per term (within about 260u relative, u = 2⁻⁵³; 6–10 % faster estimates): the
/// digest was 0x309f_0be6_9624_3e3f; compared with the CLI on every
/// built-in scene (7 strategies, independent samples, f32, 2^10…2^16 × 4
/// replicates, seed 3, 728 rows), no mean moved; standard errors moved
/// by at most 4.4e-15 relative and sample variances by at most 6.6e-15,
/// in independent rows only (the randomized-QMC errors come from the
/// replicates' spread). The f64 digests did not move. Re-pinned when
/// `from_values` summed the samples themselves with plain adds in windows
/// of 256 values (16 per lane) when none is negative, a chunk of equal
/// samples exactly, and the rounding floor grew from 5u to 21u to match:
/// the digest was 0x4939_44bb_4d82_da89; compared with the CLI on the
/// same 728 rows, means moved in 2 rows by at most 1.7e-16 relative,
/// sample variances in 13 by at most 2.9e-15, and standard errors in 208,
/// the floor-bound ones by the floor's factor 4.2. Re-pinned when the f32
/// SplitMix64 fill took its grouped layout (each group of 16 points from
/// 16 outputs, the first 8 giving x and the last 8 y, so that a vector of
/// outputs converts without shuffles: 0.91× the time of an f32 light or
/// MIS estimate): the digest was 0xd110_d128_8832_5ba3. Every independent
/// f32 sample has new numbers, so the independent rows are new draws:
/// compared with the CLI on the same 728 rows, the mean coverage of the
/// 99 % intervals went from 99.42 % to 99.28 % (randomized-QMC points
/// do not come from this stream). Re-pinned when light sampling of a
/// sphere or sky cap, and the light half of MIS on them, came to draw n·ω
/// alone (`ConeCosine`, the cone's azimuth measured from the normal's
/// projection: the same distribution, not the same value for the same
/// u; 0.80× the time of the f32 light estimate): the digest was
/// 0x1bbd_28cf_9647_085b. Compared with the CLI on every built-in scene
/// (7 strategies × 3 sequences, f32, 2^10…2^16 × 4 replicates, seed 3,
/// 2,184 rows), the 273 rows of the tilted, straddling and several-lights
/// spheres and the sky cap that use a cone's light samples are new draws
/// and no other row moved; per strategy and sequence the geometric mean
/// of the new to the old relative RMSE lies between 0.87 and 1.06.
/// Re-pinned when the f32 coordinates of stratified points on grids that
/// are not powers of two (N ≤ 2²⁴ per replicate; 10 007 samples here)
/// became the nearest f32 to the coordinate with its jitter cut to 24 −
/// ⌈log₂ N⌉ bits, computed in f32 lanes, instead of the f64 coordinate
/// rounded down: the digest was 0xb7d5_c468_46c3_2132. The f64 points
/// did not move, and the changed f32 ones lie within 2⁻²² of them.
/// Compared with the CLI on seven of the built-in scenes written as scene
/// files (the sky cap, the small coaxial and the close offset disks, the
/// tilted and straddling spheres, the triangle, the grazing rectangle), 7
/// strategies, stratified f32 at
/// 10 007, 160 000 and 1 600 000 samples, seeds 1–8 (147 rows): the
/// geometric mean of the new to the old relative RMSE is 1.000 (0.93 to
/// 1.11), 122 rows equal to three digits, and the 99 % intervals cover
/// the closed form in 1,163 of 1,176 runs before and after.)
/// Re-pinned when the first pair of stratified points came to visit its
/// cells column by column instead of in the golden order of all cells
/// (`lambert_sampling`'s `stratified` module): the digest was
/// 0x044f_586d_0614_1ece. Each pass's points are relabelled, the same in
/// distribution, so every stratified row is a new draw of the same
/// estimator (relative RMSE over 40 seeds before and after, in the module
/// docs, equal within their noise); no other row reads these points.
/// Re-pinned when the later pairs of stratified points (MIS's second
/// point) took their cells from Feistel rounds on grids of 16 columns or
/// more whose N is not a power of two (`lambert_sampling`'s
/// `stratified_shuffle` module): the digest was 0xdeae_e9ce_f324_0c6b.
/// Another relabelling, of which sample gets which cell of a later pair,
/// tested there to pair as at random; only the stratified rows that read a
/// later pair (MIS's second point) moved, new draws of the same
/// estimators.
/// Re-pinned when those rounds moved to 16-bit lanes with a 16-bit hash
/// (the same module): the digest was 0x327c_8b43_461d_137d; another
/// relabelling of the same kind, and the same rows moved.
/// Re-pinned when independent samples came to read one SplitMix64 stream
/// per run, each chunk its window of it (`chunk::ChunkStream`), instead of
/// a stream started at each chunk's seed (whose windows could overlap):
/// the digest was 0xdc11_fd03_8791_5a58; only independent rows moved (new
/// draws; the Sobol and stratified points are not read from the stream).
/// Re-pinned when the projected polygon sampler's arc corrections took
/// their angle from `lambert_sampling`'s branch-free `atan2` instead of
/// libm's (within 3 ulps of it), so that its batch vectorises: the digest
/// was 0x13c6_1135_39d5_2703; only projected rows of polygons moved, in
/// their last bits (a rectangle's mean by 5e-12 relative, its standard
/// error 7e-6).
/// Re-pinned when the concentric map took the sine and cosine of its
/// angle (π/4)t from polynomials in t (`sin_cos_eighth`) instead of Taylor
/// series at the rounded (π/4)t, an ulp or two closer to the exact values:
/// the digest was 0x1a43_8c9c_4101_c76b. Only rows that draw through the
/// concentric map can move (cosine-hemisphere sampling, MIS's cosine half,
/// area sampling of disks, projected sampling of caps and spheres); in f64
/// the same change moved the reference study's means by at most 2.2e-15
/// relative (`chunk_bits.rs`), and the f32 rows were not compared one by
/// one.
#[test]
fn f32_values_are_pinned() {
    let mut bits = Vec::new();
    for named in builtin_scenes() {
        for strategy in strategies() {
            for sequence in SequenceKind::ALL {
                let mut c = config(strategy, sequence, 3);
                c.samples = 10_007;
                let r = estimate(&named.scene, &c).unwrap();
                bits.extend([r.mean.to_bits(), r.std_error.to_bits()]);
            }
        }
    }
    assert_eq!(digest(bits), PINNED, "f32 values changed");
}

/// The digest of [`f32_values_are_pinned`].
const PINNED: u64 = 0x1854_4f04_ed5f_639e;

fn up() -> Receiver {
    Receiver::new(DVec3::ZERO, DVec3::Z).unwrap()
}

fn sphere_at(distance: f64, radius: f64, radiance: f64) -> Scene {
    let tilt = 30f64.to_radians();
    let c = DVec3::new(tilt.sin(), 0.0, tilt.cos()) * distance;
    Scene::new(
        up(),
        vec![Emitter::Sphere(
            SphereLight::new(c, radius, radiance).unwrap(),
        )],
    )
    .unwrap()
}

/// z-test of one f32 estimate at level α = 1e-3 (one test each), N = 2^18;
/// an estimate with a rare-event interval (few hits) must contain the
/// truth in its interval instead.
fn z_ok(scene: &Scene, strategy: Strategy) -> (f64, bool) {
    let r = estimate(scene, &config(strategy, SequenceKind::Independent, 11)).unwrap();
    let truth = closed_form(scene);
    let z = (r.mean - truth) / r.std_error;
    if r.interval != IntervalKind::CentralLimit {
        return (z, r.ci99.0 <= truth && truth <= r.ci99.1);
    }
    (z, z.abs() <= critical(SequenceKind::Independent, 1e-3))
}

/// Where f32 is not enough, the emitter runs in f64 and the estimate says
/// so; where it is, it does not:
/// - a sphere of radius 1 at distance 1e3 (θmax = 1e-3 rad) under uniform
///   hemisphere sampling: the band of misjudged directions along its
///   outline is ~32ε·P/Ω⊥ ≈ 8e-3 of its irradiance — f64, `ErrorBound`;
///   under light sampling (no hit test) it runs in f32;
/// - a disk 1e16 m away: `Range`;
/// - a sky cap of half-angle 1e-4 rad under light sampling runs in f32
///   (its cone is formed from 1 − cos θmax, exact in f32), under cosine
///   sampling it runs in f64;
/// - a sphere of radiance 1e300, far beyond f32's range: f32 (the radiance
///   stays in f64), and its estimate is right.
///
/// Each estimate is z-tested (α = 1e-3 each) against the closed form.
#[test]
fn f32_falls_back_to_f64_where_it_is_not_enough_and_says_why() {
    let far = sphere_at(1e3, 1.0, 1.0);
    let f = f32_fallbacks(&far, Strategy::UniformHemisphere);
    assert_eq!(f.len(), 1, "{f:?}");
    assert!(
        matches!(f[0].reason, FallbackReason::ErrorBound { relative } if relative > 1e-3),
        "{f:?}"
    );
    assert!(f[0]
        .to_string()
        .starts_with("emitters[0] (a sphere) runs in f64: its f32 error bound"));
    assert!(f32_fallbacks(&far, Strategy::Light).is_empty());
    for s in [Strategy::UniformHemisphere, Strategy::Light] {
        let (z, ok) = z_ok(&far, s);
        assert!(ok, "far sphere {s}: z {z}");
    }
    let r = estimate(
        &far,
        &config(Strategy::UniformHemisphere, SequenceKind::Independent, 1),
    )
    .unwrap();
    assert_eq!(r.f64_fallbacks, 1);

    let distant_disk = Scene::new(
        up(),
        vec![Emitter::Disk(
            DiskLight::new(DVec3::new(0.0, 0.0, 1e16), -DVec3::Z, 1e15, 1.0, false).unwrap(),
        )],
    )
    .unwrap();
    let f = f32_fallbacks(&distant_disk, Strategy::Light);
    assert!(matches!(f[0].reason, FallbackReason::Range { .. }), "{f:?}");
    let (z, ok) = z_ok(&distant_disk, Strategy::Light);
    assert!(ok, "distant disk: z {z}");

    let cap = Scene::new(
        up(),
        vec![Emitter::SkyCap(
            SkyCap::new(DVec3::new(0.3, 0.0, 1.0), 1e-4, 2.0).unwrap(),
        )],
    )
    .unwrap();
    assert!(f32_fallbacks(&cap, Strategy::Light).is_empty());
    assert_eq!(f32_fallbacks(&cap, Strategy::CosineHemisphere).len(), 1);
    let (z, ok) = z_ok(&cap, Strategy::Light);
    assert!(ok, "tiny cap: z {z}");

    let bright = sphere_at(10.0, 1.0, 1e300);
    assert!(f32_fallbacks(&bright, Strategy::Light).is_empty());
    let (z, ok) = z_ok(&bright, Strategy::Light);
    assert!(ok, "radiance 1e300: z {z}");
}

/// Zero variance in f32: projected sampling of an unoccluded sphere gives
/// every sample the closed form up to the f32 rounding of Ω⊥ and of each
/// sample's cos θ/p; the estimate lies within its reported standard error
/// (whose floor carries the f32 error bound, ~40ε of the irradiance) of
/// the closed form, and that floor is below 1e-5 relative.
#[test]
fn f32_zero_variance_estimates_are_within_their_error_bound() {
    for distance in [1.5, 10.0, 1e3] {
        let scene = sphere_at(distance, 1.0, 3.0);
        let truth = closed_form(&scene);
        let r = estimate(
            &scene,
            &config(Strategy::Projected, SequenceKind::Independent, 2),
        )
        .unwrap();
        assert_eq!(r.f64_fallbacks, 0);
        assert!(
            (r.mean - truth).abs() <= r.std_error,
            "d {distance}: mean {} truth {truth} se {:e}",
            r.mean,
            r.std_error
        );
        assert!(
            r.std_error <= 1e-5 * truth,
            "d {distance}: se {:e}",
            r.std_error
        );
    }
}

/// Light sampling of a sphere light the horizon does not cut counts every
/// sample as a hit (its kernel then skips the clamp and the count, and
/// reports the block's length); one the horizon cuts counts some but not
/// all. Each case on every sequence; the straddling sphere is the negative
/// control, showing the count is not the sample count regardless.
#[test]
fn f32_sphere_light_hits_are_every_sample_only_above_the_horizon() {
    // Centre 30° off the normal: radius 1 at distance 10 clears the
    // horizon (half-angle 5.7°); radius 1 at distance 1.05 does not
    // (half-angle 72°, reaching 102° from the normal).
    let clear = sphere_at(10.0, 1.0, 1.0);
    let cut = sphere_at(1.05, 1.0, 1.0);
    for sequence in SequenceKind::ALL {
        let mut c = config(Strategy::Light, sequence, 5);
        c.samples = 70_003;
        let r = estimate(&clear, &c).unwrap();
        assert_eq!(r.hits, c.samples, "{sequence:?}");
        let r = estimate(&cut, &c).unwrap();
        assert!(r.hits > 0 && r.hits < c.samples, "{sequence:?}: {}", r.hits);
    }
}
