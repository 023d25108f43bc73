//! Emitters: uniform Lambertian lights and the two delta lights.
//!
//! Every emitter is additive: lights do not occlude each other (occlusion is
//! the tracer's business), so the irradiance of a scene is the sum of its
//! emitters' irradiances, E = Σₖ ∫ Lₖ(ω) cos θ dω + Σ_delta Eₖ. One-sided
//! emitters (disks, polygons) are dark seen from behind.

mod arrival;
mod directional;
mod disk;
mod error;
mod point;
mod polygon;
mod sky;
mod sky_cap;
mod sphere;

pub use arrival::Arrival;
pub use directional::DirectionalLight;
pub use disk::DiskLight;
pub use error::EmitterError;
pub use point::PointLight;
pub use polygon::PolygonLight;
pub use sky::Sky;
pub use sky_cap::SkyCap;
pub use sphere::SphereLight;

use glam::DVec3;

use crate::receiver::Receiver;
use lambert_geometry::f64::{Intersect, Ray};

/// Any emitter of a scene.
#[derive(Clone, Debug, PartialEq)]
pub enum Emitter {
    /// Radiance L from every direction.
    Sky(Sky),
    /// Radiance L from a cone of directions.
    SkyCap(SkyCap),
    /// A uniform spherical light.
    Sphere(SphereLight),
    /// A uniform disk light.
    Disk(DiskLight),
    /// A uniform planar convex polygon light.
    Polygon(PolygonLight),
    /// An isotropic point light (delta).
    Point(PointLight),
    /// A directional light (delta).
    Directional(DirectionalLight),
}

