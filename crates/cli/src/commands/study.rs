//! `lambert study`: a convergence study (the built-in one by default) into
//! `notebooks-data/runs/<name>/` (git-ignored; the committed reference of
//! the built-in study in `notebooks-data/builtin/` is only written with
//! `--out notebooks-data/builtin`): `results.csv`, `summary.md` and plots.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lambert_study::{plan, plot, run_study, summary_markdown, RunOptions, Shard, StudyConfig};

/// Options of `lambert study`.
#[derive(Args, Debug, Clone, Default)]
pub struct StudyOptions {
    /// A study file (TOML); the built-in study when absent.
    pub study: Option<PathBuf>,
    /// The quick built-in study (N up to 2^14; what CI runs).
    #[arg(long, conflicts_with = "study")]
    pub quick: bool,
    /// Output folder (default: `notebooks-data/runs/<study name>`, which git
    /// ignores; the committed reference output is `notebooks-data/builtin`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Run only slice K of N (rows with index % N == K), e.g. 0/4; combine
    /// the slices with `lambert merge`.
    #[arg(long)]
    pub shard: Option<Shard>,
    /// Keep the finished rows of an existing results.csv and run the rest.
    #[arg(long)]
    pub resume: bool,
    /// No progress bar and no report on stdout.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs the study.
pub fn run(options: &StudyOptions) -> Result<(), String> {
    let config = match (&options.study, options.quick) {
        (Some(path), _) => StudyConfig::load(path).map_err(|e| e.to_string())?,
        (None, true) => StudyConfig::quick(),
        (None, false) => StudyConfig::builtin(),
    };
    let shard = options.shard.unwrap_or(Shard::ALL);
    let out = options
        .out
        .clone()
        .unwrap_or_else(|| config.default_out_dir());
    let rows_total = plan(&config).len();
    if !options.quiet {
        println!(
            "lambert study `{}`: {} scenes × {} strategies × {} sequences × N = 2^{}…2^{} × {} replicates = {} rows{} → {}",
            config.name,
            config.scenes.len(),
            config.strategies.len(),
            config.sequences.len(),
            config.n_min_log2,
            config.n_max_log2,
            config.replicates,
            rows_total,
            if shard.count > 1 { format!(" (shard {shard})") } else { String::new() },
            out.display()
        );
    }
    let bar = if options.quiet || !std::io::stdout().is_terminal() {
        ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
    } else {
        let b = ProgressBar::new(0);
        b.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} rows  {elapsed} (eta {eta})")
                .map_err(|e| e.to_string())?,
        );
        b
    };
    let start = Instant::now();
    let rows = run_study(
        &config,
        &out,
        RunOptions {
            shard,
            resume: options.resume,
        },
        &mut |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        },
    )?;
    bar.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    if shard.count > 1 {
        if !options.quiet {
            println!(
                "shard {shard}: {} rows in {seconds:.1} s → {}; combine the shards with `lambert merge DIR… --out DIR`",
                rows.len(),
                out.join("results.csv").display()
            );
        }
        return Ok(());
    }
    let summary = summary_markdown(&config.name, &rows);
    write_outputs(&out, &summary, &rows)?;
    if !options.quiet {
        println!("{} rows in {seconds:.1} s → {}", rows.len(), out.display());
        println!("\n{summary}");
    }
    Ok(())
}

/// Writes summary.md and the plots beside results.csv.
pub fn write_outputs(
    out: &Path,
    summary: &str,
    rows: &[lambert_study::results::ResultRow],
) -> Result<(), String> {
    let path = out.join("summary.md");
    std::fs::write(&path, summary).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    plot::write_plots(out, rows)
}
