//! The regression corpus: every input the fuzzer has found failing, kept
//! as a small TOML scene file with a header of `# key: value` comments.
//!
//! ```text
//! # symptom: `analytic` printed {"irradiance": null} with exit code 0
//! # place: crates/cli/src/commands/analytic.rs (no check that the sum is finite)
//! # call: analytic {scene} --json
//! # failed: non-finite
//! # matches: any
//! [receiver]
//! …
//! ```
//!
//! - `fixed/` holds the cases that must now be answered or refused
//!   correctly: the replay test runs each through its `call:` lines and
//!   through [`replay_calls`] (analytic and every strategy), and fails on
//!   any failure.
//! - `open/` holds the known-open cases, whose fix lives outside the CLI:
//!   the replay test runs their `call:` lines and only reports whether
//!   they still fail. Their `failed:` class and `matches:` predicate also
//!   let a fuzz run count a failure of that class on a matching scene as
//!   known-open rather than new (see [`KnownOpen`]).

use std::path::{Path, PathBuf};

use glam::DVec3;

use crate::calls::{self, Call};
use crate::oracle::Class;
use crate::scene::SceneFile;

/// One corpus file.
#[derive(Clone, Debug)]
pub struct Entry {
    /// Its path.
    pub path: PathBuf,
    /// The whole text (header comments and scene).
    pub text: String,
    /// The `symptom:` line.
    pub symptom: String,
    /// The `place:` line (where the defect lives, or lived).
    pub place: String,
    /// The `call:` lines: the calls that failed.
    pub calls: Vec<Call>,
    /// The `failed:` class: what those calls did.
    pub failed: Option<Class>,
    /// The `matches:` predicate (open cases).
    pub matches: Option<Predicate>,
}

/// Which scenes a known-open failure class covers, for counting a fuzz
/// run's failures as known rather than new.
#[derive(Clone, Debug, PartialEq)]
pub enum Predicate {
    /// Every scene.
    Any,
    /// Scenes with an emitter of this kind.
    Kind(String),
    /// Scenes with a disk whose plane crosses the receiver's plane inside
    /// the disk (the disk straddles the receiver's horizon).
    DiskStraddlesHorizon,
    /// Scenes with an emitter whose strength (`radiance`, `intensity`,
    /// `flux` or `irradiance`) is at least this.
    StrengthAbove(f64),
}

impl Predicate {
    /// Parses `any`, `kind:<kind>`, `disk-straddles-horizon` or
    /// `strength-above:<number>`.
    pub fn parse(text: &str) -> Option<Predicate> {
        match text.trim() {
            "any" => Some(Predicate::Any),
            "disk-straddles-horizon" => Some(Predicate::DiskStraddlesHorizon),
            t => {
                if let Some(k) = t.strip_prefix("kind:") {
                    Some(Predicate::Kind(k.trim().to_owned()))
                } else {
                    let x: f64 = t.strip_prefix("strength-above:")?.trim().parse().ok()?;
                    Some(Predicate::StrengthAbove(x))
                }
            }
        }
    }

    /// Whether the scene text satisfies the predicate.
    pub fn holds(&self, text: &str) -> bool {
        match self {
            Predicate::Any => true,
            Predicate::Kind(k) => SceneFile::from_toml(text)
                .is_some_and(|f| f.emitters.iter().any(|e| e.text("kind") == Some(k))),
            Predicate::DiskStraddlesHorizon => {
                SceneFile::from_toml(text).is_some_and(|f| disk_straddles_horizon(&f))
            }
            Predicate::StrengthAbove(x) => SceneFile::from_toml(text).is_some_and(|f| {
                f.emitters.iter().any(|e| {
                    ["radiance", "intensity", "flux", "irradiance"]
                        .iter()
                        .any(|k| e.float(k).is_some_and(|v| v >= *x))
                })
            }),
        }
    }
}

