//! One chunk of an estimate, computed in cache-sized blocks inside the
//! instruction set the process selected.
//!
//! A chunk's values are what they have always been (the pinned-value tests
//! check it): the independent path reads the chunk's `Pcg64Mcg` stream in
//! the same order, emitter by emitter (each emitter's n first coordinates,
//! then for MIS its n light coordinates), and the randomized-QMC path reads
//! request d of sample i from the sequence. What changed is how:
//!
//! - **Blocks.** The chunk is evaluated [`BLOCK`] samples at a time: the
//!   stream jumps to each emitter's offset for the block
//!   ([`McgStream::fill_2d`]), the coordinates land in arrays that stay
//!   in the second-level cache, and [`PreparedEmitter::add_batch_in`] adds the
//!   emitter's estimates to the block's values.
//! - **No allocation per chunk.** Every buffer is the worker thread's own,
//!   kept between chunks (`with_scratch`): a chunk of 4096 samples used to
//!   allocate ~160 KB, which the allocator returned to the system and took
//!   back (page faults, and on two threads TLB shootdowns that stall both).
//! - **One instruction set for the whole chunk.** The stream, the kernels
//!   and the summary run inside [`Isa::run`], compiled for the widest vector
//!   set the processor has; the bits do not depend on which
//!   ([`lambert_sampling::isa`]). The kernels are one out-of-line copy per
//!   set ([`PreparedEmitter::add_batch_in`]) that every chunk loop calls
//!   block by block, not a copy inlined into each loop.

mod mcg;
mod precision_f32;

use std::cell::RefCell;

use lambert_light::receiver::Receiver;
use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::SampleSequence;

pub use lambert_sampling::sequence::round_down_24;
pub use mcg::McgStream;
pub use precision_f32::{independent_chunk_f32, sequence_chunk_f32};

use crate::statistics::Estimate;
use crate::strategy::{PartHits, PreparedEmitter, Store};

/// Samples evaluated together: a whole chunk of the estimator's
/// ([`crate::estimation::CHUNK_SIZE`], 4096), whose coordinates (4 arrays
/// of f64, 128 KB) and values stay in the second-level cache.
///
/// Each block pays a fixed cost per emitter: the stream's jump to the
/// emitter's offset (a 128-bit power by squaring, then sixteen lane
/// states) and the kernel's set-up (its frame, its cone, its dispatch).
/// Blocks of 512 that fit the first-level cache paid it eight times a
/// chunk; measured against them (alternated runs, medians of 7, the same
/// values and hits), whole-chunk blocks took 0.94× the time per sample
/// of f64 and f32 light sampling of a sphere light, 0.94–0.97× with MIS,
/// 0.96–0.99× on Sobol and stratified points, and no longer on a scene
/// of a polygon, a disk and a sky cap; 1024 took 0.96×.
pub const BLOCK: usize = crate::estimation::CHUNK_SIZE as usize;

/// A chunk's estimate and, per emitter, how many samples had a non-zero
/// value in each part of its estimate.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChunkResult {
    /// The chunk's estimate.
    pub estimate: Estimate,
    /// Per emitter (in order), the non-zero counts of its parts.
    pub hits: Vec<PartHits>,
}

