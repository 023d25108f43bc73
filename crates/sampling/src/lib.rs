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
//! The f64 warps are in [`f64`](mod@f64) (also re-exported at the crate root); the
//! f32 ones, for path tracers, in [`f32`](mod@f32). Conventions: the local
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

mod area;
mod area_light;
mod atan;
mod carlson;
mod cone;
mod cone_cosine;
mod direction_sample;
mod discrete;
mod disk;
mod disk_light;
mod disk_table;
pub mod error;
mod hemisphere;
mod horizon_clip;
pub mod isa;
mod light_sample;
mod light_sampler;
mod polygon_area_fan;
mod polygon_light;
mod projected_cap;
mod projected_cap_batch;
mod projected_polygon;
mod projected_sector;
mod projected_sphere;
mod projected_table;
mod projected_whole;
mod segment;
pub mod sequence;
mod soa;
mod sphere;
mod sphere_light;
mod spherical;
mod spherical_fan;
mod spherical_rectangle;
mod spherical_triangle;
#[cfg(test)]
mod test_shapes;
mod triangle;
mod triangle_light;
mod trig;
mod uniform_solid_angle;

pub use error::SamplingError;
pub use horizon_clip::MAX_POLYGON_VERTICES;

/// The public items of one precision, re-exported once (one path per item
/// and precision).
macro_rules! public_api {
    ($p:ident) => {
        pub use crate::area::$p::{UniformDiskArea, UniformParallelogram};
        pub use crate::area_light::$p::{
            DiskAreaSampler, PolygonAreaSampler, SphereAreaSampler, TriangleAreaSampler,
        };
        pub use crate::atan::$p::atan2;
        pub use crate::cone::$p::UniformCone;
        pub use crate::cone_cosine::$p::ConeCosine;
        pub use crate::direction_sample::$p::DirectionSample;
        pub use crate::discrete::$p::{pick_by_cumulative, rescale_within};
        pub use crate::disk::$p::{
            concentric_polar, invert_concentric_disk, invert_uniform_disk, pdf_concentric_disk,
            pdf_uniform_disk, sample_concentric_disk, sample_uniform_disk,
        };
        pub use crate::disk_light::$p::{DiskLightSampler, DiskSolidAngle};
        pub use crate::disk_table::$p::TabulatedDiskSolidAngle;
        pub use crate::hemisphere::$p::{
            invert_cosine_hemisphere, invert_uniform_hemisphere, pdf_cosine_hemisphere,
            pdf_uniform_hemisphere, sample_cosine_hemisphere, sample_cosine_hemisphere_batch,
            sample_cosine_hemisphere_soa, sample_uniform_hemisphere,
            sample_uniform_hemisphere_batch, sample_uniform_hemisphere_soa,
        };
        pub use crate::light_sample::$p::{pdf_area_to_solid_angle, LightSample, PointSample};
        pub use crate::light_sampler::$p::{seen_from, seen_from_or_zero, LightSampler};
        pub use crate::polygon_area_fan::$p::PolygonAreaFan;
        pub use crate::polygon_light::$p::{
            PolygonLightSampler, PolygonSolidAngle, SingleTriangle,
        };
        pub use crate::projected_cap::$p::ProjectedCap;
        pub use crate::projected_polygon::$p::{ProjectedPolygon, ProjectedPolygonSampler};
        pub use crate::projected_sphere::$p::{ProjectedSphere, ProjectedSphereSampler};
        pub use crate::projected_table::$p::TabulatedProjectedPolygon;
        pub use crate::projected_whole::$p::{WholeProjectedCap, WholeProjectedSphere};
        pub use crate::sphere::$p::{
            invert_uniform_sphere, pdf_uniform_sphere, sample_uniform_sphere,
            sample_uniform_sphere_batch, sample_uniform_sphere_soa,
        };
        pub use crate::sphere_light::$p::{SphereLightSampler, SphereSolidAngle};
        pub use crate::spherical::$p::{azimuth_fraction, direction_from, one_minus_cos_theta};
        pub use crate::spherical_fan::$p::SphericalFan;
        pub use crate::spherical_rectangle::$p::SphericalRectangle;
        pub use crate::spherical_triangle::$p::SphericalTriangle;
        pub use crate::triangle::$p::UniformTriangle;
        pub use crate::triangle_light::$p::{TriangleLightSampler, TriangleSolidAngle};
        pub use crate::trig::$p::{
            cos_2pi, sin, sin_cos, sin_cos_2pi, sin_cos_eighth, sin_cos_quarter,
        };
        pub use crate::uniform_solid_angle::$p::UniformSolidAngle;
    };
}

/// Every warp, sampler and helper in f64 (glam's `DVec2`, `DVec3`).
pub mod f64 {
    public_api!(f64);
}

/// Every warp, sampler and helper in f32 (glam's `Vec2`, `Vec3`), from the
/// same source as [`mod@f64`], for path tracers.
pub mod f32 {
    public_api!(f32);
}
