//! A fuzz run: generate cases from a seed, run every call of every case
//! (on `jobs` worker threads, each case on its own), judge each outcome,
//! and tally the verdicts.
//!
//! Case `i` depends only on the seed and `i` (its own PCG stream), so a run
//! of N cases is the same set of calls whatever the thread count, and any
//! case can be regenerated alone (`lambert-fuzz show --seed S --case i`).
//! With `--seconds`, workers stop taking new cases at the deadline: the
//! run covers cases 0 … N−1 for the N it reached.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use serde_json::json;

use crate::calls::{self, Call};
use crate::corpus::KnownOpen;
use crate::generate;
use crate::mutate;
use crate::oracle::{judge, Class, ClosedForm, Context, Failure, Verdict};
use crate::run::{run, Outcome};

/// One generated case: a scene file's text and the calls to make on it.
#[derive(Clone, Debug)]
pub struct Case {
    /// Its index in the run.
    pub index: u64,
    /// The scene file's text.
    pub text: String,
    /// Whether the text was garbled after generation.
    pub garbled: bool,
    /// The calls.
    pub calls: Vec<Call>,
}

/// The PCG stream of case `index` (SplitMix64 of seed and index).
fn case_rng(seed: u64, index: u64) -> rand_pcg::Pcg64Mcg {
    let mut z = seed.wrapping_add(index.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    rand_pcg::Pcg64Mcg::seed_from_u64(z ^ (z >> 31))
}

/// Case `index` of the run with `seed`.
pub fn case(seed: u64, index: u64, render: Option<&Call>) -> Case {
    let mut rng = case_rng(seed, index);
    let file = generate::scene(&mut rng);
    let mut text = file.to_toml();
    let garbled = rng.random_bool(mutate::MUTATED_FRACTION);
    if garbled {
        text = mutate::garble(&mut rng, &text);
    }
    let calls = calls::for_scene(&mut rng, render);
    Case {
        index,
        text,
        garbled,
        calls,
    }
}

/// The verdict on one call of a case.
#[derive(Clone, Debug)]
pub struct CallResult {
    /// The call.
    pub call: Call,
    /// The verdict.
    pub verdict: Verdict,
    /// Wall time, seconds.
    pub seconds: f64,
    /// The known-open class that covers this failure, if any.
    pub known_open: Option<PathBuf>,
    /// The first line of a refusal's message.
    pub message: Option<String>,
    /// An answered estimate that claims to be exact (standard error 0) yet
    /// differs from the closed form by more than 1e-6 relative: not a
    /// failure of this contract (the numbers are finite), but dishonest
    /// uncertainty worth counting.
    pub exact_but_wrong: bool,
    /// An answered estimate with |z| > 10 against the closed form (a wrong
    /// closed form, a biased estimator or a dishonest standard error).
    pub far_from_closed_form: bool,
}

/// What an answered estimate says about its own accuracy, beyond this
/// contract: whether it claims `std_error` 0 with `|rel_error|` above 1e-6
/// (exact but wrong), and whether `|z|` exceeds 10 (the estimate and the
/// closed form disagree far beyond the reported error). Only estimates
/// without a `warning` claim either: one with a warning says that its
/// standard error does not describe its error (few or no hits, a heavy
/// tail), and its interval comes from rare-event bounds instead.
fn accuracy(call: &Call, verdict: &Verdict, stdout: &str) -> (bool, bool) {
    if call.command != calls::Command::Estimate || *verdict != Verdict::Answered {
        return (false, false);
    }
    let Ok(v) = serde_json::from_str::<serde_json::Value>(stdout) else {
        return (false, false);
    };
    let claims = v["warning"].is_null();
    let exact_but_wrong = claims
        && v["std_error"].as_f64() == Some(0.0)
        && v["rel_error"].as_f64().is_some_and(|r| r.abs() > 1e-6);
    let far = claims && v["z"].as_f64().is_some_and(|z| z.abs() > 10.0);
    (exact_but_wrong, far)
}

/// The verdicts on a case's calls.
#[derive(Clone, Debug)]
pub struct CaseResult {
    /// The case.
    pub case: Case,
    /// One result per call, in call order.
    pub calls: Vec<CallResult>,
}

/// Runs every call of `text` (written to `scene_path`), in order, each
/// within `limit`; the estimates are checked against the analytic call
/// when it comes first.
///
/// # Errors
/// When the binary cannot be run or the file cannot be written.
pub fn run_calls(
    binary: &Path,
    text: &str,
    calls: &[Call],
    scene_path: &Path,
    limit: Duration,
) -> std::io::Result<Vec<(Call, Verdict, Outcome)>> {
    std::fs::write(scene_path, text)?;
    let out_path = scene_path.with_extension("out.exr");
    let emitters = text
        .parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("emitters").and_then(|e| e.as_array().map(Vec::len)));
    let scene = scene_path.to_string_lossy().into_owned();
    let out = out_path.to_string_lossy().into_owned();
    let mut closed_form = None;
    let mut results = Vec::with_capacity(calls.len());
    for call in calls {
        let _ = std::fs::remove_file(&out_path);
        let writes_file = call.args.iter().any(|a| a.contains("{out}"));
        let outcome = run(binary, &call.argv(&scene, &out), limit)?;
        let context = Context {
            emitters,
            closed_form,
            out_file: writes_file.then_some(out_path.as_path()),
        };
        let verdict = judge(call, &outcome, &context);
        if call.command == calls::Command::Analytic {
            closed_form = match &verdict {
                Verdict::Answered => serde_json::from_str::<serde_json::Value>(&outcome.stdout)
                    .ok()
                    .and_then(|v| v["irradiance"].as_f64())
                    .map(ClosedForm::Total),
                Verdict::Refused => Some(ClosedForm::Refused),
                Verdict::Failed(_) => None,
            };
        }
        results.push((call.clone(), verdict, outcome));
    }
    let _ = std::fs::remove_file(&out_path);
    Ok(results)
}

