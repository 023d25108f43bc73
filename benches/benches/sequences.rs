//! ns per 2-D point of the sample sequences over a chunk of 4096 samples,
//! as the randomized-QMC estimator reads them: point by point through the
//! cursor (`start_sample` then `next_2d`, the path the estimator used to
//! take) against the batch fill (`fill_2d`, one dimension pair for the
//! whole chunk). Both give the same values to the bit; the ratio is the
//! speed-up of the batch kernels. The `split` rows are the fills the
//! estimator calls (`fill_2d_split`, and `fill_2d_split_f32` for its f32
//! path), run inside `Isa::run` as the estimator runs them. Stratified
//! uses N = 3 125 000, one replicate of a 5·10⁷-sample estimate (a
//! 1250 × 2500 grid), and N = 2²⁰, one of a 2²⁴-sample estimate's (a
//! 1024 × 1024 grid, where the keyed permutation of request 1 needs no
//! cycle walk). The `chunk stream` rows are the independent estimator's
//! stream (a chunk's window of the run's SplitMix64 stream), block by
//! block, in each instruction set.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::{DVec2, Vec2};
use lambert_benches::config;
use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::{Independent, SampleSequence, Sobol, Stratified};

/// Samples per chunk, as in the estimator.
const CHUNK: usize = 4096;

/// Chunks cycled through, so successive iterations read different indices
/// of one pass of the stratified sequence.
const CHUNKS: u64 = 700;

fn bench_sequence<S: SampleSequence>(c: &mut Criterion, name: &str, seq: S) {
    let mut g = c.benchmark_group("sequences");
    g.throughput(Throughput::Elements(CHUNK as u64));
    for request in [0u64, 1] {
        g.bench_function(format!("{name} request {request} cursor"), |b| {
            let mut s = seq.clone();
            let mut out = vec![DVec2::ZERO; CHUNK];
            let mut chunk = 0u64;
            b.iter(|| {
                chunk = (chunk + 1) % CHUNKS;
                let first = chunk * CHUNK as u64;
                for (k, o) in out.iter_mut().enumerate() {
                    s.start_sample(first + k as u64);
                    for _ in 0..request {
                        s.next_2d();
                    }
                    *o = s.next_2d();
                }
                black_box(&out);
            })
        });
        g.bench_function(format!("{name} request {request} batch"), |b| {
            let mut out = vec![DVec2::ZERO; CHUNK];
            let mut chunk = 0u64;
            b.iter(|| {
                chunk = (chunk + 1) % CHUNKS;
                seq.fill_2d(chunk * CHUNK as u64, request, &mut out);
                black_box(&out);
            })
        });
    }
    // As the estimator reads them: structure of arrays, inside
    // `Isa::run` (the widest set this processor has), f64 and f32.
    let isa = Isa::selected();
    for request in [0u64, 1] {
        bench_split(
            &mut g,
            format!("{name} request {request} split {isa}"),
            |first, x: &mut [f64], y: &mut [f64]| {
                isa.run(
                    #[inline(always)]
                    || seq.fill_2d_split(first, request, x, y),
                )
            },
        );
        bench_split(
            &mut g,
            format!("{name} request {request} split f32 {isa}"),
            |first, x: &mut [f32], y: &mut [f32]| {
                isa.run(
                    #[inline(always)]
                    || seq.fill_2d_split_f32(first, request, x, y),
                )
            },
        );
    }
    g.bench_function(format!("{name} request 0 batch f32"), |b| {
        let mut out = vec![Vec2::ZERO; CHUNK];
        let mut chunk = 0u64;
        b.iter(|| {
            chunk = (chunk + 1) % CHUNKS;
            seq.fill_2d_f32(chunk * CHUNK as u64, 0, &mut out);
            black_box(&out);
        })
    });
    g.finish();
}

/// Times `fill(first, x, y)` on a chunk's arrays, chunk after chunk.
fn bench_split<T: Copy + Default>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: String,
    fill: impl Fn(u64, &mut [T], &mut [T]),
) {
    g.bench_function(name, |b| {
        let (mut x, mut y) = (vec![T::default(); CHUNK], vec![T::default(); CHUNK]);
        let mut chunk = 0u64;
        b.iter(|| {
            chunk = (chunk + 1) % CHUNKS;
            fill(chunk * CHUNK as u64, &mut x, &mut y);
            black_box((&x, &y));
        })
    });
}

/// The independent estimator's own stream (`ChunkStream`, a chunk's
/// window of the run's SplitMix64 stream), filled block by block as a
/// chunk reads it: 4096 outputs as f64 and as f32 coordinates, in every
/// instruction set this processor has.
fn chunk_stream(c: &mut Criterion) {
    use lambert_estimator::chunk::{ChunkStream, BLOCK};
    let mut g = c.benchmark_group("sequences");
    g.throughput(Throughput::Elements(CHUNK as u64));
    let stream = ChunkStream::new(1, 1, 0);
    // One fill per block, as the chunk loop calls it, in either precision.
    macro_rules! blocks {
        ($isa:expr, |$first:ident, $x:ident, $y:ident| $fill:expr) => {
            |first: u64, x: &mut [_], y: &mut [_]| {
                $isa.run(
                    #[inline(always)]
                    || {
                        for (k, ($x, $y)) in
                            x.chunks_mut(BLOCK).zip(y.chunks_mut(BLOCK)).enumerate()
                        {
                            let $first = first + (k * BLOCK) as u64;
                            $fill;
                        }
                    },
                )
            }
        };
    }
    for isa in Isa::available() {
        bench_split::<f64>(
            &mut g,
            format!("chunk stream {isa}"),
            blocks!(isa, |at, x, y| stream.fill_2d_in(isa, at, x, y)),
        );
        bench_split::<f32>(
            &mut g,
            format!("chunk stream f32 {isa}"),
            blocks!(isa, |at, x, y| stream.fill_2d_f32_in(isa, at, x, y)),
        );
    }
    g.finish();
}

fn sequences(c: &mut Criterion) {
    chunk_stream(c);
    bench_sequence(c, "independent", Independent::new(1));
    bench_sequence(c, "sobol", Sobol::new(1));
    bench_sequence(c, "stratified", Stratified::new(3_125_000, 1).unwrap());
    // A power-of-two pass (a 1024 × 1024 grid), as in a 2²⁴-sample
    // estimate's 16 randomizations and every row of the study.
    bench_sequence(c, "stratified 2^20", Stratified::new(1 << 20, 1).unwrap());
}

// criterion_group! generates an undocumented pub fn.
#[allow(missing_docs)]
mod group {
    use super::*;
    criterion_group! {
        name = benches;
        config = config();
        targets = sequences
    }
}
criterion_main!(group::benches);
