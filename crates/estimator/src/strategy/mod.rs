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
mod cone_mis;
mod cone_window;
mod control_variate;
mod emitter_area;
mod emitter_light;
mod emitter_projected;
mod fallback;
mod listing;
mod occluded;
mod prepared;
mod prepared_f32;
mod store;
pub mod value_bound;

pub use control_variate::ControlVariate;
pub use emitter_area::EmitterArea;
pub use emitter_light::{EmitterLight, LightDirection};
pub use emitter_projected::EmitterProjected;
pub use fallback::TechniqueFallback;
pub use occluded::{delta_irradiance_visible, OccludedEmitter};
pub(crate) use prepared::sample_dimensions;
pub use prepared::{PartHits, PreparedEmitter};
pub use prepared_f32::{F32Fallback, FallbackReason, PreparedEmitterF32, F32_MAX_RELATIVE_ERROR};
pub use store::Store;
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

    /// A sample's weighted value w_a·f/p_a in one division: f/(p_a + p_b)
    /// (balance) or f·p_a/(p_a² + p_b²) (power), for a sample of integrand
    /// value `f` drawn with density `pa` against technique b of density
    /// `pb` ≥ 0 at the same direction (Veach & Guibas 1995). The estimator's
    /// MIS kernels use it: [`Heuristic::weight`] followed by `· f / p_a`
    /// costs three divisions (two for the weight's fallback), and on
    /// vectors every lane pays for both branches.
    ///
    /// Range: both densities are first scaled by the power of two
    /// s = 2^−e that brings the larger into [1, 2) (exact: only the
    /// exponent changes), and the result is scaled back; so the squares
    /// neither overflow (a light under ~1e−154 sr) nor underflow, and for
    /// densities in [1, 2) the form is the textbook one as written. 0 when
    /// p_a is not a positive finite number.
    ///
    /// ```
    /// use lambert_estimator::strategy::Heuristic;
    /// assert_eq!(Heuristic::Power.weighted(3.0, 1.0, 1.0), 1.5);
    /// assert_eq!(Heuristic::Balance.weighted(3.0, 1.0, 2.0), 1.0);
    /// // A light of 1e-200 sr (density 1e200) against cosine sampling:
    /// // the light-sampled value is f/p_a, to rounding.
    /// let v = Heuristic::Power.weighted(2.0, 1e200, 0.3);
    /// assert!((v / 2e-200 - 1.0).abs() < 1e-15);
    /// ```
    #[inline(always)]
    pub fn weighted(self, f: f64, pa: f64, pb: f64) -> f64 {
        let q = self.quotient(f, pa, pb);
        q.select(q.numerator / q.denominator * q.scale)
    }

    /// The two halves of a two-sample MIS estimate at once, each
    /// [`Heuristic::weighted`]: `(f₁, p_a₁, p_b₁)` for the sample of
    /// technique a, `(f₂, p_a₂, p_b₂)` for the sample of technique b (with
    /// the densities in the order "own, other"). One division serves both:
    /// with r = 1/(D₁D₂), N₁/D₁ = N₁D₂r and N₂/D₂ = N₂D₁r, safe because
    /// the scaled denominators lie in [1, 8). The values may differ from two
    /// [`Heuristic::weighted`] calls by an ulp or two.
    ///
    /// ```
    /// use lambert_estimator::strategy::Heuristic;
    /// let (a, b) = Heuristic::Power.weighted_pair((3.0, 1.0, 1.0), (2.0, 1.0, 0.0));
    /// assert_eq!((a, b), (1.5, 2.0));
    /// ```
    #[inline(always)]
    pub fn weighted_pair(self, first: (f64, f64, f64), second: (f64, f64, f64)) -> (f64, f64) {
        let q1 = self.quotient(first.0, first.1, first.2);
        let q2 = self.quotient(second.0, second.1, second.2);
        // A denominator outside the normal range only comes with a density
        // that is not a positive finite number, whose value is 0 anyway:
        // 1 stands in, so it cannot spoil the other half.
        let sane = |d: f64| if d > 0.0 && d < f64::INFINITY { d } else { 1.0 };
        let (d1, d2) = (sane(q1.denominator), sane(q2.denominator));
        let r = 1.0 / (d1 * d2);
        (
            q1.select(q1.numerator * (d2 * r) * q1.scale),
            q2.select(q2.numerator * (d1 * r) * q2.scale),
        )
    }

    /// w_a·f/p_a as numerator/denominator·scale, both densities scaled by
    /// the power of two that brings the larger into [1, 2).
    #[inline(always)]
    fn quotient(self, f: f64, pa: f64, pb: f64) -> Quotient {
        let scale = scale_to_unit(pa.max(pb));
        let (a, b) = (pa * scale, pb * scale);
        let (numerator, denominator) = match self {
            Heuristic::Balance => (f, a + b),
            Heuristic::Power => (f * a, a * a + b * b),
        };
        Quotient {
            numerator,
            denominator,
            scale,
            drawn: pa > 0.0 && pa < f64::INFINITY,
        }
    }

    /// [`Heuristic::weighted`] in f32 (the f32 estimator's kernels), with
    /// the same scaling: f32 squares overflow already at densities of
    /// ~1.8e19 per steradian.
    ///
    /// ```
    /// use lambert_estimator::strategy::Heuristic;
    /// assert_eq!(Heuristic::Power.weighted_f32(3.0, 1.0, 1.0), 1.5);
    /// let v = Heuristic::Power.weighted_f32(2.0, 1e30, 0.3);
    /// assert!((v / 2e-30 - 1.0).abs() < 1e-6);
    /// ```
    #[inline(always)]
    pub fn weighted_f32(self, f: f32, pa: f32, pb: f32) -> f32 {
        let s = scale_to_unit_f32(pa.max(pb));
        let (a, b) = (pa * s, pb * s);
        let v = match self {
            Heuristic::Balance => f / (a + b),
            Heuristic::Power => f * a / (a * a + b * b),
        } * s;
        if pa > 0.0 && pa < f32::INFINITY {
            v
        } else {
            0.0
        }
    }
}

