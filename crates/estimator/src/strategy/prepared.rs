//! One emitter prepared at one receiver: its technique and samplers, the
//! one-sample estimate F = L cos θ / p, and the bounds of its parts
//! ([`PartBound`]).

use glam::{DVec2, DVec3};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    pdf_cosine_hemisphere, pdf_uniform_hemisphere, sample_cosine_hemisphere,
    sample_uniform_hemisphere,
};
use lambert_sampling::sequence::SampleSequence;

use super::cone_mis::ConeMis;
use super::cone_window::CosineWindow;
use super::{
    ControlVariate, EmitterArea, EmitterLight, EmitterProjected, PartBound, Store, Strategy,
    Technique, TechniqueFallback,
};
use lambert_geometry::f64::Frame;

/// One emitter prepared for estimation at one receiver: its technique, its
/// samplers, and the bounds of the one or two parts of its one-sample
/// estimate.
#[derive(Clone, Debug)]
pub struct PreparedEmitter {
    /// The emitter.
    pub emitter: Emitter,
    /// The technique used for it.
    pub technique: Technique,
    /// The technique the strategy asked for, where its sampler could not
    /// be built and `technique` replaces it ([`TechniqueFallback`]).
    pub fallback: Option<TechniqueFallback>,
    pub(super) light: EmitterLight,
    pub(super) area: EmitterArea,
    pub(super) projected: EmitterProjected,
    pub(super) control: Option<ControlVariate>,
    /// The radiance every light sample sees, when it is known without a
    /// lookup ([`light_sample_radiance`]); `None` where each light sample
    /// must look the emitter up.
    pub(super) light_radiance: Option<f64>,
    /// The radiance every area sample sees, when it is known without a
    /// lookup ([`area_sample_radiance`]); `None` where each area sample
    /// must look the emitter up.
    pub(super) area_radiance: Option<f64>,
    parts: [PartBound; 2],
    /// [`cone_mis`](Self::cone_mis) and its [`CosineWindow`] at the
    /// receiver this emitter was prepared for, with that receiver's frame:
    /// built once, since the window costs inverse sines and tangents.
    cone_mis_at: Option<(Frame, ConeMis, CosineWindow)>,
}

/// How many samples of a batch had a non-zero value in each part of an
/// emitter's estimate (part 1 only for MIS: its light-sampled direction).
pub type PartHits = [u64; 2];

/// The 2-D points one sample draws for all of `prepared`: the sum of
/// their techniques' dimensions (two for MIS, one otherwise), D in the
/// chunk layouts (`chunk::ChunkStream`: emitter k's requests follow the
/// points of the emitters before it).
pub(crate) fn sample_dimensions(prepared: &[PreparedEmitter]) -> usize {
    prepared.iter().map(|p| p.technique.dimensions()).sum()
}

