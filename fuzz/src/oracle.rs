//! The contract every call must keep, and the verdict on one outcome.
//!
//! A call either **answers** — exit code 0, one line of JSON on stdout with
//! exactly the documented keys, every number finite, no `null` where a
//! number belongs, and the numbers consistent with each other — or
//! **refuses** — exit code 2, nothing on stdout, and a message on stderr
//! that names where the problem is (an `emitters[i]` or `receiver.` field,
//! a command-line option, or the line and column of a TOML error). Anything
//! else is a failure of one of the classes of [`Class`].

use std::fmt;
use std::path::Path;

use serde_json::{Map, Value};

use crate::calls::{Call, Command};
use crate::run::{Exit, Outcome};

/// The wording by which `lambert` reports a defect of its own (a NaN from
/// a closed form, say) rather than of the input: such a refusal is a
/// failure.
pub const DEFECT_MARKER: &str = "a defect in lambert";

/// What kind of failure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Class {
    /// The process panicked (exit code 101 or a panic message).
    Panic,
    /// The process was killed by a signal.
    Signal,
    /// The process outlived its time limit.
    Hang,
    /// Exit code 0 with `null`, NaN or ±∞ where a number belongs.
    NonFinite,
    /// An exit code other than 0 and 2 (and 101).
    ExitCode,
    /// Exit code 2 with a message that names no field, option or line.
    NoField,
    /// Exit code 2 with something written to stdout (or an output file).
    HalfWritten,
    /// Exit code 0 with output that is not the documented JSON.
    BadJson,
    /// Exit code 0 with numbers that contradict each other or another call
    /// (a negative irradiance, an interval not containing its mean, an
    /// `analytic` field that differs from `lambert analytic`).
    Inconsistent,
    /// Exit code 2 with a message saying lambert itself is at fault.
    Defect,
    /// `estimate` refused a scene whose irradiance `analytic` answered as a
    /// finite number: the estimate is representable, the estimator could
    /// not produce it (an intermediate overflowed, or a sample was NaN).
    Unanswered,
}

impl Class {
    /// Every class, in report order.
    pub const ALL: [Class; 11] = [
        Class::Panic,
        Class::Signal,
        Class::Hang,
        Class::NonFinite,
        Class::ExitCode,
        Class::NoField,
        Class::HalfWritten,
        Class::BadJson,
        Class::Inconsistent,
        Class::Defect,
        Class::Unanswered,
    ];

    /// The class's name in reports and corpus headers.
    pub fn name(self) -> &'static str {
        match self {
            Class::Panic => "panic",
            Class::Signal => "signal",
            Class::Hang => "hang",
            Class::NonFinite => "non-finite",
            Class::ExitCode => "exit-code",
            Class::NoField => "no-field",
            Class::HalfWritten => "half-written",
            Class::BadJson => "bad-json",
            Class::Inconsistent => "inconsistent",
            Class::Defect => "defect",
            Class::Unanswered => "unanswered",
        }
    }

    /// The class of that name.
    pub fn from_name(name: &str) -> Option<Class> {
        Class::ALL.into_iter().find(|c| c.name() == name)
    }
}

impl fmt::Display for Class {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A failure: its class and what exactly was seen.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The class.
    pub class: Class,
    /// What was seen (the offending key, the panic line, the message).
    pub detail: String,
}

/// The verdict on one call.
#[derive(Clone, Debug, PartialEq)]
pub enum Verdict {
    /// A finite, consistent answer.
    Answered,
    /// A clear refusal (exit code 2 naming the field).
    Refused,
    /// A failure.
    Failed(Failure),
}

/// What `lambert analytic` said about the same scene, for the estimates'
/// `analytic` field to agree with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClosedForm {
    /// It answered this total.
    Total(f64),
    /// It refused.
    Refused,
}

/// What the judge knows besides the outcome.
#[derive(Clone, Copy, Debug, Default)]
pub struct Context<'a> {
    /// The number of `[[emitters]]` tables in the file, if it is TOML.
    pub emitters: Option<usize>,
    /// The analytic call's result on the same scene, if it kept the
    /// contract.
    pub closed_form: Option<ClosedForm>,
    /// The file the call may write (render's image).
    pub out_file: Option<&'a Path>,
}

fn fail(class: Class, detail: impl Into<String>) -> Verdict {
    Verdict::Failed(Failure {
        class,
        detail: detail.into(),
    })
}

