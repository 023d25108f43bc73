//! Irradiance images: at the first hit of each camera ray, the irradiance
//! E = ∫ L V cos θ dω from every emitter, with visibility tested against
//! the scene.

use lambert_geometry::f64::Ray;

use super::context::Context;
use super::Pixel;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::Surface;

/// One camera ray's first hit and the irradiance there on the side facing
/// the camera: estimated with the configured strategy × sequence (delta
/// lights exact), or the closed form ignoring occluders when
/// `config.analytic`. The RGB channels show the radiance a diffuse surface
/// of the hit's albedo would reflect, ρE/π (ρ = 1 for mirrors and
/// dielectrics); pixels that see an emitter show its radiance, and pixels
/// that see an emitter or nothing have E = 0 and standard error 0.
pub(super) fn pixel(cx: &Context<'_>, ray: &Ray) -> Result<Pixel, TracerError> {
    cx.camera.set(cx.camera.get() + 1);
    let Some(sh) = cx.scene.nearest_hit(ray, f64::INFINITY) else {
        return Ok(Pixel::background(cx.scene.escaped(ray.direction)));
    };
    let hit = sh.hit;
    let albedo = match sh.material.surface {
        Surface::Emitter {
            radiance,
            two_sided,
        } => {
            let seen = hit.is_front(ray.direction) || two_sided;
            return Ok(Pixel::background(Rgb::grey(if seen {
                radiance
            } else {
                0.0
            })));
        }
        Surface::Diffuse(texture) => texture.at_lazy(|| sh.surface_parameters(ray)),
        Surface::Mirror(_) | Surface::Dielectric { .. } => Rgb::WHITE,
    };
    let n = hit.facing_normal(ray.direction);
    let (irradiance, std_error) = if cx.config.analytic {
        (cx.closed_form(&hit, n)?, 0.0)
    } else {
        let e = cx.estimate(&hit, n, cx.scene.emitters())?;
        (e.mean, e.std_error)
    };
    Ok(Pixel {
        rgb: albedo * (irradiance / std::f64::consts::PI),
        irradiance,
        std_error,
    })
}
