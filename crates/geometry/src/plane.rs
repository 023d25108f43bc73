//! Ray–plane and ray–disk intersections.

use glam::DVec3;

/// The distance t > 0 at which the ray o + t·w meets the plane through
/// `on_plane` with normal `normal`, or `None` (parallel, or behind).
#[inline]
pub fn ray_plane(origin: DVec3, w: DVec3, on_plane: DVec3, normal: DVec3) -> Option<f64> {
    let denom = normal.dot(w);
    let t = normal.dot(on_plane - origin) / denom;
    (t > 0.0 && t.is_finite()).then_some(t)
}

/// The distance t > 0 at which the ray meets the disk (center, unit normal,
/// radius), or `None`.
#[inline]
pub fn ray_disk(origin: DVec3, w: DVec3, center: DVec3, normal: DVec3, radius: f64) -> Option<f64> {
    let t = ray_plane(origin, w, center, normal)?;
    let p = origin + w * t - center;
    (p.length_squared() <= radius * radius).then_some(t)
}
