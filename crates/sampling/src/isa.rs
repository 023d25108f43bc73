//! The instruction set a batch kernel runs with, chosen at run time.
//!
//! lambert's batch kernels (the `*_soa` warps here, the estimator's chunk
//! kernels) are plain loops over arrays written to be vectorised. A release
//! build for generic x86-64 may only use SSE2, two f64 lanes; the machines
//! the code runs on mostly have AVX2 and FMA (four f64 lanes) and often
//! AVX-512 (eight). [`Isa::run`] runs a closure as if the crate had been
//! compiled for one of those sets: the closure and everything it inlines
//! is compiled once per set and the set is picked when the call is made,
//! after checking that the processor has it. The dispatch itself is the
//! `pulp` crate's (`pulp::x86::V3`/`V4`, safe to call: it checks the
//! processor's features first), so the workspace keeps `forbid(unsafe_code)`.
//!
//! **Results do not depend on the set.** Vectorising a loop changes how
//! many lanes an instruction works on, never what each lane computes: Rust
//! does not contract `a·b + c` into a fused multiply-add or reassociate sums
//! unless the code asks for it, and lambert's kernels ask for neither, so
//! every lane rounds exactly as the baseline build does. The same input
//! gives the same bits with [`Isa::Baseline`], [`Isa::Avx2Fma`] and
//! [`Isa::Avx512`]; the tests force each available set and compare. (The
//! "FMA" in the name is the processor feature the set requires, as x86-64-v3
//! does; the kernels do not use it for that reason.)
//!
//! What the set does not cover: calls into the C library's transcendental
//! functions (`atan2`, `atan`, `hypot`, …) run whichever build of them the
//! C library picked for the processor (glibc has FMA, AVX and SSE2 builds),
//! and those can differ in the last bit. Values computed through them can
//! therefore differ between machines, not between sets on one machine; the
//! workspace's `libm_variants` test bounds that difference.
//!
//! The set a process uses is [`Isa::selected`]: the widest one available,
//! or a narrower one named in the environment variable `LAMBERT_ISA`
//! (`baseline`, `avx2`, `avx512` or `avx512-gfni`), for measuring one set
//! against another.
//!
//! [`Isa::Avx512Gfni`] is AVX-512 with the Galois-field instructions
//! (GFNI). The kernels never name them; the compiler uses them on its own
//! for one operation, reversing the bits of 32-bit lanes
//! (`u32::reverse_bits`, three per scrambled Sobol point): a byte shuffle
//! and one `vgf2p8affineqb` where AVX-512 alone needs two nibble lookups,
//! shifts, masks and an OR. Bit reversal is exact integer work, so the
//! values are the same as every other set's.
//!
//! Everything a kernel calls must be inlined into the closure for it to be
//! compiled for the chosen set (a function that is not inlined keeps the
//! baseline code): the hot functions are `#[inline]` or `#[inline(always)]`.
//!
//! ```
//! use lambert_sampling::isa::Isa;
//! let xs: Vec<f64> = (0..1000).map(|i| i as f64).collect();
//! let sum_of_squares = |xs: &[f64]| xs.iter().map(|x| x * x).fold(0.0, |a, b| a + b);
//! let best = Isa::selected().run(|| sum_of_squares(&xs));
//! let baseline = Isa::Baseline.run(|| sum_of_squares(&xs));
//! assert_eq!(best.to_bits(), baseline.to_bits());
//! ```

use std::fmt;
use std::str::FromStr;
use std::sync::OnceLock;

/// An instruction set for the batch kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Isa {
    /// What the build targets (SSE2 on generic x86-64): always available.
    Baseline,
    /// x86-64-v3: AVX2, FMA, BMI1/2 (Haswell, Zen 1 and later).
    Avx2Fma,
    /// x86-64-v4: AVX-512 F, BW, CD, DQ, VL (Skylake-SP, Zen 4 and later).
    Avx512,
    /// x86-64-v4 and GFNI (Ice Lake, Zen 4 and later): see the module docs.
    Avx512Gfni,
}

impl Isa {
    /// Every set, narrowest first.
    pub const ALL: [Isa; 4] = [Isa::Baseline, Isa::Avx2Fma, Isa::Avx512, Isa::Avx512Gfni];

