//! `lambert estimate` and `lambert analytic`: the JSON interface, every
//! strategy × sequence, thread-count independence, closed forms, and exit
//! code 2 with a message naming the field (and nothing on stdout) on bad
//! input.

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

fn lambert(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lambert"))
        .args(args)
        .output()
        .expect("the lambert binary runs")
}

/// A scene file under the temp directory, removed on drop.
struct TempScene(PathBuf);

impl TempScene {
    fn new(test: &str, text: &str) -> Self {
        let path = std::env::temp_dir().join(format!(
            "lambert-estimate-command-{test}-{}.toml",
            std::process::id()
        ));
        std::fs::write(&path, text).expect("temp file written");
        TempScene(path)
    }

    fn path(&self) -> &str {
        self.0.to_str().expect("a UTF-8 temp path")
    }
}

impl Drop for TempScene {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

const SPHERE: &str = r#"
[receiver]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[emitters]]
kind = "sphere"
center = [0.0, 5.0, 8.66]
radius = 1.0
radiance = 1.0
"#;

const SKY_AND_POINT: &str = r#"
[receiver]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[emitters]]
kind = "sky"
radiance = 0.7

[[emitters]]
kind = "point"
position = [1.0, 2.0, 3.0]
intensity = 64.9
"#;

fn success_json(out: &Output) -> (Value, String) {
    let stdout = String::from_utf8(out.stdout.clone()).expect("UTF-8 stdout");
    assert!(
        out.status.success(),
        "status {:?}, stderr {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(stdout.trim_end().lines().count(), 1, "one line: {stdout}");
    let value: Value = serde_json::from_str(&stdout).expect("valid JSON");
    (value, stdout)
}

/// The literal text of a top-level number in a one-line JSON object.
fn raw_number<'a>(json: &'a str, key: &str) -> &'a str {
    let start = json.find(&format!("\"{key}\":")).expect("key present") + key.len() + 3;
    let rest = &json[start..];
    let end = rest.find([',', '}']).expect("value ends");
    &rest[..end]
}

#[test]
fn json_has_exactly_the_documented_keys() {
    let scene = TempScene::new("json_keys", SPHERE);
    let out = lambert(&[
        "estimate",
        scene.path(),
        "--json",
        "--samples",
        "4096",
        "--seed",
        "3",
    ]);
    let (v, _) = success_json(&out);
    let obj = v.as_object().expect("a JSON object");
    let mut keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    keys.sort_unstable();
    assert_eq!(
        keys,
        [
            "analytic",
            "ci99",
            "f64_fallbacks",
            "fallback",
            "hits",
            "interval",
            "mean",
            "ns_per_sample",
            "precision",
            "rel_error",
            "samples",
            "seconds",
            "std_error",
            "warning",
            "z"
        ]
    );
    // Light sampling of a sphere wholly above the horizon: every sample
    // hits, and the interval is the central-limit one, without a warning.
    assert_eq!(v["hits"].as_u64(), Some(4096));
    assert_eq!(v["interval"].as_str(), Some("clt"));
    assert!(v["warning"].is_null(), "{v}");
    assert!(v["fallback"].is_null(), "{v}");
    let mean = v["mean"].as_f64().unwrap();
    let se = v["std_error"].as_f64().unwrap();
    let ci = v["ci99"].as_array().expect("ci99 is an array");
    assert_eq!(ci.len(), 2);
    let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
    assert!(lo < mean && mean < hi, "{lo} < {mean} < {hi}");
    assert!(se > 0.0 && mean > 0.0);
    assert_eq!(v["samples"].as_u64(), Some(4096));
    assert!(v["seconds"].as_f64().unwrap() >= 0.0);
    assert!(v["ns_per_sample"].as_f64().unwrap() >= 0.0);
    // Every emitter kind has a closed form: analytic, rel_error and z are
    // numbers (z is null only when the standard error is 0).
    assert!(v["analytic"].as_f64().is_some(), "{v}");
    assert!(
        v["rel_error"].as_f64().is_some() && v["z"].as_f64().is_some(),
        "{v}"
    );
}

