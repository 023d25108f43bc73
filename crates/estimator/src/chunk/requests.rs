//! A chunk's sequence points, every request of its samples, filled two
//! requests at a time: a multiple-importance emitter's two points come
//! from consecutive requests, and a sequence computes the work the two
//! share once ([`SampleSequence::fill_2d_split_two`]; for Sobol points the
//! index shuffle, a third of a pair's hashes).

use lambert_sampling::sequence::SampleSequence;

/// Requests `0 … x.len()/n − 1` of samples `first …` in f64: request r's
/// points in `x[r·n..(r + 1)·n]` and `y[…]` (the lengths are whole
/// multiples of n; nothing to fill for n = 0).
#[inline(always)]
pub(super) fn fill_requests<S: SampleSequence>(
    sequence: &S,
    first: u64,
    n: usize,
    x: &mut [f64],
    y: &mut [f64],
) {
    in_pairs(
        n,
        x,
        y,
        #[inline(always)]
        |request, x, y| sequence.fill_2d_split(first, request, x, y),
        #[inline(always)]
        |request, arrays| sequence.fill_2d_split_two(first, request, arrays),
    );
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
    in_pairs(
        n,
        x,
        y,
        #[inline(always)]
        |request, x, y| sequence.fill_2d_split_f32(first, request, x, y),
        #[inline(always)]
        |request, arrays| sequence.fill_2d_split_f32_two(first, request, arrays),
    );
}

/// The requests of `x` and `y` (`n` points each) by `two(r, [x_r, y_r,
/// x_{r+1}, y_{r+1}])` for r = 0, 2, 4, …, and an odd last one by
/// `one(r, x_r, y_r)`. The fills are passed `#[inline(always)]`, so that
/// they run in the caller's instruction set.
#[inline(always)]
fn in_pairs<T>(
    n: usize,
    x: &mut [T],
    y: &mut [T],
    one: impl Fn(u64, &mut [T], &mut [T]),
    two: impl Fn(u64, [&mut [T]; 4]),
) {
    if n == 0 {
        return;
    }
    for (pair, (x, y)) in x.chunks_mut(2 * n).zip(y.chunks_mut(2 * n)).enumerate() {
        let request = 2 * pair as u64;
        if x.len() == 2 * n {
            let (x0, x1) = x.split_at_mut(n);
            let (y0, y1) = y.split_at_mut(n);
            two(request, [x0, y0, x1, y1]);
        } else {
            one(request, x, y);
        }
    }
}
