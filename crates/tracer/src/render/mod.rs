//! Rendering an image: the three modes, tiles on rayon's threads, and what
//! a render reports.
//!
//! Every pixel is computed from its own index and the seed alone (its
//! sample streams are seeded by [`stream_seed`]`(seed, pixel)`), and the
//! summary statistics are summed in pixel order after the parallel part,
//! so an image is the same, to the bit, whatever the number of threads and
//! the order in which tiles finish.

mod context;
mod irradiance;
mod raycast;
mod wavefront;
mod whitted;

pub use context::RayCounts;

use std::fmt;
use std::str::FromStr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use lambert_estimator::estimation::SequenceKind;
#[allow(unused_imports)] // linked from the docs
use lambert_estimator::point::stream_seed;
use lambert_estimator::point::PointConfig;
use lambert_estimator::strategy::Strategy;
use lambert_light::emitter::Emitter;
use lambert_sampling::isa::Isa;
use rayon::prelude::*;

use crate::color::Rgb;
use crate::error::TracerError;
use crate::image::Image;
use crate::scene::Scene;
use context::Context;

/// What to compute at each pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Ray casting (Appel 1968): nearest hit, direct light with shadow
    /// rays, max(0, n·l).
    Raycast,
    /// Recursive ray tracing (Whitted 1980): reflection and refraction to
    /// a depth limit, Fresnel, total internal reflection, shadow rays.
    Whitted,
    /// E = ∫ L V cos θ dω at each pixel's first hit, with its standard
    /// error.
    Irradiance,
}

impl Mode {
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Raycast => "raycast",
            Mode::Whitted => "whitted",
            Mode::Irradiance => "irradiance",
        }
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "raycast" => Ok(Mode::Raycast),
            "whitted" => Ok(Mode::Whitted),
            "irradiance" => Ok(Mode::Irradiance),
            other => Err(format!(
                "unknown mode {other:?} (expected raycast, whitted or irradiance)"
            )),
        }
    }
}

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderConfig {
    /// The mode.
    pub mode: Mode,
    /// The recursion limit of the whitted mode: reflected and refracted
    /// rays are followed to this many bounces.
    pub max_depth: u32,
    /// How irradiance is estimated (irradiance mode; area emitters in the
    /// other modes): strategy, sequence, samples per estimate, seed.
    pub estimate: PointConfig,
    /// Irradiance mode: the closed form, ignoring occluders, instead of
    /// the estimate.
    pub analytic: bool,
    /// Tile side, pixels (the unit of parallel work and of progress).
    pub tile: u32,
}

impl Default for RenderConfig {
    /// Whitted mode, depth 5; 64 samples, automatic strategy, independent
    /// samples, seed 0; 16-pixel tiles.
    fn default() -> Self {
        RenderConfig {
            mode: Mode::Whitted,
            max_depth: 5,
            estimate: PointConfig {
                strategy: Strategy::Auto,
                sequence: SequenceKind::Independent,
                samples: 64,
                seed: 0,
            },
            analytic: false,
            tile: 16,
        }
    }
}

/// One pixel's values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Pixel {
    /// The radiance (linear RGB).
    pub rgb: Rgb,
    /// The irradiance at the first hit, W/m².
    pub irradiance: f64,
    /// Its standard error.
    pub std_error: f64,
}

impl Pixel {
    /// A pixel that sees `rgb` and has no irradiance.
    pub fn background(rgb: Rgb) -> Self {
        Pixel {
            rgb,
            irradiance: 0.0,
            std_error: 0.0,
        }
    }
}

/// What a render measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderStats {
    /// Wall time of the render (not of writing files), seconds.
    pub seconds: f64,
    /// Rays traced.
    pub rays: RayCounts,
    /// The mean over pixels with E > 0 of the relative standard error
    /// σ_E / E (0 when no pixel has one).
    pub mean_relative_std_error: f64,
}

