//! How a batch kernel stores each sample's value in its output slot.

/// What a batch kernel does with `out[i]` (`PreparedEmitter::add_batch_in`,
/// `PreparedEmitterF32::add_batch_in`).
///
/// A chunk's values start as the first emitter's estimates and each
/// further emitter adds its own, so the first emitter may overwrite a
/// buffer that still holds the previous chunk's values instead of adding
/// to one zeroed first: zeroing 4096 values and reading them back cost
/// about 5 % of an f32 light-sampled estimate (the `memset` alone was
/// 2.7 % of an f64 one's profile). The estimate is the same to the bit:
/// `0 + x` and `x` differ only when x = −0, and the sums, the count of
/// non-zero values, M₂ and the rule for a chunk of equal values treat −0
/// as +0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Store {
    /// `out[i] += value`.
    Add,
    /// `out[i] = value`: every slot of `out` is written, whatever it held.
    Overwrite,
}

impl Store {
    /// `*o += value` or `*o = value`.
    #[inline(always)]
    pub(crate) fn put(self, o: &mut f64, value: f64) {
        match self {
            Store::Add => *o += value,
            Store::Overwrite => *o = value,
        }
    }
}