#[test]
fn json_compares_with_the_closed_form_when_there_is_one() {
    let scene = TempScene::new("json_closed_form", SKY_AND_POINT);
    for strategy in ["uniform-hemisphere", "cosine-hemisphere"] {
        let out = lambert(&[
            "estimate",
            scene.path(),
            "--json",
            "--samples",
            "4096",
            "--strategy",
            strategy,
        ]);
        let (v, _) = success_json(&out);
        let analytic = v["analytic"].as_f64().expect("a number");
        let mean = v["mean"].as_f64().unwrap();
        let rel = v["rel_error"].as_f64().expect("a number");
        assert_eq!(rel, (mean - analytic) / analytic);
        if strategy == "cosine-hemisphere" {
            // Zero variance under a uniform sky: exact, to rounding; the
            // standard error is the rounding floor (21u + 4(N + 2)u²)·|E|,
            // u = 2⁻⁵³, and the error is within it.
            let u = f64::EPSILON / 2.0;
            let floor = (21.0 * u + 4.0 * (4096.0 + 2.0) * u * u) * mean;
            assert_eq!(v["std_error"].as_f64(), Some(floor));
            assert!(v["z"].as_f64().expect("a number").abs() <= 1.0, "{v}");
            assert!(rel.abs() < 1e-14, "{rel}");
        } else {
            let z = v["z"].as_f64().expect("a number");
            assert!(z.abs() < 5.0, "z = {z}");
        }
    }
}

/// A sphere 1e-4 rad wide: cosine sampling sees it with probability 1e-8,
/// so none of 4096 samples hits. The estimate says so: 0 hits, a warning,
/// and the one-sided interval [0, b] with b ≥ E (here the bound πL·Ω/π =
/// LΩ, which no mean can exceed), not [0, 0].
#[test]
fn json_reports_zero_hits_with_a_warning_and_a_one_sided_interval() {
    let scene = TempScene::new(
        "json_zero_hits",
        &SPHERE
            .replace("center = [0.0, 5.0, 8.66]", "center = [0.0, 0.0, 10.0]")
            .replace("radius = 1.0", "radius = 1e-3"),
    );
    let out = lambert(&[
        "estimate",
        scene.path(),
        "--json",
        "--samples",
        "4096",
        "--strategy",
        "cosine-hemisphere",
    ]);
    let (v, _) = success_json(&out);
    assert_eq!(v["hits"].as_u64(), Some(0));
    assert_eq!(v["mean"].as_f64(), Some(0.0));
    assert_eq!(v["interval"].as_str(), Some("bounded"));
    let warning = v["warning"].as_str().expect("a warning");
    assert!(warning.contains("no hit"), "{warning}");
    let analytic = v["analytic"].as_f64().unwrap();
    let ci = v["ci99"].as_array().unwrap();
    assert_eq!(ci[0].as_f64(), Some(0.0));
    assert!(ci[1].as_f64().unwrap() >= analytic, "{v}");
}

/// Samples per run of `every_strategy_and_sequence_agrees_with_the_closed_form`:
/// uniform-hemisphere sampling sees the sphere (α = 0.1 rad) in 0.5 % of
/// its samples, so 2^18 give ≈ 1300 hits, 82 in each of the 16
/// randomizations of the randomized-QMC sequences — the range where their
/// normal and t intervals are honest (below ~20 hits per randomization the
/// t interval is not; see the study's interval tests) and where a 25 %
/// error is found with power ≥ 0.999 by every strategy.
const CLOSED_FORM_SAMPLES: &str = "262144";

