//! `lambert analytic SCENE`: the closed-form irradiance of a scene.

use std::path::PathBuf;

use clap::Args;
use lambert_light::analytic::AnalyticError;
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

/// The closed form of every emitter, or `Ok(None)` with the reason when
/// one could not be resolved within its work bound (a disk cut by the
/// receiver's plane whose rim quadrature did not reach its error target).
///
/// # Errors
/// When an emitter's irradiance or the total is beyond the f64 range (the
/// message names the emitter and its strength, [`super::finite`]), or the
/// closed form rejects the geometry.
pub fn closed_form(scene: &Scene) -> Result<Result<ClosedForm, String>, String> {
    let mut per_emitter = Vec::with_capacity(scene.emitters.len());
    for (i, e) in scene.emitters.iter().enumerate() {
        match e.try_closed_form_irradiance(&scene.receiver) {
            Ok(v) => per_emitter.push(finite::emitter_irradiance(i, e, v)?),
            Err(AnalyticError::Overflow { .. }) => {
                finite::emitter_irradiance(i, e, f64::INFINITY)?;
            }
            Err(unresolved @ AnalyticError::Unresolved { .. }) => {
                return Ok(Err(format!("emitters[{i}] ({}): {unresolved}", e.kind())));
            }
            Err(other) => return Err(format!("emitters[{i}] ({}): {other}", e.kind())),
        }
    }
    Ok(Ok(ClosedForm {
        total: finite::total(&scene.emitters, &per_emitter)?,
        per_emitter,
    }))
}

/// Runs the command.
pub fn run(options: &AnalyticOptions) -> Result<(), String> {
    let scene =
        Scene::load(&options.scene).map_err(|e| format!("{}: {e}", options.scene.display()))?;
    let c = closed_form(&scene)
        .map_err(|e| format!("{}: {e}", options.scene.display()))?
        .map_err(|e| format!("{}: {e}", options.scene.display()))?;
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
