//! How surfaces scatter light: diffuse, perfect mirror, smooth dielectric,
//! emitter, each with optional Blinn–Phong highlights.

use crate::color::Rgb;
use crate::error::TracerError;
use crate::texture::{reflectance, Texture};

/// What a surface does with light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Surface {
    /// Lambertian reflection with the albedo ρ: BRDF ρ/π, so the radiance
    /// leaving is ρ E / π for irradiance E.
    Diffuse(Texture),
    /// A perfect mirror with this reflectance per channel.
    Mirror(Rgb),
    /// A smooth dielectric (glass) of refractive index `ior` (outside: 1):
    /// reflection and Snell refraction weighted by the exact Fresnel
    /// reflectance, total internal reflection inside.
    Dielectric {
        /// The refractive index η > 0.
        ior: f64,
    },
    /// The surface of an area emitter: radiance L (grey) toward its front
    /// side, or both sides when `two_sided`; black otherwise.
    Emitter {
        /// The radiance, W·m⁻²·sr⁻¹.
        radiance: f64,
        /// Whether the back face emits too.
        two_sided: bool,
    },
}

/// Blinn–Phong highlights from the delta lights (Blinn 1977, "Models of
/// light reflection for computer synthesized pictures"): the BRDF term
/// k_s (e + 8)/(8π) (n·h)^e, h the unit half vector between the directions
/// to the viewer and to the light, normalised so that it reflects at most
/// k_s of the light (Akenine-Möller, Haines & Hoffman, *Real-Time
/// Rendering*, 3rd ed., §7.6). The radiance added is that BRDF times the
/// light's irradiance I cos θ / r² (or E⊥ cos θ).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Highlight {
    /// k_s per channel, in [0, 1].
    pub specular: Rgb,
    /// The exponent e ≥ 0 (larger: smaller, sharper highlights).
    pub exponent: f64,
}

impl Highlight {
    /// The BRDF value k_s (e + 8)/(8π) (n·h)^e for cos_h = n·h (0 for
    /// n·h ≤ 0).
    #[inline]
    pub fn brdf(&self, cos_h: f64) -> Rgb {
        if cos_h <= 0.0 {
            return Rgb::BLACK;
        }
        let e = self.exponent;
        // Integer exponents (the usual case) by repeated squaring: a few
        // multiplications instead of a general power.
        let power = if e.fract() == 0.0 && e <= i32::MAX as f64 {
            cos_h.powi(e as i32)
        } else {
            cos_h.powf(e)
        };
        self.specular * ((e + 8.0) / (8.0 * std::f64::consts::PI) * power)
    }
}

/// A material: a surface and, optionally, highlights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// How the surface scatters.
    pub surface: Surface,
    /// Blinn–Phong highlights from the delta lights (not on emitters).
    pub highlight: Option<Highlight>,
}

impl Material {
    /// A diffuse material of constant albedo.
    pub fn diffuse(albedo: Rgb) -> Self {
        Material {
            surface: Surface::Diffuse(Texture::Constant(albedo)),
            highlight: None,
        }
    }

    /// A perfect mirror reflecting `reflectance`.
    pub fn mirror(reflectance: Rgb) -> Self {
        Material {
            surface: Surface::Mirror(reflectance),
            highlight: None,
        }
    }

    /// A smooth dielectric of index `ior`.
    pub fn dielectric(ior: f64) -> Self {
        Material {
            surface: Surface::Dielectric { ior },
            highlight: None,
        }
    }

    /// The same material with highlights.
    pub fn with_highlight(self, specular: Rgb, exponent: f64) -> Self {
        Material {
            highlight: Some(Highlight { specular, exponent }),
            ..self
        }
    }

    /// Checks the parameters (errors name the field: `albedo`,
    /// `reflectance`, `ior`, `specular`, `shininess`, `radiance`).
    pub fn validate(&self) -> Result<(), TracerError> {
        match self.surface {
            Surface::Diffuse(t) => t.validate("albedo")?,
            Surface::Mirror(c) => reflectance("reflectance", c)?,
            Surface::Dielectric { ior } => {
                if !(ior.is_finite() && ior > 0.0) {
                    return Err(TracerError::new(
                        "ior",
                        format!("must be finite and positive, got {ior}"),
                    ));
                }
            }
            Surface::Emitter { radiance, .. } => {
                if !(radiance.is_finite() && radiance >= 0.0) {
                    return Err(TracerError::new(
                        "radiance",
                        format!("must be finite and non-negative, got {radiance}"),
                    ));
                }
            }
        }
        if let Some(h) = self.highlight {
            reflectance("specular", h.specular)?;
            if !(h.exponent.is_finite() && h.exponent >= 0.0) {
                return Err(TracerError::new(
                    "shininess",
                    format!("must be finite and non-negative, got {}", h.exponent),
                ));
            }
        }
        Ok(())
    }
}
