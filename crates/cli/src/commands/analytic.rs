//! `lambert analytic SCENE`: the closed-form irradiance of a scene.

use std::path::PathBuf;

use clap::Args;
use lambert_light::Scene;
use serde_json::json;

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

/// The closed form of every emitter, or `None` if one has none.
pub fn closed_form(scene: &Scene) -> Option<ClosedForm> {
    let per_emitter: Option<Vec<f64>> = scene
        .emitters
        .iter()
        .map(|e| e.closed_form_irradiance(&scene.receiver))
        .collect();
    let per_emitter = per_emitter?;
    Some(ClosedForm {
        total: per_emitter.iter().sum(),
        per_emitter,
    })
}

/// Runs the command.
pub fn run(options: &AnalyticOptions) -> Result<(), String> {
    let scene =
        Scene::load(&options.scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let Some(c) = closed_form(&scene) else {
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