impl Emitter {
    /// The kind, as a scene file spells it.
    pub fn kind(&self) -> &'static str {
        match self {
            Emitter::Sky(_) => "sky",
            Emitter::SkyCap(_) => "sky_cap",
            Emitter::Sphere(_) => "sphere",
            Emitter::Disk(_) => "disk",
            Emitter::Polygon(_) => "polygon",
            Emitter::Point(_) => "point",
            Emitter::Directional(_) => "directional",
        }
    }

    /// The emitter's strength, the factor every irradiance it gives is
    /// proportional to: radiance L (W m⁻² sr⁻¹) for the sky, caps, spheres,
    /// disks and polygons; intensity I (W sr⁻¹) for a point light;
    /// irradiance E⊥ (W m⁻²) for a directional light.
    pub fn strength(&self) -> f64 {
        match self {
            Emitter::Sky(s) => s.radiance,
            Emitter::SkyCap(c) => c.radiance,
            Emitter::Sphere(s) => s.radiance,
            Emitter::Disk(d) => d.radiance,
            Emitter::Polygon(p) => p.radiance,
            Emitter::Point(p) => p.intensity,
            Emitter::Directional(d) => d.irradiance,
        }
    }

    /// This emitter with its [`strength`](Self::strength) multiplied by
    /// `factor`, its geometry unchanged. Irradiance is linear in strength,
    /// so every irradiance it gives is multiplied by `factor`; for a power
    /// of two the product is exact while it stays in the normal range,
    /// which is how estimates of extreme radiances are kept in range.
    pub fn with_strength_scaled(&self, factor: f64) -> Emitter {
        let mut e = self.clone();
        match &mut e {
            Emitter::Sky(s) => s.radiance *= factor,
            Emitter::SkyCap(c) => c.radiance *= factor,
            Emitter::Sphere(s) => s.radiance *= factor,
            Emitter::Disk(d) => d.radiance *= factor,
            Emitter::Polygon(p) => p.radiance *= factor,
            Emitter::Point(p) => p.intensity *= factor,
            Emitter::Directional(d) => d.irradiance *= factor,
        }
        e
    }

    /// Whether the emitter is a delta light (point or directional), whose
    /// irradiance is added exactly rather than estimated.
    pub fn is_delta(&self) -> bool {
        matches!(self, Emitter::Point(_) | Emitter::Directional(_))
    }

    /// Errors when the receiver cannot be placed where it is relative to
    /// this emitter: inside or on a sphere light.
    pub fn check_receiver(&self, receiver: &Receiver) -> Result<(), EmitterError> {
        if let Emitter::Sphere(s) = self {
            if s.sphere.contains(receiver.point) {
                let d = s.sphere.distance_to_center(receiver.point);
                return Err(EmitterError::new(
                    "receiver.point",
                    format!(
                        "is inside or on the sphere light (distance to its center {d} <= radius {})",
                        s.sphere.radius()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The radiance L arriving at `origin` from the unit direction `w`
    /// (0 where the emitter is not seen, or seen from the back of a
    /// one-sided face); 0 for delta lights. Each kind's own
    /// `radiance_toward` (e.g. [`SphereLight::radiance_toward`]) does the
    /// same without the match, for loops over one emitter.
    #[inline]
    pub fn radiance_toward(&self, origin: DVec3, w: DVec3) -> f64 {
        match self {
            Emitter::Sky(s) => s.radiance,
            Emitter::SkyCap(c) => c.radiance_toward(w),
            Emitter::Sphere(s) => s.radiance_toward(origin, w),
            Emitter::Disk(d) => d.radiance_toward(origin, w),
            Emitter::Polygon(p) => p.radiance_toward(origin, w),
            Emitter::Point(_) | Emitter::Directional(_) => 0.0,
        }
    }

    /// The exact irradiance of a delta light at the receiver (0 for the
    /// others): a point light gives I max(cos θ, 0)/r², a directional one
    /// E⊥ max(n·d, 0).
    pub fn delta_irradiance(&self, receiver: &Receiver) -> f64 {
        match self {
            Emitter::Point(p) => {
                let v = p.position - receiver.point;
                let r2 = v.length_squared();
                if r2 == 0.0 {
                    return 0.0;
                }
                let cos = receiver.normal.dot(v) / r2.sqrt();
                p.intensity * cos.max(0.0) / r2
            }
            Emitter::Directional(d) => d.irradiance * receiver.normal.dot(d.direction).max(0.0),
            _ => 0.0,
        }
    }
}

impl SkyCap {
    /// The radiance arriving from the unit direction `w`: L inside the
    /// cap, 0 outside.
    #[inline]
    pub fn radiance_toward(&self, w: DVec3) -> f64 {
        if self.contains(w) {
            self.radiance
        } else {
            0.0
        }
    }
}

impl SphereLight {
    /// The radiance arriving at `origin` (outside the sphere) from the unit
    /// direction `w`: L if the ray meets the sphere, else 0. Always
    /// inlined: the batch loops over a sphere call it per sample, and out of
    /// line it ran in the baseline instruction set.
    #[inline(always)]
    pub fn radiance_toward(&self, origin: DVec3, w: DVec3) -> f64 {
        let ray = Ray::new(origin, w);
        if self.sphere.hit_distance(&ray, f64::INFINITY).is_some() {
            self.radiance
        } else {
            0.0
        }
    }
}

impl DiskLight {
    /// The radiance arriving at `origin` from the unit direction `w`: L if
    /// the ray meets the disk on an emitting side (both, or the side its
    /// normal faces), else 0.
    ///
    /// Both tests run for every direction (`&`, not `&&`): the ray test is
    /// a few branch-free operations, and without the short circuit a loop
    /// over many directions reads the disk once, before the loop, and
    /// vectorises (under the branch its fields were gathered again per
    /// direction).
    #[inline]
    pub fn radiance_toward(&self, origin: DVec3, w: DVec3) -> f64 {
        let ray = Ray::new(origin, w);
        if (self.two_sided | (w.dot(self.disk.normal()) < 0.0))
            & self.disk.hit_distance(&ray, f64::INFINITY).is_some()
        {
            self.radiance
        } else {
            0.0
        }
    }
}

impl PolygonLight {
    /// The radiance arriving at `origin` from the unit direction `w`: L if
    /// the ray meets the polygon on an emitting side, else 0.
    #[inline]
    pub fn radiance_toward(&self, origin: DVec3, w: DVec3) -> f64 {
        let ray = Ray::new(origin, w);
        if (self.two_sided || w.dot(self.polygon.normal()) < 0.0)
            && self.polygon.hit_distance(&ray, f64::INFINITY).is_some()
        {
            self.radiance
        } else {
            0.0
        }
    }
}

impl Emitter {
    /// The closed-form irradiance this emitter gives the receiver
    /// ([`crate::analytic`]: Lπ for a sky, the cap formula for sky caps and
    /// spheres, the disk and polygon formulas with clipping at the
    /// receiver's plane, inverse-square and cosine laws for delta lights);
    /// `None` if the analytic function rejects the geometry or the result
    /// is not representable ([`Emitter::try_closed_form_irradiance`] says
    /// which).
    pub fn closed_form_irradiance(&self, receiver: &Receiver) -> Option<f64> {
        self.try_closed_form_irradiance(receiver).ok()
    }

    /// [`Emitter::closed_form_irradiance`] with the reason when there is no
    /// value: the geometry rejected, the irradiance overflowing f64
    /// ([`crate::analytic::AnalyticError::Overflow`], e.g. a sky of radiance
    /// 1e308), or a quadrature that did not resolve within its work bound
    /// ([`crate::analytic::AnalyticError::Unresolved`]). Never ∞ or NaN.
    pub fn try_closed_form_irradiance(
        &self,
        receiver: &Receiver,
    ) -> Result<f64, crate::analytic::AnalyticError> {
        use crate::analytic::{
            disk_irradiance, polygon_irradiance, sky_cap_irradiance, sky_irradiance,
            sphere_irradiance, AnalyticError, Emission,
        };
        let emission = |two_sided: bool| {
            if two_sided {
                Emission::TwoSided
            } else {
                Emission::OneSided
            }
        };
        let n = receiver.normal;
        match self {
            Emitter::Sky(s) => sky_irradiance(s.radiance),
            Emitter::SkyCap(c) => sky_cap_irradiance(c.radiance, n, c.axis, c.half_angle),
            Emitter::Sphere(s) => sphere_irradiance(&s.sphere, s.radiance, receiver),
            Emitter::Disk(d) => {
                disk_irradiance(&d.disk, emission(d.two_sided), d.radiance, receiver)
            }
            Emitter::Polygon(q) => {
                polygon_irradiance(&q.polygon, emission(q.two_sided), q.radiance, receiver)
            }
            Emitter::Point(_) | Emitter::Directional(_) => {
                let e = self.delta_irradiance(receiver);
                if e.is_finite() {
                    Ok(e)
                } else {
                    Err(AnalyticError::Overflow {
                        quantity: "irradiance",
                    })
                }
            }
        }
    }
}
