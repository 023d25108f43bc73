//! The `lambert` calls made on each scene: `analytic --json`, `estimate
//! --json` with every strategy, and `render` when the binary has it.
//!
//! A call is a command name and an argument template in which `{scene}`
//! stands for the scene file and `{out}` for a file the call may write
//! (render's image). The render call is a template so that it can follow
//! the subcommand's options as they settle (`--render-args`).

use rand::Rng;

/// The strategies of `lambert estimate --strategy`, as a user's script
/// names them (the fuzzer knows the command line's vocabulary, not the
/// library's types, so that it tests what a user sees).
pub const STRATEGIES: [&str; 7] = [
    "auto",
    "uniform-hemisphere",
    "cosine-hemisphere",
    "light",
    "area",
    "mis",
    "mis-balance",
];

/// The default render template: a tiny irradiance image with a few samples
/// per pixel, JSON summary on stdout.
pub const DEFAULT_RENDER_ARGS: &str =
    "render {scene} --mode irradiance --width 4 --height 4 --spp 4 --out {out} --json";

/// Which subcommand a call runs (the oracle checks each one's output
/// contract).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Command {
    /// `lambert analytic --json`.
    Analytic,
    /// `lambert estimate --json`.
    Estimate,
    /// `lambert render`.
    Render,
}

impl Command {
    /// The subcommand's name.
    pub fn name(self) -> &'static str {
        match self {
            Command::Analytic => "analytic",
            Command::Estimate => "estimate",
            Command::Render => "render",
        }
    }

    /// The command of that name.
    pub fn from_name(name: &str) -> Option<Command> {
        match name {
            "analytic" => Some(Command::Analytic),
            "estimate" => Some(Command::Estimate),
            "render" => Some(Command::Render),
            _ => None,
        }
    }
}

/// One call of the binary.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Call {
    /// The subcommand.
    pub command: Command,
    /// The arguments, with `{scene}` and `{out}` placeholders.
    pub args: Vec<String>,
}

impl Call {
    /// The call from a whitespace-separated template (its first word is the
    /// subcommand); `None` for an unknown subcommand.
    pub fn from_template(template: &str) -> Option<Call> {
        let args: Vec<String> = template.split_whitespace().map(str::to_owned).collect();
        let command = Command::from_name(args.first()?)?;
        Some(Call { command, args })
    }

    /// The arguments with the placeholders filled in.
    pub fn argv(&self, scene: &str, out: &str) -> Vec<String> {
        self.args
            .iter()
            .map(|a| a.replace("{scene}", scene).replace("{out}", out))
            .collect()
    }

    /// The call as a shell line (`lambert estimate SCENE --json …`).
    pub fn label(&self) -> String {
        let argv = self.argv("SCENE", "OUT");
        format!("lambert {}", argv.join(" "))
    }

    /// The value of option `--name`, if given.
    pub fn option(&self, name: &str) -> Option<&str> {
        let flag = format!("--{name}");
        let i = self.args.iter().position(|a| *a == flag)?;
        self.args.get(i + 1).map(String::as_str)
    }
}

/// `lambert analytic {scene} --json`.
pub fn analytic() -> Call {
    Call {
        command: Command::Analytic,
        args: ["analytic", "{scene}", "--json"]
            .map(str::to_owned)
            .to_vec(),
    }
}

/// `lambert estimate {scene} --json` with `strategy` and a random
/// sequence (independent 70 %, stratified and Sobol 15 % each), a small
/// sample count (the sequence's minimum up to 256), a random seed, and two
/// threads one time in five.
pub fn estimate<R: Rng>(rng: &mut R, strategy: &str) -> Call {
    let sequence = match rng.random_range(0..20) {
        0..=13 => "independent",
        14..=16 => "stratified",
        _ => "sobol",
    };
    let minimum = if sequence == "independent" { 2 } else { 32 };
    let samples = [minimum, 64, 64, 100, 256][rng.random_range(0..5)];
    let seed = rng.random_range(0..1000u32);
    let mut args: Vec<String> = [
        "estimate",
        "{scene}",
        "--json",
        "--strategy",
        strategy,
        "--sequence",
        sequence,
        "--samples",
        &samples.to_string(),
        "--seed",
        &seed.to_string(),
    ]
    .map(str::to_owned)
    .to_vec();
    if rng.random_bool(0.2) {
        args.extend(["--threads".to_owned(), "2".to_owned()]);
    }
    Call {
        command: Command::Estimate,
        args,
    }
}

/// `calls` with `analytic` put first when an estimate is among them and
/// analytic is not: the estimates' `analytic` field, and whether a refusal
/// is a clear error or an unanswered scene, are judged against it.
pub fn with_closed_form(calls: &[Call]) -> Vec<Call> {
    let mut out = Vec::with_capacity(calls.len() + 1);
    let has = |c: Command| calls.iter().any(|x| x.command == c);
    if has(Command::Estimate) && !has(Command::Analytic) {
        out.push(analytic());
    }
    out.extend(calls.iter().cloned());
    out
}

/// The calls made on one scene: analytic first (the estimates are checked
/// against its answer), then one estimate per strategy, then `render` if
/// a template is given.
pub fn for_scene<R: Rng>(rng: &mut R, render: Option<&Call>) -> Vec<Call> {
    let mut calls = vec![analytic()];
    calls.extend(STRATEGIES.iter().map(|s| estimate(rng, s)));
    calls.extend(render.cloned());
    calls
}