/// Judges one call's outcome.
pub fn judge(call: &Call, outcome: &Outcome, context: &Context) -> Verdict {
    let first_line = |s: &str| s.lines().next().unwrap_or("").to_owned();
    let panic_line = outcome
        .stderr
        .lines()
        .find(|l| l.contains("panicked at"))
        .map(str::to_owned);
    match outcome.exit {
        Exit::TimedOut => fail(
            Class::Hang,
            format!("no answer within {:.1} s", outcome.seconds),
        ),
        Exit::Signal(s) => fail(Class::Signal, format!("killed by signal {s:?}")),
        Exit::Code(101) => fail(
            Class::Panic,
            panic_line.unwrap_or_else(|| first_line(&outcome.stderr)),
        ),
        _ if panic_line.is_some() => fail(Class::Panic, panic_line.unwrap_or_default()),
        Exit::Code(0) => {
            if let Some(out) = context.out_file {
                if !out.is_file() {
                    return fail(Class::BadJson, "exit code 0 but no output file");
                }
            }
            match judge_json(call, &outcome.stdout, context) {
                Ok(()) => Verdict::Answered,
                Err(f) => Verdict::Failed(f),
            }
        }
        Exit::Code(2) => {
            let message = outcome.stderr.trim();
            if !outcome.stdout.is_empty() {
                return fail(
                    Class::HalfWritten,
                    format!(
                        "exit code 2 after writing {:?}",
                        first_line(&outcome.stdout)
                    ),
                );
            }
            if context.out_file.is_some_and(Path::exists) {
                return fail(Class::HalfWritten, "exit code 2 left an output file");
            }
            if message.contains(DEFECT_MARKER) {
                return fail(Class::Defect, first_line(message));
            }
            if !(message.starts_with("error:") && names_a_field(message, context.emitters)) {
                return fail(Class::NoField, first_line(message));
            }
            match (call.command, context.closed_form) {
                (Command::Estimate, Some(ClosedForm::Total(e))) => fail(
                    Class::Unanswered,
                    format!(
                        "analytic answered {e:e}; estimate refused: {}",
                        first_line(message)
                    ),
                ),
                _ => Verdict::Refused,
            }
        }
        Exit::Code(code) => fail(
            Class::ExitCode,
            format!("exit code {code}: {}", first_line(&outcome.stderr)),
        ),
    }
}

/// Options a message may name.
const OPTIONS: [&str; 10] = [
    "--strategy",
    "--sequence",
    "--samples",
    "--seed",
    "--threads",
    "--mode",
    "--width",
    "--height",
    "--spp",
    "--out",
];

/// Keys of the commands' JSON output a message may begin with (the
/// quantity that could not be given, e.g. `irradiance: … overflows`).
const QUANTITIES: [&str; 5] = ["irradiance", "mean", "std_error", "rel_error", "z"];

/// Whether `message` says where the problem is: an `emitters[i]` with i
/// below the number of emitters (when known), a `receiver.` field, the
/// `emitters:` list itself, a command-line option, a TOML position
/// `line N, column M`, or — as the message's subject — the output
/// quantity that could not be given.
pub fn names_a_field(message: &str, emitters: Option<usize>) -> bool {
    let body = message
        .strip_prefix("error:")
        .unwrap_or(message)
        .trim_start();
    let body = body.rsplit_once(".toml: ").map_or(body, |(_, b)| b);
    let quantity = QUANTITIES
        .iter()
        .any(|q| body.strip_prefix(q).is_some_and(|r| r.starts_with(':')));
    let emitter_index = message.match_indices("emitters[").any(|(i, m)| {
        let rest = &message[i + m.len()..];
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        let closed = rest[digits.len()..].starts_with(']');
        match digits.parse::<usize>() {
            Ok(k) if closed => emitters.is_none_or(|n| k < n),
            _ => false,
        }
    });
    let position = message.match_indices("line ").any(|(i, m)| {
        let rest = &message[i + m.len()..];
        let digits = rest.chars().take_while(char::is_ascii_digit).count();
        digits > 0 && rest[digits..].starts_with(", column ")
    });
    emitter_index
        || quantity
        || position
        || message.contains("receiver.point")
        || message.contains("receiver.normal")
        || message.contains("emitters:")
        || OPTIONS.iter().any(|o| message.contains(o))
}

