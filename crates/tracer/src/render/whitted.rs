//! Recursive ray tracing (Whitted 1980, "An improved illumination model
//! for shaded display"): at each hit, direct light with shadow rays plus
//! the radiance of the reflected and refracted rays, traced recursively to
//! a depth limit.

use lambert_geometry::f64::Ray;

use super::context::Context;
use super::Pixel;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::Surface;
use crate::optics::{fresnel_dielectric, reflect, refract};

/// One camera ray traced recursively; the irradiance layer holds the
/// direct irradiance at the first hit (0 where the ray escapes or meets an
/// emitter).
pub(super) fn pixel(cx: &Context<'_>, ray: &Ray) -> Result<Pixel, TracerError> {
    cx.camera.set(cx.camera.get() + 1);
    let mut first = None;
    let rgb = trace(cx, ray, 0, &mut first)?;
    let (irradiance, std_error) = first.unwrap_or((0.0, 0.0));
    Ok(Pixel {
        rgb,
        irradiance,
        std_error,
    })
}

/// The radiance arriving along `ray` at recursion `depth` (0 for camera
/// rays). Reflected and refracted rays are traced while depth <
/// `max_depth`. `first` receives the direct irradiance at the first
/// diffuse-shaded hit of the camera ray.
fn trace(
    cx: &Context<'_>,
    ray: &Ray,
    depth: u32,
    first: &mut Option<(f64, f64)>,
) -> Result<Rgb, TracerError> {
    let Some(sh) = cx.scene.nearest_hit(ray, f64::INFINITY) else {
        return Ok(cx.scene.escaped(ray.direction));
    };
    let hit = sh.hit;
    let d = ray.direction;
    let front = hit.is_front(d);
    let n = hit.facing_normal(d);
    let wo = -d;
    let highlight = sh.material.highlight.as_ref();
    let deeper = depth < cx.config.max_depth;
    let follow = |dir, first: &mut Option<(f64, f64)>| -> Result<Rgb, TracerError> {
        cx.secondary.set(cx.secondary.get() + 1);
        trace(cx, &hit.spawn_ray(dir), depth + 1, first)
    };
    match sh.material.surface {
        Surface::Emitter {
            radiance,
            two_sided,
        } => Ok(Rgb::grey(if front || two_sided { radiance } else { 0.0 })),
        Surface::Diffuse(texture) => {
            let direct = cx.direct(&hit, n, wo, highlight, true)?;
            if depth == 0 {
                *first = Some((direct.irradiance, direct.std_error));
            }
            Ok(texture.at_lazy(|| sh.surface_parameters(ray))
                * (direct.irradiance / std::f64::consts::PI)
                + direct.highlight)
        }
        Surface::Mirror(reflectance) => {
            let mut c = match highlight {
                Some(h) => cx.direct(&hit, n, wo, Some(h), false)?.highlight,
                None => Rgb::BLACK,
            };
            if deeper {
                c += reflectance * follow(reflect(d, n), &mut None)?;
            }
            Ok(c)
        }
        Surface::Dielectric { ior } => {
            // Entering (front face): η_i/η_t = 1/ior; leaving: ior.
            let eta = if front { 1.0 / ior } else { ior };
            let mut c = match highlight {
                Some(h) if front => cx.direct(&hit, n, wo, Some(h), false)?.highlight,
                _ => Rgb::BLACK,
            };
            if deeper {
                let fresnel = fresnel_dielectric(wo.dot(n), eta);
                c += follow(reflect(d, n), &mut None)? * fresnel;
                if fresnel < 1.0 {
                    if let Some((t, _)) = refract(d, n, eta) {
                        c += follow(t, &mut None)? * (1.0 - fresnel);
                    }
                }
            }
            Ok(c)
        }
    }
}
