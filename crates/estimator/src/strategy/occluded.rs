//! One emitter prepared at one receiver in a scene with occluders: the
//! one-sample estimate F = L V cos θ / p, with the visibility V asked of the
//! caller.

use glam::{DVec2, DVec3};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    pdf_cosine_hemisphere, pdf_uniform_hemisphere, sample_cosine_hemisphere,
    sample_uniform_hemisphere,
};
use lambert_sampling::sequence::SampleSequence;

use super::{
    ControlVariate, EmitterArea, EmitterLight, EmitterProjected, Strategy, Technique,
    TechniqueFallback,
};

/// One emitter prepared at one receiver for estimates of
/// E = ∫ L(ω) V(ω) max(cos θ, 0) dω, where V(ω) ∈ {0, 1} says whether the
/// emitter is seen along ω or hidden by an occluder. The techniques and
/// their densities are those of [`PreparedEmitter`](super::PreparedEmitter)
/// (the same warps, the same dimensions of the sequence); each direction
/// drawn is kept only where the caller's visibility test passes, so each
/// one-sample estimate is F = L V cos θ / p, unbiased for the occluded
/// integral (Kajiya 1986, "The rendering equation": V is the geometry
/// term's visibility).
///
/// Visibility is a callback `visible(origin, direction, max_distance)`:
/// whether the segment from the receiver's point along the unit
/// `direction` is clear of occluders up to `max_distance`, the distance to
/// the emitter's surface along that direction
/// ([`Emitter::arrival`]; ∞ for skies). The caller decides how a ray leaves
/// its surface (a renderer offsets it past the hit point's rounding error)
/// and how short of the emitter it stops.
#[derive(Clone, Debug)]
pub struct OccludedEmitter<'a> {
    /// The emitter.
    pub emitter: &'a Emitter,
    /// The technique used for it ([`Strategy::resolve`], or the fallback).
    pub technique: Technique,
    /// The technique the strategy asked for, where its sampler could not
    /// be built and `technique` replaces it ([`TechniqueFallback`]).
    pub fallback: Option<TechniqueFallback>,
    light: EmitterLight,
    area: EmitterArea,
    projected: EmitterProjected,
    control: Option<ControlVariate>,
}

impl<'a> OccludedEmitter<'a> {
    /// Prepares `emitter` (not a delta light: see [`delta_irradiance_visible`])
    /// at `receiver` for `strategy`, resolved for this emitter.
    pub fn new(emitter: &'a Emitter, receiver: &Receiver, strategy: Strategy) -> Self {
        let mut technique = strategy.resolve(emitter, receiver);
        let light = EmitterLight::new(emitter, receiver);
        let (mut projected, mut control) =
            ControlVariate::samplers_for(technique, emitter, receiver);
        // Light sampling and the control variate's residual without a
        // projected sampler (disks) draw from the light sampler.
        let draws_light = technique == Technique::Light
            || (technique == Technique::ControlVariate
                && matches!(projected, EmitterProjected::None));
        let fallback = TechniqueFallback::check(technique, emitter, receiver, &light, draws_light);
        if let Some(f) = fallback {
            technique = f.used;
            (projected, control) = ControlVariate::samplers_for(technique, emitter, receiver);
        }
        OccludedEmitter {
            emitter,
            technique,
            fallback,
            light,
            area: EmitterArea::new(emitter, receiver),
            projected,
            control,
        }
    }

    /// One sample of the occluded estimate, drawing this emitter's
    /// dimensions from `sequence` (already positioned at the sample): one
    /// 2-D point, two for MIS.
    #[inline]
    pub fn evaluate<S, V>(&self, receiver: &Receiver, sequence: &mut S, visible: &V) -> f64
    where
        S: SampleSequence,
        V: Fn(DVec3, DVec3, f64) -> bool,
    {
        let u = sequence.next_2d();
        let u2 = if self.technique.dimensions() > 1 {
            sequence.next_2d()
        } else {
            DVec2::ZERO
        };
        self.evaluate_u(receiver, u, u2, visible)
    }

