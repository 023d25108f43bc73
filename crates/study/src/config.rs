//! What a study runs: its scenes, strategies, sequences, N range, replicates
//! and seed; the built-in default and quick studies; custom studies from TOML.
//!
//! The TOML format (every key but `scenes` optional; unknown keys are errors
//! naming the field):
//!
//! ```toml
//! name = "my-study"                       # output folder name
//! strategies = ["light", "mis"]           # Strategy names (default: the eight of the built-in study)
//! sequences = ["independent", "sobol"]    # default: all three
//! precisions = ["f64", "f32"]             # per-sample arithmetic (default: ["f64"])
//! n_min_log2 = 5                          # N = 2^5 … 2^12
//! n_max_log2 = 12
//! replicates = 8                          # M
//! seed = 1
//! scenes = [
//!   "scenes/sphere.toml",                 # a scene file, relative to this file
//!   # an inline scene (TOML inline tables stay on one line)
//!   { name = "sky", receiver = { point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }, emitters = [{ kind = "sky", radiance = 1.0 }] },
//!   "builtin:uniform-sky",                # a built-in scene by name
//! ]
//! ```

use std::fmt;
use std::path::Path;

use serde::Deserialize;

use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::Strategy;
use lambert_light::builtin::builtin_scenes;
use lambert_light::scene::Scene;

/// A scene of a study, with its name and its closed-form irradiance.
#[derive(Clone, Debug)]
pub struct StudyScene {
    /// The name (a CSV field and part of plot file names).
    pub name: String,
    /// The scene.
    pub scene: Scene,
    /// The closed-form irradiance: the sum of every emitter's
    /// [`lambert_light::Emitter::closed_form_irradiance`], `None` if any emitter has
    /// none (then the study reports no error columns for the scene).
    pub reference: Option<f64>,
}

impl StudyScene {
    /// A named scene with its reference computed.
    pub fn new(name: impl Into<String>, scene: Scene) -> Self {
        let reference = scene
            .emitters
            .iter()
            .map(|e| e.closed_form_irradiance(&scene.receiver))
            .sum::<Option<f64>>();
        StudyScene {
            name: name.into(),
            scene,
            reference,
        }
    }
}

/// A study's configuration.
#[derive(Clone, Debug)]
pub struct StudyConfig {
    /// The study's name (the default output folder is
    /// [`StudyConfig::default_out_dir`], `notebooks-data/runs/<name>`).
    pub name: String,
    /// Scenes, in order.
    pub scenes: Vec<StudyScene>,
    /// Strategies, in order.
    pub strategies: Vec<Strategy>,
    /// Sequences, in order.
    pub sequences: Vec<SequenceKind>,
    /// Precisions of the per-sample arithmetic, in order: an axis of the
    /// study like the sequences (`precisions = ["f64", "f32"]`; the
    /// default is f64 alone). A row's
    /// `precision` column says which it used; with f32, an emitter that
    /// f32 cannot estimate accurately enough runs in f64
    /// ([`lambert_estimator::strategy::F32Fallback`]; `lambert estimate
    /// --precision f32` names them).
    pub precisions: Vec<Precision>,
    /// Smallest N = 2^n_min_log2.
    pub n_min_log2: u32,
    /// Largest N = 2^n_max_log2.
    pub n_max_log2: u32,
    /// Replicates M per row.
    pub replicates: usize,
    /// The study's base seed.
    pub seed: u64,
}

/// A study configuration that cannot be used: a message naming the field.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyError(pub String);

impl fmt::Display for StudyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for StudyError {}

/// The strategies of the built-in study.
pub const BUILTIN_STRATEGIES: [Strategy; 8] = Strategy::ALL;

/// The built-in study's seed.
pub const BUILTIN_SEED: u64 = 20261122;

/// The folder, relative to the working directory, under which studies are
/// written by default ([`StudyConfig::default_out_dir`]); git-ignored.
pub const RUNS_DIR: &str = "notebooks-data/runs";

fn all_builtin_scenes() -> Vec<StudyScene> {
    builtin_scenes()
        .into_iter()
        .map(|s| StudyScene::new(s.name, s.scene))
        .collect()
}