    /// The name `LAMBERT_ISA` and reports use.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::Avx2Fma => "avx2",
            Isa::Avx512 => "avx512",
            Isa::Avx512Gfni => "avx512-gfni",
        }
    }

    /// Whether this processor (and this build's target) has the set.
    pub fn is_available(self) -> bool {
        match self {
            Isa::Baseline => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2Fma => pulp::x86::V3::is_available(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => pulp::x86::V4::is_available(),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512Gfni => V4Gfni::is_available(),
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The sets this processor has, narrowest first.
    pub fn available() -> Vec<Isa> {
        Isa::ALL.into_iter().filter(|i| i.is_available()).collect()
    }

    /// The widest set this processor has.
    pub fn widest() -> Isa {
        Isa::ALL
            .into_iter()
            .rev()
            .find(|i| i.is_available())
            .unwrap_or(Isa::Baseline)
    }

    /// The set the process's kernels use: [`Isa::widest`], or the set named
    /// by the environment variable `LAMBERT_ISA` if it is available (an
    /// unknown or unavailable name is ignored). Read once.
    pub fn selected() -> Isa {
        static SELECTED: OnceLock<Isa> = OnceLock::new();
        *SELECTED.get_or_init(|| {
            std::env::var("LAMBERT_ISA")
                .ok()
                .and_then(|name| name.parse::<Isa>().ok())
                .filter(|i| i.is_available())
                .unwrap_or_else(Isa::widest)
        })
    }

    /// Runs `f` compiled for this set (module docs); if the processor lacks
    /// the set, for the widest narrower one it has. The result is the same
    /// to the bit whichever set runs it, for lambert's kernels.
    #[inline(always)]
    pub fn run<R>(self, f: impl FnOnce() -> R) -> R {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512Gfni => match V4Gfni::try_new() {
                Some(simd) => simd.vectorize(f),
                None => Isa::Avx512.run_without_gfni(f),
            },
            // The narrower sets: the same dispatch as without GFNI.
            _ => self.run_without_gfni(f),
        }
    }

    /// [`run`](Self::run) for code that has no use for GFNI: with
    /// [`Isa::Avx512Gfni`] it runs the [`Isa::Avx512`] copy, so `f` is
    /// compiled three times instead of four. The compiler uses GFNI only
    /// for bit reversal (module docs), which only the Sobol points do; the
    /// estimator's kernels and its independent-sample chunks have none, and
    /// their fourth copy was the same code again, built for nothing (the
    /// estimator crate's kernels are most of the workspace's build time).
    /// The result is the same to the bit as [`run`](Self::run)'s.
    #[inline(always)]
    pub fn run_without_gfni<R>(self, f: impl FnOnce() -> R) -> R {
        match self {
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512Gfni | Isa::Avx512 => match pulp::x86::V4::try_new() {
                Some(simd) => simd.vectorize(f),
                None => Isa::Avx2Fma.run_without_gfni(f),
            },
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2Fma => match pulp::x86::V3::try_new() {
                Some(simd) => simd.vectorize(f),
                None => f(),
            },
            _ => f(),
        }
    }
}

impl fmt::Display for Isa {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Isa {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Isa::ALL.into_iter().find(|i| i.name() == s).ok_or_else(|| {
            format!(
                "unknown instruction set {s:?} (expected baseline, avx2, avx512 or avx512-gfni)"
            )
        })
    }
}

#[cfg(target_arch = "x86_64")]
pulp::simd_type! {
    /// The features of [`Isa::Avx512Gfni`]: `pulp::x86::V4`'s and GFNI.
    /// Declared with `pulp`'s own macro, which checks the processor before
    /// it runs anything compiled for them, as `V4::try_new` does.
    struct V4Gfni {
        sse: "sse",
        sse2: "sse2",
        fxsr: "fxsr",
        sse3: "sse3",
        ssse3: "ssse3",
        sse4_1: "sse4.1",
        sse4_2: "sse4.2",
        popcnt: "popcnt",
        avx: "avx",
        avx2: "avx2",
        bmi1: "bmi1",
        bmi2: "bmi2",
        fma: "fma",
        lzcnt: "lzcnt",
        avx512f: "avx512f",
        avx512bw: "avx512bw",
        avx512cd: "avx512cd",
        avx512dq: "avx512dq",
        avx512vl: "avx512vl",
        gfni: "gfni",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_baseline_is_always_there() {
        for isa in Isa::ALL {
            assert_eq!(isa.name().parse::<Isa>(), Ok(isa));
        }
        assert!("sse9".parse::<Isa>().unwrap_err().contains("sse9"));
        assert!(Isa::Baseline.is_available());
        assert!(Isa::available().contains(&Isa::widest()));
        assert!(Isa::selected().is_available());
    }

    /// Bit reversal, which the compiler writes with GFNI in
    /// [`Isa::Avx512Gfni`] and with nibble lookups otherwise, gives every
    /// set the scalar reversal's bits, on a pseudo-random 32-bit sequence
    /// and on the 32 basis vectors. Negative control: the byte swap alone
    /// (what the GFNI form adds its per-byte reversal to) differs.
    #[test]
    fn every_set_reverses_bits_alike() {
        let mut x = 0x9e37_79b9u32;
        let mut words: Vec<u32> = (0..4099)
            .map(|_| {
                x = x.wrapping_mul(0x2c1b_3c6d).wrapping_add(0x297a_2d39);
                x
            })
            .collect();
        words.extend((0..32).map(|b| 1u32 << b));
        let reverse = |w: &[u32]| -> Vec<u32> { w.iter().map(|w| w.reverse_bits()).collect() };
        let want: Vec<u32> = words
            .iter()
            .map(|&w| (0..32).fold(0, |r, b| r | ((w >> b) & 1) << (31 - b)))
            .collect();
        for isa in Isa::available() {
            assert_eq!(isa.run(|| reverse(&words)), want, "{isa}");
        }
        let swapped: Vec<u32> = words.iter().map(|w| w.swap_bytes()).collect();
        assert_ne!(swapped, want);
    }

    #[test]
    fn every_set_computes_the_same_bits() {
        // A loop the compiler vectorises: square roots, divisions, selects.
        let xs: Vec<f64> = (1..4096).map(|i| (i as f64).sqrt() * 0.37).collect();
        let kernel = |xs: &[f64]| -> Vec<f64> {
            xs.iter()
                .map(|&x| {
                    let y = (x * x + 1.0).sqrt() / (x + 0.5);
                    if y > 1.0 {
                        y - x.max(0.25)
                    } else {
                        y
                    }
                })
                .collect()
        };
        let want = kernel(&xs);
        for isa in Isa::available() {
            let got = isa.run(|| kernel(&xs));
            let without_gfni = isa.run_without_gfni(|| kernel(&xs));
            for (got, how) in [(got, "run"), (without_gfni, "run_without_gfni")] {
                assert!(
                    got.iter()
                        .zip(&want)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "{isa} {how}"
                );
            }
        }
    }
}
