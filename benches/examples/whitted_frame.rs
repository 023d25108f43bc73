//! The `whitted` frame (512×512, depth 5, one sample per pixel) rendered
//! `frames` times on `threads` threads, for profilers (`perf record`) and
//! instruction counts (`valgrind --tool=callgrind`), which the criterion
//! bench `tracer_whitted` cannot give alone (its group sets up the other
//! tracer benches too):
//!
//! ```text
//! cargo build --release -p lambert-benches --example whitted_frame
//! target/release/examples/whitted_frame 20 2 [TILE]
//! ```
//!
//! (`TILE`: the tile side, 16 by default) prints the median and fastest frame's milliseconds and the rays per
//! second of the median frame. Timed assertions have no place here: the
//! figures are for comparing two builds in one session.

use std::hint::black_box;
use std::time::Instant;

use lambert_tracer::{builtin, render, Mode, RenderConfig};

fn main() {
    let mut args = std::env::args().skip(1);
    let mut next = |name: &str, default: usize| -> usize {
        args.next().map_or(default, |a| {
            a.parse()
                .unwrap_or_else(|_| panic!("{name}: expected a count, got {a:?}"))
        })
    };
    let frames = next("frames", 20);
    let threads = next("threads", 1).max(1);
    let tile = next("tile", 16).max(1) as u32;
    let scene = builtin::whitted();
    let config = RenderConfig {
        mode: Mode::Whitted,
        max_depth: 5,
        tile,
        ..RenderConfig::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let mut ms = Vec::with_capacity(frames);
    let mut rays = 0;
    for _ in 0..frames {
        let start = Instant::now();
        let r = pool.install(|| black_box(render(&scene, &config, &|_, _| {}).unwrap()));
        ms.push(start.elapsed().as_secs_f64() * 1e3);
        rays = r.stats.rays.total();
        if std::env::var_os("WHITTED_COUNTS").is_some() {
            eprintln!("{:?}", r.stats.rays);
        }
    }
    if ms.is_empty() {
        return;
    }
    ms.sort_by(f64::total_cmp);
    let median = ms[ms.len() / 2];
    println!(
        "{frames} frames, {threads} thread(s): median {median:.2} ms, fastest {:.2} ms, {rays} rays, {:.1} M rays/s",
        ms[0],
        rays as f64 / median * 1e-3
    );
}