impl PreparedEmitter {
    /// Prepares `emitter` at `receiver` for `strategy` (resolved for this
    /// emitter).
    pub fn new(emitter: &Emitter, receiver: &Receiver, strategy: Strategy) -> Self {
        let mut technique = strategy.resolve(emitter, receiver);
        let light = EmitterLight::new(emitter, receiver);
        let area = EmitterArea::new(emitter, receiver);
        let (mut projected, mut control) =
            ControlVariate::samplers_for(technique, emitter, receiver);
        // Where the directions come from the light sampler: light sampling,
        // and the control variate without a closed form or projected
        // sampler (evaluate_u).
        let draws_light = technique == Technique::Light
            || (technique == Technique::ControlVariate
                && control.is_none()
                && matches!(projected, EmitterProjected::None));
        let fallback = TechniqueFallback::check(technique, emitter, receiver, &light, draws_light);
        if let Some(f) = fallback {
            technique = f.used;
            (projected, control) = ControlVariate::samplers_for(technique, emitter, receiver);
        }
        // The techniques that draw light samples draw many at this one
        // receiver: worth a disk's table.
        let light = match technique {
            Technique::Light | Technique::Mis(_) | Technique::ControlVariate => {
                light.for_many_samples()
            }
            _ => light,
        };
        // Projected sampling likewise (the control variate without
        // occluders returns its closed form and draws nothing).
        if technique == Technique::Projected {
            projected = projected.for_many_samples();
        }
        let [first, second] = PartBound::of(
            technique,
            emitter,
            receiver,
            &light,
            &area,
            &projected,
            control.as_ref(),
        );
        let none = PartBound {
            max: 0.0,
            shape: super::PartShape::Bounded,
            hit_probability: 0.0,
            name: "none",
        };
        let light_radiance = light_sample_radiance(emitter, receiver, &light);
        let area_radiance = area_sample_radiance(emitter, receiver, &area);
        let mut prepared = PreparedEmitter {
            emitter: emitter.clone(),
            technique,
            fallback,
            light,
            area,
            projected,
            control,
            light_radiance,
            area_radiance,
            parts: [first.unwrap_or(none), second.unwrap_or(none)],
            cone_mis_at: None,
        };
        if let Technique::Mis(_) = prepared.technique {
            let cone = prepared.build_cone_mis(receiver);
            prepared.cone_mis_at = cone.map(|cone| (receiver.frame, cone, cone.window()));
        }
        prepared
    }

    /// The bounds of the parts of this emitter's one-sample estimate: one
    /// for every technique but MIS, which has two (its cosine-sampled and
    /// its light-sampled direction), in the order of
    /// [`evaluate_batch`](Self::evaluate_batch)'s hit counts.
    pub fn parts(&self) -> &[PartBound] {
        &self.parts[..self.technique.dimensions()]
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

    /// The radiance every projected sample sees ([`EmitterProjected`]
    /// samples only what the receiver sees of the emitter's lit side);
    /// light samples take theirs from `light_radiance`.
    pub(super) fn uniform_radiance(&self) -> f64 {
        match &self.emitter {
            Emitter::Sphere(s) => s.radiance,
            Emitter::SkyCap(c) => c.radiance,
            Emitter::Sky(s) => s.radiance,
            Emitter::Polygon(p) => p.radiance,
            _ => 0.0,
        }
    }

    /// A bound on the error that every sample's value carries alike (W/m²):
    /// for the `projected` technique, L times the bound on the rounding
    /// error of the sampler's Ω⊥
    /// ([`EmitterProjected::projected_solid_angle_error`]), since every
    /// sample's value is L Ω⊥; 0 for the other techniques, whose samplers'
    /// normalisation errors are a few ulps of each value and lie under the
    /// rounding floor.
    pub fn systematic_error(&self) -> f64 {
        match self.technique {
            Technique::Projected => {
                self.uniform_radiance() * self.projected.projected_solid_angle_error()
            }
            _ => 0.0,
        }
    }

    /// One projected sample's value L max(n·ω, 0)/p (L Ω⊥ for every
    /// sample of a uniform emitter), 0 when nothing is sampled.
    #[inline]
    fn projected_value(&self, receiver: &Receiver, u: DVec2) -> f64 {
        match self.projected.sample(u) {
            Some(s) => self.uniform_radiance() * s.direction.dot(receiver.normal).max(0.0) / s.pdf,
            None => 0.0,
        }
    }

    /// L(ω)·max(cos θ, 0) for the unit direction `w` at the receiver.
    #[inline]
    fn radiance_cos(&self, receiver: &Receiver, w: DVec3) -> f64 {
        let cos = w.dot(receiver.normal);
        if cos > 0.0 {
            self.emitter.radiance_toward(receiver.point, w) * cos
        } else {
            0.0
        }
    }

    /// One sample of the estimate from the uniform 2-D points `u` (and
    /// `u2`, the light sample of MIS).
    #[inline]
    pub fn evaluate_u(&self, receiver: &Receiver, u: DVec2, u2: DVec2) -> f64 {
        let p = receiver.point;
        let frame = &receiver.frame;
        let radiance_cos = |w: DVec3| self.radiance_cos(receiver, w);
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
            Technique::Light => match (self.light.sample(u), self.light_radiance) {
                (Some(s), Some(l)) => l * s.direction.dot(receiver.normal).max(0.0) / s.pdf,
                (Some(s), None) => radiance_cos(s.direction) / s.pdf,
                (None, _) => 0.0,
            },
            Technique::Area => match (self.area.sample(u), self.area_radiance) {
                (Some(s), Some(l)) => l * s.direction.dot(receiver.normal).max(0.0) / s.pdf,
                (Some(s), None) => radiance_cos(s.direction) / s.pdf,
                (None, _) => 0.0,
            },
            Technique::Mis(h) => {
                let (cosine, light) = self.mis_parts(receiver, h, u, u2);
                cosine + light
            }
            Technique::Projected => self.projected_value(receiver, u),
            // Nothing occludes here: the control variate is the closed
            // form itself (V = 1 in every sample); without one, the
            // residual sampler's plain estimate.
            Technique::ControlVariate => match (&self.control, &self.projected) {
                (Some(c), _) => c.unoccluded,
                (None, EmitterProjected::None) => match self.light.sample(u) {
                    Some(s) => radiance_cos(s.direction) / s.pdf,
                    None => 0.0,
                },
                (None, _) => self.projected_value(receiver, u),
            },
        }
    }