/// Every strategy × sequence against the `analytic` value the output
/// carries: z = (mean − analytic)/std_error within the two-sided critical
/// value at the Šidák level of the 21 runs (normal for independent
/// samples, t(15) for the 16 randomizations of randomized QMC), or, with a
/// standard error of 0, the mean equal to it to 1e-14. Negative control:
/// the same runs judged against an analytic value 25 % high must all be
/// rejected; each run's power there, from its own standard error, is
/// printed and must be ≥ 0.999.
#[test]
fn every_strategy_and_sequence_agrees_with_the_closed_form() {
    use lambert_estimator::ConfidenceInterval;
    use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
    let scene = TempScene::new("every_strategy", SPHERE);
    let strategies = [
        "auto",
        "uniform-hemisphere",
        "cosine-hemisphere",
        "light",
        "area",
        "mis",
        "mis-balance",
        "projected",
        "control-variate",
    ];
    let sequences = ["independent", "stratified", "sobol"];
    let precisions = ["f64", "f32"];
    let alpha =
        lambert_validate::sidak_level(0.01, strategies.len() * sequences.len() * precisions.len());
    let mut failures = Vec::new();
    for (strategy, precision) in strategies
        .iter()
        .flat_map(|s| precisions.iter().map(move |p| (*s, *p)))
    {
        for sequence in sequences {
            let out = lambert(&[
                "estimate",
                scene.path(),
                "--precision",
                precision,
                "--json",
                "--samples",
                CLOSED_FORM_SAMPLES,
                "--strategy",
                strategy,
                "--sequence",
                sequence,
            ]);
            let (v, _) = success_json(&out);
            let mean = v["mean"].as_f64().unwrap();
            let se = v["std_error"].as_f64().unwrap();
            let analytic = v["analytic"]
                .as_f64()
                .expect("the sphere has a closed form");
            assert!(mean.is_finite() && se.is_finite() && se >= 0.0);
            if se == 0.0 {
                if (mean - analytic).abs() > 1e-14 * analytic {
                    failures.push(format!(
                        "{strategy} × {sequence}: exact {mean} ≠ {analytic}"
                    ));
                }
                continue;
            }
            // The quantile the estimator's own intervals use: normal for
            // n ≥ 30, t(n − 1) below (n = 16 randomizations).
            let n = if sequence == "independent" {
                1 << 18
            } else {
                16
            };
            let critical = ConfidenceInterval::new(0.0, 1.0, n, 1.0 - alpha).quantile;
            let z = (mean - analytic) / se;
            assert_eq!(v["z"].as_f64(), Some(z), "the output's own z");
            let z_control = (mean - 1.25 * analytic) / se;
            let shift = 0.25 * analytic / se;
            let power = if n == 16 {
                let t = StudentsT::new(0.0, 1.0, 15.0).unwrap();
                t.cdf(shift - critical) + t.cdf(-shift - critical)
            } else {
                let d = Normal::standard();
                d.cdf(shift - critical) + d.cdf(-shift - critical)
            };
            eprintln!(
                "{strategy:>18} × {sequence:<11} {precision}: z = {z:6.2} (critical {critical:.2}); \
                 control (analytic × 1.25): z = {z_control:7.1}, power {power:.6}"
            );
            if z.abs() > critical {
                failures.push(format!(
                    "{strategy} × {sequence} {precision}: {mean} vs {analytic}, z = {z:.2} beyond {critical:.2}"
                ));
            }
            assert!(
                power >= 0.999,
                "{strategy} × {sequence}: control power {power}"
            );
            assert!(
                z_control.abs() > critical,
                "{strategy} × {sequence}: control not rejected (z = {z_control})"
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn thread_count_does_not_change_the_result() {
    let scene = TempScene::new("threads", SPHERE);
    for sequence in ["independent", "stratified", "sobol"] {
        let run = |threads: &str| {
            let out = lambert(&[
                "estimate",
                scene.path(),
                "--json",
                "--samples",
                "20000",
                "--sequence",
                sequence,
                "--strategy",
                "mis",
                "--threads",
                threads,
            ]);
            success_json(&out).1
        };
        let (one, two) = (run("1"), run("2"));
        for key in ["mean", "std_error", "hits"] {
            assert_eq!(
                raw_number(&one, key),
                raw_number(&two, key),
                "{sequence}: {key}"
            );
        }
        assert_eq!(
            one.split("\"ci99\":").nth(1).unwrap().split(']').next(),
            two.split("\"ci99\":").nth(1).unwrap().split(']').next(),
            "{sequence}: ci99"
        );
    }
}

#[test]
fn analytic_gives_sky_plus_point_exactly() {
    let scene = TempScene::new("analytic", SKY_AND_POINT);
    let out = lambert(&["analytic", scene.path(), "--json"]);
    let (v, _) = success_json(&out);
    let obj = v.as_object().unwrap();
    assert_eq!(obj.len(), 2);
    // E = L π + I cos θ / r². The sky term is one multiplication, so exact;
    // the point term comes out 1 ulp away from the left-to-right evaluation
    // of I·cos θ/r² here (the library's rounding order differs, e.g.
    // I·(cos θ/r²)), so it and the total are compared to 1e-15 relative,
    // a few ulps.
    let sky = 0.7 * std::f64::consts::PI;
    let (x, y, z) = (1.0f64, 2.0f64, 3.0f64);
    let r2 = x * x + y * y + z * z;
    let cos = z / r2.sqrt();
    let point = 64.9 * cos / r2;
    let per: Vec<f64> = v["per_emitter"]
        .as_array()
        .expect("per_emitter is an array")
        .iter()
        .map(|e| e.as_f64().unwrap())
        .collect();
    assert_eq!(per.len(), 2);
    assert_eq!(per[0], sky);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b.abs();
    assert!(close(per[1], point), "{} vs {point}", per[1]);
    let total = v["irradiance"].as_f64().expect("a number");
    assert!(close(total, sky + point), "{total} vs {}", sky + point);
    assert_eq!(total, per[0] + per[1], "the total is the sum shown");
}

#[test]
fn analytic_covers_every_emitter_kind() {
    // One emitter of each kind: each gets a finite closed form, and the
    // total is their sum.
    let text = r#"
[receiver]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
[[emitters]]
kind = "sky"
radiance = 0.1
[[emitters]]
kind = "sky_cap"
axis = [1.0, 0.0, 0.3]
half_angle_deg = 30.0
radiance = 1.0
[[emitters]]
kind = "sphere"
center = [0.0, 5.0, 8.66]
radius = 1.0
radiance = 1.0
[[emitters]]
kind = "disk"
center = [1.0, 0.0, 2.0]
normal = [0.0, 0.0, -1.0]
radius = 0.5
radiance = 1.0
[[emitters]]
kind = "polygon"
vertices = [[-1.0, -1.0, 2.0], [-1.0, 1.0, 2.0], [1.0, 1.0, 2.0]]
radiance = 1.0
[[emitters]]
kind = "point"
position = [0.0, 0.0, 2.0]
intensity = 1.0
[[emitters]]
kind = "directional"
direction = [0.0, 1.0, 1.0]
irradiance = 2.0
"#;
    let scene = TempScene::new("every_kind", text);
    let out = lambert(&["analytic", scene.path(), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let per: Vec<f64> = v["per_emitter"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e.as_f64().unwrap())
        .collect();
    assert_eq!(per.len(), 7);
    assert!(per.iter().all(|e| e.is_finite() && *e > 0.0), "{per:?}");
    assert_eq!(v["irradiance"].as_f64().unwrap(), per.iter().sum::<f64>());
}

/// Exit code 2, an empty stdout and every needle in stderr.
fn user_error(args: &[&str], needles: &[&str]) {
    let out = lambert(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}: stdout {:?}", out.stdout);
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err:?} should contain {n:?}");
    }
}

#[test]
fn bad_input_exits_2_naming_the_field() {
    let good = TempScene::new("bad_input_good", SPHERE);
    let zero_radius = TempScene::new(
        "bad_input_zero_radius",
        &SPHERE.replace("radius = 1.0", "radius = 0.0"),
    );
    let unknown_key = TempScene::new(
        "bad_input_unknown_key",
        &SPHERE.replace("radiance = 1.0", "radiance = 1.0\ncolour = 3"),
    );
    let inside = TempScene::new(
        "bad_input_inside",
        &SPHERE.replace("radius = 1.0", "radius = 20.0"),
    );
    let syntax = TempScene::new("bad_input_syntax", "[receiver\n");
    let missing = std::env::temp_dir().join(format!(
        "lambert-estimate-command-missing-{}.toml",
        std::process::id()
    ));
    let missing = missing.to_str().unwrap();

    for command in ["estimate", "analytic"] {
        user_error(
            &[command, zero_radius.path(), "--json"],
            &["emitters[0].radius", "must be positive"],
        );
        user_error(
            &[command, unknown_key.path(), "--json"],
            &["colour", "unknown field"],
        );
        user_error(
            &[command, inside.path(), "--json"],
            &["receiver.point", "inside or on the sphere light"],
        );
        user_error(&[command, syntax.path(), "--json"], &["line 1"]);
        user_error(&[command, missing, "--json"], &["cannot read", missing]);
    }
    let g = good.path();
    user_error(
        &["estimate", g, "--json", "--strategy", "best"],
        &["--strategy", "unknown strategy \"best\""],
    );
    user_error(
        &["estimate", g, "--json", "--sequence", "halton"],
        &["--sequence", "unknown sequence \"halton\""],
    );
    user_error(
        &["estimate", g, "--json", "--samples", "0"],
        &["--samples", "must be at least"],
    );
    user_error(
        &[
            "estimate",
            g,
            "--json",
            "--samples",
            "16",
            "--sequence",
            "sobol",
        ],
        &["--samples", "must be at least 32"],
    );
    user_error(
        &["estimate", g, "--json", "--threads", "0"],
        &["--threads", "must be at least 1"],
    );
    user_error(&["estimate", g, "--json", "--samples", "-3"], &["'-3'"]);
}

#[test]
fn results_beyond_the_f64_range_exit_2_naming_the_emitter() {
    let sky = |radiance: &str| {
        format!(
            "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n[[emitters]]\nkind = \"sky\"\nradiance = {radiance}\n"
        )
    };
    // E = π·1e308 overflows: an error naming the emitter's radiance and
    // the irradiance, never {"irradiance": null} with exit code 0.
    let one = TempScene::new("overflow_one", &sky("1e308"));
    // 1.57e308 twice: each finite, the sum not.
    let two = TempScene::new(
        "overflow_sum",
        &format!(
            "{}[[emitters]]\nkind = \"sky\"\nradiance = 5e307\n",
            sky("5e307")
        ),
    );
    for command in ["analytic", "estimate"] {
        user_error(
            &[command, one.path(), "--json"],
            &["emitters[0].radiance", "irradiance", "overflows", "1e308"],
        );
        user_error(
            &[command, two.path(), "--json"],
            &[
                "irradiance:",
                "emitters[0] (sky)",
                "emitters[1] (sky)",
                "sum overflows",
            ],
        );
    }
}

#[test]
fn sample_values_near_1e160_are_answered() {
    // Sample values near 1e160 once made the sum of squared deviations
    // overflow inside the estimator; the estimator now scales strengths by
    // a power of two (lambert_estimator::strength_scale), so the scene
    // answers, within its interval of the closed form π·1e160 + 1.
    let scene = TempScene::new(
        "statistics_overflow",
        "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n[[emitters]]\nkind = \"point\"\nposition = [0.0, 0.0, 1.0]\nintensity = 1.0\n[[emitters]]\nkind = \"sky\"\nradiance = 1e160\n",
    );
    let out = lambert(&[
        "estimate",
        scene.path(),
        "--json",
        "--samples",
        "64",
        "--strategy",
        "uniform-hemisphere",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let (v, _) = success_json(&out);
    let mean = v["mean"].as_f64().expect("a finite mean");
    let (lo, hi) = (
        v["ci99"][0].as_f64().unwrap(),
        v["ci99"][1].as_f64().unwrap(),
    );
    let truth = std::f64::consts::PI * 1e160 + 1.0;
    // One 99 % interval at a fixed seed: covers the truth (checked once;
    // the coverage of these intervals is the estimator suites' business).
    assert!(mean.is_finite() && lo <= truth && truth <= hi, "{v}");
}

/// `--precision`: f32 runs and says so; an emitter f32 cannot estimate
/// accurately enough (a unit sphere 1e3 away under uniform hemisphere
/// sampling: its f32 hit-test error bound is ~1 % of its irradiance) is
/// named with the reason, in JSON and in text; an unknown value is a user
/// error naming the option.
#[test]
fn precision_f32_is_reported_with_its_fallbacks_and_a_bad_value_exits_2() {
    let scene = TempScene::new("precision_f32", SPHERE);
    let out = lambert(&[
        "estimate",
        scene.path(),
        "--json",
        "--samples",
        "4096",
        "--precision",
        "f32",
    ]);
    let (v, _) = success_json(&out);
    assert_eq!(v["precision"].as_str(), Some("f32"));
    assert_eq!(v["f64_fallbacks"].as_array().map(Vec::len), Some(0), "{v}");
    let far = TempScene::new(
        "precision_far",
        &SPHERE.replace("center = [0.0, 5.0, 8.66]", "center = [0.0, 500.0, 866.0]"),
    );
    let args = [
        "estimate",
        far.path(),
        "--samples",
        "4096",
        "--strategy",
        "uniform-hemisphere",
        "--precision",
        "f32",
    ];
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let (v, _) = success_json(&lambert(&json_args));
    let fallbacks = v["f64_fallbacks"].as_array().expect("a list");
    assert_eq!(fallbacks.len(), 1, "{v}");
    assert_eq!(fallbacks[0]["emitter"].as_u64(), Some(0));
    assert_eq!(fallbacks[0]["kind"].as_str(), Some("sphere"));
    assert!(
        fallbacks[0]["reason"]
            .as_str()
            .unwrap()
            .contains("f32 error bound"),
        "{v}"
    );
    let text = lambert(&args);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("emitters[0] (a sphere) runs in f64: its f32 error bound"),
        "{text}"
    );
    user_error(
        &["estimate", scene.path(), "--precision", "f16"],
        &["--precision", "\"f16\"", "f64 or f32"],
    );
}
