//! Ray–sphere intersection.

use glam::DVec3;

/// The nearest positive distance t at which the ray o + t·w (w unit) meets
/// the sphere (center, radius), or `None`.
///
/// With v = o − c, the roots of t² + 2(v·w)t + (|v|² − r²) = 0 are formed
/// without cancellation (pbrt-v4 §6.8.1, Numerical Recipes' q form):
/// discriminant from |v − (v·w)w|² (the squared distance of the center from
/// the line), and the smaller root as c/q where the larger would cancel.
#[inline]
pub fn ray_sphere(origin: DVec3, w: DVec3, center: DVec3, radius: f64) -> Option<f64> {
    let v = origin - center;
    let b = v.dot(w);
    let perp = v - w * b;
    let disc = (radius - perp.length()) * (radius + perp.length());
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let c = v.length_squared() - radius * radius;
    // q = −(b + sign(b)·√disc); roots q and c/q.
    let q = if b > 0.0 { -(b + root) } else { -b + root };
    let (t0, t1) = {
        let a = q;
        let other = if q != 0.0 { c / q } else { 0.0 };
        if a < other {
            (a, other)
        } else {
            (other, a)
        }
    };
    if t0 > 0.0 {
        Some(t0)
    } else if t1 > 0.0 {
        Some(t1)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hits_misses_and_far_spheres() {
        let t = ray_sphere(DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 0.0, 10.0), 1.0).unwrap();
        assert_eq!(t, 9.0);
        assert!(ray_sphere(DVec3::ZERO, DVec3::X, DVec3::new(0.0, 0.0, 10.0), 1.0).is_none());
        assert!(ray_sphere(DVec3::ZERO, -DVec3::Z, DVec3::new(0.0, 0.0, 10.0), 1.0).is_none());
        // 1e6 away: the near root keeps full relative precision.
        let t = ray_sphere(DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 0.0, 1e6), 1.0).unwrap();
        assert_eq!(t, 1e6 - 1.0);
        // From inside: the far root.
        let t = ray_sphere(DVec3::ZERO, DVec3::Z, DVec3::ZERO, 2.0).unwrap();
        assert_eq!(t, 2.0);
    }
}