    /// MIS on a sphere or sky cap, whose light sampler is a uniform cone:
    /// the two halves in the frames where they are cheapest ([`ConeMis`]);
    /// `None` for other light samplers.
    #[inline(always)]
    pub(super) fn cone_mis(&self, receiver: &Receiver) -> Option<ConeMis> {
        match self.cone_mis_at {
            Some((frame, cone, _)) if frame == receiver.frame => Some(cone),
            _ => self.build_cone_mis(receiver),
        }
    }

    /// [`cone_mis`](Self::cone_mis) with its [`CosineWindow`], for the
    /// batch kernel: the ones built with this emitter when `receiver` is
    /// the one it was prepared for.
    pub(super) fn cone_mis_window(&self, receiver: &Receiver) -> Option<(ConeMis, CosineWindow)> {
        match self.cone_mis_at {
            Some((frame, cone, window)) if frame == receiver.frame => Some((cone, window)),
            _ => self
                .build_cone_mis(receiver)
                .map(|cone| (cone, cone.window())),
        }
    }

    /// [`cone_mis`](Self::cone_mis), built.
    fn build_cone_mis(&self, receiver: &Receiver) -> Option<ConeMis> {
        let l = self.uniform_radiance();
        match &self.light {
            EmitterLight::Sphere(s) => Some(ConeMis::new(l, s.frame(), s.cone(), &receiver.frame)),
            EmitterLight::Cap(frame, cone) => Some(ConeMis::new(l, frame, cone, &receiver.frame)),
            _ => None,
        }
    }

    /// The two parts of an MIS sample: the weighted value of the
    /// cosine-sampled direction (from `u`) and of the light-sampled one
    /// (from `u2`); each is 0 when its direction is not drawn or misses.
    #[inline]
    fn mis_parts(
        &self,
        receiver: &Receiver,
        h: super::Heuristic,
        u: DVec2,
        u2: DVec2,
    ) -> (f64, f64) {
        if let Some(cone) = self.cone_mis(receiver) {
            return cone.parts(h, u, u2);
        }
        let frame = &receiver.frame;
        let radiance_cos = |w: DVec3| self.radiance_cos(receiver, w);
        let mut cosine = 0.0;
        let local = sample_cosine_hemisphere(u);
        let w = frame.from_local(local);
        let p_cos = pdf_cosine_hemisphere(local);
        if p_cos > 0.0 {
            let p_light = self.light.pdf(w);
            cosine = h.weighted(radiance_cos(w), p_cos, p_light);
        }
        let mut light = 0.0;
        if let Some(s) = self.light.sample(u2) {
            let local = frame.to_local(s.direction);
            let p_cos = pdf_cosine_hemisphere(local);
            let l_cos = match self.light_radiance {
                Some(l) => l * s.direction.dot(receiver.normal).max(0.0),
                None => radiance_cos(s.direction),
            };
            light = h.weighted(l_cos, s.pdf, p_cos);
        }
        (cosine, light)
    }

