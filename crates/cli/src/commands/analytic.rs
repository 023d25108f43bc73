//! `lambert analytic SCENE`: the closed-form irradiance of a scene.

use std::path::PathBuf;

use clap::Args;
use lambert_light::Scene;
use serde_json::json;

use super::finite;

/// Options of `lambert analytic`.
#[derive(Args, Debug, Clone)]
pub struct AnalyticOptions {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Print JSON: {"irradiance": …, "per_emitter": […]}.
    #[arg(long)]
    pub json: bool,
}

/// A scene's closed-form irradiance, total and per emitter.
pub struct ClosedForm {
    /// Σ over emitters.
    pub total: f64,
    /// Each emitter's irradiance, in file order.
    pub per_emitter: Vec<f64>,
}

/// The closed form of every emitter, or `Ok(None)` if one has none.
///
/// # Errors
/// When an emitter's irradiance or the total is not a finite f64 (an
/// overflow names the emitter and its strength, [`super::finite`]).
pub fn closed_form(scene: &Scene) -> Result<Option<ClosedForm>, String> {
    let mut per_emitter = Vec::with_capacity(scene.emitters.len());
    let mut complete = true;
    for (i, e) in scene.emitters.iter().enumerate() {
        match e.closed_form_irradiance(&scene.receiver) {
            Some(v) => per_emitter.push(finite::emitter_irradiance(i, e, v)?),
            None => complete = false,
        }
    }
    if !complete {
        return Ok(None);
    }
    Ok(Some(ClosedForm {
        total: finite::total(&scene.emitters, &per_emitter)?,
        per_emitter,
    }))
}

/// Runs the command.
pub fn run(options: &AnalyticOptions) -> Result<(), String> {
    let scene =
        Scene::load(&options.scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let closed = closed_form(&scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let Some(c) = closed else {
        return Err(format!(
            "{}: this scene has no closed form (an emitter without one: {})",
            options.scene.display(),
            scene
                .emitters
                .iter()
                .enumerate()
                .filter(|(_, e)| e.closed_form_irradiance(&scene.receiver).is_none())
                .map(|(i, e)| format!("emitters[{i}] ({})", e.kind()))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    };
    if options.json {
        println!(
            "{}",
            json!({ "irradiance": c.total, "per_emitter": c.per_emitter })
        );
    } else {
        println!("E = {:.15e} W/m²", c.total);
        for (i, (e, v)) in scene.emitters.iter().zip(&c.per_emitter).enumerate() {
            println!("  emitters[{i}] {:<11} {v:.15e}", e.kind());
        }
    }
    Ok(())
}
