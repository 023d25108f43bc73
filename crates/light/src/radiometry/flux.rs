//! Radiant flux (power) Φ, in watts.

use super::{Irradiance, RadiantEnergy, RadiantIntensity};

/// Radiant flux Φ = dQ/dt, in watts (W = J/s) (lecture; pbrt-v4 §4.1.1).
/// For photometric flux read lumens.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct RadiantFlux(pub f64);

impl RadiantFlux {
    /// The flux, W.
    #[inline]
    pub fn watts(self) -> f64 {
        self.0
    }

    /// The energy delivered at constant flux over `seconds`: Q = Φ t, J.
    ///
    /// ```
    /// use lambert_light::radiometry::RadiantFlux;
    /// // The lecture's 11 W LED bulb, for one hour: 39.6 kJ.
    /// assert_eq!(RadiantFlux(11.0).energy_over(3600.0).joules(), 39_600.0);
    /// ```
    #[inline]
    pub fn energy_over(self, seconds: f64) -> RadiantEnergy {
        RadiantEnergy(self.0 * seconds)
    }

    /// The average irradiance when the flux falls on area `area_m2`
    /// perpendicular to the beam: E = Φ/A, W/m².
    #[inline]
    pub fn irradiance_over(self, area_m2: f64) -> Irradiance {
        Irradiance(self.0 / area_m2)
    }

    /// The intensity of an isotropic point source of this flux:
    /// Φ = ∫_{S²} I dω = 4π I, so I = Φ/(4π), W/sr
    /// ([`RadiantIntensity::isotropic`]).
    #[inline]
    pub fn isotropic_intensity(self) -> RadiantIntensity {
        RadiantIntensity::isotropic(self)
    }
}
