//! A chunk's sequence points, every request of its samples, filled two
//! requests at a time: a multiple-importance emitter's two points come
//! from consecutive requests, and a sequence computes the work the two
//! share once ([`SampleSequence::fill_2d_split_two`]; for Sobol points the
//! index shuffle, a third of a pair's hashes).

use lambert_sampling::sequence::SampleSequence;

/// Requests `0 … x.len()/n − 1` of samples `first …` in f64: request r's
/// points in `x[r·n..(r + 1)·n]` and `y[…]` (n > 0; the lengths are
/// whole multiples of n).
#[inline(always)]
pub(super) fn fill_requests<S: SampleSequence>(
    sequence: &S,
    first: u64,
    n: usize,
    x: &mut [f64],
    y: &mut [f64],
) {
    let mut pairs = x.chunks_mut(2 * n).zip(y.chunks_mut(2 * n)).enumerate();
    for (pair, (x, y)) in &mut pairs {
        let request = 2 * pair as u64;
        if x.len() == 2 * n {
            let (x0, x1) = x.split_at_mut(n);
            let (y0, y1) = y.split_at_mut(n);
            sequence.fill_2d_split_two(first, request, [x0, y0, x1, y1]);
        } else {
            sequence.fill_2d_split(first, request, x, y);
        }
    }
}

/// [`fill_requests`] in f32.
#[inline(always)]
pub(super) fn fill_requests_f32<S: SampleSequence>(
    sequence: &S,
    first: u64,
    n: usize,
    x: &mut [f32],
    y: &mut [f32],
) {
    let mut pairs = x.chunks_mut(2 * n).zip(y.chunks_mut(2 * n)).enumerate();
    for (pair, (x, y)) in &mut pairs {
        let request = 2 * pair as u64;
        if x.len() == 2 * n {
            let (x0, x1) = x.split_at_mut(n);
            let (y0, y1) = y.split_at_mut(n);
            sequence.fill_2d_split_f32_two(first, request, [x0, y0, x1, y1]);
        } else {
            sequence.fill_2d_split_f32(first, request, x, y);
        }
    }
}
