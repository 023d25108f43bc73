//! The closed-form control variate of one emitter at one receiver.

use glam::DVec3;
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;

use super::emitter_light::LightDirection;
use super::{EmitterProjected, Technique};

/// The closed form as a control variate for occluded irradiance:
///
/// E = ∫ L V cos θ dω = E_u − ∫ (1 − V) L cos θ dω,
///
/// with E_u the emitter's unoccluded irradiance in closed form
/// ([`Emitter::closed_form_irradiance`]: Lambert's formula for polygons,
/// the cap formula for spheres and sky caps, the disk's closed form) and
/// V(ω) ∈ {0, 1} the visibility. Only the second term is estimated: with ω
/// drawn with density p over the emitter's visible directions,
///
/// F = E_u − (1 − V(ω)) L(ω) max(cos θ, 0)/p(ω),
///
/// unbiased for E (its expectation is E_u − ∫ (1 − V) L cos θ dω), equal
/// to E_u in every sample where nothing occludes (zero variance there), and
/// noisy only where some samples are hidden (penumbrae). This is the
/// classical control variate with coefficient 1 (Kahn & Marshall 1953;
/// Glasserman 2004, §4.1), the unoccluded integrand as control and its
/// closed form as the control's known mean.
///
/// ω comes from the emitter's projected-solid-angle sampler where it has
/// one, and from its solid-angle sampler otherwise (disks), where the
/// control removes the variance of the unoccluded part. With the projected
/// sampler, p = cos θ/Ω⊥ and E_u = L Ω⊥ for a uniform emitter, so
/// L cos θ/p = E_u and F = E_u V(ω): each sample is E_u or exactly 0, and
/// its expectation is E_u ∫ V cos θ dω/Ω⊥ = E, still unbiased. That form is
/// used, so that a wholly hidden light gives exactly 0 rather than
/// E_u − E_u(1 + δ) with δ a rounding error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlVariate {
    /// E_u, the emitter's unoccluded closed-form irradiance, W/m².
    pub unoccluded: f64,
    /// Whether the residual is drawn by the projected sampler
    /// (L cos θ/p = E_u in every sample).
    projected: bool,
}

impl ControlVariate {
    /// The control variate of `emitter` at `receiver`, whose residual is
    /// drawn by `projected` (or by the emitter's light sampler when that is
    /// [`EmitterProjected::None`]), or `None` when the emitter has no
    /// closed form there (then the strategy estimates E directly with the
    /// same sampler).
    pub fn new(
        emitter: &Emitter,
        receiver: &Receiver,
        projected: &EmitterProjected,
    ) -> Option<Self> {
        emitter
            .closed_form_irradiance(receiver)
            .filter(|e| e.is_finite())
            .map(|unoccluded| ControlVariate {
                unoccluded,
                projected: !matches!(projected, EmitterProjected::None),
            })
    }

    /// The projected sampler and control variate that `technique` needs
    /// for `emitter` at `receiver`: the sampler for `Projected` and
    /// `ControlVariate` (its residual sampler), the control for
    /// `ControlVariate`; nothing otherwise.
    pub fn samplers_for(
        technique: Technique,
        emitter: &Emitter,
        receiver: &Receiver,
    ) -> (EmitterProjected, Option<Self>) {
        let projected = match technique {
            Technique::Projected | Technique::ControlVariate => {
                EmitterProjected::new(emitter, receiver)
            }
            _ => EmitterProjected::None,
        };
        let control = match technique {
            Technique::ControlVariate => ControlVariate::new(emitter, receiver, &projected),
            _ => None,
        };
        (projected, control)
    }

    /// One sample of F = E_u − (1 − V) L cos θ/p for the direction `s`
    /// drawn by the residual sampler (`None`: nothing drawn, F = E_u), with
    /// `visible(origin, direction, max_distance)` the caller's visibility
    /// test (see [`OccludedEmitter`](super::OccludedEmitter)).
    #[inline]
    pub fn sample<V>(
        &self,
        emitter: &Emitter,
        receiver: &Receiver,
        s: Option<LightDirection>,
        visible: &V,
    ) -> f64
    where
        V: Fn(DVec3, DVec3, f64) -> bool,
    {
        let Some(s) = s else {
            return self.unoccluded;
        };
        let cos = s.direction.dot(receiver.normal);
        if !(cos > 0.0) {
            return self.unoccluded;
        }
        let p = receiver.point;
        match emitter.arrival(p, s.direction) {
            Some(a) if !visible(p, s.direction, a.distance) => {
                if self.projected {
                    0.0
                } else {
                    self.unoccluded - a.radiance * cos / s.pdf
                }
            }
            _ => self.unoccluded,
        }
    }
}