impl StudyConfig {
    /// The default study (`lambert study`, `cargo run --release`): every
    /// built-in scene × the eight strategies × the three sequences × N =
    /// 2^5 … 2^20 × 8 replicates. N starts at 2^5 because the randomized-QMC
    /// estimates need 2 samples in each of their 16 randomizations; 2^20 is
    /// the issue's size for a study that finishes in under two minutes on
    /// two cores (measured on a 2-core AVX-512 machine: 4,992 rows in 42 s;
    /// on a 2-core AVX2 machine without AVX-512, 173 to 232 s over three
    /// runs, so that target is not met there; README).
    pub fn builtin() -> Self {
        StudyConfig {
            name: "builtin".into(),
            scenes: all_builtin_scenes(),
            strategies: BUILTIN_STRATEGIES.to_vec(),
            sequences: SequenceKind::ALL.to_vec(),
            precisions: vec![Precision::F64],
            n_min_log2: 5,
            n_max_log2: 20,
            replicates: 8,
            seed: BUILTIN_SEED,
        }
    }

    /// Where `lambert study` writes this study when no `--out` is given,
    /// relative to the working directory: [`RUNS_DIR`]`/<name>`.
    ///
    /// Not `notebooks-data/<name>`: the repository keeps the built-in
    /// study's reference output in `notebooks-data/builtin/`, and its timing
    /// columns and plots change on every run, so a newcomer's first
    /// `cargo run --release` would leave the checkout modified. Runs go to
    /// `notebooks-data/runs/`, which the repository ignores; the reference
    /// is refreshed on purpose with `lambert study --out notebooks-data/builtin`.
    pub fn default_out_dir(&self) -> std::path::PathBuf {
        Path::new(RUNS_DIR).join(&self.name)
    }

    /// The quick study (`--quick`, run by CI): as the default but N = 2^5 …
    /// 2^14 (a few seconds).
    pub fn quick() -> Self {
        StudyConfig {
            name: "quick".into(),
            n_max_log2: 14,
            ..Self::builtin()
        }
    }

    /// Checks the ranges.
    pub fn validate(&self) -> Result<(), StudyError> {
        let err = |m: String| Err(StudyError(m));
        if self.name.is_empty() || self.name.contains(['/', '\\']) {
            return err(format!(
                "name: must be a non-empty folder name without slashes, got {:?}",
                self.name
            ));
        }
        if self.scenes.is_empty() {
            return err("scenes: a study needs at least one scene".into());
        }
        if self.strategies.is_empty() {
            return err("strategies: a study needs at least one strategy".into());
        }
        if self.sequences.is_empty() {
            return err("sequences: a study needs at least one sequence".into());
        }
        if self.precisions.is_empty() {
            return err("precisions: a study needs at least one precision".into());
        }
        if self.n_min_log2 < 1 {
            return err("n_min_log2: must be at least 1 (an estimate needs 2 samples)".into());
        }
        if self.n_max_log2 > 40 {
            return err(format!(
                "n_max_log2: must be at most 40, got {}",
                self.n_max_log2
            ));
        }
        if self.n_min_log2 > self.n_max_log2 {
            return err(format!(
                "n_min_log2: {} is larger than n_max_log2 {}",
                self.n_min_log2, self.n_max_log2
            ));
        }
        if self.replicates < 2 {
            return err(format!(
                "replicates: must be at least 2, got {}",
                self.replicates
            ));
        }
        let mut names = std::collections::HashSet::new();
        for s in &self.scenes {
            if s.name.is_empty() || s.name.contains([',', '"', '\n', '/', '\\']) {
                return err(format!(
                    "scenes: scene name {:?} must be non-empty, without commas, quotes or slashes",
                    s.name
                ));
            }
            if !names.insert(s.name.clone()) {
                return err(format!("scenes: the name {:?} is used twice", s.name));
            }
        }
        Ok(())
    }

