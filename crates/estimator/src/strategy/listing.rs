//! The listing step of the cone MIS kernels (`batch::cone_mis_batch` in
//! f64, `batch_f32::cone_mis_batch` in f32): the few samples of a span
//! whose cosine direction may see the cone, found from one bit mask per
//! group of lanes, listed by index and their coordinates gathered, so that
//! the cosine half runs in whole vectors of listed samples only (stream
//! compaction; e.g. Billeter, Olsson & Assarsson 2009, "Efficient stream
//! compaction on wide SIMD many-core architectures").

/// Appends to `listed[count..]` the index `g·group + k` of every bit `k`
/// set in mask `g` of `masks`, in increasing order, and returns the new
/// count. `listed` must have room for them.
#[inline(always)]
pub(super) fn list_set_bits<M: Copy + Into<u32>>(
    masks: &[M],
    group: usize,
    listed: &mut [u16],
    mut count: usize,
) -> usize {
    for (g, &mask) in masks.iter().enumerate() {
        let mut mask: u32 = mask.into();
        while mask != 0 {
            listed[count] = (g * group + mask.trailing_zeros() as usize) as u16;
            count += 1;
            mask &= mask - 1;
        }
    }
    count
}

/// `(gx[i], gy[i]) = (x[listed[i]], y[listed[i]])` for every listed
/// sample: their coordinates, gathered in order.
#[inline(always)]
pub(super) fn gather<T: Copy>(listed: &[u16], x: &[T], y: &[T], gx: &mut [T], gy: &mut [T]) {
    for ((&k, gx), gy) in listed.iter().zip(gx.iter_mut()).zip(gy.iter_mut()) {
        (*gx, *gy) = (x[usize::from(k)], y[usize::from(k)]);
    }
}

/// The cosine half of the listed samples: their coordinates gathered
/// ([`gather`]) into `gux`, `guy`, then `values[i] = value(gux[i],
/// guy[i])` over whole groups of `G` lanes, the last group padded with
/// whatever the arrays held past the listed count (earlier coordinates, or
/// zero), whose values are computed but not used, so that the loop runs
/// in whole vectors. Returns the listed samples' values, in order.
#[inline(always)]
pub(super) fn grouped_values<'v, T: Copy, const G: usize>(
    listed: &[u16],
    (ux, uy): (&[T], &[T]),
    [gux, guy, values]: [&'v mut [T]; 3],
    value: impl Fn(T, T) -> T,
) -> &'v [T] {
    let count = listed.len();
    gather(listed, ux, uy, gux, guy);
    let padded = count.div_ceil(G) * G;
    let (value_groups, _) = values[..padded].as_chunks_mut::<G>();
    let (x_groups, _) = gux[..padded].as_chunks::<G>();
    let (y_groups, _) = guy[..padded].as_chunks::<G>();
    for (out, (x, y)) in value_groups.iter_mut().zip(x_groups.iter().zip(y_groups)) {
        for k in 0..G {
            out[k] = value(x[k], y[k]);
        }
    }
    let values: &'v [T] = values;
    &values[..count]
}
