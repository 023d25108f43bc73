//! The f32 estimator's random stream: SplitMix64 addressed by output
//! index, generated many lanes at a time.
//!
//! SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom
//! number generators", OOPSLA) steps its state by the odd constant
//! γ = 0x9E3779B97F4A7C15 and outputs a mix of it (two multiply–xorshift
//! rounds, Stafford's "Mix13" variant): xₖ = mix(s + (k + 1)·γ). Its
//! output k is a function of k alone, so a block of outputs is a loop of
//! independent lanes of 64-bit integer arithmetic, which vectorises (8
//! lanes per AVX-512 register, `vpmullq`) where the f64 path's
//! `Pcg64Mcg` stream steps 128-bit states in a scalar chain
//! ([`super::McgStream`]). It passes BigCrush (the authors' tests), and
//! each 64-bit output gives one 2-D point of two 24-bit coordinates, the
//! resolution of an f32 in [0, 1).

/// γ, the golden-ratio increment of SplitMix64.
const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function (Stafford's Mix13).
#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A SplitMix64 stream, addressed by output index (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitMixStream {
    /// The state before output 0.
    seed: u64,
}

impl SplitMixStream {
    /// The stream whose state starts at `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMixStream { seed }
    }

    /// Output number `index`: mix(seed + (index + 1)·γ).
    #[inline(always)]
    pub fn at(&self, index: u64) -> u64 {
        mix(self
            .seed
            .wrapping_add(index.wrapping_add(1).wrapping_mul(GAMMA)))
    }

    /// Outputs `first + k` as f32 points: `x[k]`, `y[k]` are the top 24
    /// bits of the output's high and low 32-bit halves times 2⁻²⁴ (exact
    /// in f32, in [0, 1 − 2⁻²⁴]). Fills the shorter length.
    #[inline(always)]
    pub fn fill_2d_f32(&self, first: u64, x: &mut [f32], y: &mut [f32]) {
        const SCALE: f32 = 1.0 / 16_777_216.0;
        let mut state = self.seed.wrapping_add(first.wrapping_mul(GAMMA));
        for (xk, yk) in x.iter_mut().zip(y.iter_mut()) {
            state = state.wrapping_add(GAMMA);
            let bits = mix(state);
            let (hi, lo) = ((bits >> 32) as u32, bits as u32);
            *xk = (hi >> 8) as f32 * SCALE;
            *yk = (lo >> 8) as f32 * SCALE;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SplitMix64 as its authors step it, one output after the other.
    fn reference(seed: u64, count: usize) -> Vec<u64> {
        let mut state = seed;
        (0..count)
            .map(|_| {
                state = state.wrapping_add(GAMMA);
                mix(state)
            })
            .collect()
    }

    #[test]
    fn same_numbers_as_the_serial_generator_from_any_offset() {
        // The published first output of SplitMix64 seeded with 0.
        assert_eq!(reference(0, 1)[0], 0xE220_A839_7B1D_CDAF);
        for seed in [0u64, 1, 0xdead_beef, u64::MAX] {
            let want = reference(seed, 300);
            let stream = SplitMixStream::new(seed);
            for (k, &w) in want.iter().enumerate() {
                assert_eq!(stream.at(k as u64), w, "seed {seed}, output {k}");
            }
            for first in [0usize, 1, 5, 130] {
                for len in [0usize, 1, 3, 17, 101] {
                    let (mut x, mut y) = (vec![0.0f32; len], vec![0.0f32; len]);
                    stream.fill_2d_f32(first as u64, &mut x, &mut y);
                    for k in 0..len {
                        let bits = want[first + k];
                        assert_eq!(f64::from(x[k]), (bits >> 40) as f64 / 16_777_216.0);
                        let lo = ((bits & 0xffff_ffff) >> 8) as f64 / 16_777_216.0;
                        assert_eq!(f64::from(y[k]), lo);
                        assert!(x[k] < 1.0 && y[k] < 1.0);
                    }
                }
            }
        }
    }
}
