//! Radiometric quantities and solid angles, one concept per file.
//!
//! | quantity | symbol | unit | relation |
//! |---|---|---|---|
//! | radiant energy | Q | J | Q = ∫ Φ dt; one photon Q = hc/λ |
//! | radiant flux | Φ | W = J/s | Φ = dQ/dt |
//! | irradiance | E | W/m² | E = dΦ/dA |
//! | radiant intensity | I | W/sr | I = dΦ/dω |
//! | radiance | L | W/(m²·sr) | L = d²Φ/(dA dω cos θ) |
//!
//! The photometric twins (lumen, lux, candela, nit) obey the same relations;
//! the same functions apply to them (the lecture's 815 lm bulb is 64.9 cd).
//! Sources: J. H. Lambert, *Photometria*, 1760 (cosine law); pbrt-v4,
//! ch. 4.1 (conventions, names); the lecture in `seeds/` (worked numbers).
//!
//! Files: [`energy`] (Q, photon energy, CODATA h and c), [`flux`] (Φ),
//! [`irradiance`] (E, Lambert's cosine law, inverse-square falloff),
//! [`intensity`] (I, isotropic point sources), [`radiance`] (L, uniform
//! hemisphere E = Lπ, the disk's projected solid angle), [`solid_angle`]
//! (caps, spheres, disks, triangles, rectangles, convex polygons).

pub mod energy;
pub mod flux;
pub mod intensity;
pub mod irradiance;
pub mod radiance;
pub mod solid_angle;

pub use energy::{photon_energy, RadiantEnergy, PLANCK, SPEED_OF_LIGHT};
pub use flux::RadiantFlux;
pub use intensity::RadiantIntensity;
pub use irradiance::{inverse_square_irradiance, lambert_cosine_irradiance, Irradiance};
pub use radiance::{disk_projected_solid_angle, uniform_hemisphere_irradiance, Radiance};
pub use solid_angle::{
    cap_solid_angle, cap_solid_angle_from_sin2, disk_solid_angle, polygon_solid_angle,
    rectangle_solid_angle, sphere_solid_angle, triangle_solid_angle,
};
