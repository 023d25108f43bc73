//! One chunk of an f32 estimate ([`crate::precision::Precision::F32`]).
//!
//! Its coordinates are 24-bit: u₃₂ = k·2⁻²⁴, exactly representable in
//! f32 and never 1.
//! - **Independent samples** come from the chunk's window of the run's
//!   SplitMix64 stream ([`ChunkStream`]), as in f64: emitter by emitter,
//!   point `offset + i` of the stream's grouped f32 layout
//!   ([`SplitMix64::fill_2d_f32`]) is sample i's point (MIS's second point
//!   `n` points later), with the chunk's instruction set
//!   ([`ChunkStream::fill_2d_f32_in`]).
//! - **Randomized-QMC sequences** give their f32 points
//!   ([`SampleSequence::fill_2d_split_f32`]): Sobol's are the f64 chunk's
//!   points rounded down to 24 bits, ⌊2²⁴u⌋/2²⁴
//!   ([`lambert_sampling::sequence::round_down_24`]), so a point set keeps
//!   its strata down to cells of 2⁻²⁴; stratified points are computed in
//!   f32 (for up to 2²⁴ samples per replicate, each coordinate with its
//!   jitter cut to what an f32 shows, rounded to nearest: within 2⁻²² of
//!   the f64 point and never past its stratum's upper edge;
//!   `lambert_sampling::sequence::Stratified`).
//!
//! An emitter that runs in f64 ([`crate::strategy::F32Fallback`]) gets the
//! f64 chunk's coordinates (the stream's f64 points, or the sequence's
//! points) and the f64 kernel, so its part of the estimate is what an f64
//! estimate computes. The values are accumulated in f64 and
//! summarised as in f64 ([`Estimate::from_values`]), so the result does
//! not depend on the number of threads; nor on the instruction set (no
//! fused multiply-adds, no reassociation: the f32 lanes round as the
//! baseline build does, [`lambert_sampling::isa`]).

use std::cell::RefCell;

use lambert_light::receiver::Receiver;
use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::SampleSequence;
#[cfg(doc)]
use lambert_sampling::sequence::SplitMix64;

use super::{ChunkResult, ChunkStream, BLOCK};
use crate::statistics::Estimate;
use crate::strategy::{PreparedEmitter, PreparedEmitterF32, Store};

/// A worker thread's buffers for f32 chunks, kept from chunk to chunk.
#[derive(Default)]
struct Scratch {
    values: Vec<f64>,
    /// f32 coordinates (u, then MIS's second point v).
    u32s: [Vec<f32>; 4],
    /// f64 coordinates, for emitters that run in f64.
    u64s: [Vec<f64>; 4],
    /// A chunk's sequence points, request after request: x and y.
    points: [Vec<f64>; 2],
    /// The same in f32, when every emitter runs in f32.
    points_f32: [Vec<f32>; 2],
}

thread_local! {
    static SCRATCH: RefCell<Scratch> = RefCell::new(Scratch::default());
}

/// Whether the first emitter's kernel overwrites each block's values
/// ([`Store::Overwrite`]), so that the chunk's values need not be zeroed
/// first: it does whenever there is one (in f32 or f64).
fn first_overwrites(f32s: &[Option<PreparedEmitterF32>]) -> bool {
    !f32s.is_empty()
}

/// Runs `f` with this thread's f32 scratch: values sized `n`, zeroed
/// unless [`first_overwrites`] (then they hold whatever the previous
/// chunk left), coordinate blocks sized [`BLOCK`].
fn with_scratch<R>(
    n: usize,
    f32s: &[Option<PreparedEmitterF32>],
    f: impl FnOnce(&mut Scratch) -> R,
) -> R {
    SCRATCH.with(|cell| {
        let mut guard = cell.borrow_mut();
        let s = &mut *guard;
        if first_overwrites(f32s) {
            // Only slots past the previous length are written here.
            s.values.truncate(n);
        } else {
            s.values.clear();
        }
        s.values.resize(n, 0.0);
        s.u32s.iter_mut().for_each(|v| v.resize(BLOCK, 0.0));
        s.u64s.iter_mut().for_each(|v| v.resize(BLOCK, 0.0));
        f(s)
    })
}

