//! What an emitter sends along a ray: its radiance, and how far away the
//! surface it comes from lies (what a shadow ray toward it must clear).

use glam::DVec3;
use lambert_geometry::f64::{Intersect, Ray};

use super::Emitter;

/// The light an emitter sends to a point along one direction: the radiance
/// L (W·m⁻²·sr⁻¹) and the distance to the emitting surface along that
/// direction (∞ for a sky or a sky cap, which are infinitely far).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrival {
    /// The radiance arriving, W·m⁻²·sr⁻¹ (> 0).
    pub radiance: f64,
    /// The distance from the point to the emitter along the direction, in
    /// metres (the nearest intersection; ∞ for skies).
    pub distance: f64,
}

impl Emitter {
    /// The radiance arriving at `origin` from the unit direction `w` and
    /// the distance to where it leaves the emitter: the nearest
    /// intersection of the ray (origin, w) with the emitter's shape, front
    /// faces only for one-sided disks and polygons, at ∞ for skies. `None`
    /// where the emitter is not seen along `w`, where its radiance is 0,
    /// and for delta lights (they are reached by no direction drawn from a
    /// density).
    ///
    /// Agrees with [`Emitter::radiance_toward`], which is this radiance or
    /// 0; a renderer with occluders tests visibility up to `distance`
    /// (for irradiance with visibility, E = ∫ L V cos θ dω).
    ///
    /// ```
    /// use glam::DVec3;
    /// use lambert_light::emitter::{Emitter, SphereLight};
    /// let light = Emitter::Sphere(SphereLight::new(DVec3::new(0.0, 0.0, 5.0), 1.0, 2.0)?);
    /// let a = light.arrival(DVec3::ZERO, DVec3::Z).unwrap();
    /// assert_eq!((a.radiance, a.distance), (2.0, 4.0));
    /// assert_eq!(light.arrival(DVec3::ZERO, -DVec3::Z), None);
    /// # Ok::<(), lambert_light::EmitterError>(())
    /// ```
    #[inline]
    pub fn arrival(&self, origin: DVec3, w: DVec3) -> Option<Arrival> {
        let ray = Ray::new(origin, w);
        let at = |radiance: f64, distance: Option<f64>| {
            distance
                .filter(|_| radiance > 0.0)
                .map(|distance| Arrival { radiance, distance })
        };
        match self {
            Emitter::Sky(s) => at(s.radiance, Some(f64::INFINITY)),
            Emitter::SkyCap(c) => at(c.radiance, c.contains(w).then_some(f64::INFINITY)),
            Emitter::Sphere(s) => at(s.radiance, s.sphere.hit_distance(&ray, f64::INFINITY)),
            Emitter::Disk(d) if d.two_sided || w.dot(d.disk.normal()) < 0.0 => {
                at(d.radiance, d.disk.hit_distance(&ray, f64::INFINITY))
            }
            Emitter::Polygon(p) if p.two_sided || w.dot(p.polygon.normal()) < 0.0 => {
                at(p.radiance, p.polygon.hit_distance(&ray, f64::INFINITY))
            }
            Emitter::Disk(_) | Emitter::Polygon(_) => None,
            Emitter::Point(_) | Emitter::Directional(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emitter::{DiskLight, PointLight, PolygonLight, Sky, SkyCap, SphereLight};

    /// `arrival` and `radiance_toward` agree on every emitter kind, seen
    /// and unseen, front and back.
    #[test]
    fn agrees_with_radiance_toward() {
        let emitters = [
            Emitter::Sky(Sky::new(0.5).unwrap()),
            Emitter::SkyCap(SkyCap::new(DVec3::Z, 0.3, 1.5).unwrap()),
            Emitter::Sphere(SphereLight::new(DVec3::new(0.2, 0.0, 3.0), 1.0, 2.0).unwrap()),
            Emitter::Disk(
                DiskLight::new(DVec3::new(0.0, 0.0, 2.0), -DVec3::Z, 1.0, 3.0, false).unwrap(),
            ),
            Emitter::Disk(
                DiskLight::new(DVec3::new(0.0, 0.0, 2.0), DVec3::Z, 1.0, 3.0, false).unwrap(),
            ),
            Emitter::Polygon(
                PolygonLight::new(
                    vec![
                        DVec3::new(-1.0, -1.0, 2.0),
                        DVec3::new(-1.0, 1.0, 2.0),
                        DVec3::new(1.0, 1.0, 2.0),
                        DVec3::new(1.0, -1.0, 2.0),
                    ],
                    4.0,
                    true,
                )
                .unwrap(),
            ),
            Emitter::Point(PointLight::with_intensity(DVec3::Z, 1.0).unwrap()),
        ];
        for e in &emitters {
            for i in 0..200 {
                let a = i as f64 * 0.1;
                let w =
                    DVec3::new(0.6 * a.cos(), 0.6 * a.sin(), (i as f64 / 100.0) - 1.0).normalize();
                let l = e.radiance_toward(DVec3::ZERO, w);
                let arrival = e.arrival(DVec3::ZERO, w);
                assert_eq!(arrival.map_or(0.0, |a| a.radiance), l, "{} {w}", e.kind());
                if let Some(a) = arrival {
                    assert!(a.distance > 0.0, "{}", e.kind());
                }
            }
        }
    }
}