    /// Adds this emitter's estimate for each sample of a chunk to `out`
    /// (`out[i] += F(u[i], u2[i])`) and returns, per part
    /// ([`parts`](Self::parts)), how many samples had a non-zero value
    /// there (counted in the same pass, without a branch). The points are
    /// split into coordinate arrays a block at a time and run through
    /// [`add_batch_in`](Self::add_batch_in) (one specialised loop per
    /// technique and emitter kind) with the process's instruction set,
    /// [`Isa::selected`](lambert_sampling::isa::Isa::selected).
    pub fn evaluate_batch(
        &self,
        receiver: &Receiver,
        u: &[DVec2],
        u2: &[DVec2],
        out: &mut [f64],
    ) -> PartHits {
        const BLOCK: usize = 256;
        let isa = lambert_sampling::isa::Isa::selected();
        let mut hits = [0u64; 2];
        let mis = self.technique.dimensions() > 1;
        let mut c = [[0.0f64; BLOCK]; 4];
        let n = u
            .len()
            .min(out.len())
            .min(if mis { u2.len() } else { usize::MAX });
        for start in (0..n).step_by(BLOCK) {
            let m = BLOCK.min(n - start);
            let [ux, uy, vx, vy] = &mut c;
            for k in 0..m {
                (ux[k], uy[k]) = (u[start + k].x, u[start + k].y);
                if mis {
                    (vx[k], vy[k]) = (u2[start + k].x, u2[start + k].y);
                }
            }
            let h = self.add_batch_in(
                isa,
                receiver,
                &ux[..m],
                &uy[..m],
                &vx[..m],
                &vy[..m],
                &mut out[start..start + m],
                Store::Add,
            );
            hits[0] += h[0];
            hits[1] += h[1];
        }
        hits
    }
}

/// The radiance of `emitter` along every direction from `receiver` that
/// meets it, where one value holds for all of them: a sphere's or a sky
/// cap's; a polygon's or a disk's when its emitting side faces the
/// receiver, that is when the light is two-sided or the receiver lies
/// strictly on the side its normal points to ((p − c)·n > 0 for a point c
/// of its plane). `None` for a one-sided light seen from its back or from
/// its own plane, and for the other emitters.
fn facing_radiance(emitter: &Emitter, receiver: &Receiver) -> Option<f64> {
    let faces = |two_sided: bool, on_plane: DVec3, normal: DVec3| {
        two_sided || (receiver.point - on_plane).dot(normal) > 0.0
    };
    match emitter {
        Emitter::Sphere(s) => Some(s.radiance),
        Emitter::SkyCap(c) => Some(c.radiance),
        Emitter::Polygon(p) => {
            faces(p.two_sided, p.polygon.vertices()[0], p.polygon.normal()).then_some(p.radiance)
        }
        Emitter::Disk(d) => {
            faces(d.two_sided, d.disk.center(), d.disk.normal()).then_some(d.radiance)
        }
        _ => None,
    }
}

