//! What a technique falls back to when the sampler it draws from cannot be
//! built at a receiver.

use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::DiskLightSampler;
use std::fmt;

use super::{EmitterLight, Technique};

/// A technique replaced by another for one emitter at one receiver, and
/// why: the emitter is seen, but the sampler the requested technique draws
/// its directions from could not be built there.
///
/// The one case is a disk whose spherical ellipse (Guillén et al. 2017)
/// cannot be set up from the receiver
/// ([`DiskSolidAngle::new`](lambert_sampling::f64::DiskSolidAngle::new)'s
/// errors: a height below the rounding of the disk's size, so that its cone
/// is the hemisphere to within rounding; a solid angle whose density 1/Ω is
/// not representable; a distance beyond the f64 range). Light sampling
/// (and `projected`, `auto` and the control variate's residual, which use
/// it for disks) would then draw nothing and estimate 0 with an interval
/// of width 0 — silently wrong. Cosine-hemisphere sampling takes its place:
/// it needs no geometry but the disk's intersection test, it is unbiased
/// for any visible emitter, and its values are bounded by πL (two-valued,
/// 0 or πL), so its interval holds however few samples hit; where the disk
/// fills nearly the whole hemisphere (the first error) it is nearly exact.
/// Area sampling, the other candidate, is not used: its value
/// L cos θ cos θ_l A/d² is heavy-tailed for such disks (A/d_min² huge when
/// the disk is far larger than its height) and its d² overflows for the
/// same far geometries that defeat the ellipse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TechniqueFallback {
    /// The technique the strategy asked for.
    pub requested: Technique,
    /// The technique used instead.
    pub used: Technique,
    /// Why the requested technique's sampler could not be built.
    pub reason: &'static str,
}

impl TechniqueFallback {
    /// The fallback for `emitter` at `receiver` when `technique` takes its
    /// directions from the emitter's solid-angle sampler (`draws_light`)
    /// and `light`, that sampler, could not be built although the emitter
    /// is seen; `None` otherwise (including an emitter seen edge-on or not
    /// at all, whose irradiance is 0 and needs no samples).
    pub fn check(
        technique: Technique,
        emitter: &Emitter,
        receiver: &Receiver,
        light: &EmitterLight,
        draws_light: bool,
    ) -> Option<Self> {
        if !draws_light || !matches!(light, EmitterLight::None) {
            return None;
        }
        let Emitter::Disk(d) = emitter else {
            return None;
        };
        // In the disk's plane the disk is seen edge-on: nothing to sample.
        // (The height decides, not Ω > 0: the Ω of a far, tiny disk that is
        // still seen can underflow to 0, one of the cases that need the
        // fallback.)
        if d.disk.height_and_offset(receiver.point).0 == 0.0 {
            return None;
        }
        let reason = match DiskLightSampler::new(d.disk).at(receiver.point) {
            Err(lambert_sampling::SamplingError::Degenerate { what }) => what,
            Err(_) => "the disk's solid-angle sampler cannot be built here",
            Ok(_) => return None,
        };
        Some(TechniqueFallback {
            requested: technique,
            used: Technique::CosineHemisphere,
            reason,
        })
    }
}

impl fmt::Display for TechniqueFallback {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the disk's solid-angle sampler (spherical ellipse) cannot be built: {}; \
             cosine-hemisphere sampling used instead of {}",
            self.reason,
            self.requested.name()
        )
    }
}