    /// Parses a study file; scene paths are relative to `base_dir`.
    pub fn from_toml(text: &str, base_dir: &Path) -> Result<Self, StudyError> {
        let raw: RawStudy =
            toml::from_str(text).map_err(|e| StudyError(format!("study file: {e}")))?;
        let mut scenes = Vec::new();
        for (i, entry) in raw.scenes.iter().enumerate() {
            scenes.push(scene_entry(i, entry, base_dir)?);
        }
        let strategies = match raw.strategies {
            None => BUILTIN_STRATEGIES.to_vec(),
            Some(list) => list
                .iter()
                .map(|s| {
                    s.parse::<Strategy>()
                        .map_err(|e| StudyError(format!("strategies: {e}")))
                })
                .collect::<Result<_, _>>()?,
        };
        let sequences = match raw.sequences {
            None => SequenceKind::ALL.to_vec(),
            Some(list) => list
                .iter()
                .map(|s| {
                    s.parse::<SequenceKind>()
                        .map_err(|e| StudyError(format!("sequences: {e}")))
                })
                .collect::<Result<_, _>>()?,
        };
        let precisions = match raw.precisions {
            None => vec![Precision::F64],
            Some(list) => list
                .iter()
                .map(|s| {
                    s.parse::<Precision>()
                        .map_err(|e| StudyError(format!("precisions: {e}")))
                })
                .collect::<Result<_, _>>()?,
        };
        let default = Self::builtin();
        let config = StudyConfig {
            name: raw.name.unwrap_or_else(|| "custom".into()),
            scenes,
            strategies,
            sequences,
            precisions,
            n_min_log2: raw.n_min_log2.unwrap_or(default.n_min_log2),
            n_max_log2: raw.n_max_log2.unwrap_or(12),
            replicates: raw.replicates.unwrap_or(default.replicates),
            seed: raw.seed.unwrap_or(default.seed),
        };
        config.validate()?;
        Ok(config)
    }

    /// Reads and parses a study file.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| StudyError(format!("cannot read {}: {e}", path.display())))?;
        let base = path.parent().unwrap_or(Path::new("."));
        Self::from_toml(&text, base).map_err(|e| StudyError(format!("{}: {e}", path.display())))
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    name: Option<String>,
    scenes: Vec<toml::Value>,
    strategies: Option<Vec<String>>,
    sequences: Option<Vec<String>>,
    precisions: Option<Vec<String>>,
    n_min_log2: Option<u32>,
    n_max_log2: Option<u32>,
    replicates: Option<usize>,
    seed: Option<u64>,
}