/// What to run.
#[derive(Clone, Debug)]
pub struct Settings {
    /// The `lambert` binary.
    pub binary: PathBuf,
    /// The run's seed.
    pub seed: u64,
    /// Stop after this many cases.
    pub cases: Option<u64>,
    /// Stop taking new cases after this long.
    pub seconds: Option<f64>,
    /// Per-call time limit.
    pub limit: Duration,
    /// Worker threads (each runs one child process at a time).
    pub jobs: usize,
    /// The render call, if the binary has one.
    pub render: Option<Call>,
    /// Known-open failure classes.
    pub known_open: Vec<KnownOpen>,
    /// No per-failure progress lines on stderr.
    pub quiet: bool,
}

/// Tallies of a run.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    /// Cases run.
    pub cases: u64,
    /// Of which garbled.
    pub garbled: u64,
    /// Calls made.
    pub calls: u64,
    /// Finite, consistent answers.
    pub answers: u64,
    /// Clear refusals.
    pub refusals: u64,
    /// Failures per class (known-open included).
    pub failures: BTreeMap<Class, u64>,
    /// Failures covered by a known-open class.
    pub known_open: u64,
    /// Refusals per message signature (numbers and paths elided).
    pub refusal_messages: BTreeMap<String, u64>,
    /// Answered estimates with standard error 0 that differ from the
    /// closed form ([`CallResult::exact_but_wrong`]).
    pub exact_but_wrong: u64,
    /// Answered estimates with |z| > 10 ([`CallResult::far_from_closed_form`]).
    pub far_from_closed_form: u64,
    /// The first cases of each observation, for a look.
    pub observed_cases: BTreeMap<&'static str, Vec<u64>>,
    /// Wall time, seconds.
    pub seconds: f64,
}

impl Summary {
    /// Failures of `class`.
    pub fn count(&self, class: Class) -> u64 {
        self.failures.get(&class).copied().unwrap_or(0)
    }

    /// All failures.
    pub fn failed(&self) -> u64 {
        self.failures.values().sum()
    }

    /// Failures not covered by a known-open class.
    pub fn new_failures(&self) -> u64 {
        self.failed() - self.known_open
    }

    /// The one-line summary.
    pub fn line(&self, seed: u64) -> String {
        format!(
            "lambert-fuzz seed {seed}: {} cases ({} garbled), {} calls: {} answers, {} clear errors, {} panics, {} hangs, {} non-finite, {} other failures; {} failures in all, {} known-open, {} new; {:.1} s",
            self.cases,
            self.garbled,
            self.calls,
            self.answers,
            self.refusals,
            self.count(Class::Panic),
            self.count(Class::Hang),
            self.count(Class::NonFinite),
            self.failed()
                - self.count(Class::Panic)
                - self.count(Class::Hang)
                - self.count(Class::NonFinite),
            self.failed(),
            self.known_open,
            self.new_failures(),
            self.seconds
        )
    }
}

/// A run's results: the summary and every case that had a failure.
#[derive(Clone, Debug)]
pub struct Report {
    /// The tallies.
    pub summary: Summary,
    /// Cases with at least one failed call, by index.
    pub failing: Vec<CaseResult>,
}