impl RenderStats {
    /// Rays per second.
    pub fn rays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.seconds
    }
}

/// An image and what its render measured.
#[derive(Clone, Debug)]
pub struct Rendered {
    /// The image.
    pub image: Image,
    /// The statistics.
    pub stats: RenderStats,
}

/// Renders `scene` with `config` on the current rayon pool, calling
/// `progress(done, total)` (tiles) as tiles finish.
///
/// # Errors
/// A configuration the estimator rejects (`samples`), a closed form that
/// does not exist (`--analytic`), or a non-finite estimate.
pub fn render(
    scene: &Scene,
    config: &RenderConfig,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Rendered, TracerError> {
    let start = Instant::now();
    let uses_estimates =
        config.mode == Mode::Irradiance && !config.analytic || scene.has_area_emitters();
    if uses_estimates {
        config.estimate.validate()?;
    }
    if config.tile == 0 {
        return Err(TracerError::new("tile", "must be at least 1 pixel, got 0"));
    }
    let camera = scene.camera();
    let (w, h) = (camera.width(), camera.height());
    let t = config.tile;
    let done = AtomicU64::new(0);
    let area_emitters: Vec<Emitter> = scene
        .emitters()
        .iter()
        .filter(|e| !e.is_delta())
        .cloned()
        .collect();
    let by_generation = config.mode == Mode::Whitted && wavefront::applies(scene);
    let isa = Isa::selected();
    // Each tile writes its pixels straight into its part of the image
    // (a per-tile vector of pixels, copied into the image afterwards,
    // cost an allocation per tile and fresh memory every frame).
    let mut image = Image::new(w, h, config.mode == Mode::Irradiance);
    let tiles = image.tiles_mut(t);
    let total = tiles.len() as u64;
    let results: Vec<Result<RayCounts, TracerError>> = tiles
        .into_par_iter()
        .map_init(
            || (wavefront::Scratch::default(), Vec::new()),
            |(scratch, pixels), mut tile| {
                let ((x0, x1), (y0, y1)) = (tile.x, tile.y);
                if by_generation {
                    let counts =
                        wavefront::tile(scene, camera, config, isa, tile.x, tile.y, scratch);
                    tile.set_all(scratch.pixels());
                    progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                    return Ok(counts);
                }
                let mut cx = Context::new(scene, config, &area_emitters);
                pixels.clear();
                for y in y0..y1 {
                    for x in x0..x1 {
                        cx.start_pixel(y as u64 * w as u64 + x as u64);
                        let ray = camera.pixel_ray(x, y);
                        let p = match config.mode {
                            Mode::Raycast => raycast::pixel(&cx, &ray),
                            Mode::Whitted => whitted::pixel(&cx, &ray),
                            Mode::Irradiance => irradiance::pixel(&cx, &ray),
                        }
                        .map_err(|e| e.within(&format!("pixel ({x}, {y})")))?;
                        pixels.push(p);
                    }
                }
                tile.set_all(pixels);
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                Ok(cx.counts())
            },
        )
        .collect();
    // The first error in tile order, or every tile's ray counts.
    let rays = results
        .into_iter()
        .try_fold(RayCounts::default(), |sum, counts| {
            counts.map(|c| sum.plus(c))
        })?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(Rendered {
        stats: RenderStats {
            seconds,
            rays,
            mean_relative_std_error: image.mean_relative_std_error(),
        },
        image,
    })
}

/// [`render`] on a pool of `threads` threads (the image does not depend on
/// the number).
pub fn render_with_threads(
    scene: &Scene,
    config: &RenderConfig,
    threads: usize,
    progress: &(dyn Fn(u64, u64) + Sync),
) -> Result<Rendered, TracerError> {
    if threads == 0 {
        return Err(TracerError::new("--threads", "must be at least 1, got 0"));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| TracerError::new("--threads", e.to_string()))?;
    pool.install(|| render(scene, config, progress))
}