/// The answer's JSON: one line, one object.
fn parse_one_line(stdout: &str) -> Result<Map<String, Value>, Failure> {
    let failure = |class, detail: String| Failure { class, detail };
    let text = stdout.trim_end();
    if text.lines().count() != 1 {
        return Err(failure(
            Class::BadJson,
            format!("{} lines on stdout, expected 1", text.lines().count()),
        ));
    }
    match serde_json::from_str::<Value>(text) {
        Ok(Value::Object(map)) => Ok(map),
        Ok(other) => Err(failure(Class::BadJson, format!("not an object: {other}"))),
        Err(e) => {
            let non_finite = ["NaN", "nan", "inf", "Infinity"]
                .iter()
                .any(|t| text.contains(t));
            let class = if non_finite {
                Class::NonFinite
            } else {
                Class::BadJson
            };
            Err(failure(class, format!("unparsable JSON ({e}): {text}")))
        }
    }
}

/// A finite number at `key`.
fn number(map: &Map<String, Value>, key: &str) -> Result<f64, Failure> {
    match map.get(key) {
        Some(Value::Number(n)) => match n.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(Failure {
                class: Class::NonFinite,
                detail: format!("`{key}` = {n}"),
            }),
        },
        Some(Value::Null) => Err(Failure {
            class: Class::NonFinite,
            detail: format!("`{key}` is null"),
        }),
        Some(other) => Err(Failure {
            class: Class::BadJson,
            detail: format!("`{key}` = {other} is not a number"),
        }),
        None => Err(Failure {
            class: Class::BadJson,
            detail: format!("`{key}` is missing"),
        }),
    }
}

/// A finite number at `key`, or `null` exactly when `defined` is false.
fn number_if(map: &Map<String, Value>, key: &str, defined: bool) -> Result<Option<f64>, Failure> {
    if defined {
        return number(map, key).map(Some);
    }
    match map.get(key) {
        Some(Value::Null) => Ok(None),
        other => Err(Failure {
            class: Class::Inconsistent,
            detail: format!("`{key}` should be null (undefined), got {other:?}"),
        }),
    }
}

fn inconsistent(detail: String) -> Failure {
    Failure {
        class: Class::Inconsistent,
        detail,
    }
}

fn keys_are(map: &Map<String, Value>, expected: &[&str]) -> Result<(), Failure> {
    let mut keys: Vec<&str> = map.keys().map(String::as_str).collect();
    keys.sort_unstable();
    let mut want = expected.to_vec();
    want.sort_unstable();
    if keys == want {
        Ok(())
    } else {
        Err(Failure {
            class: Class::BadJson,
            detail: format!("keys {keys:?}, expected {want:?}"),
        })
    }
}

fn judge_json(call: &Call, stdout: &str, context: &Context) -> Result<(), Failure> {
    match call.command {
        Command::Analytic => judge_analytic(&parse_one_line(stdout)?, context),
        Command::Estimate => judge_estimate(call, &parse_one_line(stdout)?, context),
        Command::Render => {
            if stdout.trim().is_empty() {
                return Ok(());
            }
            all_finite(&Value::Object(parse_one_line(stdout)?), "")
        }
    }
}

/// `{"irradiance": E, "per_emitter": [E₀, …]}`: E and every Eᵢ finite and
/// ≥ 0, one Eᵢ per emitter, E = Σ Eᵢ summed left to right.
fn judge_analytic(map: &Map<String, Value>, context: &Context) -> Result<(), Failure> {
    keys_are(map, &["irradiance", "per_emitter"])?;
    let total = number(map, "irradiance")?;
    let Some(Value::Array(items)) = map.get("per_emitter") else {
        return Err(Failure {
            class: Class::BadJson,
            detail: "`per_emitter` is not an array".into(),
        });
    };
    if let Some(n) = context.emitters {
        if items.len() != n {
            return Err(inconsistent(format!(
                "{} per_emitter values for {n} emitters",
                items.len()
            )));
        }
    }
    let mut sum = 0.0;
    for (i, item) in items.iter().enumerate() {
        let wrapped: Map<String, Value> = [(format!("per_emitter[{i}]"), item.clone())]
            .into_iter()
            .collect();
        let e = number(&wrapped, &format!("per_emitter[{i}]"))?;
        if !(e >= 0.0) {
            return Err(inconsistent(format!("per_emitter[{i}] = {e} < 0")));
        }
        sum += e;
    }
    if !(total >= 0.0) {
        return Err(inconsistent(format!("irradiance = {total} < 0")));
    }
    if total != sum {
        return Err(inconsistent(format!(
            "irradiance {total} != sum of per_emitter {sum}"
        )));
    }
    Ok(())
}

