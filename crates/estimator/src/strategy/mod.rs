//! Estimation strategies: how directions are drawn to estimate one
//! emitter's irradiance E = ∫ L cos θ dω at a receiver.
//!
//! With ω drawn with density p, the one-sample estimator is
//! F = L(ω) max(cos θ, 0) / p(ω) (Kajiya 1986; pbrt-v4 §2.1):
//! - uniform hemisphere: p = 1/2π, F = 2π L cos θ;
//! - cosine hemisphere: p = cos θ/π, F = π L (zero variance under a
//!   uniform sky);
//! - light: the emitter's solid-angle sampler ([`LightSampler`]);
//! - area: uniform points on the emitter, p_ω = p_A d²/|cos θ_l|
//!   ([`AreaSampler`]);
//! - MIS: one cosine and one light sample, weighted by the balance or power
//!   heuristic (Veach & Guibas 1995, "Optimally combining sampling
//!   techniques for Monte Carlo rendering").
//!
//! Delta lights (point, directional) are never sampled: their irradiance is
//! added exactly. With several emitters each sample draws, for every
//! non-delta emitter, that emitter's own direction(s) from its own
//! dimensions of the sequence, and the sample's value is the sum of the
//! per-emitter estimates: unbiased, since each term is.

mod area_sampler;
mod discrete;
mod light_sampler;

pub use area_sampler::AreaSampler;
pub use discrete::pick_by_cumulative;
pub use light_sampler::{LightDirection, LightSampler};

use std::fmt;
use std::str::FromStr;

use glam::{DVec2, DVec3};
use lambert_sampling::f64::{
    pdf_cosine_hemisphere, pdf_uniform_hemisphere, sample_cosine_hemisphere,
    sample_uniform_hemisphere,
};
use lambert_sampling::SampleSequence;

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
    /// `pa`, against technique b with density `pb` at the same direction.
    #[inline]
    pub fn weight(self, pa: f64, pb: f64) -> f64 {
        match self {
            Heuristic::Balance => pa / (pa + pb),
            Heuristic::Power => pa * pa / (pa * pa + pb * pb),
        }
    }
}

/// A strategy for the whole scene, as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// The best available strategy per emitter ([`Strategy::resolve`]).
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
}

impl Strategy {
    /// Every concrete strategy (not `Auto`).
    pub const ALL: [Strategy; 6] = [
        Strategy::UniformHemisphere,
        Strategy::CosineHemisphere,
        Strategy::Light,
        Strategy::Area,
        Strategy::Mis(Heuristic::Balance),
        Strategy::Mis(Heuristic::Power),
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
        }
    }

    /// The concrete strategy used for `emitter`: `Auto` picks cosine for a
    /// sky (zero variance), light sampling for spheres and polygons (exact
    /// solid-angle samplers), MIS (power) for sky caps and disks (which may
    /// be large or cross the horizon, where cosine sampling wins); `Area`
    /// on an emitter without area (sky, sky cap) uses its light sampler.
    pub fn resolve(self, emitter: &Emitter) -> Strategy {
        match (self, emitter) {
            (Strategy::Auto, Emitter::Sky(_)) => Strategy::CosineHemisphere,
            (Strategy::Auto, Emitter::Sphere(_) | Emitter::Polygon(_)) => Strategy::Light,
            (Strategy::Auto, _) => Strategy::Mis(Heuristic::Power),
            (Strategy::Area, Emitter::Sky(_) | Emitter::SkyCap(_)) => Strategy::Light,
            (s, _) => s,
        }
    }

    /// How many 2-D sample dimensions one evaluation consumes.
    pub fn dimensions(self) -> usize {
        match self {
            Strategy::Mis(_) => 2,
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
            other => {
                return Err(format!(
                    "unknown strategy {other:?} (expected auto, uniform-hemisphere, cosine-hemisphere, light, area, mis, mis-balance)"
                ))
            }
        })
    }
}

/// One emitter prepared for estimation at one receiver: its concrete
/// strategy and its samplers.
#[derive(Clone, Debug)]
pub struct PreparedEmitter {
    /// The emitter.
    pub emitter: Emitter,
    /// The concrete strategy used for it.
    pub strategy: Strategy,
    light: LightSampler,
    area: AreaSampler,
}

impl PreparedEmitter {
    /// Prepares `emitter` at `receiver` for `strategy` (resolved per
    /// emitter).
    pub fn new(emitter: &Emitter, receiver: &Receiver, strategy: Strategy) -> Self {
        let strategy = strategy.resolve(emitter);
        PreparedEmitter {
            emitter: emitter.clone(),
            strategy,
            light: LightSampler::new(emitter, receiver),
            area: AreaSampler::new(emitter, receiver),
        }
    }

