//! Uniform skies: the whole sky, a dome, and a cap of directions.

use super::cap::{cap_over_sin2, clear_of_horizon, CapAngles};
use super::disk::power_of_two_above;
use super::double_double::Dd;
use super::error::{finite, unit, AnalyticError};
use super::exact_sum;
use super::scaled;
use glam::DVec3;
use lambert_geometry::GeometryError;
use std::f64::consts::PI;

/// A uniform sky of radiance L over the whole receiver hemisphere:
/// E = ∫_{H²} L cos θ dω = Lπ, W/m² (closed form,
/// [`uniform_hemisphere_irradiance`](crate::radiometry::uniform_hemisphere_irradiance)).
///
/// Errors: a non-finite L is [`AnalyticError::Input`]; E exceeds f64::MAX
/// for L > 5.7e307, which is [`AnalyticError::Overflow`] (never ∞).
///
/// ```
/// use lambert_light::analytic::{sky_irradiance, AnalyticError};
/// assert_eq!(sky_irradiance(2.0), Ok(2.0 * std::f64::consts::PI));
/// assert_eq!(sky_irradiance(1e308), Err(AnalyticError::Overflow { quantity: "irradiance" }));
/// ```
pub fn sky_irradiance(radiance: f64) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    scaled::product("irradiance", &[radiance, PI])
}

/// A uniform dome (the hemisphere of directions about `zenith`) of
/// radiance L over a receiver of normal `n` tilted by β from the zenith:
/// E = Lπ (1 + cos β)/2, W/m² (closed form; the cap of half-angle π/2).
/// 1 + cos β is evaluated as |n + zenith|²/2, exact near β = π.
pub fn dome_irradiance(radiance: f64, normal: DVec3, zenith: DVec3) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    let n = unit("normal", normal)?;
    let z = unit("zenith", zenith)?;
    scaled::product(
        "irradiance",
        &[radiance, PI * 0.25 * (n + z).length_squared()],
    )
}

/// A uniform sky of radiance L inside the cone of directions of unit
/// `axis` and half-angle γ ∈ (0, π], over a receiver of unit normal `n`:
/// E = L ∫_{cap ∩ H²(n)} cos θ dω, W/m² (closed form for any tilt,
/// including caps crossing the horizon; see
/// [`cap_projected_solid_angle`](super::cap_projected_solid_angle)). γ = π is the whole sky (E = Lπ),
/// γ = π/2 a dome. Caps clearly off the horizon are computed in f64; for
/// the others cos β is the exact dot product of the given vectors over
/// their exact lengths, and sin γ, cos γ are double-doubles when the rim
/// passes close to the horizon (module `cap`), so a cap that barely shows
/// keeps its digits.
///
/// ```
/// use glam::DVec3;
/// use lambert_light::analytic::{dome_irradiance, sky_cap_irradiance};
/// use std::f64::consts::FRAC_PI_2;
/// let n = DVec3::new(0.6, 0.0, 0.8);
/// let cap = sky_cap_irradiance(1.0, n, DVec3::Z, FRAC_PI_2).unwrap();
/// assert!((cap - dome_irradiance(1.0, n, DVec3::Z).unwrap()).abs() < 1e-15);
/// ```
pub fn sky_cap_irradiance(
    radiance: f64,
    normal: DVec3,
    axis: DVec3,
    half_angle: f64,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    let n_unit = unit("normal", normal)?;
    let a_unit = unit("axis", axis)?;
    finite("half_angle", half_angle)?;
    if !(half_angle > 0.0 && half_angle <= PI) {
        return Err(AnalyticError::Input(GeometryError::OutOfRange {
            field: "half_angle",
            value: half_angle,
            range: "(0, π]",
        }));
    }
    // Caps clearly off the horizon: f64 (cos β to 8u from the normalised
    // vectors, module `cap`).
    let (sg, cg) = half_angle.sin_cos();
    if cg >= 0.0 {
        if let Some((q, s)) = clear_of_horizon(n_unit.dot(a_unit), sg) {
            return scaled::product("irradiance", &[radiance, q, s, s]);
        }
    }
    // cos β from the exact inputs: the exact dot product of the raw
    // vectors (each scaled by a power of two, exactly) over their lengths.
    let (n, a) = (
        normal / power_of_two_above(normal.abs().max_element()),
        axis / power_of_two_above(axis.abs().max_element()),
    );
    let cb = exact_sum::dot(n, a) / (exact_sum::length_f64(n) * exact_sum::length_f64(a));
    // sin γ and cos γ in double-double when the cap's rim passes close to
    // the horizon (|cos β| / sin γ within 1/8 of 1), where its depth
    // sin γ − |cos β| needs them (module `cap`); elsewhere the f64 values,
    // relative error u, leave the depth within 8u.
    let ratio = (cb.to_f64() / sg).abs();
    let (sg, cg) = if (0.875..=8.0 / 7.0).contains(&ratio) {
        Dd::from(half_angle).sin_cos()
    } else {
        (Dd::from(sg.max(0.0)), Dd::from(cg))
    };
    let (q, s) = cap_over_sin2(&CapAngles::new(cb, sg, cg));
    scaled::product("irradiance", &[radiance, q, s, s])
}
