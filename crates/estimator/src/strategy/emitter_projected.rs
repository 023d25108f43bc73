//! Projected-solid-angle sampling of one emitter from one receiver, built
//! from the sampling crate's projected samplers.

use glam::{DVec2, DVec3};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    sample_cosine_hemisphere, LightSampler, ProjectedCap, ProjectedPolygon,
    ProjectedPolygonSampler, ProjectedSphere, TabulatedProjectedPolygon,
};

use super::emitter_light::LightDirection;

/// Projected-solid-angle (cosine-weighted) sampling of an emitter at one
/// receiver: directions with density p(ω) = cos θ/Ω⊥ per steradian on the
/// part of the emitter above the receiver's horizon, Ω⊥ = ∫ cos θ dω its
/// projected solid angle. For a uniform emitter of radiance L every
/// sample's L cos θ/p is then the irradiance L Ω⊥ (zero variance where
/// nothing occludes), and no sample is wasted below the horizon.
///
/// - sky: cosine-weighted directions (the sky's projection is the whole
///   disk; Malley's method);
/// - sky cap and sphere: the cap of directions (Ureña & Georgiev 2018,
///   [`ProjectedCap`], [`ProjectedSphere`]), caps cut by the horizon
///   included;
/// - convex polygon: clipped at the receiver's plane and sampled by
///   Peters' (2021) sectors ([`ProjectedPolygon`]; polygons of more than
///   [`ProjectedPolygon::MAX_VERTICES`] vertices by
///   [`ProjectedPolygonSampler`]'s fan, per sample). A one-sided polygon
///   seen from behind is dark: nothing to sample;
/// - disk: no projected sampler is known (the spherical ellipse cut by the
///   horizon has no area-preserving map); the `projected` strategy samples
///   disks by solid angle ([`Strategy::resolve`](super::Strategy::resolve)).
///
/// Every density is formed from cos θ = n·ω with the receiver's own unit
/// normal, the same product the estimate multiplies by, so that
/// L (n·ω)/p is L Ω⊥ to a few ulps even where cos θ is tiny.
#[derive(Clone, Debug)]
pub enum EmitterProjected {
    /// The sky: cosine-weighted directions about the normal, Ω⊥ = π.
    Sky(Receiver),
    /// A sky cap, in the receiver's frame.
    Cap(ProjectedCap, Receiver),
    /// A sphere's cap of directions.
    Sphere(ProjectedSphere),
    /// A polygon of at most [`ProjectedPolygon::MAX_VERTICES`] vertices.
    Polygon(Box<ProjectedPolygon>),
    /// The same with its sectors' inverses tabulated, for many samples at
    /// the receiver ([`EmitterProjected::for_many_samples`]).
    PolygonTable(Box<TabulatedProjectedPolygon>),
    /// A larger polygon, through the light sampler's fan.
    PolygonFan(ProjectedPolygonSampler, Receiver, f64),
    /// Nothing to sample: the emitter is wholly below the horizon, a
    /// one-sided polygon seen from behind, a disk or a delta light.
    None,
}

impl EmitterProjected {
    /// Prepares projected-solid-angle sampling of `emitter` from `receiver`.
    pub fn new(emitter: &Emitter, receiver: &Receiver) -> EmitterProjected {
        let (p, n) = (receiver.point, receiver.normal);
        match emitter {
            Emitter::Sky(_) => EmitterProjected::Sky(*receiver),
            Emitter::SkyCap(c) => {
                match ProjectedCap::from_theta_max(receiver.frame.to_local(c.axis), c.half_angle) {
                    Ok(cap) => EmitterProjected::Cap(cap, *receiver),
                    Err(_) => EmitterProjected::None,
                }
            }
            Emitter::Sphere(s) => match ProjectedSphere::new(p, n, &s.sphere) {
                Ok(sampler) => EmitterProjected::Sphere(sampler),
                Err(_) => EmitterProjected::None,
            },
            Emitter::Polygon(poly) => {
                let front = poly.polygon.normal().dot(p - poly.polygon.vertices()[0]) > 0.0;
                if !(poly.two_sided || front) {
                    return EmitterProjected::None;
                }
                if poly.polygon.vertices().len() <= ProjectedPolygon::MAX_VERTICES {
                    return match ProjectedPolygon::new(p, n, &poly.polygon) {
                        Ok(sampler) => EmitterProjected::Polygon(Box::new(sampler)),
                        Err(_) => EmitterProjected::None,
                    };
                }
                let sampler = ProjectedPolygonSampler::new(poly.polygon.clone());
                // Ω⊥ from the closed form: the bound of the estimate's value.
                match emitter.closed_form_irradiance(receiver) {
                    Some(e) if e > 0.0 && poly.radiance > 0.0 => {
                        EmitterProjected::PolygonFan(sampler, *receiver, e / poly.radiance)
                    }
                    _ => EmitterProjected::None,
                }
            }
            Emitter::Disk(_) | Emitter::Point(_) | Emitter::Directional(_) => {
                EmitterProjected::None
            }
        }
    }

