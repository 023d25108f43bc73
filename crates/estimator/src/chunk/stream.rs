//! The numbers of an independent-sample estimate: one SplitMix64 stream
//! per run, read by output index, each chunk its own window of it.

use lambert_sampling::isa::Isa;
use lambert_sampling::sequence::SplitMix64;

/// Where one chunk of an independent-sample estimate reads its numbers.
///
/// A run with seed s reads the SplitMix64 stream of state mix64(s)
/// ([`SplitMix64::new`]; Steele, Lea & Flood 2014). A sample draws D 2-D
/// points (the sum of its emitters' dimensions: one each, two for MIS),
/// one 64-bit output per point, so the chunk of samples `start..start + n`
/// reads outputs `start·D ..` `(start + n)·D`, emitter by emitter: the
/// emitter whose earlier emitters draw d points per sample reads its
/// request r of sample `start + i` at output `start·D + (d + r)·n + i`.
/// Chunks read disjoint windows of one stream, so no two samples of a run
/// share a number below 2⁶⁴ outputs (the stream's period), whatever the
/// chunk count.
///
/// Why this generator, and why one stream: until 2026-12-06 the f64 path
/// read `rand_pcg`'s `Pcg64Mcg` (a 128-bit multiplicative congruential
/// state), one stream per chunk seeded mix64(s + k·γ). Stepped sixteen
/// lanes at a time it still cost ten 32-bit multiplies per output where a
/// vector set has no 64-bit multiply (AVX2), against SplitMix64's six: in
/// one run on an AVX2 host, 1.50 against 1.12 ns per point filled (4096
/// points, medians of 9), and 0.40 for the conversion and stores alone.
/// The f32 path already read SplitMix64, one stream per chunk started at
/// its chunk seed; but chunks started at random states of one 2⁶⁴ cycle
/// can overlap (two chunks' windows of w outputs meet with probability
/// 2w/2⁶⁴: a run of C chunks expects C²w/2⁶⁴ overlapping pairs, 0.5 for
/// 2²⁵ chunks of 2¹³ outputs, 1.4·10¹¹ samples of MIS), and reading one
/// stream by chunk offset rules that out. Both
/// precisions now read it (the f32 path's grouped layout,
/// [`SplitMix64::fill_2d_f32`]; the f64 path's point per output,
/// [`SplitMix64::fill_2d_in`]), and every independent estimate took new
/// values of the same distribution.
///
/// ```
/// use lambert_estimator::chunk::ChunkStream;
/// use lambert_sampling::isa::Isa;
/// // Two emitters of one dimension each: chunk 1 (samples 4096..) reads
/// // outputs from 2·4096 on, after chunk 0's 8192.
/// let (mut x, mut y) = ([0.0; 4], [0.0; 4]);
/// ChunkStream::new(7, 2, 4096).fill_2d_in(Isa::selected(), 0, &mut x, &mut y);
/// let (mut x0, mut y0) = ([0.0; 4], [0.0; 4]);
/// ChunkStream::new(7, 2, 0).fill_2d_in(Isa::Baseline, 8192, &mut x0, &mut y0);
/// assert_eq!((x, y), (x0, y0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkStream {
    /// The run's stream.
    stream: SplitMix64,
    /// The output the chunk's first point is: `start·D` (mod 2⁶⁴).
    first: u64,
}

impl ChunkStream {
    /// The window of the run with seed `seed` whose samples draw
    /// `dimensions` points each (D), for the chunk that starts at sample
    /// `start` (type docs). Indices wrap modulo 2⁶⁴, the stream's period.
    pub fn new(seed: u64, dimensions: u64, start: u64) -> Self {
        ChunkStream {
            stream: SplitMix64::new(seed),
            first: start.wrapping_mul(dimensions),
        }
    }

    /// Points `offset + k` of the chunk's window in f64, with the
    /// instruction set `isa` ([`SplitMix64::fill_2d_in`]: x and y the high
    /// and low halves of an output, k·2⁻³²; the same bits with any set).
    #[inline(always)]
    pub fn fill_2d_in(&self, isa: Isa, offset: u64, x: &mut [f64], y: &mut [f64]) {
        self.stream
            .fill_2d_in(isa, self.first.wrapping_add(offset), x, y);
    }

    /// Points `offset + k` of the chunk's window in f32, with the
    /// instruction set `isa` ([`SplitMix64::fill_2d_f32_in`]: the grouped
    /// layout, 24-bit coordinates). A chunk's window starts at a multiple
    /// of 4096, so the groups of 16 stay aligned.
    #[inline(always)]
    pub fn fill_2d_f32_in(&self, isa: Isa, offset: u64, x: &mut [f32], y: &mut [f32]) {
        self.stream
            .fill_2d_f32_in(isa, self.first.wrapping_add(offset), x, y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chunk windows tile the stream: the last point of chunk k and the
    /// first of chunk k + 1 are consecutive outputs of one stream, in both
    /// precisions, and a seed's stream is not another seed's (negative
    /// control: the same offsets of seed 8 differ).
    #[test]
    fn chunks_tile_one_stream() {
        let dims = 3;
        let whole = ChunkStream::new(7, dims, 0);
        for start in [4096u64, 8192, 3 * 4096] {
            let chunk = ChunkStream::new(7, dims, start);
            let (mut x, mut y) = ([0.0; 20], [0.0; 20]);
            chunk.fill_2d_in(Isa::Baseline, 0, &mut x, &mut y);
            let (mut wx, mut wy) = ([0.0; 20], [0.0; 20]);
            whole.fill_2d_in(Isa::selected(), start * dims, &mut wx, &mut wy);
            assert_eq!((x, y), (wx, wy), "start {start}");
            let (mut fx, mut fy) = ([0.0f32; 32], [0.0f32; 32]);
            chunk.fill_2d_f32_in(Isa::Baseline, 16, &mut fx, &mut fy);
            let (mut wfx, mut wfy) = ([0.0f32; 32], [0.0f32; 32]);
            whole.fill_2d_f32_in(Isa::Baseline, start * dims + 16, &mut wfx, &mut wfy);
            assert_eq!((fx, fy), (wfx, wfy), "start {start}");
        }
        let (mut a, mut b) = ([0.0; 8], [0.0; 8]);
        ChunkStream::new(8, dims, 0).fill_2d_in(Isa::Baseline, 0, &mut a, &mut b);
        let (mut c, mut d) = ([0.0; 8], [0.0; 8]);
        whole.fill_2d_in(Isa::Baseline, 0, &mut c, &mut d);
        assert_ne!(a, c);
    }
}
