//! One chunk of an estimate, computed in cache-sized blocks inside the
//! instruction set the process selected.
//!
//! The independent path reads the run's SplitMix64 stream ([`ChunkStream`])
//! emitter by emitter (each emitter's n first coordinates, then for MIS its
//! n light coordinates), and the randomized-QMC path reads request d of
//! sample i from the sequence. How:
//!
//! - **Blocks.** The chunk is evaluated [`BLOCK`] samples at a time: the
//!   stream is read from each emitter's offset for the block
//!   ([`SplitMix64::fill_2d`]), the coordinates land in arrays that stay
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

mod precision_f32;
mod requests;
mod stream;

use std::cell::RefCell;

use lambert_light::receiver::Receiver;
use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::SampleSequence;
#[cfg(doc)]
use lambert_sampling::sequence::SplitMix64;

pub use lambert_sampling::sequence::round_down_24;
pub use precision_f32::{independent_chunk_f32, sequence_chunk_f32};
pub use stream::ChunkStream;

use crate::statistics::Estimate;
use crate::strategy::{PartHits, PreparedEmitter, Store};

/// Samples evaluated together: a whole chunk of the estimator's
/// ([`crate::estimation::CHUNK_SIZE`], 4096), whose coordinates (4 arrays
/// of f64, 128 KB) and values stay in the second-level cache.
///
/// Each block pays a fixed cost per emitter: the stream's lane states at
/// the emitter's offset (before 2026-12-06, a 128-bit power by squaring,
/// when the stream was `Pcg64Mcg`'s) and the kernel's set-up (its frame,
/// its cone, its dispatch).
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

/// One chunk of `n` independent samples, whose numbers `stream` gives
/// ([`ChunkStream`]), run with instruction set `isa`.
pub fn independent_chunk(
    prepared: &[PreparedEmitter],
    receiver: &Receiver,
    stream: ChunkStream,
    n: usize,
    isa: Isa,
) -> ChunkResult {
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
                        stream.fill_2d_in(isa, first, &mut s.ux[..m], &mut s.uy[..m]);
                        if p.technique.dimensions() > 1 {
                            let first = first + n as u64;
                            stream.fill_2d_in(isa, first, &mut s.vx[..m], &mut s.vy[..m]);
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
    let dims = crate::strategy::sample_dimensions(prepared);
    with_scratch(n, prepared.len(), |s| {
        // Every element is written by the fills below: no zeroing per chunk.
        s.px.resize(n * dims, 0.0);
        s.py.resize(n * dims, 0.0);
        isa.run(
            #[inline(always)]
            || {
                requests::fill_requests(sequence, range.start, n, &mut s.px, &mut s.py);
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