    /// One sample of this emitter's irradiance estimate, drawing its
    /// dimensions from `sequence` (positioned at the sample already).
    #[inline]
    pub fn evaluate<S: SampleSequence>(&self, receiver: &Receiver, sequence: &mut S) -> f64 {
        let u = sequence.next_2d();
        let u2 = if self.strategy.dimensions() > 1 {
            sequence.next_2d()
        } else {
            DVec2::ZERO
        };
        self.evaluate_u(receiver, u, u2)
    }

    /// Whether every light sample is known to see the emitter with
    /// radiance L (a sphere's or a sky cap's cone, a spherical polygon seen
    /// from its emitting side), so the radiance lookup can be skipped.
    fn light_always_hits(&self) -> bool {
        matches!(self.light, LightSampler::Cone(_) | LightSampler::Cap(..))
    }

    /// The emitter's radiance when [`light_always_hits`](Self::light_always_hits).
    fn uniform_radiance(&self) -> f64 {
        match &self.emitter {
            Emitter::Sphere(s) => s.radiance,
            Emitter::SkyCap(c) => c.radiance,
            _ => 0.0,
        }
    }

    /// One sample of the estimate from the uniform 2-D points `u` (and
    /// `u2`, the light sample of MIS).
    #[inline]
    pub fn evaluate_u(&self, receiver: &Receiver, u: DVec2, u2: DVec2) -> f64 {
        let p = receiver.point;
        let frame = &receiver.frame;
        let radiance_cos = |w: DVec3| {
            let cos = w.dot(receiver.normal);
            if cos > 0.0 {
                self.emitter.radiance_toward(p, w) * cos
            } else {
                0.0
            }
        };
        match self.strategy {
            Strategy::UniformHemisphere => {
                let local = sample_uniform_hemisphere(u);
                radiance_cos(frame.from_local(local)) / pdf_uniform_hemisphere(local)
            }
            Strategy::CosineHemisphere => {
                let local = sample_cosine_hemisphere(u);
                let w = frame.from_local(local);
                // L cos θ / (cos θ/π) = π L: no division by a tiny cosine.
                if local.z > 0.0 {
                    std::f64::consts::PI * self.emitter.radiance_toward(p, w)
                } else {
                    0.0
                }
            }
            Strategy::Light => match self.light.sample(u) {
                Some(s) if self.light_always_hits() => {
                    self.uniform_radiance() * s.direction.dot(receiver.normal).max(0.0) / s.pdf
                }
                Some(s) => radiance_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Strategy::Area => match self.area.sample(u) {
                Some(s) => radiance_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Strategy::Mis(h) => {
                let mut f = 0.0;
                let local = sample_cosine_hemisphere(u);
                let w = frame.from_local(local);
                let p_cos = pdf_cosine_hemisphere(local);
                if p_cos > 0.0 {
                    let p_light = self.light.pdf(w);
                    f += h.weight(p_cos, p_light) * radiance_cos(w) / p_cos;
                }
                if let Some(s) = self.light.sample(u2) {
                    let local = frame.to_local(s.direction);
                    let p_cos = pdf_cosine_hemisphere(local);
                    f += h.weight(s.pdf, p_cos) * radiance_cos(s.direction) / s.pdf;
                }
                f
            }
            Strategy::Auto => unreachable!("strategies are resolved per emitter"),
        }
    }

    /// Adds this emitter's estimate for each sample of a chunk to `out`
    /// (`out[i] += F(u[i], u2[i])`). Light sampling of a cone (spheres,
    /// sky caps) runs through the slice form of the cone warp, which the
    /// compiler can vectorise; everything else loops over
    /// [`evaluate_u`](Self::evaluate_u).
    pub fn evaluate_batch(&self, receiver: &Receiver, u: &[DVec2], u2: &[DVec2], out: &mut [f64]) {
        if let (Strategy::Light, LightSampler::Cone(sphere)) = (self.strategy, &self.light) {
            // pdf is the constant 1/Ω: F = L Ω max(n·ω, 0).
            let scale = self.uniform_radiance() * sphere.solid_angle();
            let cone = sphere.cone();
            let frame = sphere.frame();
            // Rotate the normal into the cone's frame once: n·ω = n_local·ω_local.
            let n_local = frame.to_local(receiver.normal);
            const BLOCK: usize = 256;
            let mut local = [DVec3::ZERO; BLOCK];
            for (u_block, out_block) in u.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
                let local = &mut local[..u_block.len()];
                cone.sample_batch(u_block, local);
                for (o, w) in out_block.iter_mut().zip(local.iter()) {
                    *o += scale * n_local.dot(*w).max(0.0);
                }
            }
            return;
        }
        for ((o, &a), &b) in out.iter_mut().zip(u).zip(u2) {
            *o += self.evaluate_u(receiver, a, b);
        }
    }
}