/// The estimate's documented keys; every number finite; `analytic` equal
/// to `lambert analytic`'s answer (null when it refused); `rel_error`
/// null exactly when `analytic` is null or 0, `z` null exactly when
/// `analytic` is null or the standard error is 0; mean ≥ 0, standard
/// error ≥ 0, the interval ordered around the mean, `samples` as asked,
/// `hits` at most `samples`, `interval` one of clt, rare-event, bounded,
/// and a `warning` (text) exactly when the interval is not clt.
fn judge_estimate(call: &Call, map: &Map<String, Value>, context: &Context) -> Result<(), Failure> {
    keys_are(
        map,
        &[
            "mean",
            "std_error",
            "ci99",
            "samples",
            "seconds",
            "ns_per_sample",
            "analytic",
            "rel_error",
            "z",
            "hits",
            "interval",
            "warning",
            "fallback",
            "precision",
            "f64_fallbacks",
        ],
    )?;
    // The fuzzer runs f64 estimates: their precision is "f64" and no
    // emitter can fall back to f64.
    if map.get("precision").and_then(Value::as_str) != Some("f64")
        || map
            .get("f64_fallbacks")
            .and_then(Value::as_array)
            .map(Vec::len)
            != Some(0)
    {
        return Err(Failure {
            class: Class::BadJson,
            detail: format!(
                "`precision` = {:?}, `f64_fallbacks` = {:?} in an f64 estimate",
                map.get("precision"),
                map.get("f64_fallbacks")
            ),
        });
    }
    if !matches!(map.get("fallback"), Some(Value::String(_) | Value::Null)) {
        return Err(Failure {
            class: Class::BadJson,
            detail: format!(
                "`fallback` = {:?} is neither text nor null",
                map.get("fallback")
            ),
        });
    }
    let mean = number(map, "mean")?;
    let se = number(map, "std_error")?;
    let interval = map.get("interval").and_then(Value::as_str);
    if !matches!(interval, Some("clt" | "rare-event" | "bounded")) {
        return Err(Failure {
            class: Class::BadJson,
            detail: format!("`interval` = {:?}", map.get("interval")),
        });
    }
    let warned = match map.get("warning") {
        Some(Value::String(_)) => true,
        Some(Value::Null) => false,
        other => {
            return Err(Failure {
                class: Class::BadJson,
                detail: format!("`warning` = {other:?} is neither text nor null"),
            })
        }
    };
    if warned == (interval == Some("clt")) {
        return Err(inconsistent(format!(
            "interval {interval:?} with warning {:?}: a warning must come with \
             every interval but the clt one",
            map.get("warning")
        )));
    }
    number(map, "seconds")?;
    number(map, "ns_per_sample")?;
    let ci = match map.get("ci99") {
        Some(Value::Array(a)) if a.len() == 2 => {
            let m: Map<String, Value> = [
                ("ci99[0]".to_owned(), a[0].clone()),
                ("ci99[1]".to_owned(), a[1].clone()),
            ]
            .into_iter()
            .collect();
            (number(&m, "ci99[0]")?, number(&m, "ci99[1]")?)
        }
        other => {
            return Err(Failure {
                class: Class::BadJson,
                detail: format!("`ci99` = {other:?} is not a pair"),
            })
        }
    };
    let asked: Option<u64> = call.option("samples").and_then(|s| s.parse().ok());
    let samples = map.get("samples").and_then(Value::as_u64);
    if samples.is_none() || (asked.is_some() && samples != asked) {
        return Err(inconsistent(format!(
            "samples {:?}, asked {asked:?}",
            map.get("samples")
        )));
    }
    let hits = map.get("hits").and_then(Value::as_u64);
    if hits.is_none_or(|h| Some(h) > samples) {
        return Err(inconsistent(format!(
            "hits {:?} of {samples:?} samples",
            map.get("hits")
        )));
    }
    let analytic = match context.closed_form {
        Some(ClosedForm::Refused) => number_if(map, "analytic", false)?,
        Some(ClosedForm::Total(t)) => {
            let a = number(map, "analytic")?;
            if a != t {
                return Err(inconsistent(format!(
                    "analytic {a} differs from `lambert analytic` {t}"
                )));
            }
            Some(a)
        }
        None => match map.get("analytic") {
            Some(Value::Null) => None,
            _ => Some(number(map, "analytic")?),
        },
    };
    number_if(map, "rel_error", analytic.is_some_and(|a| a != 0.0))?;
    number_if(
        map,
        "z",
        analytic.is_some() && se > 0.0 && interval == Some("clt"),
    )?;
    if !(mean >= 0.0) {
        return Err(inconsistent(format!("mean {mean} < 0")));
    }
    if !(se >= 0.0) {
        return Err(inconsistent(format!("std_error {se} < 0")));
    }
    if !(ci.0 <= mean && mean <= ci.1) {
        return Err(inconsistent(format!(
            "ci99 [{}, {}] does not contain the mean {mean}",
            ci.0, ci.1
        )));
    }
    Ok(())
}