/// Runs a campaign.
///
/// # Errors
/// When the temporary directory cannot be made or the binary cannot be
/// run.
pub fn campaign(settings: &Settings) -> Result<Report, String> {
    let dir = tempfile::Builder::new()
        .prefix("lambert-fuzz-")
        .tempdir()
        .map_err(|e| format!("temporary directory: {e}"))?;
    let start = Instant::now();
    let deadline = settings.seconds.map(|s| start + Duration::from_secs_f64(s));
    let limit_cases = settings.cases.unwrap_or(u64::MAX);
    let next = AtomicU64::new(0);
    let results: Mutex<Vec<CaseResult>> = Mutex::new(Vec::new());
    let error: Mutex<Option<String>> = Mutex::new(None);
    std::thread::scope(|scope| {
        for worker in 0..settings.jobs.max(1) {
            let (next, results, error, dir) = (&next, &results, &error, dir.path());
            scope.spawn(move || loop {
                if deadline.is_some_and(|d| Instant::now() >= d)
                    || error.lock().map(|e| e.is_some()).unwrap_or(true)
                {
                    break;
                }
                let index = next.fetch_add(1, Ordering::Relaxed);
                if index >= limit_cases {
                    break;
                }
                let case = case(settings.seed, index, settings.render.as_ref());
                let path = dir.join(format!("w{worker}-case-{index}.toml"));
                match run_calls(
                    &settings.binary,
                    &case.text,
                    &case.calls,
                    &path,
                    settings.limit,
                ) {
                    Ok(done) => {
                        let calls = done
                            .into_iter()
                            .map(|(call, verdict, outcome)| {
                                let known_open = match &verdict {
                                    Verdict::Failed(f) => settings
                                        .known_open
                                        .iter()
                                        .find(|k| k.covers(f.class, &call, &case.text))
                                        .map(|k| k.path.clone()),
                                    _ => None,
                                };
                                let message = (verdict == Verdict::Refused).then(|| {
                                    outcome.stderr.lines().next().unwrap_or("").to_owned()
                                });
                                let (exact_but_wrong, far_from_closed_form) =
                                    accuracy(&call, &verdict, &outcome.stdout);
                                CallResult {
                                    exact_but_wrong,
                                    far_from_closed_form,
                                    call,
                                    verdict,
                                    seconds: outcome.seconds,
                                    known_open,
                                    message,
                                }
                            })
                            .collect();
                        let result = CaseResult { case, calls };
                        if !settings.quiet {
                            progress(&result);
                        }
                        if let Ok(mut r) = results.lock() {
                            r.push(result);
                        }
                    }
                    Err(e) => {
                        if let Ok(mut slot) = error.lock() {
                            *slot = Some(format!("{}: {e}", settings.binary.display()));
                        }
                    }
                }
            });
        }
    });
    if let Some(e) = error.into_inner().ok().flatten() {
        return Err(e);
    }
    let mut results = results.into_inner().map_err(|e| e.to_string())?;
    results.sort_by_key(|r| r.case.index);
    let mut summary = Summary {
        seconds: start.elapsed().as_secs_f64(),
        ..Summary::default()
    };
    let mut failing = Vec::new();
    for r in results {
        summary.cases += 1;
        summary.garbled += u64::from(r.case.garbled);
        let mut failed = false;
        for c in &r.calls {
            summary.calls += 1;
            summary.exact_but_wrong += u64::from(c.exact_but_wrong);
            summary.far_from_closed_form += u64::from(c.far_from_closed_form);
            for (name, seen) in [
                ("exact_but_wrong", c.exact_but_wrong),
                ("abs_z_above_10", c.far_from_closed_form),
            ] {
                let cases = summary.observed_cases.entry(name).or_default();
                if seen && cases.len() < 50 && cases.last() != Some(&r.case.index) {
                    cases.push(r.case.index);
                }
            }
            match &c.verdict {
                Verdict::Answered => summary.answers += 1,
                Verdict::Refused => {
                    summary.refusals += 1;
                    let m = elide(c.message.as_deref().unwrap_or(""));
                    *summary.refusal_messages.entry(m).or_default() += 1;
                }
                Verdict::Failed(f) => {
                    *summary.failures.entry(f.class).or_default() += 1;
                    summary.known_open += u64::from(c.known_open.is_some());
                    failed = true;
                }
            }
        }
        if failed {
            failing.push(r);
        }
    }
    Ok(Report { summary, failing })
}

fn progress(result: &CaseResult) {
    for c in &result.calls {
        if let Verdict::Failed(f) = &c.verdict {
            let known = if c.known_open.is_some() {
                " (known-open)"
            } else {
                ""
            };
            eprintln!(
                "case {}: {}: {}{known}: {}",
                result.case.index,
                c.call.label(),
                f.class,
                f.detail
            );
        }
    }
}

