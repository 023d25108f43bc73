//! Solid-angle sampling of one emitter from one receiver, built from the
//! sampling crate's light samplers.

use glam::{DVec2, DVec3};
use lambert_geometry::f64::Frame;
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    pdf_uniform_sphere, sample_uniform_sphere, DiskLightSampler, DiskSolidAngle,
    PolygonLightSampler, PolygonSolidAngle, SphereLightSampler, SphereSolidAngle,
    TabulatedDiskSolidAngle, UniformCone, UniformSolidAngle,
};

/// A direction toward a light with its density per steradian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightDirection {
    /// Unit direction from the receiver.
    pub direction: DVec3,
    /// Density per steradian (> 0).
    pub pdf: f64,
}

/// The best available solid-angle sampler of an emitter, prepared at one
/// receiver for many samples: the subtended cone for spheres
/// ([`SphereLightSampler`]; Shirley et al. 1996) and sky caps, the uniform
/// sphere for a sky, the spherical rectangle (Ureña et al. 2013) or a fan of
/// spherical triangles chosen by solid angle (Arvo 1995) for polygons
/// ([`PolygonLightSampler`]), and the spherical ellipse a disk subtends
/// ([`DiskLightSampler`]; Guillén et al. 2017, "Area-preserving
/// parameterizations for spherical ellipses"), whose density 1/Ω replaces
/// area sampling's d²/(A|cos θ_l|): its values LΩ cos θ are bounded, where
/// area sampling's grow without bound as the receiver nears the disk.
///
/// **What is sampled.** Polygons are clipped to the receiver's hemisphere
/// first, so every sample sees the light and the density is 1/Ω of the
/// visible part. Spheres' and caps' cones and disks are sampled whole:
/// samples below the horizon score 0 (the sampling crate's `LightSampler`
/// docs say why there is no closed-form sampler of the visible part of the
/// uniform cone or the spherical ellipse; the `projected` strategy samples
/// only the visible part of caps and spheres). For a disk crossing the
/// horizon `auto` therefore uses MIS (power) with cosine sampling.
#[derive(Clone, Debug)]
pub enum EmitterLight {
    /// The whole sphere of directions, uniform.
    Sky,
    /// A sky cap's cone of directions, with its frame.
    Cap(Frame, UniformCone),
    /// A sphere's subtended cone.
    Sphere(SphereSolidAngle),
    /// A polygon's spherical rectangle or fan of spherical triangles.
    Polygon(PolygonSolidAngle),
    /// A disk's spherical ellipse.
    Disk(DiskSolidAngle),
    /// A disk's spherical ellipse with its inverse tabulated, for many
    /// samples at the receiver ([`EmitterLight::for_many_samples`]).
    DiskTable(TabulatedDiskSolidAngle),
    /// Nothing to sample (the emitter is invisible from here, or a delta
    /// light).
    None,
}

impl EmitterLight {
    /// Prepares solid-angle sampling of `emitter` from `receiver`.
    pub fn new(emitter: &Emitter, receiver: &Receiver) -> EmitterLight {
        let p = receiver.point;
        match emitter {
            Emitter::Sky(_) => EmitterLight::Sky,
            Emitter::SkyCap(c) => EmitterLight::Cap(c.frame, c.cone),
            Emitter::Sphere(s) => match SphereLightSampler::new(s.sphere).at(p) {
                Ok(sampler) => EmitterLight::Sphere(sampler),
                Err(_) => EmitterLight::None,
            },
            Emitter::Disk(d) => match DiskLightSampler::new(d.disk).at(p) {
                Ok(sampler) => EmitterLight::Disk(sampler),
                // The receiver in the disk's plane: it sees the disk
                // edge-on, no solid angle.
                Err(_) => EmitterLight::None,
            },
            Emitter::Polygon(poly) => match PolygonLightSampler::new(poly.polygon.clone()) {
                Ok(sampler) => match sampler.at(p, receiver.normal) {
                    PolygonSolidAngle::Fan { triangles, .. } if triangles.is_empty() => {
                        EmitterLight::None
                    }
                    prepared => EmitterLight::Polygon(prepared),
                },
                // More vertices than the sampler holds: rejected when the
                // emitter is built (`PolygonLight::new`), so unreachable
                // from a scene; nothing to sample.
                Err(_) => EmitterLight::None,
            },
            Emitter::Point(_) | Emitter::Directional(_) => EmitterLight::None,
        }
    }

    /// This sampler prepared for many samples at its receiver (an
    /// estimate, not a renderer's few samples per shading point): a disk's
    /// spherical ellipse gets its [`TabulatedDiskSolidAngle`], whose
    /// samples cost a fraction of [`DiskSolidAngle`]'s for a build of tens
    /// of samples' worth; the other kinds are unchanged.
    pub fn for_many_samples(self) -> EmitterLight {
        match self {
            EmitterLight::Disk(d) => EmitterLight::DiskTable(TabulatedDiskSolidAngle::new(d)),
            other => other,
        }
    }

