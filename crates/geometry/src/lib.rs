//! # lambert-geometry
//!
//! Rays and the shapes that lights and scenes are made of, each defined
//! once and shared by lambert's samplers, closed forms, estimator and
//! tracer: [`Sphere`](f64::Sphere), [`Disk`](f64::Disk),
//! [`Triangle`](f64::Triangle), [`Parallelogram`](f64::Parallelogram),
//! [`ConvexPolygon`](f64::ConvexPolygon) and [`Plane`](f64::Plane). Every
//! shape has
//!
//! - a validating constructor whose [`GeometryError`] names the field and
//!   the value ([`validate`] holds the rules, in one place);
//! - nearest-hit intersection ([`Intersect`](f64::Intersect)) returning a
//!   [`Hit`](f64::Hit) with the distance, point, geometric normal, surface
//!   parameters and a bound on the point's rounding error, from which
//!   [`Hit::spawn_ray`](f64::Hit::spawn_ray) starts secondary rays that
//!   cannot re-hit the surface they leave (pbrt-v4's error-bounded
//!   offsets; see [`mod@f64`]'s `Ray` docs);
//! - its area and the solid angle it subtends from a point, without
//!   cancellation for tiny, distant and nearly touching shapes.
//!
//! Everything exists in f64 ([`mod@f64`], glam's `DVec3`) and in f32
//! ([`mod@f32`], `Vec3`) from one implementation (see [`precision`]). The
//! crate depends on glam only.
//!
//! ```
//! use glam::DVec3;
//! use lambert_geometry::f64::{Intersect, Plane, Ray, Sphere};
//! // A sphere resting on a plane: the ray that grazes the contact point
//! // finds the sphere, and the shadow ray from the floor next to the
//! // contact does not leak through it.
//! let floor = Plane::new(DVec3::ZERO, DVec3::Z)?;
//! let ball = Sphere::new(DVec3::new(0.0, 0.0, 1.0), 1.0)?;
//! let down = Ray::new(DVec3::new(0.01, 0.0, 5.0), -DVec3::Z);
//! let hit = floor.intersect(&down, f64::INFINITY).unwrap();
//! let toward_light = DVec3::new(0.0, 0.0, 1.0);
//! let shadow = hit.spawn_ray(toward_light);
//! assert!(ball.hit_distance(&shadow, f64::INFINITY).is_some());
//! # Ok::<(), lambert_geometry::GeometryError>(())
//! ```

pub mod precision;

mod batch;
mod clip;
mod disk;
mod error;
mod frame;
mod parallelogram;
mod plane;
mod polygon;
mod polygon_from_origin;
mod ray;
mod solid_angle;
mod sphere;
mod sphere_from_outside;
mod triangle;
pub mod validate;

pub use error::GeometryError;

/// The public items of one precision, re-exported once.
macro_rules! public_api {
    ($p:ident) => {
        pub use crate::batch::$p::RayBatch;
        pub use crate::clip::$p::clip_to_half_space;
        pub use crate::disk::$p::Disk;
        pub use crate::frame::$p::Frame;
        pub use crate::parallelogram::$p::Parallelogram;
        pub use crate::plane::$p::Plane;
        pub use crate::polygon::$p::ConvexPolygon;
        pub use crate::polygon_from_origin::$p::PolygonFromOrigin;
        pub use crate::ray::$p::{gamma, offset_origin, Hit, Intersect, Ray, SHADOW_EPSILON};
        pub use crate::solid_angle::$p::{
            cap_solid_angle, cap_solid_angle_from_sin2, convex_polygon_solid_angle,
            disk_solid_angle_hs, one_minus_cos_from_sin2, solid_angle_van_oosterom,
            triangle_solid_angle,
        };
        pub use crate::sphere::$p::Sphere;
        pub use crate::sphere_from_outside::$p::SphereFromOutside;
        pub use crate::triangle::$p::Triangle;
        pub use crate::validate::$p::unit_vector;
    };
}

/// Every type and function in f64 (glam's `DVec2`, `DVec3`): the default.
pub mod f64 {
    public_api!(f64);
}

/// Every type and function in f32 (glam's `Vec2`, `Vec3`), for path tracers.
pub mod f32 {
    public_api!(f32);
}
