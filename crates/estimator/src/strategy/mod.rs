//! Estimation strategies: how directions are drawn to estimate one
//! emitter's irradiance E = ∫ L cos θ dω at a receiver.
//!
//! With ω drawn with density p, the one-sample estimator is
//! F = L(ω) max(cos θ, 0) / p(ω) (Kajiya 1986; pbrt-v4 §2.1):
//! - uniform hemisphere: p = 1/2π, F = 2π L cos θ;
//! - cosine hemisphere: p = cos θ/π, F = π L (zero variance under a
//!   uniform sky);
//! - light: the emitter's solid-angle sampler ([`EmitterLight`]; disks by
//!   the solid angle of their spherical ellipse, Guillén et al. 2017);
//! - projected: the emitter's projected-solid-angle sampler,
//!   p = cos θ/Ω⊥ on its part above the horizon ([`EmitterProjected`];
//!   Ureña & Georgiev 2018 for caps and spheres, Peters 2021 for
//!   polygons): F = L Ω⊥ for every sample of a uniform emitter, zero
//!   variance where nothing occludes;
//! - control variate: the emitter's closed-form irradiance E_u minus an
//!   estimate of what occluders hide, F = E_u − (1 − V(ω)) L cos θ/p with
//!   ω from the projected sampler (the light sampler for disks): unbiased,
//!   exact where nothing occludes, noisy only in penumbrae
//!   ([`ControlVariate`]). Without occluders it is the closed form;
//! - area: uniform points on the emitter, p_ω = p_A d²/|cos θ_l|
//!   ([`EmitterArea`]);
//! - MIS: one cosine and one light sample, weighted by the balance or power
//!   heuristic (Veach & Guibas 1995, "Optimally combining sampling
//!   techniques for Monte Carlo rendering").
//!
//! **Bounded and heavy-tailed strategies.** Every technique's one-sample
//! value is bounded ([`value_bound`] tabulates the bounds): by 2πL, πL,
//! LΩ or 4πL for the hemisphere and solid-angle techniques, by 3πL/2 (power
//! heuristic) or 2πL (balance) for MIS, whose weights tame whichever
//! density is small. Those have finite variance everywhere. **Area
//! sampling** — the `area` strategy on spheres, disks and polygons — is
//! different: its value
//! L cos θ cos θ_l A/d² reaches L·A/d_min², so its relative variance grows
//! as A/d_min² and is unbounded as the receiver approaches the emitter (a
//! receiver close under a disk, or a disk far larger than its height); it
//! is infinite in the limit. Its large values come from a core of the
//! emitter that a sample reaches with probability q ≈ 3π d_min²/A, so with
//! N·q small the sample mean is far too small and the sample variance hides
//! it (|z| of tens to millions). `auto` never picks area sampling alone;
//! an estimate that uses it with N·q below
//! [`CLT_MIN_EVENTS`](crate::interval::CLT_MIN_EVENTS) reports a
//! heavy-tail warning and the interval from its value bound
//! ([`crate::interval`]), and the study summary flags rows whose replicate
//! spread disagrees with their reported standard error.
//!
//! Delta lights (point, directional) are never sampled: their irradiance is
//! added exactly. With several emitters each sample draws, for every
//! non-delta emitter, that emitter's own direction(s) from its own
//! dimensions of the sequence, and the sample's value is the sum of the
//! per-emitter estimates: unbiased, since each term is.

mod batch;
mod batch_f32;
mod control_variate;
mod emitter_area;
mod emitter_light;
mod emitter_projected;
mod fallback;
mod occluded;
mod prepared;
mod prepared_f32;
pub mod value_bound;

pub use control_variate::ControlVariate;
pub use emitter_area::EmitterArea;
pub use emitter_light::{EmitterLight, LightDirection};
pub use emitter_projected::EmitterProjected;
pub use fallback::TechniqueFallback;
pub use occluded::{delta_irradiance_visible, OccludedEmitter};
pub use prepared::{PartHits, PreparedEmitter};
pub use prepared_f32::{F32Fallback, FallbackReason, PreparedEmitterF32, F32_MAX_RELATIVE_ERROR};
pub use value_bound::{PartBound, PartShape};

use std::fmt;
use std::str::FromStr;

use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;

/// How to combine the two samples of MIS.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Heuristic {
    /// w_a = p_a / (p_a + p_b).
    Balance,
    /// w_a = p_a² / (p_a² + p_b²) (exponent 2, Veach's recommendation).
    Power,
}

