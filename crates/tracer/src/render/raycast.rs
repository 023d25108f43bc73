//! Ray casting (Appel 1968): the nearest surface along each camera ray,
//! lit directly.

use lambert_geometry::f64::Ray;

use super::context::Context;
use super::Pixel;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::Surface;

/// One camera ray: the nearest hit, shaded as a diffuse surface by the
/// light that reaches it directly (delta lights with shadow rays,
/// max(0, n·l); area emitters estimated). Mirrors show their reflectance
/// and dielectrics white, as diffuse colours: ray casting follows no
/// reflected or refracted ray. Emitters show their radiance.
pub(super) fn pixel(cx: &Context<'_>, ray: &Ray) -> Result<Pixel, TracerError> {
    cx.camera.set(cx.camera.get() + 1);
    let Some(sh) = cx.scene.nearest_hit(ray, f64::INFINITY) else {
        return Ok(Pixel::background(cx.scene.escaped(ray.direction)));
    };
    let hit = sh.hit;
    let front = hit.is_front(ray.direction);
    let colour = match sh.material.surface {
        Surface::Emitter {
            radiance,
            two_sided,
        } => {
            let seen = if front || two_sided { radiance } else { 0.0 };
            return Ok(Pixel::background(Rgb::grey(seen)));
        }
        Surface::Diffuse(texture) => texture.at_lazy(|| sh.surface_parameters(ray)),
        Surface::Mirror(reflectance) => reflectance,
        Surface::Dielectric { .. } => Rgb::WHITE,
    };
    let n = hit.facing_normal(ray.direction);
    let direct = cx.direct(&hit, n, -ray.direction, None, true)?;
    Ok(Pixel {
        rgb: colour * (direct.irradiance / std::f64::consts::PI),
        irradiance: direct.irradiance,
        std_error: direct.std_error,
    })
}
