//! `lambert-fuzz`: run a fuzz campaign against the `lambert` binary, replay
//! the regression corpus, shrink a failing input, or show one case.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use clap::{Args, Parser, Subcommand};
use lambert_fuzz::calls::{Call, DEFAULT_RENDER_ARGS};
use lambert_fuzz::campaign::{self, Settings};
use lambert_fuzz::corpus::{self, KnownOpen};
use lambert_fuzz::oracle::Class;
use lambert_fuzz::{default_lambert, replay, run, shrink};

/// A structure-aware fuzzer for `lambert`: random scene files through
/// `analytic`, `estimate` (every strategy) and `render`; every call must
/// answer with finite numbers or exit 2 naming the field, within a time
/// limit.
#[derive(Parser, Debug)]
#[command(
    name = "lambert-fuzz",
    version,
    about,
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    run: RunOptions,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run a campaign (the default).
    Run(RunOptions),
    /// Replay corpus files or directories; fails if a case fails (unless
    /// --report-only, for the known-open cases).
    Replay(ReplayOptions),
    /// Shrink a failing scene while one call keeps failing the same way.
    Shrink(ShrinkOptions),
    /// Print case N of a seed's run: its scene file and its calls.
    Show(ShowOptions),
}

#[derive(Args, Debug, Clone)]
struct Binary {
    /// The lambert binary (default: $LAMBERT_BIN, or `lambert` beside this
    /// executable).
    #[arg(long)]
    lambert: Option<PathBuf>,
    /// Per-call time limit, seconds; a call still running is killed and
    /// counted as a hang.
    #[arg(long, default_value_t = 10.0)]
    time_limit: f64,
}

impl Binary {
    fn path(&self) -> Result<PathBuf, String> {
        let path = self.lambert.clone().or_else(default_lambert).ok_or(
            "--lambert: no lambert binary found beside lambert-fuzz (build it: cargo build --release -p lambert-cli)",
        )?;
        if path.is_file() {
            Ok(path)
        } else {
            Err(format!("--lambert: {} is not a file", path.display()))
        }
    }

    fn limit(&self) -> Result<Duration, String> {
        Duration::try_from_secs_f64(self.time_limit)
            .ok()
            .filter(|d| !d.is_zero())
            .ok_or_else(|| {
                format!(
                    "--time-limit: must be a positive number of seconds, got {}",
                    self.time_limit
                )
            })
    }
}