impl Heuristic {
    /// The weight of a sample drawn from technique a, whose density is
    /// `pa`, against technique b with density `pb` ≥ 0 at the same
    /// direction: p_a/(p_a + p_b) (balance) or p_a²/(p_a² + p_b²) (power).
    ///
    /// Where that textbook form leaves the f64 range (a light under ~1e-154
    /// sr makes p_a² overflow to ∞/∞, a huge one makes both squares
    /// underflow to 0/0) the same weight is taken from the ratio
    /// r = p_b/p_a as 1/(1 + r) or 1/(1 + r²), which only saturates to 0 or
    /// 1; elsewhere the textbook form is kept, so ordinary results do not
    /// change by an ulp. 0 when p_a = 0.
    #[inline]
    pub fn weight(self, pa: f64, pb: f64) -> f64 {
        let w = match self {
            Heuristic::Balance => pa / (pa + pb),
            Heuristic::Power => pa * pa / (pa * pa + pb * pb),
        };
        if w.is_finite() || !(pa > 0.0) {
            return if pa > 0.0 { w } else { 0.0 };
        }
        let r = pb / pa;
        match self {
            Heuristic::Balance => 1.0 / (1.0 + r),
            Heuristic::Power => 1.0 / (1.0 + r * r),
        }
    }
}

/// A strategy for the whole scene, as the command line and study files name
/// it: one technique for every emitter, or `Auto` (the best per emitter,
/// [`Strategy::resolve`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// The best available technique per emitter ([`Strategy::resolve`]).
    Auto,
    /// Uniform directions on the hemisphere.
    UniformHemisphere,
    /// Cosine-weighted directions.
    CosineHemisphere,
    /// The emitter's solid-angle sampler.
    Light,
    /// Uniform points on the emitter's area.
    Area,
    /// Cosine + light with the given heuristic.
    Mis(Heuristic),
    /// The emitter's projected-solid-angle sampler (solid angle for disks).
    Projected,
    /// The closed form minus an estimate of what occluders hide.
    ControlVariate,
}

impl Strategy {
    /// Every concrete strategy (not `Auto`).
    pub const ALL: [Strategy; 8] = [
        Strategy::UniformHemisphere,
        Strategy::CosineHemisphere,
        Strategy::Light,
        Strategy::Area,
        Strategy::Mis(Heuristic::Balance),
        Strategy::Mis(Heuristic::Power),
        Strategy::Projected,
        Strategy::ControlVariate,
    ];

    /// The name used on the command line and in reports.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Auto => "auto",
            Strategy::UniformHemisphere => "uniform-hemisphere",
            Strategy::CosineHemisphere => "cosine-hemisphere",
            Strategy::Light => "light",
            Strategy::Area => "area",
            Strategy::Mis(Heuristic::Power) => "mis",
            Strategy::Mis(Heuristic::Balance) => "mis-balance",
            Strategy::Projected => "projected",
            Strategy::ControlVariate => "control-variate",
        }
    }

    /// The technique used for `emitter` at `receiver`.
    ///
    /// `Auto` picks, per emitter kind, the technique that reaches a given
    /// error soonest where nothing occludes:
    /// - a sky: cosine sampling (zero variance);
    /// - a sky cap, a sphere, a polygon: projected-solid-angle sampling
    ///   (zero variance without occluders, and the importance function
    ///   L cos θ itself with them; nothing drawn below the horizon): one
    ///   sample reaches any error, though a sample costs more than a cone
    ///   or spherical-polygon sample (up to about 10× a spherical
    ///   rectangle for a polygon away from the zenith; the sampling crate's
    ///   `ProjectedPolygon` docs give the measured costs);
    /// - a disk wholly above the horizon: solid-angle sampling of its
    ///   spherical ellipse (bounded values LΩ cos θ); a disk crossing the
    ///   horizon: MIS (power) of cosine and solid-angle sampling, since the
    ///   solid-angle sampler cannot leave out the part below the horizon
    ///   (no area-preserving map of the cut ellipse is known) and cosine
    ///   sampling covers it.
    ///
    /// It never picks a heavy-tailed technique (area sampling; module
    /// docs). `Projected` on a disk is solid-angle sampling (no projected
    /// sampler of a disk is known) and on a sky cosine sampling; `Area` on
    /// an emitter without area (sky, sky cap) uses its light sampler.
    pub fn resolve(self, emitter: &Emitter, receiver: &Receiver) -> Technique {
        match (self, emitter) {
            (Strategy::Auto, Emitter::Sky(_)) => Technique::CosineHemisphere,
            (Strategy::Auto, Emitter::Sphere(_) | Emitter::SkyCap(_) | Emitter::Polygon(_)) => {
                Technique::Projected
            }
            (Strategy::Auto, Emitter::Disk(d)) => {
                if disk_above_horizon(&d.disk, receiver) {
                    Technique::Light
                } else {
                    Technique::Mis(Heuristic::Power)
                }
            }
            (Strategy::Auto, _) => Technique::Mis(Heuristic::Power),
            (Strategy::Area, Emitter::Sky(_) | Emitter::SkyCap(_)) => Technique::Light,
            (Strategy::Projected, Emitter::Sky(_)) => Technique::CosineHemisphere,
            (Strategy::Projected, Emitter::Disk(_)) => Technique::Light,
            (Strategy::UniformHemisphere, _) => Technique::UniformHemisphere,
            (Strategy::CosineHemisphere, _) => Technique::CosineHemisphere,
            (Strategy::Light, _) => Technique::Light,
            (Strategy::Area, _) => Technique::Area,
            (Strategy::Mis(h), _) => Technique::Mis(h),
            (Strategy::Projected, _) => Technique::Projected,
            (Strategy::ControlVariate, _) => Technique::ControlVariate,
        }
    }
}