fn scene_entry(i: usize, entry: &toml::Value, base_dir: &Path) -> Result<StudyScene, StudyError> {
    let at = |m: String| StudyError(format!("scenes[{i}]: {m}"));
    match entry {
        toml::Value::String(s) => {
            if let Some(name) = s.strip_prefix("builtin:") {
                return all_builtin_scenes()
                    .into_iter()
                    .find(|b| b.name == name)
                    .ok_or_else(|| at(format!("no built-in scene named {name:?}")));
            }
            let path = base_dir.join(s);
            let scene = Scene::load(&path).map_err(|e| at(e.to_string()))?;
            let name = Path::new(s)
                .file_stem()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| format!("scene-{i}"));
            Ok(StudyScene::new(name, scene))
        }
        toml::Value::Table(t) => {
            let mut t = t.clone();
            let name = match t.remove("name") {
                None => format!("scene-{i}"),
                Some(toml::Value::String(n)) => n,
                Some(other) => return Err(at(format!("name: expected a string, got {other}"))),
            };
            let text = toml::to_string(&t).map_err(|e| at(e.to_string()))?;
            let scene = Scene::from_toml(&text).map_err(|e| at(e.to_string()))?;
            Ok(StudyScene::new(name, scene))
        }
        other => Err(at(format!(
            "expected a scene table or a path, got {}",
            other.type_str()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_inline_and_builtin_scenes() {
        let text = r#"
            name = "t"
            strategies = ["light", "mis", "projected", "control-variate"]
            sequences = ["sobol"]
            n_min_log2 = 6
            n_max_log2 = 8
            replicates = 3
            seed = 7
            scenes = [
              { name = "sky", receiver = { point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }, emitters = [{ kind = "sky", radiance = 2.0 }] },
              "builtin:triangle",
            ]
        "#;
        let c = StudyConfig::from_toml(text, Path::new(".")).unwrap();
        assert_eq!(c.name, "t");
        assert_eq!(c.scenes.len(), 2);
        assert_eq!(c.scenes[0].name, "sky");
        assert_eq!(c.scenes[0].reference, Some(2.0 * std::f64::consts::PI));
        assert_eq!(
            c.strategies,
            vec![
                Strategy::Light,
                Strategy::Mis(lambert_estimator::strategy::Heuristic::Power),
                Strategy::Projected,
                Strategy::ControlVariate
            ]
        );
        assert_eq!(c.sequences, vec![SequenceKind::Sobol]);
        assert_eq!(
            (c.n_min_log2, c.n_max_log2, c.replicates, c.seed),
            (6, 8, 3, 7)
        );
    }

    #[test]
    fn errors_name_the_field() {
        let e = StudyConfig::from_toml("scenes = []\nreplicate = 3", Path::new("."))
            .unwrap_err()
            .0;
        assert!(e.contains("replicate"), "{e}");
        let e = StudyConfig::from_toml("scenes = [\"builtin:nope\"]", Path::new("."))
            .unwrap_err()
            .0;
        assert!(e.contains("scenes[0]") && e.contains("nope"), "{e}");
        let e = StudyConfig::from_toml(
            "scenes = [\"builtin:triangle\"]\nstrategies = [\"best\"]",
            Path::new("."),
        )
        .unwrap_err()
        .0;
        assert!(e.contains("strategies"), "{e}");
        let e = StudyConfig::from_toml(
            "scenes = [{ receiver = { point = [0.0,0.0,0.0], normal = [0.0,0.0,1.0] }, emitters = [{ kind = \"sky\", radiance = 1.0, colour = 2 }] }]",
            Path::new("."),
        )
        .unwrap_err()
        .0;
        assert!(e.contains("colour"), "{e}");
        let e = StudyConfig::from_toml(
            "scenes = [\"builtin:triangle\"]\nn_min_log2 = 9\nn_max_log2 = 8",
            Path::new("."),
        )
        .unwrap_err()
        .0;
        assert!(e.contains("n_min_log2"), "{e}");
        let e = StudyConfig::from_toml(
            "scenes = [\"builtin:triangle\"]\nprecisions = [\"f64\", \"f16\"]",
            Path::new("."),
        )
        .unwrap_err()
        .0;
        assert!(e.contains("precisions") && e.contains("\"f16\""), "{e}");
        let e = StudyConfig::from_toml(
            "scenes = [\"builtin:triangle\"]\nprecisions = []",
            Path::new("."),
        )
        .unwrap_err()
        .0;
        assert!(e.contains("precisions"), "{e}");
    }

    /// `precisions` is an axis of the plan (inside the sequences, outside
    /// N), f64 alone by default; each row carries its precision.
    #[test]
    fn precisions_are_an_axis_of_the_plan() {
        use lambert_estimator::precision::Precision;
        let base = "scenes = [\"builtin:triangle\"]\nstrategies = [\"light\"]\nsequences = [\"independent\"]\nn_min_log2 = 5\nn_max_log2 = 6\n";
        let c = StudyConfig::from_toml(base, Path::new(".")).unwrap();
        assert_eq!(c.precisions, vec![Precision::F64]);
        let c = StudyConfig::from_toml(
            &format!("{base}precisions = [\"f64\", \"f32\"]"),
            Path::new("."),
        )
        .unwrap();
        let rows = crate::plan::plan(&c);
        let got: Vec<_> = rows.iter().map(|r| (r.precision, r.log2_n)).collect();
        assert_eq!(
            got,
            vec![
                (Precision::F64, 5),
                (Precision::F64, 6),
                (Precision::F32, 5),
                (Precision::F32, 6)
            ]
        );
    }

    #[test]
    fn builtin_and_quick_are_valid() {
        StudyConfig::builtin().validate().unwrap();
        StudyConfig::quick().validate().unwrap();
    }

    /// The kernel sweep the README points to loads: eight emitter scenes
    /// × six strategies × two precisions at one N, one row each.
    #[test]
    fn kernel_sweep_file_is_valid() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/studies/kernel-sweep.toml");
        let c = StudyConfig::load(&path).unwrap();
        c.validate().unwrap();
        assert_eq!(c.scenes.len(), 8);
        assert_eq!(crate::plan::plan(&c).len(), 8 * 6 * 2);
    }
}