/// A worker thread's buffers, kept from chunk to chunk.
#[derive(Default)]
struct Scratch {
    values: Vec<f64>,
    ux: Vec<f64>,
    uy: Vec<f64>,
    vx: Vec<f64>,
    vy: Vec<f64>,
    /// A chunk's sequence points, request after request: x coordinates.
    px: Vec<f64>,
    /// … and y coordinates.
    py: Vec<f64>,
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Runs `f` with this thread's scratch buffers: values sized `n`, zeroed
/// unless there are emitters (the first one's kernel overwrites each
/// block's values, [`Store::Overwrite`], so they may hold whatever the
/// previous chunk left), coordinate blocks sized [`BLOCK`].
fn with_scratch<R>(n: usize, emitters: usize, f: impl FnOnce(&mut Scratch) -> R) -> R {
    SCRATCH.with(|cell| {
        let mut guard = cell.borrow_mut();
        let s = &mut *guard;
        if emitters > 0 {
            // Only slots past the previous length are written here.
            s.values.truncate(n);
        } else {
            s.values.clear();
        }
        s.values.resize(n, 0.0);
        for v in [&mut s.ux, &mut s.uy, &mut s.vx, &mut s.vy] {
            v.resize(BLOCK, 0.0);
        }
        f(s)
    })
}

/// How emitter `k` of a chunk stores its values: the first overwrites
/// the block ([`with_scratch`] leaves it unzeroed), the others add.
fn first_overwrites(k: usize) -> Store {
    if k == 0 {
        Store::Overwrite
    } else {
        Store::Add
    }
}

/// One chunk of `n` independent samples from the `Pcg64Mcg` stream seeded
/// with `chunk_seed` (module docs), run with instruction set `isa`.
pub fn independent_chunk(
    prepared: &[PreparedEmitter],
    receiver: &Receiver,
    chunk_seed: u64,
    n: usize,
    isa: Isa,
) -> ChunkResult {
    let stream = McgStream::seed_from_u64(chunk_seed);
    with_scratch(n, prepared.len(), |s| {
        isa.run_without_gfni(
            #[inline(always)]
            || {
                let mut hits = vec![[0u64; 2]; prepared.len()];
                let mut start = 0;
                while start < n {
                    let m = BLOCK.min(n - start);
                    let mut offset = 0u64;
                    for (k, (p, h)) in prepared.iter().zip(hits.iter_mut()).enumerate() {
                        let first = offset + start as u64;
                        stream.fill_2d(first, &mut s.ux[..m], &mut s.uy[..m]);
                        if p.technique.dimensions() > 1 {
                            let first = first + n as u64;
                            stream.fill_2d(first, &mut s.vx[..m], &mut s.vy[..m]);
                        }
                        let got = p.add_batch_in(
                            isa,
                            receiver,
                            &s.ux[..m],
                            &s.uy[..m],
                            &s.vx[..m],
                            &s.vy[..m],
                            &mut s.values[start..start + m],
                            first_overwrites(k),
                        );
                        h[0] += got[0];
                        h[1] += got[1];
                        offset += (p.technique.dimensions() * n) as u64;
                    }
                    start += m;
                }
                ChunkResult {
                    estimate: Estimate::from_values(&s.values),
                    hits,
                }
            },
        )
    })
}

/// One chunk of a randomized-QMC estimate over the sample indices `range`:
/// sample i's request d is read from `sequence` (each emitter's dimensions
/// in emitter order), a whole chunk per request ([`SampleSequence::fill_2d`],
/// whose per-call set-up is per chunk), and evaluated block by block.
pub fn sequence_chunk<S: SampleSequence>(
    prepared: &[PreparedEmitter],
    receiver: &Receiver,
    sequence: &S,
    range: std::ops::Range<u64>,
    isa: Isa,
) -> ChunkResult {
    let n = (range.end - range.start) as usize;
    let dims: usize = prepared.iter().map(|p| p.technique.dimensions()).sum();
    with_scratch(n, prepared.len(), |s| {
        // Every element is written by the fills below: no zeroing per chunk.
        s.px.resize(n * dims, 0.0);
        s.py.resize(n * dims, 0.0);
        isa.run(
            #[inline(always)]
            || {
                for (request, (x, y)) in
                    s.px.chunks_exact_mut(n)
                        .zip(s.py.chunks_exact_mut(n))
                        .enumerate()
                {
                    sequence.fill_2d_split(range.start, request as u64, x, y);
                }
                let mut hits = vec![[0u64; 2]; prepared.len()];
                let mut start = 0;
                while start < n {
                    let m = BLOCK.min(n - start);
                    let mut d = 0;
                    for (k, (p, h)) in prepared.iter().zip(hits.iter_mut()).enumerate() {
                        let at = |request: usize| request * n + start..request * n + start + m;
                        // MIS's second point is request d + 1; other
                        // techniques read only their first.
                        let second = if p.technique.dimensions() > 1 {
                            at(d + 1)
                        } else {
                            at(d)
                        };
                        let got = p.add_batch_in(
                            isa,
                            receiver,
                            &s.px[at(d)],
                            &s.py[at(d)],
                            &s.px[second.clone()],
                            &s.py[second],
                            &mut s.values[start..start + m],
                            first_overwrites(k),
                        );
                        h[0] += got[0];
                        h[1] += got[1];
                        d += p.technique.dimensions();
                    }
                    start += m;
                }
                ChunkResult {
                    estimate: Estimate::from_values(&s.values),
                    hits,
                }
            },
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimation::prepare;
    use crate::strategy::{Strategy, Technique};
    use glam::DVec2;
    use glam::DVec3;
    use lambert_light::builtin::{builtin_scenes, NamedScene};
    use lambert_light::emitter::{Emitter, PolygonLight};
    use lambert_light::Scene;
    use lambert_sampling::sequence::{Sobol, Stratified};

    /// One sample's value by the one-sample path,
    /// [`PreparedEmitter::evaluate_u`], except light sampling of a sphere,
    /// which the estimator has always taken through its cone:
    /// F = L Ω max(n_local·ω_local, 0), with n_local·ω_local drawn by
    /// `ConeCosine` (the azimuth measured from n_local's projection).
    fn reference_value(p: &PreparedEmitter, receiver: &Receiver, u: DVec2, u2: DVec2) -> f64 {
        use lambert_sampling::f64::{ConeCosine, SphereLightSampler};
        if let (Technique::Light, Emitter::Sphere(e)) = (p.technique, &p.emitter) {
            return match SphereLightSampler::new(e.sphere).at(receiver.point) {
                Ok(s) => {
                    let n_local = s.frame().to_local(receiver.normal);
                    let cosine = ConeCosine::new(s.cone(), n_local).sample(u);
                    e.radiance * s.solid_angle() * cosine.max(0.0)
                }
                Err(_) => 0.0,
            };
        }
        p.evaluate_u(receiver, u, u2)
    }

    /// The chunk as the estimator computed it before blocks, lanes and
    /// instruction sets: the whole chunk's points from `rand_pcg`, one
    /// emitter after the other, one sample at a time.
    fn reference_independent(
        prepared: &[PreparedEmitter],
        receiver: &Receiver,
        seed: u64,
        n: usize,
    ) -> (Estimate, Vec<u64>) {
        use rand_core::{RngCore, SeedableRng};
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
        let mut values = vec![0.0; n];
        let (mut u, mut u2) = (vec![DVec2::ZERO; n], vec![DVec2::ZERO; n]);
        let scale = 1.0 / (1u64 << 32) as f64;
        let mut next = || {
            let bits = rng.next_u64();
            DVec2::new(
                (bits >> 32) as f64 * scale,
                (bits & 0xffff_ffff) as f64 * scale,
            )
        };
        let mut nonzero = Vec::new();
        for p in prepared {
            u.iter_mut().for_each(|x| *x = next());
            if p.technique.dimensions() > 1 {
                u2.iter_mut().for_each(|x| *x = next());
            }
            let mut count = 0;
            for (k, v) in values.iter_mut().enumerate() {
                let value = reference_value(p, receiver, u[k], u2[k]);
                count += u64::from(value != 0.0);
                *v += value;
            }
            nonzero.push(count);
        }
        (Estimate::from_values(&values), nonzero)
    }

    /// Polygons of more vertices than the built-in scenes have: a tilted
    /// one-sided pentagon and a two-sided hexagon, whose hit tests take the
    /// padded loop of eight edges (`PolygonFromOrigin::padded`), and a
    /// nonagon, which takes the general test.
    fn many_sided_scenes() -> Vec<NamedScene> {
        let polygon = |n: u32, two_sided: bool| {
            let vertices = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
                    // Counter-clockwise seen from below: the front faces the receiver.
                    DVec3::new(a.cos(), -a.sin(), 2.0 + 0.4 * a.cos())
                })
                .collect();
            Emitter::Polygon(PolygonLight::new(vertices, 1.5, two_sided).unwrap())
        };
        let receiver = Receiver::new(DVec3::ZERO, DVec3::Z).unwrap();
        [
            ("pentagon", 5, false),
            ("hexagon", 6, true),
            ("nonagon", 9, false),
        ]
        .into_iter()
        .map(|(name, n, two_sided)| NamedScene {
            name,
            scene: Scene::new(receiver, vec![polygon(n, two_sided)]).unwrap(),
        })
        .collect()
    }

    /// Every built-in scene and [`many_sided_scenes`] × strategy ×
    /// instruction set: the block kernels give the chunk estimate of the
    /// old path to the bit, for a full chunk and a partial one.
    #[test]
    fn blocks_lanes_and_instruction_sets_keep_every_bit() {
        // Sphere light sampling's chunks with every sample a hit and with
        // some missed: both of its kernel's paths are compared.
        let mut sphere_paths = [0; 2];
        for named in builtin_scenes().into_iter().chain(many_sided_scenes()) {
            let receiver = named.scene.receiver;
            for strategy in std::iter::once(Strategy::Auto).chain(Strategy::ALL) {
                let (prepared, _) = prepare(&named.scene, strategy);
                for (seed, n) in [(3u64, 4096usize), (17, 1000)] {
                    let (want, nonzero) = reference_independent(&prepared, &receiver, seed, n);
                    for isa in Isa::available() {
                        let got = independent_chunk(&prepared, &receiver, seed, n, isa);
                        assert_eq!(got.estimate, want, "{} {strategy} {isa}", named.name);
                        // A sphere's light sampling counts its non-zero
                        // values, with or without the clamp (a cone above
                        // the horizon counts every sample).
                        for ((p, hits), &count) in prepared.iter().zip(&got.hits).zip(&nonzero) {
                            if let (Technique::Light, Emitter::Sphere(_)) =
                                (p.technique, &p.emitter)
                            {
                                assert_eq!(*hits, [count, 0], "{} {strategy} {isa}", named.name);
                                sphere_paths[usize::from(count < n as u64)] += 1;
                            }
                        }
                    }
                }
                // Randomized QMC: the old path evaluated the whole chunk's
                // points emitter by emitter.
                let sobol = Sobol::new(5);
                let stratified = Stratified::new(5000, 5).unwrap();
                let range = 4096..5000u64;
                let n = 904;
                let dims: usize = prepared.iter().map(|p| p.technique.dimensions()).sum();
                let reference = |seq: &dyn Fn(u64, &mut [DVec2])| {
                    let mut points = vec![DVec2::ZERO; n * dims];
                    for (r, block) in points.chunks_exact_mut(n).enumerate() {
                        seq(r as u64, block);
                    }
                    let mut values = vec![0.0; n];
                    let mut d = 0;
                    for p in &prepared {
                        let u = &points[d * n..(d + 1) * n];
                        let u2 = if p.technique.dimensions() > 1 {
                            &points[(d + 1) * n..(d + 2) * n]
                        } else {
                            u
                        };
                        for (k, v) in values.iter_mut().enumerate() {
                            *v += reference_value(p, &receiver, u[k], u2[k]);
                        }
                        d += p.technique.dimensions();
                    }
                    Estimate::from_values(&values)
                };
                let want_sobol = reference(&|r, b| sobol.fill_2d(range.start, r, b));
                let want_strat = reference(&|r, b| stratified.fill_2d(range.start, r, b));
                for isa in Isa::available() {
                    let got = sequence_chunk(&prepared, &receiver, &sobol, range.clone(), isa);
                    assert_eq!(
                        got.estimate, want_sobol,
                        "{} {strategy} sobol {isa}",
                        named.name
                    );
                    let got = sequence_chunk(&prepared, &receiver, &stratified, range.clone(), isa);
                    assert_eq!(
                        got.estimate, want_strat,
                        "{} {strategy} strat {isa}",
                        named.name
                    );
                }
            }
        }
        assert!(sphere_paths.iter().all(|&c| c > 0), "{sphere_paths:?}");
    }

    /// Sets this thread's f64 values buffer to `values`.
    fn leave_in_buffer(values: Vec<f64>) {
        SCRATCH.with(|cell| cell.borrow_mut().values = values);
    }

    /// `run` (a chunk of `n` samples) gives the same estimate and hits
    /// after `leave` put NaNs or a longer chunk's values in its values
    /// buffer as on an empty one, and a finite estimate: the check of both
    /// precisions' `overwriting_first_emitter_ignores_what_the_buffer_held`.
    pub(super) fn assert_ignores_stale_buffer(
        leave: fn(Vec<f64>),
        run: &dyn Fn() -> ChunkResult,
        n: usize,
        case: &str,
    ) {
        leave(Vec::new());
        let fresh = run();
        assert_eq!(fresh.estimate.non_finite(), 0, "{case}");
        for stale in [vec![f64::NAN; 2 * n], vec![1e300; n + 1]] {
            leave(stale);
            let again = run();
            assert_eq!(again.estimate, fresh.estimate, "{case}");
            assert_eq!(again.hits, fresh.hits, "{case}");
        }
    }

    /// The first emitter overwrites each block's values ([`first_overwrites`]),
    /// so a chunk gives the bits of one on a zeroed buffer whatever the
    /// buffer held: NaNs (an unwritten slot would carry one into the
    /// estimate as a non-finite sample) or a longer chunk's values;
    /// independent and Sobol chunks, every built-in scene × every strategy
    /// and `auto` × every instruction set, at a chunk length that ends
    /// inside a block. Negative control: a kernel that adds to the
    /// poisoned buffer leaves NaNs.
    #[test]
    fn overwriting_first_emitter_ignores_what_the_buffer_held() {
        let n = BLOCK + 37;
        let sobol = Sobol::new(7);
        for named in builtin_scenes() {
            let (scene, receiver) = (&named.scene, &named.scene.receiver);
            for strategy in std::iter::once(Strategy::Auto).chain(Strategy::ALL) {
                let (prepared, _) = prepare(scene, strategy);
                for isa in Isa::available() {
                    let runs: [&dyn Fn() -> ChunkResult; 2] = [
                        &|| independent_chunk(&prepared, receiver, 7, n, isa),
                        &|| sequence_chunk(&prepared, receiver, &sobol, 64..64 + n as u64, isa),
                    ];
                    let case = format!("{} {strategy} {isa}", named.name);
                    for run in runs {
                        assert_ignores_stale_buffer(leave_in_buffer, run, n, &case);
                    }
                }
            }
        }
        let scene = &builtin_scenes()[0].scene;
        let (prepared, _) = prepare(scene, Strategy::Light);
        let u = vec![0.25; 64];
        for (store, finite) in [(Store::Overwrite, true), (Store::Add, false)] {
            let mut out = vec![f64::NAN; 64];
            let isa = Isa::selected();
            prepared[0].add_batch_in(isa, &scene.receiver, &u, &u, &u, &u, &mut out, store);
            assert_eq!(out.iter().all(|v| v.is_finite()), finite, "{store:?}");
        }
    }
}