    /// A direction and its density per steradian, or `None` (nothing to
    /// sample, or a sample of zero or non-finite density).
    #[inline]
    pub fn sample(&self, u: DVec2) -> Option<LightDirection> {
        match self {
            EmitterLight::Sky => sample_sky(u),
            EmitterLight::Sphere(s) => sample_sphere(s, u),
            EmitterLight::Cap(frame, cone) => sample_cap(frame, cone, u),
            EmitterLight::Polygon(p) => sample_polygon(p, u),
            EmitterLight::Disk(d) => sample_disk(d, u),
            EmitterLight::DiskTable(d) => sample_disk_table(d, u),
            EmitterLight::None => None,
        }
    }

    /// The density per steradian with which [`EmitterLight::sample`]
    /// produces the unit direction `w`.
    #[inline]
    pub fn pdf(&self, w: DVec3) -> f64 {
        match self {
            EmitterLight::Sky => pdf_uniform_sphere(w),
            EmitterLight::Sphere(s) => s.pdf(w),
            EmitterLight::Cap(frame, cone) => cone.pdf(frame.to_local(w)),
            EmitterLight::Polygon(p) => p.pdf(w),
            EmitterLight::Disk(d) => d.pdf(w),
            EmitterLight::DiskTable(d) => d.pdf(w),
            EmitterLight::None => 0.0,
        }
    }
}

// One function per kind of [`EmitterLight::sample`], so that a batch loop
// over one emitter calls its kind's sampler directly (strategy::batch).

/// A direction with density `pdf`, if the density is positive and finite.
#[inline(always)]
fn checked(direction: DVec3, pdf: f64) -> Option<LightDirection> {
    (pdf > 0.0 && pdf.is_finite()).then_some(LightDirection { direction, pdf })
}

/// [`EmitterLight::sample`] of a sky: the uniform sphere.
#[inline(always)]
pub(super) fn sample_sky(u: DVec2) -> Option<LightDirection> {
    let w = sample_uniform_sphere(u);
    checked(w, pdf_uniform_sphere(w))
}

/// [`EmitterLight::sample`] of a sphere: its subtended cone. The direction
/// and density of [`SphereSolidAngle::sample`] (the cone's direction in its
/// frame, 1/Ω), without the point on the sphere and its distance, which
/// irradiance does not need.
#[inline(always)]
pub(super) fn sample_sphere(s: &SphereSolidAngle, u: DVec2) -> Option<LightDirection> {
    let cone = s.cone();
    checked(
        s.frame().from_local(cone.sample(u)),
        1.0 / cone.solid_angle(),
    )
}

/// [`EmitterLight::sample`] of a sky cap: its cone, in its frame.
#[inline(always)]
pub(super) fn sample_cap(frame: &Frame, cone: &UniformCone, u: DVec2) -> Option<LightDirection> {
    checked(frame.from_local(cone.sample(u)), 1.0 / cone.solid_angle())
}

/// [`EmitterLight::sample`] of a polygon: its spherical polygon.
#[inline(always)]
pub(super) fn sample_polygon(p: &PolygonSolidAngle, u: DVec2) -> Option<LightDirection> {
    let l = p.sample(u)?;
    checked(l.direction, l.pdf)
}

/// [`EmitterLight::sample`] of a polygon through the form its sampler
/// takes at the point when that form samples inline
/// ([`UniformSolidAngle`]: one spherical triangle, a spherical rectangle,
/// a fan of triangles in fixed lanes): the same direction and density as
/// [`sample_polygon`], without the fan's table lookup.
#[inline(always)]
pub(super) fn sample_solid_angle(s: &impl UniformSolidAngle, u: DVec2) -> Option<LightDirection> {
    let d = s.sample_direction(u);
    checked(d.direction, d.pdf)
}

/// [`EmitterLight::sample`] of a disk: its spherical ellipse.
#[inline(always)]
pub(super) fn sample_disk(d: &DiskSolidAngle, u: DVec2) -> Option<LightDirection> {
    let l = d.sample(u);
    checked(l.direction, l.pdf)
}

/// [`EmitterLight::sample`] of a tabulated disk: its spherical ellipse.
#[inline(always)]
pub(super) fn sample_disk_table(d: &TabulatedDiskSolidAngle, u: DVec2) -> Option<LightDirection> {
    let l = d.sample(u);
    checked(l.direction, l.pdf)
}

/// [`sample_disk_table`] for a direction the sampler drew beforehand
/// ([`TabulatedDiskSolidAngle::sample_directions`]): its density is the
/// sampler's 1/Ω, computed as the sampler computes it.
#[inline(always)]
pub(super) fn disk_table_direction(
    d: &TabulatedDiskSolidAngle,
    direction: DVec3,
) -> Option<LightDirection> {
    checked(direction, 1.0 / d.solid_angle())
}
