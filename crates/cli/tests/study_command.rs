//! `lambert study` and `lambert merge`: interrupt safety and `--resume`,
//! shards merged into exactly the single run, bad input.
//!
//! Runs compare the deterministic columns of results.csv (every column but
//! the timing columns `ns_per_sample` and `efficiency`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use lambert_study::read_results;

fn lambert(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lambert"))
        .args(args)
        .output()
        .expect("the lambert binary runs")
}

/// A fresh folder under the temp directory.
fn temp_dir(test: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "lambert-study-command-{test}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const STUDY: &str = r#"
name = "t"
scenes = ["builtin:uniform-sky", "builtin:directional-and-sky", "builtin:sphere-overhead"]
strategies = ["uniform-hemisphere", "light", "mis"]
n_min_log2 = 5
n_max_log2 = N_MAX
replicates = 4
seed = 5
"#;

fn study_file(dir: &Path, n_max: u32) -> String {
    let path = dir.join("study.toml");
    std::fs::write(&path, STUDY.replace("N_MAX", &n_max.to_string())).unwrap();
    path.display().to_string()
}

/// The deterministic part of every row of `dir/results.csv`.
fn deterministic_rows(dir: &Path) -> Vec<String> {
    let (rows, _) = read_results(&dir.join("results.csv")).expect("results parse");
    rows.iter().map(|r| r.deterministic_part()).collect()
}

fn run_ok(args: &[&str]) {
    let out = lambert(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn killed_study_resumes_to_the_same_results() {
    let dir = temp_dir("resume");
    let study = study_file(&dir, 17);
    let full = dir.join("full");
    let cut = dir.join("cut");
    run_ok(&["study", &study, "--out", full.to_str().unwrap(), "--quiet"]);
    let expected = deterministic_rows(&full);
    assert_eq!(expected.len(), 3 * 3 * 3 * 13);

    // Start the same study and kill it once some rows are written.
    let mut child = Command::new(env!("CARGO_BIN_EXE_lambert"))
        .args(["study", &study, "--out", cut.to_str().unwrap(), "--quiet"])
        .spawn()
        .unwrap();
    let csv = cut.join("results.csv");
    let start = Instant::now();
    loop {
        let lines = std::fs::read(&csv)
            .map(|b| b.iter().filter(|&&c| c == b'\n').count())
            .unwrap_or(0);
        if lines > 30 || start.elapsed() > Duration::from_secs(60) {
            break;
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();

    // Only whole rows, all of them rows of the full run, in order.
    let partial = deterministic_rows(&cut);
    assert!(!partial.is_empty());
    assert!(
        partial.len() < expected.len(),
        "the study finished before it was killed; make it longer"
    );
    assert_eq!(partial[..], expected[..partial.len()]);
    // A torn last line (as a kill during a write leaves) is dropped too.
    let mut bytes = std::fs::read(&csv).unwrap();
    bytes.extend_from_slice(b"999,uniform-sky,light,sob");
    std::fs::write(&csv, &bytes).unwrap();
    assert_eq!(deterministic_rows(&cut), partial);

    run_ok(&[
        "study",
        &study,
        "--out",
        cut.to_str().unwrap(),
        "--resume",
        "--quiet",
    ]);
    assert_eq!(deterministic_rows(&cut), expected);
    assert!(cut.join("summary.md").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn four_merged_shards_equal_the_single_run() {
    let dir = temp_dir("merge");
    let study = study_file(&dir, 10);
    let single = dir.join("single");
    run_ok(&[
        "study",
        &study,
        "--out",
        single.to_str().unwrap(),
        "--quiet",
    ]);
    let mut shard_dirs = Vec::new();
    for k in 0..4 {
        let d = dir.join(format!("shard{k}"));
        run_ok(&[
            "study",
            &study,
            "--shard",
            &format!("{k}/4"),
            "--out",
            d.to_str().unwrap(),
            "--quiet",
        ]);
        shard_dirs.push(d.display().to_string());
    }
    let merged = dir.join("merged");
    let mut args = vec!["merge"];
    args.extend(shard_dirs.iter().map(String::as_str));
    args.extend(["--out", merged.to_str().unwrap(), "--quiet"]);
    run_ok(&args);
    assert_eq!(deterministic_rows(&merged), deterministic_rows(&single));
    let summary = std::fs::read_to_string(merged.join("summary.md")).unwrap();
    assert!(summary.contains("## uniform-sky"));
    // Resuming a complete shard runs nothing and keeps its bytes.
    let before = std::fs::read(dir.join("shard1/results.csv")).unwrap();
    run_ok(&[
        "study",
        &study,
        "--shard",
        "1/4",
        "--out",
        &shard_dirs[1],
        "--resume",
        "--quiet",
    ]);
    assert_eq!(
        std::fs::read(dir.join("shard1/results.csv")).unwrap(),
        before
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_input_exits_2_naming_the_field() {
    let dir = temp_dir("bad");
    let path = dir.join("bad.toml");
    std::fs::write(&path, "scenes = [\"builtin:uniform-sky\"]\nreplicas = 3\n").unwrap();
    let out = lambert(&[
        "study",
        path.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("replicas"));
    let out = lambert(&["study", "--quick", "--shard", "4/4"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("shard"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `git` run in the workspace root with `args`; `None` when git or the
/// checkout is not there (a crate built from a source archive).
fn git(args: &[&str]) -> Option<Output> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = Command::new("git")
        .arg("-C")
        .arg(&root)
        .args(args)
        .output()
        .ok()?;
    let inside = Command::new("git")
        .arg("-C")
        .arg(&root)
        .args(["rev-parse", "--is-inside-work-tree"])
        .output()
        .ok()?;
    (inside.status.success()).then_some(out)
}

/// A newcomer's first command, `cargo run --release` in the repository's
/// root, runs the built-in study into its default folder: that folder must
/// hold no tracked file and be ignored by git, so the run leaves
/// `git status` clean (the committed reference output lives in
/// `notebooks-data/builtin/`, which only `--out notebooks-data/builtin`
/// writes). And the CLI's default is that folder: a small study run without
/// `--out` in a scratch directory lands in `notebooks-data/runs/<name>/`.
#[test]
fn the_default_output_folder_is_untracked_and_ignored() {
    use lambert_study::StudyConfig;
    let default = StudyConfig::builtin().default_out_dir();
    assert_eq!(default, Path::new("notebooks-data/runs/builtin"));
    assert_ne!(default, Path::new("notebooks-data/builtin"));
    let path = default.to_str().unwrap();
    match git(&["ls-files", "--", path]) {
        None => eprintln!("not a git checkout: the tracked-path check is skipped"),
        Some(tracked) => {
            assert!(tracked.status.success());
            assert!(
                tracked.stdout.is_empty(),
                "tracked files under {path}: {}",
                String::from_utf8_lossy(&tracked.stdout)
            );
            let ignored = git(&["check-ignore", "-q", &format!("{path}/results.csv")]).unwrap();
            assert!(ignored.status.success(), "{path} is not ignored by git");
            // The committed reference is tracked, and not ignored.
            let reference = git(&["ls-files", "--", "notebooks-data/builtin/results.csv"]).unwrap();
            assert!(!reference.stdout.is_empty(), "the reference is tracked");
        }
    }

    let dir = temp_dir("default_out");
    let study = dir.join("study.toml");
    std::fs::write(
        &study,
        "name = \"t\"\nscenes = [\"builtin:uniform-sky\"]\nstrategies = [\"light\"]\n\
         sequences = [\"independent\"]\nn_min_log2 = 5\nn_max_log2 = 6\nreplicates = 2\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_lambert"))
        .current_dir(&dir)
        .args(["study", study.to_str().unwrap(), "--quiet"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("notebooks-data/runs/t/results.csv").is_file());
    assert!(!dir.join("notebooks-data/t").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
