//! Area sampling of one emitter, seen from one receiver point, with the
//! density converted to solid angle (pbrt-v4 §4.2.3: p_ω = p_A d²/|cos θ_l|).

use glam::{DVec2, DVec3};
use lambert_sampling::f64::{
    pdf_area_to_solid_angle, sample_uniform_sphere, UniformDiskArea, UniformTriangle,
};

use super::discrete::pick_by_cumulative;
use super::light_sampler::LightDirection;
use lambert_geometry::{ray_convex_polygon, ray_disk, ray_sphere};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;

/// Uniform area sampling of a sphere's whole surface, a disk, or a convex
/// polygon (a fan of triangles chosen by area).
#[derive(Clone, Debug)]
pub enum AreaSampler {
    /// The sphere's surface: density 1/(4πr²); points on the far side are
    /// hidden by the sphere itself and carry no radiance.
    Sphere {
        /// Reference point.
        from: DVec3,
        /// Center.
        center: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A disk, by the concentric map.
    Disk {
        /// Reference point.
        from: DVec3,
        /// The sampler.
        disk: UniformDiskArea,
        /// Center.
        center: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A polygon's fan of triangles, chosen by area.
    Polygon {
        /// Reference point.
        from: DVec3,
        /// The fan.
        triangles: Vec<UniformTriangle>,
        /// Cumulative areas, last = total.
        cumulative: Vec<f64>,
        /// The polygon (for the inverse query).
        polygon: lambert_geometry::ConvexPolygon,
    },
    /// The emitter has no area (sky, cap, delta).
    None,
}

impl AreaSampler {
    /// Prepares area sampling of `emitter` from `receiver`.
    pub fn new(emitter: &Emitter, receiver: &Receiver) -> AreaSampler {
        let from = receiver.point;
        match emitter {
            Emitter::Sphere(s) => AreaSampler::Sphere {
                from,
                center: s.center,
                radius: s.radius,
            },
            Emitter::Disk(d) => match UniformDiskArea::new(d.center, d.normal, d.radius) {
                Ok(disk) => AreaSampler::Disk {
                    from,
                    disk,
                    center: d.center,
                    normal: d.normal,
                    radius: d.radius,
                },
                Err(_) => AreaSampler::None,
            },
            Emitter::Polygon(p) => {
                let v = &p.polygon.vertices;
                let mut triangles = Vec::new();
                let mut cumulative = Vec::new();
                let mut total = 0.0;
                for i in 1..v.len() - 1 {
                    if let Ok(t) = UniformTriangle::new(v[0], v[i], v[i + 1]) {
                        total += t.area();
                        triangles.push(t);
                        cumulative.push(total);
                    }
                }
                AreaSampler::Polygon {
                    from,
                    triangles,
                    cumulative,
                    polygon: p.polygon.clone(),
                }
            }
            _ => AreaSampler::None,
        }
    }

    /// A direction toward a uniformly sampled point of the emitter, with
    /// its solid-angle density, or `None` (no area, edge-on, or a point on
    /// the hidden far side of a sphere).
    #[inline]
    pub fn sample(&self, u: DVec2) -> Option<LightDirection> {
        let (from, point, normal, pdf_area) = match self {
            AreaSampler::Sphere {
                from,
                center,
                radius,
            } => {
                let n = sample_uniform_sphere(u);
                let point = *center + n * *radius;
                // Hidden unless the surface faces the reference point.
                if n.dot(*from - point) <= 0.0 {
                    return None;
                }
                (
                    *from,
                    point,
                    n,
                    1.0 / (4.0 * std::f64::consts::PI * radius * radius),
                )
            }
            AreaSampler::Disk { from, disk, .. } => {
                let s = disk.sample(u);
                (*from, s.point, s.normal, s.pdf_area)
            }
            AreaSampler::Polygon {
                from,
                triangles,
                cumulative,
                ..
            } => {
                let total = *cumulative.last()?;
                let (k, u0) = pick_by_cumulative(cumulative, u.x)?;
                let s = triangles[k].sample(DVec2::new(u0, u.y));
                (*from, s.point, s.normal, 1.0 / total)
            }
            AreaSampler::None => return None,
        };
        let to = point - from;
        let distance = to.length();
        let pdf = pdf_area_to_solid_angle(pdf_area, from, point, normal);
        (pdf > 0.0 && distance > 0.0).then(|| LightDirection {
            direction: to / distance,
            pdf,
        })
    }

    /// The solid-angle density with which [`AreaSampler::sample`] produces
    /// the unit direction `w` (through the first surface point it hits).
    #[inline]
    pub fn pdf(&self, w: DVec3) -> f64 {
        match self {
            AreaSampler::Sphere {
                from,
                center,
                radius,
            } => match ray_sphere(*from, w, *center, *radius) {
                Some(t) => {
                    let point = *from + w * t;
                    let n = (point - *center) / *radius;
                    pdf_area_to_solid_angle(
                        1.0 / (4.0 * std::f64::consts::PI * radius * radius),
                        *from,
                        point,
                        n,
                    )
                }
                None => 0.0,
            },
            AreaSampler::Disk {
                from,
                center,
                normal,
                radius,
                disk,
            } => match ray_disk(*from, w, *center, *normal, *radius) {
                Some(t) => {
                    pdf_area_to_solid_angle(1.0 / disk.area(), *from, *from + w * t, *normal)
                }
                None => 0.0,
            },
            AreaSampler::Polygon {
                from,
                cumulative,
                polygon,
                ..
            } => match (ray_convex_polygon(*from, w, polygon), cumulative.last()) {
                (Some(t), Some(total)) => {
                    pdf_area_to_solid_angle(1.0 / total, *from, *from + w * t, polygon.normal)
                }
                _ => 0.0,
            },
            AreaSampler::None => 0.0,
        }
    }
}