    /// This sampler prepared for many samples at its receiver (an
    /// estimate, not a renderer's few samples per shading point): a
    /// polygon's sectors get their [`TabulatedProjectedPolygon`], whose
    /// samples evaluate the sector area about half as often, for a build
    /// of a few hundred samples' worth; the other kinds are unchanged.
    pub fn for_many_samples(self) -> EmitterProjected {
        match self {
            EmitterProjected::Polygon(p) => {
                EmitterProjected::PolygonTable(Box::new(TabulatedProjectedPolygon::new(*p)))
            }
            other => other,
        }
    }

    /// The projected solid angle Ω⊥ of what is sampled, in steradians (0
    /// when nothing is).
    pub fn projected_solid_angle(&self) -> f64 {
        match self {
            EmitterProjected::Sky(_) => std::f64::consts::PI,
            EmitterProjected::Cap(c, _) => c.projected_solid_angle(),
            EmitterProjected::Sphere(s) => s.projected_solid_angle(),
            EmitterProjected::Polygon(p) => p.projected_solid_angle(),
            EmitterProjected::PolygonTable(p) => p.projected_solid_angle(),
            EmitterProjected::PolygonFan(_, _, omega) => *omega,
            EmitterProjected::None => 0.0,
        }
    }

    /// A bound on the rounding error of
    /// [`projected_solid_angle`](Self::projected_solid_angle), in
    /// steradians: the polygon sampler's own bound
    /// ([`ProjectedPolygon::projected_solid_angle_error`]), large only for
    /// polygons grazing the horizon, and 8ε Ω⊥ for the others (the cap
    /// formulas and the fan's closed form are exact to a few ulps).
    pub fn projected_solid_angle_error(&self) -> f64 {
        match self {
            EmitterProjected::Polygon(p) => p.projected_solid_angle_error(),
            EmitterProjected::PolygonTable(p) => p.projected_solid_angle_error(),
            other => 8.0 * f64::EPSILON * other.projected_solid_angle(),
        }
    }

    /// A direction and its density per steradian, or `None` (nothing to
    /// sample, or a sample of zero density).
    #[inline]
    pub fn sample(&self, u: DVec2) -> Option<LightDirection> {
        let (direction, pdf) = match self {
            EmitterProjected::Sky(r) => {
                let w = r.frame.from_local(sample_cosine_hemisphere(u));
                (w, r.normal.dot(w).max(0.0) / std::f64::consts::PI)
            }
            EmitterProjected::Cap(cap, r) => {
                let w = r.frame.from_local(cap.sample(u).direction);
                (w, r.normal.dot(w).max(0.0) / cap.projected_solid_angle())
            }
            EmitterProjected::Sphere(s) => {
                let l = s.sample_direction(u);
                (l.direction, l.pdf)
            }
            EmitterProjected::Polygon(p) => {
                let l = p.sample(u);
                (l.direction, l.pdf)
            }
            EmitterProjected::PolygonTable(p) => {
                let l = p.sample(u);
                (l.direction, l.pdf)
            }
            EmitterProjected::PolygonFan(s, r, _) => {
                let l = s.sample(r.point, r.normal, u)?;
                (l.direction, l.pdf)
            }
            EmitterProjected::None => return None,
        };
        (pdf > 0.0 && pdf.is_finite()).then_some(LightDirection { direction, pdf })
    }

    /// The density per steradian with which [`EmitterProjected::sample`]
    /// produces the unit direction `w`.
    #[inline]
    pub fn pdf(&self, w: DVec3) -> f64 {
        match self {
            EmitterProjected::Sky(r) => r.normal.dot(w).max(0.0) / std::f64::consts::PI,
            EmitterProjected::Cap(cap, r) => {
                if cap.pdf(r.frame.to_local(w)) > 0.0 {
                    r.normal.dot(w).max(0.0) / cap.projected_solid_angle()
                } else {
                    0.0
                }
            }
            EmitterProjected::Sphere(s) => s.pdf(w),
            EmitterProjected::Polygon(p) => p.pdf(w),
            EmitterProjected::PolygonTable(p) => p.pdf(w),
            EmitterProjected::PolygonFan(s, r, _) => s.pdf(r.point, r.normal, w),
            EmitterProjected::None => 0.0,
        }
    }
}