/// Every number in `v` finite and no `null` anywhere (render's summary).
fn all_finite(v: &Value, path: &str) -> Result<(), Failure> {
    match v {
        Value::Null => Err(Failure {
            class: Class::NonFinite,
            detail: format!("`{path}` is null"),
        }),
        Value::Number(n) if !n.as_f64().is_some_and(f64::is_finite) => Err(Failure {
            class: Class::NonFinite,
            detail: format!("`{path}` = {n}"),
        }),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .try_for_each(|(i, x)| all_finite(x, &format!("{path}[{i}]"))),
        Value::Object(m) => m.iter().try_for_each(|(k, x)| {
            let p = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            all_finite(x, &p)
        }),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calls;

    fn outcome(code: i32, stdout: &str, stderr: &str) -> Outcome {
        Outcome {
            exit: Exit::Code(code),
            stdout: stdout.into(),
            stderr: stderr.into(),
            seconds: 0.01,
        }
    }

    fn class(v: Verdict) -> Option<Class> {
        match v {
            Verdict::Failed(f) => Some(f.class),
            _ => None,
        }
    }

    #[test]
    fn field_names_are_recognised() {
        assert!(names_a_field(
            "error: s.toml: emitters[0].radius: must be positive",
            Some(1)
        ));
        assert!(!names_a_field("error: emitters[3].radius: bad", Some(2)));
        assert!(names_a_field(
            "error: s.toml: receiver.normal: must be a non-zero vector",
            None
        ));
        assert!(names_a_field(
            "error: scene file: TOML parse error at line 4, column 9",
            None
        ));
        assert!(names_a_field("error: --samples: must be at least 2", None));
        assert!(!names_a_field(
            "error: --statistics: 0 sample(s) held, at least 1 needed",
            None
        ));
        assert!(!names_a_field("error: the estimate overflowed", Some(1)));
        assert!(names_a_field(
            "error: s.toml: irradiance: the sum overflows",
            Some(1)
        ));
        assert!(names_a_field(
            "error: rel_error: the relative error overflows",
            Some(1)
        ));
        assert!(!names_a_field("error: s.toml: zero: bad", Some(1)));
    }

    #[test]
    fn analytic_contract() {
        let call = calls::analytic();
        let ctx = Context {
            emitters: Some(2),
            ..Context::default()
        };
        let ok = outcome(0, "{\"irradiance\":3.0,\"per_emitter\":[1.0,2.0]}\n", "");
        assert_eq!(judge(&call, &ok, &ctx), Verdict::Answered);
        let null = outcome(0, "{\"irradiance\":null,\"per_emitter\":[null,1.0]}\n", "");
        assert_eq!(class(judge(&call, &null, &ctx)), Some(Class::NonFinite));
        let sum = outcome(0, "{\"irradiance\":4.0,\"per_emitter\":[1.0,2.0]}\n", "");
        assert_eq!(class(judge(&call, &sum, &ctx)), Some(Class::Inconsistent));
        let refused = outcome(
            2,
            "",
            "error: s.toml: emitters[1].radiance: must be finite\n",
        );
        assert_eq!(judge(&call, &refused, &ctx), Verdict::Refused);
        let vague = outcome(2, "", "error: something went wrong\n");
        assert_eq!(class(judge(&call, &vague, &ctx)), Some(Class::NoField));
        let half = outcome(2, "{}", "error: emitters[0].radius: bad\n");
        assert_eq!(class(judge(&call, &half, &ctx)), Some(Class::HalfWritten));
        let panic = outcome(101, "", "thread 'main' panicked at src/x.rs:1:1:\noops\n");
        assert_eq!(class(judge(&call, &panic, &ctx)), Some(Class::Panic));
        let hang = Outcome {
            exit: Exit::TimedOut,
            ..outcome(0, "", "")
        };
        assert_eq!(class(judge(&call, &hang, &ctx)), Some(Class::Hang));
    }

    #[test]
    fn render_contract() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("image.exr");
        let call = Call::from_template("render {scene} --out {out} --json").unwrap();
        let ctx = Context {
            out_file: Some(&out),
            ..Context::default()
        };
        let summary = outcome(0, "{\"seconds\":0.5,\"rays\":16}\n", "");
        assert_eq!(
            class(judge(&call, &summary, &ctx)),
            Some(Class::BadJson),
            "no file"
        );
        std::fs::write(&out, b"exr").unwrap();
        assert_eq!(judge(&call, &summary, &ctx), Verdict::Answered);
        let null = outcome(0, "{\"seconds\":0.5,\"error\":{\"mean\":null}}\n", "");
        assert_eq!(class(judge(&call, &null, &ctx)), Some(Class::NonFinite));
        let refused = outcome(2, "", "error: s.toml: emitters[0].radius: bad\n");
        assert_eq!(
            class(judge(&call, &refused, &ctx)),
            Some(Class::HalfWritten),
            "file left"
        );
        std::fs::remove_file(&out).unwrap();
        assert_eq!(judge(&call, &refused, &ctx), Verdict::Refused);
    }

    #[test]
    fn estimate_contract() {
        let call = Call::from_template("estimate {scene} --json --samples 64").unwrap();
        let line = |mean: &str, se: &str, analytic: &str, rel: &str, z: &str| {
            format!(
                "{{\"mean\":{mean},\"std_error\":{se},\"ci99\":[0.5,1.5],\"samples\":64,\"seconds\":0.1,\"ns_per_sample\":3.0,\"analytic\":{analytic},\"rel_error\":{rel},\"z\":{z},\"hits\":64,\"interval\":\"clt\",\"warning\":null,\"fallback\":null,\"precision\":\"f64\",\"f64_fallbacks\":[]}}\n"
            )
        };
        let ctx = Context {
            emitters: Some(1),
            closed_form: Some(ClosedForm::Total(1.0)),
            out_file: None,
        };
        let ok = outcome(0, &line("1.0", "0.1", "1.0", "0.0", "0.0"), "");
        assert_eq!(judge(&call, &ok, &ctx), Verdict::Answered);
        // An f64 call whose answer claims another precision is wrong.
        let f32_claim = outcome(
            0,
            &line("1.0", "0.1", "1.0", "0.0", "0.0").replace("\"f64\"", "\"f32\""),
            "",
        );
        assert_eq!(class(judge(&call, &f32_claim, &ctx)), Some(Class::BadJson));
        let exact = outcome(0, &line("1.0", "0.0", "1.0", "0.0", "null"), "");
        assert_eq!(judge(&call, &exact, &ctx), Verdict::Answered);
        let null_mean = outcome(0, &line("null", "0.1", "1.0", "0.0", "0.0"), "");
        assert_eq!(
            class(judge(&call, &null_mean, &ctx)),
            Some(Class::NonFinite)
        );
        let null_z = outcome(0, &line("1.0", "0.1", "1.0", "0.0", "null"), "");
        assert_eq!(class(judge(&call, &null_z, &ctx)), Some(Class::NonFinite));
        let differs = outcome(0, &line("1.0", "0.1", "2.0", "-0.5", "-10.0"), "");
        assert_eq!(
            class(judge(&call, &differs, &ctx)),
            Some(Class::Inconsistent)
        );
        let outside = outcome(0, &line("2.0", "0.1", "1.0", "1.0", "10.0"), "");
        assert_eq!(
            class(judge(&call, &outside, &ctx)),
            Some(Class::Inconsistent)
        );
        let refused = outcome(2, "", "error: s.toml: emitters[0] (sky): not finite\n");
        assert_eq!(class(judge(&call, &refused, &ctx)), Some(Class::Unanswered));
        let refused_too = Context {
            closed_form: Some(ClosedForm::Refused),
            ..ctx
        };
        assert_eq!(judge(&call, &refused, &refused_too), Verdict::Refused);
    }
}
