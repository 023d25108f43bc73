//! Radiant intensity I, in watts per steradian.

use super::RadiantFlux;

/// Radiant intensity I = dΦ/dω, in W/sr (photometric: lm/sr = candela)
/// (lecture; pbrt-v4 §4.1.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct RadiantIntensity(pub f64);

impl RadiantIntensity {
    /// The intensity, W/sr.
    #[inline]
    pub fn watts_per_sr(self) -> f64 {
        self.0
    }

    /// An isotropic point source of total flux Φ: Φ = 4π I, so I = Φ/(4π).
    ///
    /// The lecture's modern LED bulb: 815 lm isotropic → 815/(4π) ≈ 64.9 cd
    /// (the slide rounds to 65 cd).
    ///
    /// ```
    /// use lambert_light::radiometry::{RadiantFlux, RadiantIntensity};
    /// let i = RadiantIntensity::isotropic(RadiantFlux(815.0));
    /// assert!((i.0 - 64.855_639_309_947_35).abs() < 1e-12);
    /// assert_eq!(i.0.round(), 65.0);
    /// ```
    #[inline]
    pub fn isotropic(flux: RadiantFlux) -> Self {
        RadiantIntensity(flux.0 / (4.0 * std::f64::consts::PI))
    }

    /// The total flux of an isotropic source of this intensity, Φ = 4π I.
    #[inline]
    pub fn isotropic_flux(self) -> RadiantFlux {
        RadiantFlux(4.0 * std::f64::consts::PI * self.0)
    }
}
