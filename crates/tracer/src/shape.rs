//! The shapes a scene is made of: the geometry crate's, behind one enum.

use glam::DVec3;
use lambert_geometry::f64::{
    ConvexPolygon, Disk, Hit, Intersect, Parallelogram, Plane, Ray, Sphere, Triangle,
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
