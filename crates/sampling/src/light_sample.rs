//! The named results of geometry-dependent samplers.

macro_rules! light_sample_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V3};

        /// A direction sampled toward a light, with what a shading loop needs
        /// next: the density per steradian, the point hit on the light, and
        /// its distance from the reference point.
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
        #[inline]
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
            if cos_times_d == 0.0 || d2 == 0.0 {
                return 0.0;
            }
            // p_A d² / (|n·v|/d) = p_A d³ / |n·v|.
            let pdf = pdf_area * d2 * d2.sqrt() / cos_times_d;
            if pdf.is_finite() {
                pdf
            } else {
                0.0
            }
        }
    };
}

lambert_geometry::both_precisions!(light_sample_impl);