/// A failure's signature for grouping: the subcommand, the class, and the
/// detail with numbers and paths elided ([`elide`]).
pub fn signature(call: &Call, failure: &Failure) -> String {
    format!(
        "{} {} | {}",
        call.command.name(),
        failure.class,
        elide(&failure.detail)
    )
}

/// A message with every number replaced by `#`, the values of
/// `--strategy` and `--sequence` by `*`, and the scene file's path
/// (everything up to the last `.toml: `) dropped.
pub fn elide(message: &str) -> String {
    let message = match message.rfind(".toml: ") {
        Some(i) => &message[i + 7..],
        None => message,
    };
    // Option values vary per call: keep the option, drop its value.
    let mut words: Vec<&str> = message.split(' ').collect();
    for i in 1..words.len() {
        if matches!(words[i - 1], "--strategy" | "--sequence") {
            words[i] = "*";
        }
    }
    let message = words.join(" ");
    let mut out = String::new();
    let mut in_number = false;
    for ch in message.chars() {
        let numeric = ch.is_ascii_digit() || (in_number && matches!(ch, '.' | 'e' | '-' | '+'));
        if numeric {
            if !in_number {
                out.push('#');
            }
            in_number = true;
        } else {
            in_number = false;
            out.push(ch);
        }
    }
    out
}

/// The report as JSON: settings, tallies, and each failing call with its
/// scene.
pub fn to_json(settings: &Settings, report: &Report) -> serde_json::Value {
    let s = &report.summary;
    let failures: serde_json::Map<String, serde_json::Value> = Class::ALL
        .iter()
        .map(|c| (c.name().to_owned(), json!(s.count(*c))))
        .collect();
    let mut groups: BTreeMap<String, (u64, u64)> = BTreeMap::new();
    let mut failing = Vec::new();
    for r in &report.failing {
        for c in &r.calls {
            if let Verdict::Failed(f) = &c.verdict {
                let g = groups
                    .entry(signature(&c.call, f))
                    .or_insert((0, r.case.index));
                g.0 += 1;
                failing.push(json!({
                    "case": r.case.index,
                    "garbled": r.case.garbled,
                    "call": c.call.label(),
                    "class": f.class.name(),
                    "detail": f.detail,
                    "seconds": c.seconds,
                    "known_open": c.known_open.as_ref().map(|p| p.display().to_string()),
                    "scene": r.case.text,
                }));
            }
        }
    }
    json!({
        "seed": settings.seed,
        "time_limit_seconds": settings.limit.as_secs_f64(),
        "jobs": settings.jobs,
        "render": settings.render.as_ref().map(Call::label),
        "cases": s.cases,
        "garbled": s.garbled,
        "calls": s.calls,
        "answers": s.answers,
        "clear_errors": s.refusals,
        "failures": failures,
        "failed_calls": s.failed(),
        "known_open": s.known_open,
        "new_failures": s.new_failures(),
        "seconds": s.seconds,
        "clear_error_messages": s.refusal_messages,
        "observations": {
            "exact_but_wrong_estimates": s.exact_but_wrong,
            "estimates_with_abs_z_above_10": s.far_from_closed_form,
            "first_cases": s.observed_cases,
        },
        "signatures": groups.iter().map(|(k, (n, first))| json!({"signature": k, "count": n, "first_case": first})).collect::<Vec<_>>(),
        "failing": failing,
    })
}

/// Writes each failing call's scene into `dir` as a corpus candidate
/// (`case-<i>-<class>.toml`, header included).
///
/// # Errors
/// When the directory or a file cannot be written.
pub fn save_failures(report: &Report, dir: &Path) -> std::io::Result<usize> {
    std::fs::create_dir_all(dir)?;
    let mut written = 0;
    for r in &report.failing {
        let mut seen = Vec::new();
        for c in &r.calls {
            if let Verdict::Failed(f) = &c.verdict {
                if seen.contains(&f.class) {
                    continue;
                }
                seen.push(f.class);
                let calls: Vec<Call> = r
                    .calls
                    .iter()
                    .filter(|x| matches!(&x.verdict, Verdict::Failed(g) if g.class == f.class))
                    .map(|x| x.call.clone())
                    .collect();
                let text = crate::corpus::Entry::format(
                    &format!("{}: {}", f.class, f.detail.replace('\n', " ")),
                    "?",
                    &calls,
                    f.class,
                    &r.case.text,
                );
                let name = format!("case-{}-{}.toml", r.case.index, f.class);
                std::fs::write(dir.join(name), text)?;
                written += 1;
            }
        }
    }
    Ok(written)
}