/// The radiance that every direction drawn by `light` at `receiver` sees,
/// when it is known without looking the emitter up ([`facing_radiance`]):
/// a sphere's or a sky cap's cone lies wholly on the emitter, and a
/// polygon's or a disk's solid-angle sampler draws directions inside the
/// shape seen from the receiver, so each one meets it.
///
/// The lookup it saves is the ray–shape test of `radiance_toward`, about a
/// fifth of a polygon's light sample (perf, `triangle` scene). Where the
/// two differ, the sampler is right: a direction drawn on the shape's
/// rim can round to just outside it, and the lookup then reads 0 for a
/// direction the sampler's density counts as inside. `None` for the
/// other emitters and for a one-sided light seen from its back or from
/// its own plane (each sample then looks the emitter up, as before).
fn light_sample_radiance(
    emitter: &Emitter,
    receiver: &Receiver,
    light: &EmitterLight,
) -> Option<f64> {
    match (emitter, light) {
        (Emitter::Sphere(_), EmitterLight::Sphere(_))
        | (Emitter::SkyCap(_), EmitterLight::Cap(..))
        | (Emitter::Polygon(_), EmitterLight::Polygon(_))
        | (Emitter::Disk(_), EmitterLight::Disk(_) | EmitterLight::DiskTable(_)) => {
            facing_radiance(emitter, receiver)
        }
        _ => None,
    }
}

/// The radiance that every point drawn by `area` sees from `receiver`,
/// when it is known without a lookup ([`facing_radiance`]): each point
/// lies on the emitter (a sphere's only on the side that faces the
/// receiver, the sampler drops the others), so the ray toward it meets
/// the emitter there first. The f32 path has always taken area samples'
/// radiance so.
///
/// The lookup it saves is the ray–shape test of `radiance_toward`, which
/// for a polygon loops over its edges and kept the area loops scalar.
/// Where the two differ the sampler is right, as for light samples
/// ([`light_sample_radiance`]): a point drawn on the rim can give a
/// direction that rounds to just outside the shape, and the lookup read 0
/// for it. `None` where [`facing_radiance`] is, and for emitters without
/// area.
fn area_sample_radiance(emitter: &Emitter, receiver: &Receiver, area: &EmitterArea) -> Option<f64> {
    match area {
        EmitterArea::None => None,
        _ => facing_radiance(emitter, receiver),
    }
}

#[cfg(test)]
mod tests {
    use super::{PreparedEmitter, Strategy};
    use crate::strategy::Heuristic;
    use glam::{DVec2, DVec3};
    use lambert_light::emitter::{DiskLight, Emitter, PolygonLight, SphereLight};
    use lambert_light::receiver::Receiver;

    /// A triangle and a disk 2 above the origin whose normals point down
    /// (one-sided, or two-sided).
    fn lights(two_sided: bool) -> [Emitter; 2] {
        let triangle = PolygonLight::new(
            vec![
                DVec3::new(-1.0, -1.0, 2.0),
                DVec3::new(0.0, 1.5, 2.5),
                DVec3::new(2.0, -0.5, 2.2),
            ],
            1.5,
            two_sided,
        )
        .expect("valid triangle");
        let disk = DiskLight::new(
            DVec3::new(0.5, 0.3, 2.0),
            DVec3::new(0.0, 0.2, -1.0),
            0.8,
            1.5,
            two_sided,
        )
        .expect("valid disk");
        [Emitter::Polygon(triangle), Emitter::Disk(disk)]
    }

    /// The values at the midpoints of a 32 × 32 grid (u and the MIS light
    /// coordinates alike).
    fn values(e: &PreparedEmitter, r: &Receiver) -> Vec<f64> {
        let n = 32;
        (0..n * n)
            .map(|k| {
                let u = DVec2::new(
                    ((k % n) as f64 + 0.5) / n as f64,
                    ((k / n) as f64 + 0.5) / n as f64,
                );
                e.evaluate_u(r, u, DVec2::new(u.y, u.x))
            })
            .collect()
    }

