//! Radiant intensity of isotropic point sources: I = Φ/4π.

use std::f64::consts::PI;

/// The intensity I, in W/sr (photometric: candela), of an isotropic point
/// source of total flux Φ (W; photometric: lumen): Φ = ∫_{S²} I dω = 4πI,
/// so I = Φ/(4π) (pbrt-v4 §4.1.1). The point emitter's `with_flux` uses it.
///
/// ```
/// use lambert_light::radiometry::isotropic_intensity;
/// // An 815 lm LED bulb radiating evenly: ≈ 64.9 cd.
/// let i = isotropic_intensity(815.0);
/// assert!((i - 64.855_639_309_947_35).abs() < 1e-12);
/// assert_eq!(i.round(), 65.0);
/// ```
#[inline]
pub fn isotropic_intensity(flux_w: f64) -> f64 {
    flux_w / (4.0 * PI)
}

/// The total flux Φ = 4πI, in W, of an isotropic point source of
/// intensity I (W/sr).
///
/// ```
/// use lambert_light::radiometry::{isotropic_flux, isotropic_intensity};
/// assert!((isotropic_flux(isotropic_intensity(11.0)) - 11.0).abs() < 1e-14);
/// ```
#[inline]
pub fn isotropic_flux(intensity_w_sr: f64) -> f64 {
    4.0 * PI * intensity_w_sr
}
