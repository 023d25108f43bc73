//! Radiant energy: the energy of one photon, Q = hc/λ.

/// The Planck constant h, in J·s (exact since the 2019 SI redefinition).
pub const PLANCK: f64 = 6.626_070_15e-34;

/// The speed of light in vacuum c, in m/s (exact by the definition of the
/// metre).
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;

/// The energy of one photon of wavelength λ (metres): Q = hc/λ, in joules
/// (the Planck–Einstein relation; units (J·s)(m/s)/m = J). The energy of n
/// photons is n times this, and a constant flux Φ delivers Q = Φt.
///
/// ```
/// use lambert_light::radiometry::photon_energy;
/// // Red light at the visible band's end, λ = 700 nm: ≈ 2.84e-19 J.
/// let q = photon_energy(700e-9);
/// assert!((q - 2.837_8e-19).abs() < 1e-23);
/// // Rounded constants (h ≈ 6.626e-34, c ≈ 3.00e8) agree to 0.07 %.
/// let rounded = 6.626e-34 * 3.00e8 / 700e-9;
/// assert!(((q - rounded) / q).abs() < 1e-3);
/// // The blue end, λ = 390 nm, carries 700/390 times more.
/// assert!((photon_energy(390e-9) / q - 700.0 / 390.0).abs() < 1e-14);
/// ```
#[inline]
pub fn photon_energy(wavelength_m: f64) -> f64 {
    PLANCK * SPEED_OF_LIGHT / wavelength_m
}
