//! Renders a built-in scene a number of times, for profilers (callgrind,
//! perf) that want a process doing nothing else:
//!
//! ```text
//! cargo run --release -p lambert-tracer --example render_frames -- \
//!     [SCENE] [MODE] [SIZE] [THREADS] [FRAMES] [SPP]
//! ```
//!
//! Defaults: `whitted whitted 512 1 1 64` (SPP: samples per irradiance
//! estimate, for scenes with area emitters and the irradiance mode). Prints
//! the rays traced and the milliseconds of each frame.

use lambert_tracer::builtin::builtin;
use lambert_tracer::{render_with_threads, Mode, RenderConfig};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or(default.to_string());
    let name = arg(0, "whitted");
    let mode: Mode = arg(1, "whitted").parse()?;
    let size: u32 = arg(2, "512").parse()?;
    let threads: usize = arg(3, "1").parse()?;
    let frames: u32 = arg(4, "1").parse()?;
    let spp: u64 = arg(5, "64").parse()?;
    let scene = builtin(&name)
        .ok_or_else(|| format!("no built-in scene {name:?}"))?
        .with_size(size, size)?;
    let mut config = RenderConfig {
        mode,
        ..RenderConfig::default()
    };
    config.estimate.samples = spp;
    for _ in 0..frames {
        let out = render_with_threads(&scene, &config, threads, &|_, _| {})?;
        println!(
            "{} rays, {:.2} ms",
            out.stats.rays.total(),
            out.stats.seconds * 1e3
        );
    }
    Ok(())
}