/// A weighted value w_a·f/p_a = numerator/denominator·scale, before the
/// division ([`Heuristic::weighted`], [`Heuristic::weighted_pair`]).
#[derive(Clone, Copy)]
struct Quotient {
    numerator: f64,
    denominator: f64,
    scale: f64,
    /// Whether p_a is a positive finite density (else the value is 0).
    drawn: bool,
}

impl Quotient {
    #[inline(always)]
    fn select(self, value: f64) -> f64 {
        if self.drawn {
            value
        } else {
            0.0
        }
    }
}

/// The power of two 2^−e with e the exponent of `m` (m·2^−e ∈ [1, 2) for a
/// normal m), clamped to the normal range: an exact rescaling, read off the
/// bits (no division, so it vectorises at the cost of a few integer
/// operations).
#[inline(always)]
fn scale_to_unit(m: f64) -> f64 {
    let biased = ((m.to_bits() >> 52) & 0x7ff) as i64;
    f64::from_bits(((2046 - biased).clamp(1, 2046) as u64) << 52)
}

/// [`scale_to_unit`] for f32.
#[inline(always)]
fn scale_to_unit_f32(m: f32) -> f32 {
    let biased = ((m.to_bits() >> 23) & 0xff) as i32;
    f32::from_bits(((254 - biased).clamp(1, 254) as u32) << 23)
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
    fn weighted_values_are_weight_times_f_over_p() {
        // Densities over 600 decades: the one-division forms against
        // w(p_a, p_b)·f/p_a written with the ratio q = min/max ≤ 1, which
        // neither overflows nor underflows: balance f/(p_a + p_b); power
        // f/(p_a(1 + q²)) if p_a ≥ p_b, else f·q/(p_b(1 + q²)). Both sides
        // round a handful of times (~5 operations, the pair ~8): 16 ulps.
        // (`weight` itself is no reference here: for p_a = 1e-300 against
        // 1e19 its weight is subnormal and has lost digits.)
        let reference = |h: Heuristic, f: f64, pa: f64, pb: f64| match h {
            Heuristic::Balance => f / (pa + pb),
            Heuristic::Power if pa >= pb => {
                let q = pb / pa;
                f / (pa * (1.0 + q * q))
            }
            Heuristic::Power => {
                let q = pa / pb;
                f * q / (pb * (1.0 + q * q))
            }
        };
        let decades = [
            -300.0, -160.0, -20.0, -1.0, 0.0, 0.5, 3.0, 20.0, 160.0, 300.0,
        ];
        for h in [Heuristic::Balance, Heuristic::Power] {
            for &ea in &decades {
                for &eb in &decades {
                    let (pa, pb) = (1.37 * 10f64.powf(ea), 0.61 * 10f64.powf(eb));
                    let f = 2.3e-3;
                    let want = reference(h, f, pa, pb);
                    let got = h.weighted(f, pa, pb);
                    let (one, two) = h.weighted_pair((f, pa, pb), (f, pb, pa));
                    let want_two = reference(h, f, pb, pa);
                    for (g, w) in [(got, want), (one, want), (two, want_two)] {
                        assert!(
                            (g - w).abs() <= 16.0 * f64::EPSILON * w.abs(),
                            "{h:?} pa {pa:e} pb {pb:e}: {g:e} vs {w:e}"
                        );
                    }
                }
            }
            // No density, no value, and no NaN spilling into the other half.
            assert_eq!(h.weighted(1.0, 0.0, 1.0), 0.0);
            assert_eq!(h.weighted(1.0, f64::INFINITY, 1.0), 0.0);
            assert_eq!(h.weighted(1.0, f64::NAN, 1.0), 0.0);
            assert_eq!(
                h.weighted_pair((1.0, 0.0, 0.0), (2.0, 1.0, 0.0)),
                (0.0, 2.0)
            );
            assert_eq!(h.weighted_f32(1.0, 0.0, 1.0), 0.0);
            let v = h.weighted_f32(2.0, 1e30, 1e-30);
            assert!((v / 2e-30 - 1.0).abs() < 1e-6, "{h:?}: {v}");
        }
    }

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
