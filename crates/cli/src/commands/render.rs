//! `lambert render SCENE|whitted|cornell`: ray casting, Whitted ray
//! tracing or an irradiance image, written as linear OpenEXR with a PNG
//! preview beside it.

use std::path::PathBuf;

mod compare;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use lambert_estimator::point::PointConfig;
use lambert_tracer::output::write_outputs;
use lambert_tracer::{builtin, render_with_threads, scene_file, Mode, RenderConfig};
use serde_json::json;

/// Options of `lambert render`.
#[derive(Args, Debug, Clone)]
#[command(after_long_help = AFTER_HELP)]
pub struct RenderOptions {
    /// A scene file (TOML), or a built-in scene: whitted | cornell.
    pub scene: String,
    /// raycast (nearest hit, direct light, shadow rays) | whitted
    /// (recursive reflection and refraction) | irradiance (E = ∫ L V cos θ dω
    /// at each pixel's first hit, with its standard error).
    #[arg(long, default_value = "whitted")]
    pub mode: String,
    /// Image width in pixels (default: the scene's camera; 512 for the
    /// built-ins).
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (default: the scene's camera).
    #[arg(long)]
    pub height: Option<u32>,
    /// The OpenEXR file to write; the PNG preview goes beside it
    /// (FILE.png).
    #[arg(long)]
    pub out: PathBuf,
    /// Print a one-line JSON summary (seconds, rays, rays_per_second,
    /// mean_relative_std_error, …) instead of text.
    #[arg(long)]
    pub json: bool,
    /// Samples per irradiance estimate (irradiance mode; area emitters in
    /// the other modes).
    #[arg(long, default_value_t = 64)]
    pub spp: u64,
    /// auto | uniform-hemisphere | cosine-hemisphere | light | area | mis |
    /// mis-balance | projected | control-variate.
    #[arg(long, default_value = "auto")]
    pub strategy: String,
    /// independent | stratified | sobol (the last two need --spp ≥ 32).
    #[arg(long, default_value = "independent")]
    pub sequence: String,
    /// Seed (the image is the same for a seed whatever --threads).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Irradiance mode: the closed form, ignoring occluders, instead of
    /// the estimate.
    #[arg(long)]
    pub analytic: bool,
    /// Recursion depth of the whitted mode.
    #[arg(long, default_value_t = 5)]
    pub depth: u32,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Irradiance mode: compare these strategies (comma-separated, the
    /// first is the baseline of the ratios) against a reference image,
    /// per-pixel RMSE; writes `FILE.<strategy>.exr` for each and
    /// `FILE.reference.exr` (see the notes below).
    #[arg(long, value_delimiter = ',')]
    pub compare: Option<Vec<String>>,
    /// With --compare: each strategy renders with the samples per pixel
    /// that fit this many seconds (calibrated by two pilot renders); without
    /// it, every strategy uses --spp.
    #[arg(long)]
    pub seconds: Option<f64>,
    /// With --compare: the reference's samples per pixel.
    #[arg(long, default_value_t = 1024)]
    pub reference_spp: u64,
    /// With --compare: the reference's strategy.
    #[arg(long, default_value = "control-variate")]
    pub reference_strategy: String,
}

const AFTER_HELP: &str = "\
Output: FILE.exr, linear f32 OpenEXR with channels R, G, B (radiance, W/m²/sr), irradiance.Y
(W/m² at each pixel's first hit) and, in irradiance mode, std_error.Y; FILE.png, a tone-mapped
sRGB preview. Both are written to temporary files and renamed into place, so a failed run
leaves no partial image. Bad input (an unknown field, a NaN, a camera inside a sphere, a
missing or non-manifold mesh, a zero-size image) exits with code 2 and a message naming the
field.

Equal-time comparison (--compare A,B,…, irradiance mode): a reference image is rendered with
--reference-strategy at --reference-spp samples per pixel (another seed, so its error is
independent); then each strategy renders with the samples per pixel that fit --seconds (two
pilot renders measure its time per sample), or with --spp when --seconds is not given. The
table (or --json) gives per strategy its spp, measured seconds, RMSE over the pixels against
the reference, the RMSE with the reference's own RMS standard error removed in quadrature,
the ratio baseline RMSE / strategy RMSE (> 1: the strategy has the smaller error), and the
same ratio of RMSE·√seconds, which holds at exactly equal time (the pilots' fit of spp to the
budget is loose on a busy machine; its square is the efficiency ratio). Images:
FILE.reference.exr and FILE.<strategy>.exr.

Examples:
  lambert render whitted --out whitted.exr
  lambert render cornell --mode irradiance --compare light,control-variate --seconds 5 \
      --width 128 --height 128 --out cmp.exr
  lambert render cornell --mode irradiance --spp 64 --strategy light --out cornell.exr --json
  lambert render scene.toml --mode raycast --width 320 --height 240 --out scene.exr";

/// Runs the command.
pub fn run(options: &RenderOptions) -> Result<(), String> {
    let mode: Mode = options.mode.parse().map_err(|e| format!("--mode: {e}"))?;
    if options.compare.is_none() && options.seconds.is_some() {
        return Err("--seconds: only with --compare (the time budget of each strategy)".into());
    }
    if options.compare.is_some() && mode != Mode::Irradiance {
        return Err(format!(
            "--compare: compares irradiance strategies, so it needs --mode irradiance, got {mode}"
        ));
    }
    if options.compare.is_some() && options.analytic {
        return Err("--analytic: not with --compare (the reference is an estimate)".into());
    }
    let (strategy, sequence) =
        crate::parse::strategy_and_sequence(&options.strategy, &options.sequence)?;
    if options.analytic && mode != Mode::Irradiance {
        return Err("--analytic: only the irradiance mode has a closed form".into());
    }
    let threads = match options.threads {
        Some(t) => t,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    let scene = match builtin::builtin(&options.scene) {
        Some(scene) => scene,
        None => {
            let path = PathBuf::from(&options.scene);
            if !path.exists() {
                return Err(format!(
                    "SCENE: {:?} is neither a built-in scene ({}) nor a file",
                    options.scene,
                    builtin::BUILTIN_SCENES.join(", ")
                ));
            }
            scene_file::load(&path).map_err(|e| format!("{}: {e}", path.display()))?
        }
    };
    let camera = scene.camera();
    let (width, height) = (
        options.width.unwrap_or(camera.width()),
        options.height.unwrap_or(camera.height()),
    );
    let scene = scene
        .with_size(width, height)
        .map_err(|e| format!("--{e}"))?;
    let config = RenderConfig {
        mode,
        max_depth: options.depth,
        estimate: PointConfig {
            strategy,
            sequence,
            samples: options.spp,
            seed: options.seed,
        },
        analytic: options.analytic,
        ..RenderConfig::default()
    };
    if let Some(names) = &options.compare {
        return compare::run(options, names, &scene, &config, threads);
    }
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} tiles, {eta}")
            .map_err(|e| e.to_string())?,
    );
    bar.set_message(format!("render {} ({mode})", options.scene));
    let progress = |done: u64, total: u64| {
        bar.set_length(total);
        bar.set_position(done);
    };
    let rendered = render_with_threads(&scene, &config, threads, &progress).map_err(|e| {
        let message = e.to_string();
        // Estimator fields are command-line options here.
        if message.starts_with("samples:") || message.contains(".samples:") {
            format!("--spp: {}", e.problem)
        } else {
            message
        }
    })?;
    bar.finish_and_clear();
    let (exr, png) = write_outputs(&rendered.image, &options.out).map_err(|e| e.to_string())?;
    let s = &rendered.stats;
    if options.json {
        let value = json!({
            "scene": options.scene,
            "mode": mode.name(),
            "width": width,
            "height": height,
            "seconds": s.seconds,
            "rays": s.rays.total(),
            "camera_rays": s.rays.camera,
            "secondary_rays": s.rays.secondary,
            "shadow_rays": s.rays.shadow,
            "rays_per_second": s.rays_per_second(),
            "mean_relative_std_error": (mode == Mode::Irradiance && !options.analytic)
                .then_some(s.mean_relative_std_error),
            "threads": threads,
            "exr": exr.display().to_string(),
            "png": png.display().to_string(),
        });
        println!("{value}");
    } else {
        println!(
            "{} ({mode}, {width}×{height}): {:.3} s, {} rays ({:.3e} rays/s) on {threads} thread(s)",
            options.scene,
            s.seconds,
            s.rays.total(),
            s.rays_per_second()
        );
        if mode == Mode::Irradiance && !options.analytic {
            println!(
                "mean relative standard error {:.3e} ({} samples per pixel, {strategy} × {sequence})",
                s.mean_relative_std_error, options.spp
            );
        }
        println!("wrote {} and {}", exr.display(), png.display());
    }
    Ok(())
}
