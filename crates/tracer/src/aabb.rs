//! Axis-aligned bounding boxes and the robust ray–box (slab) test.

use glam::DVec3;
use lambert_geometry::f64::{gamma, Ray};

/// An axis-aligned box [min, max] (componentwise). The empty box has
/// min = +∞, max = −∞, so that [`Aabb::union`] with it is the identity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The lower corner.
    pub min: DVec3,
    /// The upper corner.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box.
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The smallest box holding every point of `points`.
    pub fn around(points: &[DVec3]) -> Aabb {
        points.iter().fold(Aabb::EMPTY, |b, &p| b.with_point(p))
    }

    /// The smallest box holding this one and `p`.
    #[inline]
    pub fn with_point(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both.
    #[inline]
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// The box grown by `relative` of its largest coordinate magnitude on
    /// every side (for boxes computed with rounding: a disk's or a
    /// sphere's).
    pub fn padded(self, relative: f64) -> Aabb {
        let m = self.min.abs().max(self.max.abs()).max_element() * relative;
        Aabb {
            min: self.min - DVec3::splat(m),
            max: self.max + DVec3::splat(m),
        }
    }

    /// The centre.
    #[inline]
    pub fn centroid(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// The surface area 2(xy + yz + zx) (0 for the empty box), the cost
    /// measure of the surface-area heuristic.
    #[inline]
    pub fn surface_area(&self) -> f64 {
        let d = self.max - self.min;
        if d.min_element() < 0.0 {
            return 0.0;
        }
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// The axis (0, 1, 2) of the largest extent.
    #[inline]
    pub fn largest_axis(&self) -> usize {
        let d = self.max - self.min;
        if d.x >= d.y && d.x >= d.z {
            0
        } else if d.y >= d.z {
            1
        } else {
            2
        }
    }

    /// Whether the ray meets the box for some t in (0, `t_max`), by the
    /// slab test with the reciprocal direction `inv_dir` = 1/d precomputed
    /// (pbrt-v4 §6.1.2). The far distance of each slab is enlarged by
    /// 1 + 2γ₃, which covers the rounding of its computation, so a ray
    /// that meets a primitive never misses the primitive's box (pbrt-v4
    /// §6.8.2). NaN (a ray parallel to a slab starting on its face) is
    /// ignored by the comparisons' order: that slab does not cut the
    /// interval.
    #[inline]
    pub fn hit(&self, ray: &Ray, inv_dir: DVec3, t_max: f64) -> bool {
        let scale = 1.0 + 2.0 * gamma(3);
        let mut t0 = 0.0;
        let mut t1 = t_max;
        for i in 0..3 {
            let a = (self.min[i] - ray.origin[i]) * inv_dir[i];
            let b = (self.max[i] - ray.origin[i]) * inv_dir[i];
            let (near, far) = if a > b { (b, a) } else { (a, b) };
            let far = far * scale;
            if near > t0 {
                t0 = near;
            }
            if far < t1 {
                t1 = far;
            }
            if t0 > t1 {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_boxes_and_parallel_rays() {
        // A box of zero thickness in z (a triangle on the floor).
        let b = Aabb::around(&[DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)]);
        let down = Ray::new(DVec3::new(0.3, 0.2, 2.0), -DVec3::Z);
        assert!(b.hit(&down, down.direction.recip(), f64::INFINITY));
        assert!(!b.hit(&down, down.direction.recip(), 1.5));
        // Parallel to the box's plane, starting on it: NaN slabs ignored.
        let along = Ray::new(DVec3::new(-3.0, 0.0, 0.0), DVec3::X);
        assert!(b.hit(&along, along.direction.recip(), f64::INFINITY));
        let above = Ray::new(DVec3::new(-3.0, 0.0, 0.1), DVec3::X);
        assert!(!b.hit(&above, above.direction.recip(), f64::INFINITY));
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        assert_eq!(b.union(Aabb::EMPTY), b);
    }
}