/// Where one emitter's coordinates for a block come from. Each call
/// returns the block's x and y: either `x` and `y` filled, or slices the
/// source already holds (no copy).
trait Coordinates {
    /// Request `request` (0: u, 1: MIS's v) of this block, in f64.
    fn f64s<'a>(&'a self, request: usize, x: &'a mut [f64], y: &'a mut [f64]) -> [&'a [f64]; 2];
    /// The same rounded down to 24 bits.
    fn f32s<'a>(&'a self, request: usize, x: &'a mut [f32], y: &'a mut [f32]) -> [&'a [f32]; 2];
}

/// Evaluates one block of every emitter into `values`, in the emitters'
/// precisions, with the coordinates `coords(k)` gives emitter k; adds the
/// part hits to `hits`. The first emitter overwrites the block's values
/// when it runs in f32 ([`first_overwrites`]); every other adds.
/// The kernels run through the emitters' `add_batch_in` (one copy per
/// instruction set, shared by the independent and sequence chunks).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn block<C: Coordinates>(
    isa: Isa,
    prepared: &[PreparedEmitter],
    f32s: &[Option<PreparedEmitterF32>],
    receiver: &Receiver,
    s: &mut Scratch,
    start: usize,
    m: usize,
    coords: impl Fn(usize) -> C,
    hits: &mut [[u64; 2]],
) {
    for (k, (p, h)) in prepared.iter().zip(hits.iter_mut()).enumerate() {
        let c = coords(k);
        let mis = p.technique.dimensions() > 1;
        let values = &mut s.values[start..start + m];
        let store = if k == 0 { Store::Overwrite } else { Store::Add };
        let got = match &f32s[k] {
            Some(q) => {
                let [ux, uy, vx, vy] = &mut s.u32s;
                let [ux, uy] = c.f32s(0, &mut ux[..m], &mut uy[..m]);
                let [vx, vy] = if mis {
                    c.f32s(1, &mut vx[..m], &mut vy[..m])
                } else {
                    [&vx[..m], &vy[..m]]
                };
                q.add_batch_in(isa, ux, uy, vx, vy, values, store)
            }
            None => {
                let [ux, uy, vx, vy] = &mut s.u64s;
                let [ux, uy] = c.f64s(0, &mut ux[..m], &mut uy[..m]);
                let [vx, vy] = if mis {
                    c.f64s(1, &mut vx[..m], &mut vy[..m])
                } else {
                    [&vx[..m], &vy[..m]]
                };
                p.add_batch_in(isa, receiver, ux, uy, vx, vy, values, store)
            }
        };
        h[0] += got[0];
        h[1] += got[1];
    }
}

/// One emitter's block of the independent stream: its request r of
/// samples `first..` starts at point `first + r·n` of the chunk's window.
struct StreamBlock<'a> {
    stream: &'a ChunkStream,
    first: u64,
    n: u64,
    /// The set the chunk runs in, which the f32 fill's body follows.
    isa: Isa,
}

impl Coordinates for StreamBlock<'_> {
    #[inline(always)]
    fn f64s<'a>(&'a self, request: usize, x: &'a mut [f64], y: &'a mut [f64]) -> [&'a [f64]; 2] {
        self.stream
            .fill_2d_in(self.isa, self.first + request as u64 * self.n, x, y);
        [x, y]
    }
    #[inline(always)]
    fn f32s<'a>(&'a self, request: usize, x: &'a mut [f32], y: &'a mut [f32]) -> [&'a [f32]; 2] {
        self.stream
            .fill_2d_f32_in(self.isa, self.first + request as u64 * self.n, x, y);
        [x, y]
    }
}

