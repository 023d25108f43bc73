//! A greedy shrinker: the smallest scene it can find that still makes one
//! call fail with the same class.
//!
//! On a file it can read as a scene tree ([`SceneFile`]) it tries, in turn,
//! removing an emitter, a top-level extra, a field, a polygon vertex, and
//! replacing a number by a simpler one (0, ±1, a power of ten, one or three
//! significant digits); on other text it removes lines. A candidate is kept
//! only if its text is strictly shorter and the call still fails with the
//! same class, so the search ends. Delta debugging in its simplest,
//! one-at-a-time form (Zeller & Hildebrandt 2002).

use std::path::Path;
use std::time::Duration;

use crate::calls::{with_closed_form, Call};
use crate::campaign::run_calls;
use crate::oracle::{Class, Verdict};
use crate::scene::{SceneFile, Value};

/// Simpler numbers to try in place of `x`, shortest first.
fn simpler(x: f64) -> Vec<f64> {
    let mut out = vec![0.0, 1.0, -1.0];
    if x.is_finite() && x != 0.0 {
        let p = 10f64.powi(x.abs().log10().round() as i32);
        if p.is_finite() && p > 0.0 {
            out.push(p.copysign(x));
        }
        for digits in [0, 2] {
            if let Ok(y) = format!("{x:.digits$e}").parse::<f64>() {
                out.push(y);
            }
        }
    }
    out
}

/// Every one-step simplification of `file`.
fn candidates(file: &SceneFile) -> Vec<SceneFile> {
    let mut out = Vec::new();
    for i in 0..file.emitters.len() {
        let mut f = file.clone();
        f.emitters.remove(i);
        out.push(f);
    }
    for i in 0..file.extra.len() {
        let mut f = file.clone();
        f.extra.remove(i);
        out.push(f);
    }
    let tables = file.receiver.iter().count() + file.emitters.len();
    for t in 0..tables {
        let fields = table(file, t).fields.len();
        for k in 0..fields {
            let mut f = file.clone();
            table_mut(&mut f, t).fields.remove(k);
            out.push(f);
            let value = table(file, t).fields[k].1.clone();
            for v in simpler_values(&value) {
                let mut f = file.clone();
                table_mut(&mut f, t).fields[k].1 = v;
                out.push(f);
            }
        }
    }
    out
}

fn table(file: &SceneFile, t: usize) -> &crate::scene::Table {
    match (&file.receiver, t) {
        (Some(r), 0) => r,
        (Some(_), t) => &file.emitters[t - 1],
        (None, t) => &file.emitters[t],
    }
}

fn table_mut(file: &mut SceneFile, t: usize) -> &mut crate::scene::Table {
    match (&mut file.receiver, t) {
        (Some(r), 0) => r,
        (Some(_), t) => &mut file.emitters[t - 1],
        (None, t) => &mut file.emitters[t],
    }
}

fn simpler_values(value: &Value) -> Vec<Value> {
    match value {
        Value::Float(x) => simpler(*x).into_iter().map(Value::Float).collect(),
        Value::Vector(v) => (0..3)
            .flat_map(|i| {
                simpler(v[i]).into_iter().map(move |y| {
                    let mut w = *v;
                    w[i] = y;
                    Value::Vector(w)
                })
            })
            .collect(),
        Value::Vectors(vs) => {
            let mut out: Vec<Value> = (0..vs.len())
                .map(|i| {
                    let mut w = vs.clone();
                    w.remove(i);
                    Value::Vectors(w)
                })
                .collect();
            for i in 0..vs.len() {
                for j in 0..3 {
                    for y in simpler(vs[i][j]) {
                        let mut w = vs.clone();
                        w[i][j] = y;
                        out.push(Value::Vectors(w));
                    }
                }
            }
            out
        }
        _ => Vec::new(),
    }
}

/// Every one-line deletion of `text`.
fn line_candidates(text: &str) -> Vec<String> {
    let lines: Vec<&str> = text.lines().collect();
    (0..lines.len())
        .map(|i| {
            let mut l = lines.clone();
            l.remove(i);
            let mut s = l.join("\n");
            s.push('\n');
            s
        })
        .collect()
}

/// Shrinks `text` while `call` keeps failing with `class` (each trial
/// within `limit`; at most `max_trials` trials). Returns the smallest text
/// found and the number of trials run.
///
/// # Errors
/// When the binary cannot be run.
pub fn shrink(
    binary: &Path,
    text: &str,
    call: &Call,
    class: Class,
    limit: Duration,
    max_trials: usize,
) -> Result<(String, usize), String> {
    let dir = tempfile::Builder::new()
        .prefix("lambert-shrink-")
        .tempdir()
        .map_err(|e| e.to_string())?;
    let path = dir.path().join("scene.toml");
    let trials = std::cell::Cell::new(0usize);
    let calls = with_closed_form(std::slice::from_ref(call));
    let fails = |t: &str| -> Result<bool, String> {
        trials.set(trials.get() + 1);
        let r = run_calls(binary, t, &calls, &path, limit)
            .map_err(|e| format!("{}: {e}", binary.display()))?;
        Ok(matches!(r.last(), Some((_, Verdict::Failed(f), _)) if f.class == class))
    };
    if !fails(text)? {
        return Err(format!(
            "the call does not fail with class {class} on this input"
        ));
    }
    let mut best = text.to_owned();
    // A structured pass on the canonical form (if it still fails), then
    // line deletion.
    if let Some(file) = SceneFile::from_toml(text) {
        let canonical = file.to_toml();
        if canonical.len() <= best.len() && fails(&canonical)? {
            best = canonical;
        }
    }
    'outer: loop {
        let cands: Vec<String> = match SceneFile::from_toml(&best) {
            Some(file) if file.to_toml() == best => {
                candidates(&file).iter().map(SceneFile::to_toml).collect()
            }
            _ => line_candidates(&best),
        };
        for c in cands {
            if trials.get() >= max_trials {
                break 'outer;
            }
            if c.len() < best.len() && fails(&c)? {
                best = c;
                continue 'outer;
            }
        }
        break;
    }
    Ok((best, trials.get()))
}
