//! # lambert-sampling
//!
//! Warps from the unit square to directions and points, each with its exact
//! density and its inverse, in f64 and in f32 from one implementation, and
//! the sample sequences that feed them.
//!
//! Every warp is a triple named alike: a sampler (`sample_*`, or `sample` on
//! the warp's struct when it has parameters to validate and precompute), its
//! density (`pdf_*` / `pdf`, 0 outside the support, never negative or NaN)
//! and its inverse (`invert_*` / `invert`). Each states the measure of its
//! density (per steradian or per square metre), its formula and its source.
//!
//! Beyond uniform solid-angle sampling of lights, the crate offers
//! projected-solid-angle (cosine-weighted) sampling of spherical caps and
//! sphere lights ([`ProjectedCap`], [`ProjectedSphere`]; Ureña & Georgiev
//! 2018) and of convex polygons clipped to the receiver's hemisphere
//! ([`ProjectedPolygon`]; Peters 2021): for an unoccluded uniform light
//! every sample's estimate L cos θ/p is the irradiance itself. Disks are
//! sampled uniformly in solid angle by [`DiskSolidAngle`] (Guillén et al.
//! 2017).
//!
//! The f64 warps are in [`f64`](mod@f64) (also re-exported at the crate root); the
//! f32 ones, for path tracers, in [`f32`](mod@f32). Conventions (DESIGN.md): the local
//! frame has +z as the normal, θ measured from +z, φ from +x; `u ∈ [0, 1)²`,
//! and `u` exactly 0 or 1 still gives a finite unit vector of positive pdf.
//!
//! ```
//! use lambert_sampling::f64::{pdf_cosine_hemisphere, sample_cosine_hemisphere};
//! use glam::DVec2;
//! let w = sample_cosine_hemisphere(DVec2::new(0.3, 0.8));
//! assert!((w.length() - 1.0).abs() < 1e-15);
//! assert!((pdf_cosine_hemisphere(w) - w.z / std::f64::consts::PI).abs() < 1e-15);
//! ```

pub(crate) mod precision;

pub mod area;
pub mod carlson;
pub mod catalog;
pub mod cone;
pub mod direction_sample;
pub mod disk;
pub mod disk_solid_angle;
pub mod error;
pub mod frame;
pub mod hemisphere;
pub mod light_sample;
pub mod projected_cap;
pub mod projected_polygon;
pub mod projected_sphere;
pub mod segment;
pub mod sequence;
pub mod sphere;
pub mod sphere_light;
pub mod spherical;
pub mod spherical_rectangle;
pub mod spherical_triangle;
pub mod triangle;
pub mod trig;

pub use error::SamplingError;
pub use sequence::{Independent, SampleSequence, Scramble, Sobol, SobolLayout, Stratified};

/// Every f64 warp and helper (`DVec2`, `DVec3`).
pub mod f64 {
    pub use crate::area::f64::*;
    pub use crate::carlson::f64::*;
    pub use crate::cone::f64::*;
    pub use crate::direction_sample::f64::*;
    pub use crate::disk::f64::*;
    pub use crate::disk_solid_angle::f64::*;
    pub use crate::error::SamplingError;
    pub use crate::frame::f64::*;
    pub use crate::hemisphere::f64::*;
    pub use crate::light_sample::f64::*;
    pub use crate::projected_cap::f64::*;
    pub use crate::projected_polygon::f64::*;
    pub use crate::projected_sphere::f64::*;
    pub use crate::segment::f64::*;
    pub use crate::sphere::f64::*;
    pub use crate::sphere_light::f64::*;
    pub use crate::spherical::f64::*;
    pub use crate::spherical_rectangle::f64::*;
    pub use crate::spherical_triangle::f64::*;
    pub use crate::triangle::f64::*;
    pub use crate::trig::f64::*;
}

/// Every f32 warp and helper (`Vec2`, `Vec3`), for path tracers.
pub mod f32 {
    pub use crate::area::f32::*;
    pub use crate::carlson::f32::*;
    pub use crate::cone::f32::*;
    pub use crate::direction_sample::f32::*;
    pub use crate::disk::f32::*;
    pub use crate::disk_solid_angle::f32::*;
    pub use crate::error::SamplingError;
    pub use crate::frame::f32::*;
    pub use crate::hemisphere::f32::*;
    pub use crate::light_sample::f32::*;
    pub use crate::projected_cap::f32::*;
    pub use crate::projected_polygon::f32::*;
    pub use crate::projected_sphere::f32::*;
    pub use crate::segment::f32::*;
    pub use crate::sphere::f32::*;
    pub use crate::sphere_light::f32::*;
    pub use crate::spherical::f32::*;
    pub use crate::spherical_rectangle::f32::*;
    pub use crate::spherical_triangle::f32::*;
    pub use crate::triangle::f32::*;
    pub use crate::trig::f32::*;
}

pub use crate::f64::*;
