//! One emitter prepared at one receiver: its technique and samplers, and
//! the one-sample estimate F = L cos θ / p.

use glam::{DVec2, DVec3};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    pdf_cosine_hemisphere, pdf_uniform_hemisphere, sample_cosine_hemisphere,
    sample_uniform_hemisphere,
};
use lambert_sampling::sequence::SampleSequence;

use super::{EmitterArea, EmitterLight, Strategy, Technique};

/// One emitter prepared for estimation at one receiver: its technique and
/// its samplers.
#[derive(Clone, Debug)]
pub struct PreparedEmitter {
    /// The emitter.
    pub emitter: Emitter,
    /// The technique used for it.
    pub technique: Technique,
    pub(super) light: EmitterLight,
    pub(super) area: EmitterArea,
}

impl PreparedEmitter {
    /// Prepares `emitter` at `receiver` for `strategy` (resolved for this
    /// emitter).
    pub fn new(emitter: &Emitter, receiver: &Receiver, strategy: Strategy) -> Self {
        let technique = strategy.resolve(emitter);
        PreparedEmitter {
            emitter: emitter.clone(),
            technique,
            light: EmitterLight::new(emitter, receiver),
            area: EmitterArea::new(emitter, receiver),
        }
    }

    /// One sample of this emitter's irradiance estimate, drawing its
    /// dimensions from `sequence` (positioned at the sample already).
    #[inline]
    pub fn evaluate<S: SampleSequence>(&self, receiver: &Receiver, sequence: &mut S) -> f64 {
        let u = sequence.next_2d();
        let u2 = if self.technique.dimensions() > 1 {
            sequence.next_2d()
        } else {
            DVec2::ZERO
        };
        self.evaluate_u(receiver, u, u2)
    }

    /// The emitter's radiance when every light sample sees it
    /// ([`EmitterLight::always_hits`]).
    pub(super) fn uniform_radiance(&self) -> f64 {
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
        match self.technique {
            Technique::UniformHemisphere => {
                let local = sample_uniform_hemisphere(u);
                radiance_cos(frame.from_local(local)) / pdf_uniform_hemisphere(local)
            }
            Technique::CosineHemisphere => {
                let local = sample_cosine_hemisphere(u);
                let w = frame.from_local(local);
                // L cos θ / (cos θ/π) = π L: no division by a tiny cosine.
                if local.z > 0.0 {
                    std::f64::consts::PI * self.emitter.radiance_toward(p, w)
                } else {
                    0.0
                }
            }
            Technique::Light => match self.light.sample(u) {
                Some(s) if self.light.always_hits() => {
                    self.uniform_radiance() * s.direction.dot(receiver.normal).max(0.0) / s.pdf
                }
                Some(s) => radiance_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Technique::Area => match self.area.sample(u) {
                Some(s) => radiance_cos(s.direction) / s.pdf,
                None => 0.0,
            },
            Technique::Mis(h) => {
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
        }
    }

    /// Adds this emitter's estimate for each sample of a chunk to `out`
    /// (`out[i] += F(u[i], u2[i])`). Light sampling of a cone (spheres,
    /// sky caps) runs through the slice form of the cone warp, which the
    /// compiler can vectorise; everything else loops over
    /// [`evaluate_u`](Self::evaluate_u).
    pub fn evaluate_batch(&self, receiver: &Receiver, u: &[DVec2], u2: &[DVec2], out: &mut [f64]) {
        if let (Technique::Light, EmitterLight::Sphere(sphere)) = (self.technique, &self.light) {
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