    /// L(ω) V(ω) along the unit direction `w` (0 where the emitter is not
    /// seen, or hidden).
    #[inline]
    fn seen<V: Fn(DVec3, DVec3, f64) -> bool>(&self, p: DVec3, w: DVec3, visible: &V) -> f64 {
        match self.emitter.arrival(p, w) {
            Some(a) if visible(p, w, a.distance) => a.radiance,
            _ => 0.0,
        }
    }

    /// One sample of the estimate from the uniform 2-D points `u` (and
    /// `u2`, the light sample of MIS). The control variate
    /// ([`ControlVariate`]) draws its direction from the projected sampler
    /// (the light sampler for disks) and subtracts what the visibility test
    /// hides from the closed form.
    #[inline]
    pub fn evaluate_u<V>(&self, receiver: &Receiver, u: DVec2, u2: DVec2, visible: &V) -> f64
    where
        V: Fn(DVec3, DVec3, f64) -> bool,
    {
        let p = receiver.point;
        let frame = &receiver.frame;
        let seen_cos = |w: DVec3| {
            let cos = w.dot(receiver.normal);
            if cos > 0.0 {
                self.seen(p, w, visible) * cos
            } else {
                0.0
            }
        };
        match self.technique {
            Technique::UniformHemisphere => {
                let local = sample_uniform_hemisphere(u);
                seen_cos(frame.from_local(local)) / pdf_uniform_hemisphere(local)
            }
            Technique::CosineHemisphere => {
                let local = sample_cosine_hemisphere(u);
                // L V cos θ / (cos θ/π) = π L V: no division by a tiny cosine.
                if local.z > 0.0 {
                    std::f64::consts::PI * self.seen(p, frame.from_local(local), visible)
                } else {
                    0.0
                }
            }
            Technique::Light => match self.light.sample(u) {
                Some(s) => seen_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Technique::Area => match self.area.sample(u) {
                Some(s) => seen_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Technique::Mis(h) => {
                let mut f = 0.0;
                let local = sample_cosine_hemisphere(u);
                let p_cos = pdf_cosine_hemisphere(local);
                if p_cos > 0.0 {
                    let w = frame.from_local(local);
                    f += h.weighted(seen_cos(w), p_cos, self.light.pdf(w));
                }
                if let Some(s) = self.light.sample(u2) {
                    let p_cos = pdf_cosine_hemisphere(frame.to_local(s.direction));
                    f += h.weighted(seen_cos(s.direction), s.pdf, p_cos);
                }
                f
            }
            Technique::Projected => match self.projected.sample(u) {
                Some(s) => seen_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Technique::ControlVariate => {
                let s = match self.projected {
                    EmitterProjected::None => self.light.sample(u),
                    _ => self.projected.sample(u),
                };
                match &self.control {
                    Some(c) => c.sample(self.emitter, receiver, s, visible),
                    None => s.map_or(0.0, |s| seen_cos(s.direction) / s.pdf),
                }
            }
        }
    }
}

/// The exact irradiance of a delta light at `receiver` with visibility
/// (0 for the other emitters): a point light of intensity I at distance r
/// gives I max(cos θ, 0)/r² if `visible(p, l, r)`, a directional light
/// E⊥ max(n·l, 0) if `visible(p, l, ∞)`, l the unit direction toward the
/// light.
pub fn delta_irradiance_visible<V>(emitter: &Emitter, receiver: &Receiver, visible: &V) -> f64
where
    V: Fn(DVec3, DVec3, f64) -> bool,
{
    let p = receiver.point;
    match emitter {
        Emitter::Point(light) => {
            let v = light.position - p;
            let r = v.length();
            if !(r > 0.0) {
                return 0.0;
            }
            let l = v / r;
            let cos = receiver.normal.dot(l);
            if cos > 0.0 && visible(p, l, r) {
                light.intensity * cos / (r * r)
            } else {
                0.0
            }
        }
        Emitter::Directional(light) => {
            let cos = receiver.normal.dot(light.direction);
            if cos > 0.0 && visible(p, light.direction, f64::INFINITY) {
                light.irradiance * cos
            } else {
                0.0
            }
        }
        _ => 0.0,
    }
}
