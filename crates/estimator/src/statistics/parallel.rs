//! A deterministic parallel runner: the same result, to the bit, on 1, 2 or
//! 64 threads.
//!
//! The sample indices `0..total_samples` are cut into **fixed** chunks,
//! `[k·c, min((k+1)·c, total))` for chunk size c, independent of the thread
//! count. Each chunk is estimated on its own (on whichever thread rayon gives
//! it) into an [`Estimate`], and the chunk estimates are merged **in chunk
//! order**, left to right, by [`Estimate::merge`]. Floating-point addition is
//! not associative, so this fixed merge tree is what makes the result
//! independent of scheduling; a rayon `reduce` would merge along a tree that
//! depends on work stealing.
//!
//! For the samples themselves to be the same, a chunk must draw sample `i`
//! from sample index `i` of a randomly accessible sequence
//! ([`SampleSequence::start_sample`]), never from a generator shared with
//! other chunks or advanced by how much work a thread did. [`run_samples`]
//! does exactly that.
//!
//! Memory: chunk estimates are collected in batches of [`BATCH_CHUNKS`]
//! chunks and folded in order, so a run holds at most that many at once.
//! Chunk size trades parallel granularity against merge overhead (one merge
//! per chunk, ~20 flops): 10⁴–10⁶ samples is a good range.

use super::error::StatisticsError;
use super::estimate::Estimate;
use super::timing::Timing;
use lambert_sampling::sequence::SampleSequence;
use rayon::prelude::*;
use std::ops::Range;
use std::sync::{Arc, Mutex};

/// Chunks estimated in parallel before their results are folded in order.
///
/// Each batch ends at a barrier: the workers that finish first wait (spin,
/// then sleep) while the last chunks and the fold finish, and are woken for
/// the next batch. On the 2-vCPU machines this project runs on, waking a
/// sleeping worker was slow for the first ~0.1 s of a process, and with
/// batches of 1024 chunks (4 Mi samples of 4096) a two-thread estimate of
/// 5·10⁷ samples ran at 2.0–2.3 ns/sample against 1.7–1.9 with one batch
/// for the whole run (the sphere light, measured side by side; at 4·10⁸
/// samples both 1.4). 16384 chunks (64 Mi samples) hold about 1.5 MB of
/// chunk results at once.
pub const BATCH_CHUNKS: u64 = 16384;

/// The most chunks one rayon task estimates in a row; a batch is split
/// into tasks of at most this many, and an idle thread steals whole
/// tasks.
///
/// Left to itself, rayon cut a batch into a few long tasks (about two per
/// thread), so a thread that ran slower than the other could not hand
/// work over: on a 2-vCPU Intel Xeon host with AVX-512 (KVM, 2026-12-07),
/// one of the two workers of a two-thread estimate filled its random
/// numbers about twice as slowly as the other for the whole run, the
/// other sat idle for a third of each batch, and two threads took 1/1.25
/// of one thread's time (f64 light sampling of the sphere light, 4·10⁸
/// samples; two one-thread processes side by side did not slow each
/// other). With tasks of at most 16 chunks the slow worker's
/// fill ran at the other's speed as well, and two threads took 1/1.87
/// (f32: 0.78 → 0.72 ns/sample at 5·10⁷). Tasks of 1, 4, 16 and 64
/// chunks measured within noise of each other; 16 chunks (65,536 samples
/// of 4096) cost one steal per ~0.1 ms of work. Which thread runs a chunk
/// never changes a bit (module docs).
const CHUNKS_PER_TASK: usize = 16;

/// A chunk's result that [`run_chunked`] can fold: `Default` is the result
/// of no samples, and `merge` must be a pure function of the two states
/// (the same states merged in the same order give the same bits).
pub trait Mergeable: Default + Send {
    /// Folds `other` (the next chunk in order) into `self`.
    fn merge(&mut self, other: &Self);
}

impl Mergeable for Estimate {
    #[inline]
    fn merge(&mut self, other: &Self) {
        Estimate::merge(self, other);
    }
}

/// The estimate and timing of a [`run_chunked_timed`] run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimedEstimate {
    /// The merged estimate.
    pub estimate: Estimate,
    /// Wall time, samples and threads of the run.
    pub timing: Timing,
}

/// Estimates over `0..total_samples` in fixed chunks of `chunk_size`
/// samples on a pool of `threads` threads, merging the chunk estimates in
/// chunk order (module docs): the result is bit-identical for any `threads`.
///
/// `chunk(k, range)` estimates chunk `k` over the sample indices `range`; it
/// must depend only on `(k, range)` for the result to be reproducible. A
/// panic in it propagates to the caller. ([`run_chunked_merge`] folds any
/// [`Mergeable`] chunk result, e.g. an estimate with counts beside it.)
///
/// ```
/// use lambert_estimator::statistics::{run_chunked, Estimate};
/// let f = |_k: u64, r: std::ops::Range<u64>| r.map(|i| (i % 10) as f64).collect::<Estimate>();
/// let one = run_chunked(100_000, 4096, 1, f).unwrap();
/// let two = run_chunked(100_000, 4096, 2, f).unwrap();
/// assert_eq!(one, two);
/// assert_eq!(one.mean(), Some(4.5));
/// ```
///
/// # Errors
/// [`StatisticsError::ZeroChunkSize`], [`StatisticsError::ZeroThreads`], or
/// [`StatisticsError::ThreadPool`] if rayon cannot start the threads.
pub fn run_chunked<F>(
    total_samples: u64,
    chunk_size: u64,
    threads: usize,
    chunk: F,
) -> Result<Estimate, StatisticsError>
where
    F: Fn(u64, Range<u64>) -> Estimate + Sync + Send,
{
    run_chunked_merge(total_samples, chunk_size, threads, chunk)
}