/// `v` scaled to unit length (by its largest component first, so that
/// neither 1e-300 nor 1e300 components are lost).
fn unit(v: [f64; 3]) -> Option<DVec3> {
    let v = DVec3::from_array(v);
    let m = v.abs().max_element();
    if !(m > 0.0) || !m.is_finite() {
        return None;
    }
    (v / m).try_normalize()
}

/// Whether some disk of the file crosses the receiver's plane: its centre
/// is closer to that plane than the disk's half-extent across it,
/// R·|m × n| (m, n the unit normals).
fn disk_straddles_horizon(file: &SceneFile) -> bool {
    let Some(r) = &file.receiver else {
        return false;
    };
    let (Some(p), Some(n)) = (r.vector("point"), r.vector("normal").and_then(unit)) else {
        return false;
    };
    file.emitters.iter().any(|e| {
        if e.text("kind") != Some("disk") {
            return false;
        }
        let (Some(c), Some(m), Some(radius)) = (
            e.vector("center"),
            e.vector("normal").and_then(unit),
            e.float("radius"),
        ) else {
            return false;
        };
        let height = n.dot(DVec3::from_array(c) - DVec3::from_array(p));
        height.abs() < radius * m.cross(n).length()
    })
}

/// A failure class that is known and open: a fuzz run counts a failure
/// of `class` on a scene satisfying `matches`, from a call like one of
/// `calls` (the same subcommand and, for estimates, the same strategy), as
/// known.
#[derive(Clone, Debug)]
pub struct KnownOpen {
    /// The corpus file that documents it.
    pub path: PathBuf,
    /// The failure class.
    pub class: Class,
    /// The calls it shows in.
    pub calls: Vec<Call>,
    /// The scenes it covers.
    pub matches: Predicate,
}

impl KnownOpen {
    /// Whether a failure of `class` from `call` on `text` is this one.
    pub fn covers(&self, class: Class, call: &Call, text: &str) -> bool {
        self.class == class
            && self.calls.iter().any(|c| {
                c.command == call.command
                    && c.option("strategy")
                        .is_none_or(|s| call.option("strategy") == Some(s))
            })
            && self.matches.holds(text)
    }
}

impl Entry {
    /// Parses a corpus file's text.
    pub fn parse(path: &Path, text: &str) -> Result<Entry, String> {
        let mut entry = Entry {
            path: path.to_owned(),
            text: text.to_owned(),
            symptom: String::new(),
            place: String::new(),
            calls: Vec::new(),
            failed: None,
            matches: None,
        };
        for line in text.lines() {
            let Some(comment) = line.strip_prefix('#') else {
                continue;
            };
            let Some((key, value)) = comment.split_once(':') else {
                continue;
            };
            let value = value.trim();
            match key.trim() {
                "symptom" => entry.symptom = value.to_owned(),
                "place" => entry.place = value.to_owned(),
                "call" => entry.calls.push(Call::from_template(value).ok_or_else(|| {
                    format!("{}: `call: {value}` is not a lambert call", path.display())
                })?),
                "failed" => {
                    entry.failed = Some(Class::from_name(value).ok_or_else(|| {
                        format!("{}: unknown failure class {value:?}", path.display())
                    })?)
                }
                "matches" => {
                    entry.matches = Some(Predicate::parse(value).ok_or_else(|| {
                        format!("{}: unknown predicate {value:?}", path.display())
                    })?)
                }
                _ => {}
            }
        }
        if entry.symptom.is_empty() || entry.calls.is_empty() {
            return Err(format!(
                "{}: a corpus file needs `# symptom:` and `# call:` lines",
                path.display()
            ));
        }
        Ok(entry)
    }

    /// The known-open class this (open) entry documents.
    pub fn known_open(&self) -> Option<KnownOpen> {
        Some(KnownOpen {
            path: self.path.clone(),
            class: self.failed?,
            calls: self.calls.clone(),
            matches: self.matches.clone()?,
        })
    }

