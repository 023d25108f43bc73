//! The shapes a scene is made of: the geometry crate's, behind one enum.

use glam::{DVec2, DVec3};
use lambert_geometry::f64::{
    ConvexPolygon, Disk, Hit, Intersect, Parallelogram, Plane, Ray, RayBatch, Sphere, Triangle,
};

use crate::aabb::Aabb;

/// Any shape of a scene: a sphere, an infinite plane, a disk, a triangle
/// (meshes are triangles), a parallelogram or a convex polygon, each
/// validated, intersected and bounded by `lambert_geometry`'s definitions.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// An infinite plane (unbounded: never in the BVH).
    Plane(Plane),
    /// A disk.
    Disk(Disk),
    /// A triangle (watertight intersection).
    Triangle(Triangle),
    /// A parallelogram.
    Parallelogram(Parallelogram),
    /// A convex planar polygon (boxed: it holds its vertices).
    Polygon(Box<ConvexPolygon>),
}

impl Shape {
    /// The kind, as scene files spell it.
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Disk(_) => "disk",
            Shape::Triangle(_) => "triangle",
            Shape::Parallelogram(_) => "parallelogram",
            Shape::Polygon(_) => "polygon",
        }
    }

    /// A box holding the shape (`None` for the unbounded plane). Boxes
    /// computed with rounding (sphere, disk) are padded by 1e-12 relative,
    /// far above their few roundings.
    pub fn bounds(&self) -> Option<Aabb> {
        Some(match self {
            Shape::Sphere(s) => {
                let r = DVec3::splat(s.radius());
                Aabb {
                    min: s.center() - r,
                    max: s.center() + r,
                }
                .padded(1e-12)
            }
            Shape::Plane(_) => return None,
            Shape::Disk(d) => {
                // Extent along axis i: r·√(1 − nᵢ²).
                let n = d.normal();
                let e = (DVec3::ONE - n * n).max(DVec3::ZERO).powf(0.5) * d.radius();
                Aabb {
                    min: d.center() - e,
                    max: d.center() + e,
                }
                .padded(1e-12)
            }
            Shape::Triangle(t) => Aabb::around(&t.vertices()),
            Shape::Parallelogram(p) => Aabb::around(&p.vertices()),
            Shape::Polygon(p) => Aabb::around(p.vertices()),
        })
    }

    /// Whether `point` is strictly inside the solid the shape bounds (only
    /// spheres bound a solid here; a camera there would see nothing of the
    /// scene).
    pub fn encloses(&self, point: DVec3) -> bool {
        match self {
            Shape::Sphere(s) => s.distance_to_center(point) < s.radius(),
            _ => false,
        }
    }

    /// The nearest hit with 0 < t < `t_max`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<Hit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Plane(s) => s.intersect(ray, t_max),
            Shape::Disk(s) => s.intersect(ray, t_max),
            Shape::Triangle(s) => s.intersect(ray, t_max),
            Shape::Parallelogram(s) => s.intersect(ray, t_max),
            Shape::Polygon(s) => s.intersect(ray, t_max),
        }
    }

    /// The record of the hit at `t`, a distance [`Shape::hit_distance`]
    /// returned, with the surface parameters left at zero (see
    /// `lambert_geometry`'s `Intersect::hit_at`).
    #[inline(always)]
    pub fn hit_at(&self, ray: &Ray, t: f64) -> Hit {
        match self {
            Shape::Sphere(s) => s.hit_at(ray, t),
            Shape::Plane(s) => s.hit_at(ray, t),
            Shape::Disk(s) => s.hit_at(ray, t),
            Shape::Triangle(s) => s.hit_at(ray, t),
            Shape::Parallelogram(s) => s.hit_at(ray, t),
            Shape::Polygon(s) => s.hit_at(ray, t),
        }
    }

    /// The surface parameters of the hit at `t`, a distance
    /// [`Shape::hit_distance`] returned: the `uv` of [`Shape::intersect`].
    #[inline]
    pub fn surface_parameters(&self, ray: &Ray, t: f64) -> DVec2 {
        match self {
            Shape::Sphere(s) => s.surface_parameters(ray, t),
            Shape::Plane(s) => s.surface_parameters(ray, t),
            Shape::Disk(s) => s.surface_parameters(ray, t),
            Shape::Triangle(s) => s.surface_parameters(ray, t),
            Shape::Parallelogram(s) => s.surface_parameters(ray, t),
            Shape::Polygon(s) => s.surface_parameters(ray, t),
        }
    }

    /// For every ray i of `rays` that meets the shape at 0 < t <
    /// `nearest[i]`: `nearest[i] = t`, `ids[i] = id` (see
    /// `lambert_geometry`'s `Intersect::nearest_in_batch`).
    #[inline(always)]
    pub fn nearest_in_batch(&self, rays: &RayBatch, id: u32, nearest: &mut [f64], ids: &mut [u32]) {
        match self {
            Shape::Sphere(s) => s.nearest_in_batch(rays, id, nearest, ids),
            Shape::Plane(s) => s.nearest_in_batch(rays, id, nearest, ids),
            Shape::Disk(s) => s.nearest_in_batch(rays, id, nearest, ids),
            Shape::Triangle(s) => s.nearest_in_batch(rays, id, nearest, ids),
            Shape::Parallelogram(s) => s.nearest_in_batch(rays, id, nearest, ids),
            Shape::Polygon(s) => s.nearest_in_batch(rays, id, nearest, ids),
        }
    }

    /// Sets `blocked[i]` for every ray i of `rays` that meets the shape at
    /// 0 < t < `t_max[i]` (see `lambert_geometry`'s
    /// `Intersect::occludes_in_batch`).
    #[inline(always)]
    pub fn occludes_in_batch(&self, rays: &RayBatch, t_max: &[f64], blocked: &mut [bool]) {
        match self {
            Shape::Sphere(s) => s.occludes_in_batch(rays, t_max, blocked),
            Shape::Plane(s) => s.occludes_in_batch(rays, t_max, blocked),
            Shape::Disk(s) => s.occludes_in_batch(rays, t_max, blocked),
            Shape::Triangle(s) => s.occludes_in_batch(rays, t_max, blocked),
            Shape::Parallelogram(s) => s.occludes_in_batch(rays, t_max, blocked),
            Shape::Polygon(s) => s.occludes_in_batch(rays, t_max, blocked),
        }
    }

    /// The distance of the nearest hit with 0 < t < `t_max` (the same
    /// decision as [`Shape::intersect`], without the hit record).
    #[inline]
    pub fn hit_distance(&self, ray: &Ray, t_max: f64) -> Option<f64> {
        match self {
            Shape::Sphere(s) => s.hit_distance(ray, t_max),
            Shape::Plane(s) => s.hit_distance(ray, t_max),
            Shape::Disk(s) => s.hit_distance(ray, t_max),
            Shape::Triangle(s) => s.hit_distance(ray, t_max),
            Shape::Parallelogram(s) => s.hit_distance(ray, t_max),
            Shape::Polygon(s) => s.hit_distance(ray, t_max),
        }
    }
}
