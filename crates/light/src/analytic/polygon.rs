//! A uniform planar convex polygon light (one- or two-sided): Lambert's
//! formula after clipping at the receiver's plane.
//!
//! Lambert (1760): for a polygon whose directions lie in the receiver's
//! hemisphere, E = (L/2) Σᵢ Γᵢ·n with Γᵢ = θᵢ unit(Rᵢ × Rᵢ₊₁),
//! Rᵢ = vᵢ − p and θᵢ = atan2(|Rᵢ × Rᵢ₊₁|, Rᵢ·Rᵢ₊₁), the angle between
//! Rᵢ and Rᵢ₊₁ (the atan2 keeps tiny and near-π angles exact, unlike
//! acos of the normalised dot product); Arvo (1995) derives it as the
//! contour form of the irradiance tensor. Rᵢ × Rᵢ₊₁ is evaluated as
//! Rᵢ × (vᵢ₊₁ − vᵢ), which is the same vector without the cancellation of
//! two long nearly parallel vectors. The sum's sign depends on the
//! polygon's orientation as seen from p; its absolute value is taken.
//!
//! The polygon is first clipped against n·(x − p) > 0 (Sutherland &
//! Hodgman, "Reentrant polygon clipping", CACM 17(1), 1974); a convex
//! polygon stays convex. The sum is evaluated relative to the polygon's
//! centre (the `lambert` module), which removes the far-field
//! cancellation: the textbook sum's terms are of size ℓ/D (ℓ the size, D
//! the distance) for a result of size (ℓ/D)², about log₁₀(D/ℓ) digits
//! lost; the centred sum's terms are of the result's size.
//!
//! A polygon clipped by the horizon to a sliver of height h (relative to
//! its size), or lying low over it, makes Lambert's terms cancel (the
//! chord's term ≈ its angle w against the others, for a result ∝ h²w);
//! there the sin²ε contour form per edge is used, with the vertices'
//! heights above the receiver's plane computed exactly (the `lambert` and
//! `sin2_contour` modules): measured within 1e-15 of the exact result at
//! h = 1e-12, 1e12 sizes away.

use super::disk::power_of_two_above;
use super::error::{finite, AnalyticError};
use super::exact_sum;
use super::scaled;
use super::Emission;
use crate::receiver::Receiver;
use glam::DVec3;
use lambert_geometry::f64::ConvexPolygon;

/// The part of the polygon `vertices` with n·(x − p) ≥ 0 (Sutherland–
/// Hodgman against the receiver's plane through `p` with normal `n`).
/// Vertices on the plane are kept; crossing edges are cut at
/// vᵢ + (vⱼ − vᵢ) dᵢ/(dᵢ − dⱼ), dᵢ = n·(vᵢ − p), with the heights dᵢ
/// computed exactly (an exact dot product rounded to double-double, in
/// coordinates scaled by a power of two), so which vertices are kept and
/// where edges are cut does not depend on rounding, however far the
/// polygon.
///
/// ```
/// use glam::DVec3;
/// use lambert_light::analytic::clip_polygon_to_hemisphere;
/// let square = [DVec3::new(0.0, -1.0, -1.0), DVec3::new(0.0, 1.0, -1.0),
///               DVec3::new(0.0, 1.0, 1.0), DVec3::new(0.0, -1.0, 1.0)];
/// let upper = clip_polygon_to_hemisphere(DVec3::new(-1.0, 0.0, 0.0), DVec3::Z, &square);
/// assert_eq!(upper.len(), 4);
/// assert!(upper.iter().all(|v| v.z >= 0.0));
/// ```
pub fn clip_polygon_to_hemisphere(p: DVec3, n: DVec3, vertices: &[DVec3]) -> Vec<DVec3> {
    let k = power_of_two_above(
        vertices
            .iter()
            .fold(p.abs().max_element(), |a, v| a.max(v.abs().max_element())),
    );
    let heights: Vec<_> = vertices
        .iter()
        .map(|&v| exact_sum::dot_of_difference(n, v / k, p / k))
        .collect();
    super::lambert::clip(vertices, &heights).0
}

/// A uniform planar convex `polygon` of radiance L (front face by the
/// right-hand rule), one- or two-sided, seen from the `receiver` at p with
/// unit normal n (closed form: Lambert's formula,
/// E = (L/2) |Σ Γᵢ·n|, after clipping the polygon at the receiver's plane;
/// module docs). A one-sided polygon seen from behind, or any polygon seen
/// edge-on or wholly below the horizon, gives 0.
///
/// Errors: a non-finite radiance; E beyond f64::MAX
/// ([`AnalyticError::Overflow`]). The polygon was validated when it was
/// built (`lambert_geometry`).
///
/// ```
/// use glam::DVec3;
/// use lambert_geometry::f64::ConvexPolygon;
/// use lambert_light::analytic::{polygon_irradiance, Emission};
/// use lambert_light::Receiver;
/// // A unit square 1 above the receiver, facing down (vertices clockwise
/// // seen from above): E = L ∫cos θ dω = 4x atan x ≈ 0.7522 with x = 0.5/√1.25
/// // (four corner rectangles, Howell catalog C-11).
/// let sq = ConvexPolygon::new(vec![DVec3::new(-0.5, -0.5, 1.0), DVec3::new(-0.5, 0.5, 1.0),
///                                  DVec3::new(0.5, 0.5, 1.0), DVec3::new(0.5, -0.5, 1.0)])?;
/// let up = Receiver::new(DVec3::ZERO, DVec3::Z)?;
/// let e = polygon_irradiance(&sq, Emission::OneSided, 1.0, &up)?;
/// let x = 0.5f64 / (1.0f64 + 0.25).sqrt();
/// let corner = 2.0 * (x * (0.5f64 / (1.25f64).sqrt()).atan());
/// assert!((e - 2.0 * corner).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn polygon_irradiance(
    polygon: &ConvexPolygon,
    emission: Emission,
    radiance: f64,
    receiver: &Receiver,
) -> Result<f64, AnalyticError> {
    finite("radiance", radiance)?;
    let (p, n) = (receiver.point, receiver.normal);
    let vertices = polygon.vertices();
    // Exact power-of-two rescaling so that no product of two lengths
    // overflows or underflows (vertices 1e300 or 1e-300 in size).
    let k = power_of_two_above(
        vertices
            .iter()
            .fold(p.abs().max_element(), |a, v| a.max(v.abs().max_element())),
    );
    let scaled_vertices: Vec<DVec3> = vertices.iter().map(|&v| v / k).collect();
    let p = p / k;
    let front = polygon.normal();
    let side = front.dot(p - scaled_vertices[0]);
    if side == 0.0 || (emission == Emission::OneSided && side < 0.0) {
        return Ok(0.0);
    }
    scaled::product(
        "irradiance",
        &[
            radiance,
            super::lambert::projected_solid_angle(p, n, &scaled_vertices),
        ],
    )
}
