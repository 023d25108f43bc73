//! Spherical coordinates in the local frame (+z the axis, θ from +z, φ from
//! +x), computed without cancellation where it matters.

macro_rules! spherical_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::trig::$p::sin_cos_2pi;
        use lambert_geometry::precision::$p::{Real, PI, V3};

        /// 1 − cos θ of the unit vector `w` about +z, without cancellation.
        ///
        /// For w_z > 0 it uses 1 − w_z = (w_x² + w_y²)/(1 + w_z), exact
        /// algebra for a unit vector, so directions a few 1e-8 rad from the
        /// axis keep full relative precision even in f32; for w_z ≤ 0 the
        /// direct difference has no cancellation.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::one_minus_cos_theta;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // 1e-8 rad off the axis: 5e-17, where 1 − cos θ computed directly is 0.
        #[doc = concat!("let w = ", stringify!($v3), "::new(1e-8, 0.0, 1.0).normalize();")]
        /// assert!((one_minus_cos_theta(w) / 5e-17 - 1.0).abs() < 1e-6);
        /// ```
        #[inline]
        pub fn one_minus_cos_theta(w: V3) -> Real {
            if w.z > 0.0 {
                (w.x * w.x + w.y * w.y) / (1.0 + w.z)
            } else {
                1.0 - w.z
            }
        }

        /// φ/(2π) ∈ [0, 1) of `w` (the azimuth as a fraction of a turn);
        /// 0 on the axis.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::azimuth_fraction;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("assert_eq!(azimuth_fraction(", stringify!($v3), "::new(0.0, 1.0, 0.0)), 0.25);")]
        #[doc = concat!("assert_eq!(azimuth_fraction(", stringify!($v3), "::Z), 0.0);")]
        /// ```
        #[inline]
        pub fn azimuth_fraction(w: V3) -> Real {
            let f = w.y.atan2(w.x) / (2.0 * PI);
            let f = if f < 0.0 { f + 1.0 } else { f };
            // f + 1 can round up to exactly 1 for tiny negative f.
            if f >= 1.0 {
                0.0
            } else {
                f
            }
        }

        /// The unit vector with sin θ, cos θ and azimuth fraction `phi_u`
        /// (φ = 2π·phi_u) in the local frame.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::direction_from;")]
        /// let w = direction_from(1.0, 0.0, 0.25);
        /// assert!((w.y - 1.0).abs() < 1e-6 && w.x.abs() < 1e-6);
        /// ```
        #[inline(always)]
        pub fn direction_from(sin_theta: Real, cos_theta: Real, phi_u: Real) -> V3 {
            let (s, c) = sin_cos_2pi(phi_u);
            V3::new(sin_theta * c, sin_theta * s, cos_theta)
        }
    };
}

lambert_geometry::both_precisions!(spherical_impl);
