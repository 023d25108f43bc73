//! Solid-angle sampling of one emitter from one receiver point.

use glam::{DVec2, DVec3};
use lambert_sampling::f64::{
    pdf_uniform_sphere, sample_uniform_sphere, SphereSolidAngle, SphericalRectangle,
    SphericalTriangle,
};

use super::area_sampler::AreaSampler;
use super::discrete::pick_by_cumulative;
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;

/// A direction toward a light with its density per steradian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightDirection {
    /// Unit direction from the receiver.
    pub direction: DVec3,
    /// Density per steradian (> 0).
    pub pdf: f64,
}

/// The best available solid-angle sampler of an emitter seen from a point:
/// the subtended cone for spheres and sky caps (Shirley et al. 1996), the
/// uniform sphere for a sky, spherical rectangles (Ureña et al. 2013) for
/// rectangles, a fan of spherical triangles chosen by solid angle (Arvo
/// 1995) for other convex polygons, and area sampling for disks (no exact
/// solid-angle sampler of a disk is implemented; area sampling is unbiased
/// and its density is converted to solid angle).
#[derive(Clone, Debug)]
pub enum LightSampler {
    /// The whole sphere of directions, uniform.
    Sky,
    /// A cone of directions about an axis (sky caps, spheres).
    Cone(SphereSolidAngle),
    /// A cap of directions (sky cap), with its frame.
    Cap(
        lambert_sampling::f64::Frame,
        lambert_sampling::f64::UniformCone,
    ),
    /// A rectangle's spherical rectangle.
    Rectangle(SphericalRectangle),
    /// A convex polygon's fan of spherical triangles, with the cumulative
    /// solid angles used to choose one.
    Triangles {
        /// The fan.
        triangles: Vec<SphericalTriangle>,
        /// Cumulative solid angles, last = total.
        cumulative: Vec<f64>,
    },
    /// Area sampling, converted to solid angle.
    Area(AreaSampler),
    /// Nothing to sample (the emitter is invisible from here).
    None,
}

impl LightSampler {
    /// Prepares solid-angle sampling of `emitter` from `receiver`.
    pub fn new(emitter: &Emitter, receiver: &Receiver) -> LightSampler {
        let p = receiver.point;
        match emitter {
            Emitter::Sky(_) => LightSampler::Sky,
            Emitter::SkyCap(c) => LightSampler::Cap(c.frame, c.cone),
            Emitter::Sphere(s) => match SphereSolidAngle::new(p, s.center, s.radius) {
                Ok(sampler) => LightSampler::Cone(sampler),
                Err(_) => LightSampler::None,
            },
            Emitter::Disk(_) => LightSampler::Area(AreaSampler::new(emitter, receiver)),
            Emitter::Polygon(poly) => {
                if let Some((corner, e0, e1)) = poly.as_rectangle() {
                    if let Ok(r) = SphericalRectangle::new(p, corner, e0, e1) {
                        return LightSampler::Rectangle(r);
                    }
                }
                let v = &poly.polygon.vertices;
                let mut triangles = Vec::new();
                let mut cumulative = Vec::new();
                let mut total = 0.0;
                for i in 1..v.len() - 1 {
                    if let Ok(t) = SphericalTriangle::new(p, v[0], v[i], v[i + 1]) {
                        total += t.solid_angle();
                        triangles.push(t);
                        cumulative.push(total);
                    }
                }
                if triangles.is_empty() {
                    LightSampler::None
                } else {
                    LightSampler::Triangles {
                        triangles,
                        cumulative,
                    }
                }
            }
            Emitter::Point(_) | Emitter::Directional(_) => LightSampler::None,
        }
    }

    /// A direction and its density, or `None` when nothing can be sampled.
    #[inline]
    pub fn sample(&self, u: DVec2) -> Option<LightDirection> {
        let (direction, pdf) = match self {
            LightSampler::Sky => {
                let w = sample_uniform_sphere(u);
                (w, pdf_uniform_sphere(w))
            }
            LightSampler::Cone(s) => {
                let l = s.sample(u);
                (l.direction, l.pdf)
            }
            LightSampler::Cap(frame, cone) => {
                (frame.from_local(cone.sample(u)), 1.0 / cone.solid_angle())
            }
            LightSampler::Rectangle(r) => {
                let d = r.sample(u);
                (d.direction, d.pdf)
            }
            LightSampler::Triangles {
                triangles,
                cumulative,
            } => {
                // Choose a triangle by solid angle with u₀ and reuse u₀.
                let total = *cumulative.last()?;
                let (k, u0) = pick_by_cumulative(cumulative, u.x)?;
                let d = triangles[k].sample(DVec2::new(u0, u.y));
                (d.direction, 1.0 / total)
            }
            LightSampler::Area(a) => {
                let s = a.sample(u)?;
                (s.direction, s.pdf)
            }
            LightSampler::None => return None,
        };
        (pdf > 0.0 && pdf.is_finite()).then_some(LightDirection { direction, pdf })
    }

    /// The density per steradian with which [`LightSampler::sample`]
    /// produces the unit direction `w`.
    #[inline]
    pub fn pdf(&self, w: DVec3) -> f64 {
        match self {
            LightSampler::Sky => pdf_uniform_sphere(w),
            LightSampler::Cone(s) => s.pdf(w),
            LightSampler::Cap(frame, cone) => cone.pdf(frame.to_local(w)),
            LightSampler::Rectangle(r) => r.pdf(w),
            LightSampler::Triangles {
                triangles,
                cumulative,
            } => {
                if triangles.iter().any(|t| t.contains(w)) {
                    1.0 / cumulative.last().copied().unwrap_or(f64::INFINITY)
                } else {
                    0.0
                }
            }
            LightSampler::Area(a) => a.pdf(w),
            LightSampler::None => 0.0,
        }
    }
}
