//! Radiometric relations, as documented functions of plain SI values, one
//! concept per file.
//!
//! | quantity | symbol | unit | relation |
//! |---|---|---|---|
//! | radiant energy | Q | J | Q = ∫ Φ dt; one photon Q = hc/λ |
//! | radiant flux | Φ | W = J/s | Φ = dQ/dt |
//! | irradiance | E | W/m² | E = dΦ/dA |
//! | radiant intensity | I | W/sr | I = dΦ/dω |
//! | radiance | L | W/(m²·sr) | L = d²Φ/(dA dω cos θ) |
//!
//! The photometric twins (lumen, lux, candela, nit) obey the same
//! relations, so the same functions apply to them. Emitters and estimates
//! carry these quantities as `f64` in the units above; the functions here
//! are what the emitters and closed forms use to relate them. Solid angles
//! of shapes are in `lambert-geometry`.
//!
//! Sources: J. H. Lambert, *Photometria*, 1760 (cosine law); pbrt-v4,
//! §4.1 (conventions, names).
//!
//! Files: [`energy`] (photon energy, the exact SI h and c),
//! [`intensity`] (isotropic point sources), [`irradiance`] (Lambert's
//! cosine law, inverse-square falloff), [`radiance`] (uniform hemisphere
//! E = Lπ, the disk's projected solid angle π sin²α).

pub mod energy;
pub mod intensity;
pub mod irradiance;
pub mod radiance;

pub use energy::{photon_energy, PLANCK, SPEED_OF_LIGHT};
pub use intensity::{isotropic_flux, isotropic_intensity};
pub use irradiance::{inverse_square_irradiance, lambert_cosine_irradiance};
pub use radiance::{disk_projected_solid_angle, uniform_hemisphere_irradiance};