    /// The header in the corpus format, followed by `scene`.
    pub fn format(
        symptom: &str,
        place: &str,
        calls: &[Call],
        failed: Class,
        scene: &str,
    ) -> String {
        let mut out = format!("# symptom: {symptom}\n# place: {place}\n");
        for c in calls {
            out.push_str(&format!("# call: {}\n", c.args.join(" ")));
        }
        out.push_str(&format!("# failed: {failed}\n"));
        out.push_str(scene);
        out
    }
}

/// Every `*.toml` file of `dir`, sorted by name.
pub fn load_dir(dir: &Path) -> Result<Vec<Entry>, String> {
    let read = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut paths: Vec<PathBuf> = read
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    paths
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))?;
            Entry::parse(p, &text)
        })
        .collect()
}

/// The calls every fixed case is replayed through besides its own:
/// `analytic`, and `estimate` with every strategy (64 samples, seed 1,
/// the sequences taken in turn).
pub fn replay_calls() -> Vec<Call> {
    let mut out = vec![calls::analytic()];
    let sequences = ["independent", "stratified", "sobol"];
    for (i, s) in calls::STRATEGIES.iter().enumerate() {
        let template = format!(
            "estimate {{scene}} --json --strategy {s} --sequence {} --samples 64 --seed 1",
            sequences[i % 3]
        );
        out.extend(Call::from_template(&template));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const STRADDLING: &str = "[receiver]\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]\n\n[[emitters]]\nkind = \"disk\"\ncenter = [0.0, 0.0, 0.5]\nnormal = [1.0, 0.0, 0.0]\nradius = 1.0\nradiance = 1.0\n";

    #[test]
    fn predicates() {
        assert!(Predicate::DiskStraddlesHorizon.holds(STRADDLING));
        let above = STRADDLING.replace("radius = 1.0", "radius = 0.4");
        assert!(!Predicate::DiskStraddlesHorizon.holds(&above));
        let facing = STRADDLING.replace("normal = [1.0, 0.0, 0.0]", "normal = [0.0, 0.0, -1.0]");
        assert!(!Predicate::DiskStraddlesHorizon.holds(&facing));
        assert!(Predicate::Kind("disk".into()).holds(STRADDLING));
        assert!(!Predicate::Kind("sky".into()).holds(STRADDLING));
        assert_eq!(
            Predicate::parse("strength-above:1e150"),
            Some(Predicate::StrengthAbove(1e150))
        );
        assert!(Predicate::StrengthAbove(0.5).holds(STRADDLING));
        assert!(!Predicate::StrengthAbove(2.0).holds(STRADDLING));
    }

    #[test]
    fn header_round_trip() {
        let call = calls::analytic();
        let text = Entry::format(
            "null irradiance",
            "cli",
            std::slice::from_ref(&call),
            Class::NonFinite,
            STRADDLING,
        );
        let mut with_match = text.replace("# failed:", "# matches: kind:disk\n# failed:");
        with_match.push('\n');
        let e = Entry::parse(Path::new("x.toml"), &with_match).unwrap();
        assert_eq!(e.symptom, "null irradiance");
        assert_eq!(e.calls, vec![call.clone()]);
        assert_eq!(e.failed, Some(Class::NonFinite));
        let k = e.known_open().unwrap();
        assert!(k.covers(Class::NonFinite, &call, STRADDLING));
        assert!(!k.covers(Class::Hang, &call, STRADDLING));
        let light = Call::from_template("estimate {scene} --json --strategy light").unwrap();
        let mis = Call::from_template("estimate {scene} --json --strategy mis").unwrap();
        let only_mis = KnownOpen {
            calls: vec![mis.clone()],
            ..k
        };
        assert!(only_mis.covers(Class::NonFinite, &mis, STRADDLING));
        assert!(!only_mis.covers(Class::NonFinite, &light, STRADDLING));
        assert!(!only_mis.covers(Class::NonFinite, &call, STRADDLING));
    }
}