/// Whether every point of `disk` lies strictly above the horizon of
/// `receiver`: its lowest point, the center lowered by R √(1 − (n·n_d)²),
/// is above the receiver's plane.
fn disk_above_horizon(disk: &lambert_geometry::f64::Disk, receiver: &Receiver) -> bool {
    let c = receiver.normal.dot(disk.normal());
    let reach = disk.radius() * ((1.0 - c) * (1.0 + c)).max(0.0).sqrt();
    receiver.normal.dot(disk.center() - receiver.point) - reach > 0.0
}

/// How one emitter's directions are drawn: a [`Strategy`] resolved for
/// that emitter (there is no "auto" technique).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Technique {
    /// Uniform directions on the hemisphere, p = 1/2π.
    UniformHemisphere,
    /// Cosine-weighted directions, p = cos θ/π.
    CosineHemisphere,
    /// The emitter's solid-angle sampler ([`EmitterLight`]).
    Light,
    /// Uniform points on the emitter's area ([`EmitterArea`]).
    Area,
    /// One cosine and one light sample, weighted by the heuristic.
    Mis(Heuristic),
    /// The emitter's projected-solid-angle sampler ([`EmitterProjected`]).
    Projected,
    /// The closed form minus the occluded part ([`ControlVariate`]).
    ControlVariate,
}

impl Technique {
    /// The name of the strategy that uses this technique on every emitter
    /// (as the command line names it).
    pub fn name(self) -> &'static str {
        match self {
            Technique::UniformHemisphere => Strategy::UniformHemisphere.name(),
            Technique::CosineHemisphere => Strategy::CosineHemisphere.name(),
            Technique::Light => Strategy::Light.name(),
            Technique::Area => Strategy::Area.name(),
            Technique::Mis(h) => Strategy::Mis(h).name(),
            Technique::Projected => Strategy::Projected.name(),
            Technique::ControlVariate => Strategy::ControlVariate.name(),
        }
    }

    /// How many 2-D sample dimensions one evaluation consumes.
    pub fn dimensions(self) -> usize {
        match self {
            Technique::Mis(_) => 2,
            _ => 1,
        }
    }
}

impl fmt::Display for Strategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Strategy {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match s {
            "auto" => Strategy::Auto,
            "uniform-hemisphere" => Strategy::UniformHemisphere,
            "cosine-hemisphere" => Strategy::CosineHemisphere,
            "light" => Strategy::Light,
            "area" => Strategy::Area,
            "mis" | "mis-power" => Strategy::Mis(Heuristic::Power),
            "mis-balance" => Strategy::Mis(Heuristic::Balance),
            "projected" => Strategy::Projected,
            "control-variate" => Strategy::ControlVariate,
            other => {
                return Err(format!(
                    "unknown strategy {other:?} (expected auto, uniform-hemisphere, cosine-hemisphere, light, area, mis, mis-balance, projected, control-variate)"
                ))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Heuristic;

    #[test]
    fn weights_stay_in_range_for_extreme_densities() {
        for h in [Heuristic::Balance, Heuristic::Power] {
            // Ordinary densities: the textbook form, exactly.
            assert_eq!(h.weight(1.0, 1.0), 0.5);
            // A light of 1e-160 sr (density 1e160) against cosine sampling.
            let w = h.weight(1e160, 0.3);
            assert!(w.is_finite() && w > 0.999_999, "{h:?}: {w}");
            assert!(h.weight(0.3, 1e160) < 1e-100);
            // A huge light: both densities tiny, the squares underflow.
            let w = h.weight(1e-170, 2e-170);
            assert!(w.is_finite() && w > 0.0 && w < 0.5, "{h:?}: {w}");
            // No density, no weight.
            assert_eq!(h.weight(0.0, 0.0), 0.0);
            assert_eq!(h.weight(0.0, 1.0), 0.0);
        }
    }
}
