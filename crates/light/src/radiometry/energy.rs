//! Radiant energy Q, in joules, and the energy of one photon.

/// The Planck constant h, in J·s (exact since the 2019 SI redefinition;
/// CODATA 2018). The lecture rounds it to 6.626e-34.
pub const PLANCK: f64 = 6.626_070_15e-34;

/// The speed of light in vacuum c, in m/s (exact by definition of the
/// metre). The lecture rounds it to 3.00e8.
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;

/// Radiant energy Q, in joules (J).
///
/// Q = ∫_{t₀}^{t₁} Φ(t) dt (lecture; pbrt-v4 §4.1.1).
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct RadiantEnergy(pub f64);

impl RadiantEnergy {
    /// The energy, J.
    #[inline]
    pub fn joules(self) -> f64 {
        self.0
    }

    /// The energy of `count` photons of wavelength `wavelength_m` (m):
    /// Q = count · hc/λ, J.
    #[inline]
    pub fn of_photons(count: f64, wavelength_m: f64) -> Self {
        RadiantEnergy(count * photon_energy(wavelength_m))
    }
}

/// The energy of one photon of wavelength λ (metres): Q = hc/λ, in joules
/// (Planck–Einstein relation; lecture: units (J·s)(m/s)/m = J).
///
/// ```
/// use lambert_light::radiometry::photon_energy;
/// // Red light at the visible band's end, λ = 700 nm: ≈ 2.84e-19 J.
/// let q = photon_energy(700e-9);
/// assert!((q - 2.837_8e-19).abs() < 1e-23);
/// // The lecture's rounded constants give the same to 0.07 %.
/// let rounded = 6.626e-34 * 3.00e8 / 700e-9;
/// assert!(((q - rounded) / q).abs() < 1e-3);
/// // Blue end, λ = 390 nm, carries 700/390 times more.
/// assert!((photon_energy(390e-9) / q - 700.0 / 390.0).abs() < 1e-14);
/// ```
#[inline]
pub fn photon_energy(wavelength_m: f64) -> f64 {
    PLANCK * SPEED_OF_LIGHT / wavelength_m
}