    #[test]
    fn light_samples_skip_the_lookup_only_where_the_lit_side_faces_them() {
        let front = Receiver::new(DVec3::ZERO, DVec3::Z).expect("receiver");
        // Above both lights, looking down at their backs.
        let back = Receiver::new(DVec3::new(0.3, 0.2, 6.0), -DVec3::Z).expect("receiver");
        for strategy in [Strategy::Light, Strategy::Mis(Heuristic::Power)] {
            for e in lights(false) {
                // Lit side toward the receiver: the lookup is skipped, and
                // the values are the looked-up ones to the bit (grid
                // midpoints give directions strictly inside the shapes).
                let skip = PreparedEmitter::new(&e, &front, strategy);
                assert_eq!(skip.light_radiance, Some(1.5), "{strategy:?} {e:?}");
                let lookup = PreparedEmitter {
                    light_radiance: None,
                    ..skip.clone()
                };
                let fast = values(&skip, &front);
                assert_eq!(fast, values(&lookup, &front), "{strategy:?} {e:?}");
                assert!(fast.iter().all(|v| *v > 0.0), "{strategy:?} {e:?}");
                // Its back toward the receiver: every sample looks the
                // emitter up and finds nothing.
                let behind = PreparedEmitter::new(&e, &back, strategy);
                assert_eq!(behind.light_radiance, None, "{strategy:?} {e:?}");
                assert!(values(&behind, &back).iter().all(|v| *v == 0.0));
            }
            // Two-sided lights are seen from the back too.
            for e in lights(true) {
                let behind = PreparedEmitter::new(&e, &back, strategy);
                assert_eq!(behind.light_radiance, Some(1.5), "{strategy:?} {e:?}");
                assert!(values(&behind, &back).iter().all(|v| *v > 0.0));
            }
        }
    }

    /// Area samples likewise: the lookup is skipped where the lit side
    /// faces the receiver (a sphere always), with the looked-up values to
    /// the bit; seen from the back, a one-sided light is looked up and
    /// gives nothing, a two-sided one is skipped and lit.
    #[test]
    fn area_samples_skip_the_lookup_only_where_the_lit_side_faces_them() {
        let front = Receiver::new(DVec3::ZERO, DVec3::Z).expect("receiver");
        let back = Receiver::new(DVec3::new(0.3, 0.2, 6.0), -DVec3::Z).expect("receiver");
        let sphere =
            Emitter::Sphere(SphereLight::new(DVec3::new(0.5, 0.0, 4.0), 1.0, 1.5).expect("sphere"));
        for (e, from) in lights(false)
            .into_iter()
            .map(|e| (e, front))
            .chain([(sphere.clone(), front), (sphere, back)])
        {
            let skip = PreparedEmitter::new(&e, &from, Strategy::Area);
            assert_eq!(skip.area_radiance, Some(1.5), "{e:?}");
            let lookup = PreparedEmitter {
                area_radiance: None,
                ..skip.clone()
            };
            let fast = values(&skip, &from);
            assert_eq!(fast, values(&lookup, &from), "{e:?}");
            // A sphere's hidden side gives no sample: the visible cap is
            // (1 − r/d)/2 of its area, 25 % from `back` (d ≈ 2.02) and
            // 38 % from `front` (d ≈ 4.03), so at least a fifth of the
            // grid is lit; the triangle and disk are lit everywhere.
            let lit = fast.iter().filter(|v| **v > 0.0).count();
            assert!(lit >= fast.len() / 5, "{e:?}: {lit}");
        }
        for e in lights(false) {
            let behind = PreparedEmitter::new(&e, &back, Strategy::Area);
            assert_eq!(behind.area_radiance, None, "{e:?}");
            assert!(values(&behind, &back).iter().all(|v| *v == 0.0));
        }
        for e in lights(true) {
            let behind = PreparedEmitter::new(&e, &back, Strategy::Area);
            assert_eq!(behind.area_radiance, Some(1.5), "{e:?}");
            assert!(values(&behind, &back).iter().all(|v| *v > 0.0));
        }
    }
}
