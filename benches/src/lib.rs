//! Shared helpers for the criterion benches: uniform samples from a PCG
//! generator in each precision, drawn inside the timed loop so every figure
//! includes the RNG (as pbrt-v4's and Mitsuba 3's reference figures do).

pub mod arvo;

use criterion::Criterion;
use glam::{DVec2, Vec2};
use rand_pcg::{Pcg32, Pcg64Mcg};

/// Samples per timed iteration; figures are reported per sample
/// (criterion's throughput in elements).
pub const BATCH: u64 = 1024;

/// The criterion configuration used by every lambert bench: short enough
/// for a 2-core machine, long enough for stable medians.
pub fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(std::time::Duration::from_millis(500))
        .measurement_time(std::time::Duration::from_secs(2))
        .sample_size(30)
}

/// u ∈ [0,1)² in f32 from one 64-bit PCG output: the top 24 bits of each
/// half, so no value rounds to 1.
#[inline(always)]
pub fn next_u32x2(rng: &mut Pcg64Mcg) -> Vec2 {
    let bits = rand_core::RngCore::next_u64(rng);
    let scale = 1.0 / (1u32 << 24) as f32;
    Vec2::new(
        ((bits >> 40) as u32) as f32 * scale,
        (((bits >> 8) & 0xff_ffff) as u32) as f32 * scale,
    )
}

/// u ∈ [0,1)² in f64 from two 64-bit PCG outputs (53 bits each).
#[inline(always)]
pub fn next_u64x2(rng: &mut Pcg64Mcg) -> DVec2 {
    let scale = 1.0 / (1u64 << 53) as f64;
    let a = rand_core::RngCore::next_u64(rng) >> 11;
    let b = rand_core::RngCore::next_u64(rng) >> 11;
    DVec2::new(a as f64 * scale, b as f64 * scale)
}

/// A seeded 128-bit multiplicative PCG (fast, small state).
pub fn rng() -> Pcg64Mcg {
    rand::SeedableRng::seed_from_u64(0x006c_616d_6265_7274)
}

/// A seeded 32-bit PCG, for comparison with pbrt-v4's PCG32.
pub fn rng32() -> Pcg32 {
    rand::SeedableRng::seed_from_u64(0x006c_616d_6265_7274)
}
