//! # lambert-tracer
//!
//! Images of scenes with occluders, in three modes, written as linear
//! OpenEXR:
//!
//! - **Ray casting** (Appel 1968, "Some techniques for shading machine
//!   renderings of solids"): one ray per pixel from the eye through the
//!   image plane; the nearest surface it meets is shaded by the light that
//!   reaches it directly, a shadow ray toward each light deciding whether
//!   the light is seen: L = ρ/π Σ I max(0, n·l) V / r².
//! - **Recursive ray tracing** (Whitted 1980, "An improved illumination
//!   model for shaded display"): at each hit the direct light plus the
//!   radiance of the reflected ray (mirrors) and of the reflected and
//!   refracted rays (glass, weighted by the exact Fresnel reflectance, with
//!   total internal reflection), each traced the same way to a depth limit:
//!   the tree of rays of Whitted's paper, with Blinn–Phong highlights.
//! - **Irradiance images**: at each pixel's first hit, E = ∫ L V cos θ dω
//!   from every emitter, with the visibility V tested against the scene,
//!   estimated by any strategy and sample sequence of `lambert-estimator`
//!   with a per-pixel standard error (or the closed form, ignoring
//!   occluders, for comparison). With occluders the closed forms stop; this
//!   is where Monte Carlo is needed.
//!
//! Camera rays start at a pinhole, so each pixel reads the radiance along
//! one ray ([`camera`] explains why a pinhole pixel measures radiance, and
//! why a uniform emitter reads the same at any distance). Shapes are
//! `lambert-geometry`'s (watertight triangles, error-bounded hit points and
//! spawned rays, so contacts neither leak nor shadow themselves), plus
//! triangle meshes from OBJ files under a BVH ([`bvh`], [`aggregate`]);
//! emitters are `lambert-light`'s, and area emitters are also shapes that
//! camera rays see and that occlude.
//!
//! ```
//! use lambert_tracer::{builtin, render, Mode, RenderConfig};
//! let scene = builtin::whitted().with_size(32, 32)?;
//! let config = RenderConfig { mode: Mode::Whitted, ..RenderConfig::default() };
//! let out = render(&scene, &config, &|_, _| {})?;
//! assert!(out.image.is_finite());
//! assert!(out.stats.rays.total() > 32 * 32);
//! # Ok::<(), lambert_tracer::TracerError>(())
//! ```

pub mod aabb;
pub mod aggregate;
pub mod builtin;
pub mod bvh;
pub mod camera;
pub mod color;
pub mod compare;
pub mod error;
pub mod image;
pub mod material;
pub mod mesh;
pub mod optics;
pub mod output;
pub mod render;
pub mod scene;
pub mod scene_file;
pub mod shape;
pub mod texture;

pub use aggregate::{Acceleration, Aggregate, Primitive, BVH_THRESHOLD};
pub use camera::Camera;
pub use color::Rgb;
pub use error::TracerError;
pub use image::Image;
pub use material::{Highlight, Material, Surface};
pub use mesh::{Mesh, Transform};
pub use render::{render, render_with_threads, Mode, Pixel, RenderConfig, RenderStats, Rendered};
pub use scene::{MaterialId, Scene, SceneBuilder};
pub use shape::Shape;
pub use texture::Texture;