/// [`super::independent_chunk`] in f32 (module docs): every emitter's
/// coordinates from the chunk's window `stream`, in f32 for the emitters
/// that run in f32 and in f64 for the others.
pub fn independent_chunk_f32(
    prepared: &[PreparedEmitter],
    f32s: &[Option<PreparedEmitterF32>],
    receiver: &Receiver,
    stream: ChunkStream,
    n: usize,
    isa: Isa,
) -> ChunkResult {
    // Emitter k's first output: the dimensions of the emitters before it.
    let offsets: Vec<u64> = prepared
        .iter()
        .scan(0u64, |o, p| {
            let first = *o;
            *o += (p.technique.dimensions() * n) as u64;
            Some(first)
        })
        .collect();
    with_scratch(n, f32s, |s| {
        isa.run_without_gfni(
            #[inline(always)]
            || {
                let mut hits = vec![[0u64; 2]; prepared.len()];
                let mut start = 0;
                while start < n {
                    let m = BLOCK.min(n - start);
                    let coords = |k: usize| StreamBlock {
                        stream: &stream,
                        first: offsets[k] + start as u64,
                        n: n as u64,
                        isa,
                    };
                    block(
                        isa, prepared, f32s, receiver, s, start, m, coords, &mut hits,
                    );
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

/// [`super::sequence_chunk`] in f32 (module docs): the sequence's f32
/// points for samples `range` ([`SampleSequence::fill_2d_split_f32`]), and
/// its f64 points as well when some emitter runs in f64.
pub fn sequence_chunk_f32<S: SampleSequence>(
    prepared: &[PreparedEmitter],
    f32s: &[Option<PreparedEmitterF32>],
    receiver: &Receiver,
    sequence: &S,
    range: std::ops::Range<u64>,
    isa: Isa,
) -> ChunkResult {
    let n = (range.end - range.start) as usize;
    let dims = crate::strategy::sample_dimensions(prepared);
    let firsts: Vec<usize> = prepared
        .iter()
        .scan(0usize, |d, p| {
            let first = *d;
            *d += p.technique.dimensions();
            Some(first)
        })
        .collect();
    let all_f32 = f32s.iter().all(Option::is_some);
    with_scratch(n, f32s, |s| {
        let [mut px, mut py] = std::mem::take(&mut s.points);
        let [mut qx, mut qy] = std::mem::take(&mut s.points_f32);
        // Every element is written by the fills below: no zeroing per chunk.
        let len = n * dims;
        qx.resize(len, 0.0);
        qy.resize(len, 0.0);
        let wide = if all_f32 { 0 } else { len };
        px.resize(wide, 0.0);
        py.resize(wide, 0.0);
        let result = isa.run(
            #[inline(always)]
            || {
                super::requests::fill_requests_f32(sequence, range.start, n, &mut qx, &mut qy);
                super::requests::fill_requests(sequence, range.start, n, &mut px, &mut py);
                let mut hits = vec![[0u64; 2]; prepared.len()];
                let mut start = 0;
                while start < n {
                    let m = BLOCK.min(n - start);
                    let coords = |k: usize| SequenceBlock {
                        points: Points {
                            f64s: [&px, &py],
                            f32s: [&qx, &qy],
                        },
                        first: firsts[k],
                        start,
                        n,
                    };
                    block(
                        isa, prepared, f32s, receiver, s, start, m, coords, &mut hits,
                    );
                    start += m;
                }
                ChunkResult {
                    estimate: Estimate::from_values(&s.values),
                    hits,
                }
            },
        );
        s.points = [px, py];
        s.points_f32 = [qx, qy];
        result
    })
}

/// A chunk's sequence points, request after request: x and y in f32, and
/// in f64 when some emitter runs in f64 (empty otherwise).
#[derive(Clone, Copy)]
struct Points<'a> {
    f64s: [&'a [f64]; 2],
    f32s: [&'a [f32]; 2],
}

/// One emitter's block of a chunk's sequence points: request r is
/// `points[(first + r)·n + start..]`.
struct SequenceBlock<'a> {
    points: Points<'a>,
    first: usize,
    start: usize,
    n: usize,
}

impl SequenceBlock<'_> {
    /// Where request `request` of this block starts in the point arrays.
    #[inline(always)]
    fn from(&self, request: usize) -> usize {
        (self.first + request) * self.n + self.start
    }
}

impl Coordinates for SequenceBlock<'_> {
    #[inline(always)]
    fn f64s<'a>(&'a self, request: usize, x: &'a mut [f64], _y: &'a mut [f64]) -> [&'a [f64]; 2] {
        let (from, len) = (self.from(request), x.len());
        // Filled whenever an emitter runs in f64, the only ones asking.
        let [px, py] = self.points.f64s;
        [&px[from..from + len], &py[from..from + len]]
    }
    #[inline(always)]
    fn f32s<'a>(&'a self, request: usize, x: &'a mut [f32], _y: &'a mut [f32]) -> [&'a [f32]; 2] {
        let (from, len) = (self.from(request), x.len());
        let [qx, qy] = self.points.f32s;
        [&qx[from..from + len], &qy[from..from + len]]
    }
}
