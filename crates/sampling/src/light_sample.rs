//! The named results of geometry-dependent samplers.

macro_rules! light_sample_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V3};

        /// A direction sampled toward a light, with what a shading loop needs
        /// next: the density per steradian, the point hit on the light, and
        /// its distance from the reference point.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, SphereLightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = SphereLightSampler::new(Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 4.0), 1.0)?);")]
        #[doc = concat!("let s = light.sample(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, ", stringify!($v2), "::new(0.0, 0.0)).unwrap();")]
        /// // u₀ = 0 is the cone's axis: straight at the sphere's nearest point.
        /// assert!((s.distance - 3.0).abs() < 1e-5 && (s.point.z - 3.0).abs() < 1e-5);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct LightSample {
            /// Unit direction from the reference point toward the light.
            pub direction: V3,
            /// Density of `direction`, per steradian.
            pub pdf: Real,
            /// The point of the light seen along `direction`.
            pub point: V3,
            /// Distance from the reference point to `point`.
            pub distance: Real,
        }

        /// A point sampled on a surface, with its unit normal and its
        /// density per unit area (m⁻²).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformTriangle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let t = Triangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X, ", stringify!($v3), "::Y)?;")]
        #[doc = concat!("let s = UniformTriangle::new(&t).sample(", stringify!($v2), "::new(0.3, 0.3));")]
        #[doc = concat!("assert_eq!((s.normal, s.pdf_area), (", stringify!($v3), "::Z, 2.0));")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct PointSample {
            /// The point.
            pub point: V3,
            /// The surface's unit normal at `point`.
            pub normal: V3,
            /// Density of `point`, per unit area.
            pub pdf_area: Real,
        }

        /// Converts a density per unit area at `point` (unit normal
        /// `normal`) into a density per steradian seen from `reference`:
        /// p_ω = p_A · d² / |cos θ_l|, with d the distance and θ_l the angle
        /// between the normal and the direction back to `reference`
        /// (pbrt-v4 §4.2.3, the change of variables dω = |cos θ_l| dA / d²).
        ///
        /// Returns 0 (not ∞) when the surface is seen exactly edge-on or the
        /// point coincides with the reference: such a sample subtends no
        /// solid angle and carries no radiance, and callers skip pdf 0.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::pdf_area_to_solid_angle;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // A point 2 m straight above, facing down: p_ω = p_A d² / cos θ = 4 p_A.
        #[doc = concat!("let p = pdf_area_to_solid_angle(0.5, ", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z * 2.0, -", stringify!($v3), "::Z);")]
        /// assert_eq!(p, 2.0);
        /// // Seen edge-on: no solid angle, density 0 (not ∞).
        #[doc = concat!("assert_eq!(pdf_area_to_solid_angle(0.5, ", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z * 2.0, ", stringify!($v3), "::X), 0.0);")]
        /// ```
        ///
        /// Without branches (the degenerate cases are selected after the
        /// division), so that a loop of area samples vectorises.
        #[inline(always)]
        pub fn pdf_area_to_solid_angle(
            pdf_area: Real,
            reference: V3,
            point: V3,
            normal: V3,
        ) -> Real {
            let to_ref = reference - point;
            let d2 = to_ref.length_squared();
            // |cos θ_l| · d = |n · (reference − point)|.
            let cos_times_d = normal.dot(to_ref).abs();
            // p_A d² / (|n·v|/d) = p_A d³ / |n·v|.
            let pdf = pdf_area * d2 * d2.sqrt() / cos_times_d;
            if (cos_times_d == 0.0) | (d2 == 0.0) | !pdf.is_finite() {
                0.0
            } else {
                pdf
            }
        }
    };
}

lambert_geometry::both_precisions!(light_sample_impl);