#[derive(Args, Debug, Clone)]
struct RunOptions {
    #[command(flatten)]
    binary: Binary,
    /// Seed of the run (case i depends only on the seed and i).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Number of cases (default 300 unless --seconds is given).
    #[arg(long)]
    cases: Option<u64>,
    /// Stop taking new cases after this many seconds.
    #[arg(long)]
    seconds: Option<f64>,
    /// Worker threads, each running one lambert process at a time.
    #[arg(long, default_value_t = 2)]
    jobs: usize,
    /// Render calls: `auto` (if `lambert render --help` succeeds), `on` or
    /// `off`.
    #[arg(long, default_value = "auto")]
    render: String,
    /// The render call's arguments; {scene} is the scene file, {out} the
    /// image it may write.
    #[arg(long, default_value = DEFAULT_RENDER_ARGS)]
    render_args: String,
    /// Directories of known-open corpus cases: failures they cover are
    /// counted as known-open, not as new.
    #[arg(long)]
    open: Vec<PathBuf>,
    /// Write the JSON report here.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write each failing case here as a corpus file.
    #[arg(long)]
    save_failures: Option<PathBuf>,
    /// No per-failure lines on stderr.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args, Debug)]
struct ReplayOptions {
    #[command(flatten)]
    binary: Binary,
    /// Corpus files or directories.
    #[arg(required = true)]
    paths: Vec<PathBuf>,
    /// Report on each case without failing (for the known-open cases).
    #[arg(long)]
    report_only: bool,
}

#[derive(Args, Debug)]
struct ShrinkOptions {
    #[command(flatten)]
    binary: Binary,
    /// The failing scene (a corpus file or any scene file).
    file: PathBuf,
    /// The call, e.g. "estimate {scene} --json --strategy light" (default:
    /// the file's first `# call:` line).
    #[arg(long)]
    call: Option<String>,
    /// The failure class to keep (default: the file's `# failed:` line).
    #[arg(long)]
    class: Option<String>,
    /// At most this many trial runs.
    #[arg(long, default_value_t = 2000)]
    max_trials: usize,
}

#[derive(Args, Debug)]
struct ShowOptions {
    /// The run's seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The case index.
    #[arg(long)]
    case: u64,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        None => run_campaign(&cli.run),
        Some(Command::Run(o)) => run_campaign(&o),
        Some(Command::Replay(o)) => run_replay(&o),
        Some(Command::Shrink(o)) => run_shrink(&o),
        Some(Command::Show(o)) => {
            let case = campaign::case(o.seed, o.case, None);
            println!("{}", case.text);
            for c in &case.calls {
                println!("# {}", c.label());
            }
            Ok(true)
        }
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

/// The render call if the binary has a `render` subcommand (or `on`).
fn render_call(options: &RunOptions, binary: &Path) -> Result<Option<Call>, String> {
    let call = || {
        Call::from_template(&options.render_args).ok_or_else(|| {
            format!(
                "--render-args: {:?} is not a lambert call",
                options.render_args
            )
        })
    };
    match options.render.as_str() {
        "off" => Ok(None),
        "on" => call().map(Some),
        "auto" => {
            let probe = run::run(
                binary,
                &["render".into(), "--help".into()],
                Duration::from_secs(10),
            )
            .map_err(|e| format!("{}: {e}", binary.display()))?;
            if probe.exit == run::Exit::Code(0) {
                call().map(Some)
            } else {
                Ok(None)
            }
        }
        other => Err(format!("--render: expected auto, on or off, got {other:?}")),
    }
}

fn run_campaign(options: &RunOptions) -> Result<bool, String> {
    let binary = options.binary.path()?;
    let mut known_open: Vec<KnownOpen> = Vec::new();
    for dir in &options.open {
        for entry in corpus::load_dir(dir)? {
            known_open.extend(entry.known_open());
        }
    }
    if options.jobs == 0 {
        return Err("--jobs: must be at least 1".into());
    }
    if let Some(s) = options.seconds {
        if !(s > 0.0 && s.is_finite()) {
            return Err(format!("--seconds: must be a positive number, got {s}"));
        }
    }
    let settings = Settings {
        render: render_call(options, &binary)?,
        binary,
        seed: options.seed,
        cases: options.cases.or(if options.seconds.is_some() {
            None
        } else {
            Some(300)
        }),
        seconds: options.seconds,
        limit: options.binary.limit()?,
        jobs: options.jobs,
        known_open,
        quiet: options.quiet,
    };
    let report = campaign::campaign(&settings)?;
    println!("{}", report.summary.line(settings.seed));
    if let Some(path) = &options.json {
        let text = serde_json::to_string_pretty(&campaign::to_json(&settings, &report))
            .map_err(|e| e.to_string())?;
        std::fs::write(path, text).map_err(|e| format!("--json: {}: {e}", path.display()))?;
    }
    if let Some(dir) = &options.save_failures {
        let n = campaign::save_failures(&report, dir)
            .map_err(|e| format!("--save-failures: {}: {e}", dir.display()))?;
        eprintln!("{n} failing case file(s) written to {}", dir.display());
    }
    Ok(report.summary.new_failures() == 0)
}

fn run_replay(options: &ReplayOptions) -> Result<bool, String> {
    let binary = options.binary.path()?;
    let limit = options.binary.limit()?;
    let mut entries = Vec::new();
    for p in &options.paths {
        if p.is_dir() {
            entries.extend(corpus::load_dir(p)?);
        } else {
            let text = std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))?;
            entries.push(corpus::Entry::parse(p, &text)?);
        }
    }
    let mut failed = 0;
    for e in &entries {
        let r = replay::replay(&binary, e, !options.report_only, limit)?;
        if r.failures.is_empty() {
            println!("ok      {} ({} calls)", e.path.display(), r.calls);
        } else {
            failed += 1;
            println!("FAILED  {} ({})", e.path.display(), e.symptom);
            for (call, f) in &r.failures {
                println!("        {}: {}: {}", call.label(), f.class, f.detail);
            }
        }
    }
    println!("{} passed, {} failed", entries.len() - failed, failed);
    Ok(options.report_only || failed == 0)
}

fn run_shrink(options: &ShrinkOptions) -> Result<bool, String> {
    let binary = options.binary.path()?;
    let text = std::fs::read_to_string(&options.file)
        .map_err(|e| format!("{}: {e}", options.file.display()))?;
    let entry = corpus::Entry::parse(&options.file, &text).ok();
    let call = match &options.call {
        Some(c) => {
            Call::from_template(c).ok_or_else(|| format!("--call: {c:?} is not a lambert call"))?
        }
        None => entry
            .as_ref()
            .and_then(|e| e.calls.first().cloned())
            .ok_or("--call: required (the file has no `# call:` line)")?,
    };
    let class = match &options.class {
        Some(c) => {
            Class::from_name(c).ok_or_else(|| format!("--class: unknown failure class {c:?}"))?
        }
        None => entry
            .as_ref()
            .and_then(|e| e.failed)
            .ok_or("--class: required (the file has no `# failed:` line)")?,
    };
    // The scene without the header comments.
    let scene: String = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    let (small, trials) = shrink::shrink(
        &binary,
        &scene,
        &call,
        class,
        options.binary.limit()?,
        options.max_trials,
    )?;
    eprintln!(
        "{} -> {} bytes in {trials} trials",
        scene.len(),
        small.len()
    );
    print!("{small}");
    Ok(true)
}