/// [`run_chunked`] for any [`Mergeable`] chunk result: the same fixed
/// chunks, folded in chunk order, so the result is bit-identical for any
/// `threads`.
///
/// # Errors
/// As [`run_chunked`].
pub fn run_chunked_merge<T, F>(
    total_samples: u64,
    chunk_size: u64,
    threads: usize,
    chunk: F,
) -> Result<T, StatisticsError>
where
    T: Mergeable,
    F: Fn(u64, Range<u64>) -> T + Sync + Send,
{
    if chunk_size == 0 {
        return Err(StatisticsError::ZeroChunkSize);
    }
    if threads == 0 {
        return Err(StatisticsError::ZeroThreads);
    }
    let chunks = total_samples.div_ceil(chunk_size);
    let range_of = |k: u64| {
        let start = k * chunk_size;
        start..start.saturating_add(chunk_size).min(total_samples)
    };
    if threads == 1 {
        // One thread: run the chunks inline, in order (the same merge order
        // as below, so the same bits), without building a thread pool —
        // which costs more than a small estimate (studies run thousands).
        let mut total = T::default();
        for k in 0..chunks {
            total.merge(&chunk(k, range_of(k)));
        }
        return Ok(total);
    }
    let pool = pool_of(threads)?;
    let mut total = T::default();
    pool.install(|| {
        let mut first = 0;
        while first < chunks {
            let last = first.saturating_add(BATCH_CHUNKS).min(chunks);
            // Offsets in usize: rayon's u64 ranges are not indexed, and
            // `with_max_len` needs an indexed iterator; a batch has at
            // most BATCH_CHUNKS chunks, so the casts are exact.
            let batch: Vec<T> = (0..(last - first) as usize)
                .into_par_iter()
                .with_max_len(CHUNKS_PER_TASK)
                .map(|i| {
                    let k = first + i as u64;
                    chunk(k, range_of(k))
                })
                .collect();
            for e in &batch {
                total.merge(e);
            }
            first = last;
        }
    });
    Ok(total)
}

/// The process's pool of `threads` worker threads, built on first use and
/// kept: a pool built per run cost its threads' start and, on every run,
/// their per-thread scratch buffers' first-touch page faults (studies run
/// thousands of estimates). Which thread runs a chunk never changes a bit
/// (module docs), so sharing pools between runs is safe.
fn pool_of(threads: usize) -> Result<Arc<rayon::ThreadPool>, StatisticsError> {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    // A poisoned lock only means a panic elsewhere while it was held; the
    // list is still whole (entries are pushed complete).
    let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, pool)) = pools.iter().find(|(n, _)| *n == threads) {
        return Ok(Arc::clone(pool));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| StatisticsError::ThreadPool(e.to_string()))?;
    let pool = Arc::new(pool);
    pools.push((threads, Arc::clone(&pool)));
    Ok(pool)
}

/// [`run_chunked`], timed: the estimate and the wall time of the whole run
/// (the first run on a thread count includes starting its pool, which later runs reuse).
///
/// # Errors
/// As [`run_chunked`].
pub fn run_chunked_timed<F>(
    total_samples: u64,
    chunk_size: u64,
    threads: usize,
    chunk: F,
) -> Result<TimedEstimate, StatisticsError>
where
    F: Fn(u64, Range<u64>) -> Estimate + Sync + Send,
{
    let (estimate, timing) = Timing::measure(total_samples, threads, || {
        run_chunked(total_samples, chunk_size, threads, chunk)
    });
    Ok(TimedEstimate {
        estimate: estimate?,
        timing,
    })
}

/// Estimates the mean of `f` over samples `0..total_samples` of `sequence`:
/// for each index i, the chunk's own clone of `sequence` is positioned with
/// `start_sample(i)` and `f` reads that sample's coordinates and returns its
/// value. Chunked and merged as [`run_chunked`], so the result is
/// bit-identical for any `threads`.
///
/// ```
/// use lambert_estimator::statistics::run_samples;
/// use lambert_sampling::sequence::{Independent, SampleSequence};
/// // ∫₀¹ x² dx = 1/3.
/// let seq = Independent::new(7);
/// let e = run_samples(&seq, 100_000, 8192, 2, |s| s.next_1d().powi(2)).unwrap();
/// assert!(e.z(1.0 / 3.0).unwrap().abs() < 4.0);
/// ```
///
/// # Errors
/// As [`run_chunked`].
pub fn run_samples<S, F>(
    sequence: &S,
    total_samples: u64,
    chunk_size: u64,
    threads: usize,
    f: F,
) -> Result<Estimate, StatisticsError>
where
    S: SampleSequence,
    F: Fn(&mut S) -> f64 + Sync + Send,
{
    run_chunked(total_samples, chunk_size, threads, |_, range| {
        let mut seq = sequence.clone();
        let mut e = Estimate::new();
        for i in range {
            seq.start_sample(i);
            e.push(f(&mut seq));
        }
        e
    })
}
