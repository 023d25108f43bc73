//! # lambert-geometry
//!
//! Ray–shape intersections, written once and shared by the estimator (which
//! asks what a direction from the receiver sees) and the tracer.

mod plane;
mod polygon;
mod sphere;

pub use plane::{ray_disk, ray_plane};
pub use polygon::{convex_polygon_contains, ray_convex_polygon, ConvexPolygon};
pub use sphere::ray_sphere;
