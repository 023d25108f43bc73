//! Area sampling of one emitter from one receiver, built from the sampling
//! crate's area samplers.

use glam::{DVec2, DVec3};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{DiskAreaSampler, LightSampler, PolygonAreaSampler, SphereAreaSampler};

use super::emitter_light::LightDirection;

/// Uniform area sampling of a sphere's whole surface, a disk, or a convex
/// polygon (a fan of triangles chosen by area), with the density converted
/// to solid angle at the receiver (pbrt-v4 §4.2.3: p_ω = p_A d²/|cos θ_l|).
///
/// Its variance is unbounded as the receiver approaches the emitter (the
/// d² of the conversion goes to 0 where the radiance does not): the value
/// reaches L·A/d_min², its relative variance grows as A/d_min², and the
/// large values come from a core of probability ≈ 3π d_min²/A that small N
/// never sample (see [`PartShape::HeavyTailed`](super::PartShape)). Area
/// sampling is offered for comparison and never chosen by `auto`.
#[derive(Clone, Debug)]
pub enum EmitterArea {
    /// A sphere's surface (points on the hidden far side give no sample).
    Sphere(SphereAreaSampler, Receiver),
    /// A disk, by the concentric map.
    Disk(DiskAreaSampler, Receiver),
    /// A polygon's fan of triangles, chosen by area.
    Polygon(PolygonAreaSampler, Receiver),
    /// The emitter has no area (sky, cap, delta).
    None,
}

impl EmitterArea {
    /// Prepares area sampling of `emitter` from `receiver`.
    pub fn new(emitter: &Emitter, receiver: &Receiver) -> EmitterArea {
        match emitter {
            Emitter::Sphere(s) => EmitterArea::Sphere(SphereAreaSampler::new(s.sphere), *receiver),
            Emitter::Disk(d) => EmitterArea::Disk(DiskAreaSampler::new(d.disk), *receiver),
            Emitter::Polygon(p) => {
                EmitterArea::Polygon(PolygonAreaSampler::new(p.polygon.clone()), *receiver)
            }
            _ => EmitterArea::None,
        }
    }

    /// A direction toward a uniformly sampled point of the emitter, with
    /// its solid-angle density, or `None` (no area, edge-on, or a point on
    /// the hidden far side of a sphere).
    #[inline]
    pub fn sample(&self, u: DVec2) -> Option<LightDirection> {
        let l = match self {
            EmitterArea::Sphere(s, r) => s.sample(r.point, r.normal, u),
            EmitterArea::Disk(s, r) => s.sample(r.point, r.normal, u),
            EmitterArea::Polygon(s, r) => s.sample(r.point, r.normal, u),
            EmitterArea::None => None,
        }?;
        Some(LightDirection {
            direction: l.direction,
            pdf: l.pdf,
        })
    }

    /// The solid-angle density with which [`EmitterArea::sample`] produces
    /// the unit direction `w` (through the first surface point it hits).
    #[inline]
    pub fn pdf(&self, w: DVec3) -> f64 {
        match self {
            EmitterArea::Sphere(s, r) => s.pdf(r.point, r.normal, w),
            EmitterArea::Disk(s, r) => s.pdf(r.point, r.normal, w),
            EmitterArea::Polygon(s, r) => s.pdf(r.point, r.normal, w),
            EmitterArea::None => 0.0,
        }
    }
}
