//! The named result of a direction sampler: a unit direction and its density.

macro_rules! direction_sample_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V3};

        /// A sampled unit direction `direction` together with the density
        /// `pdf` (per steradian) the sampler drew it with.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::SphericalTriangle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let t = SphericalTriangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X + ", stringify!($v3), "::Z, ", stringify!($v3), "::Y + ", stringify!($v3), "::Z, ", stringify!($v3), "::Z * 2.0)?;")]
        #[doc = concat!("let d = t.sample(", stringify!($v2), "::new(0.5, 0.5));")]
        /// assert_eq!(d.pdf, t.pdf(d.direction));
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct DirectionSample {
            /// The unit direction.
            pub direction: V3,
            /// Its density, per steradian (> 0 for every sample).
            pub pdf: Real,
        }
    };
}

lambert_geometry::both_precisions!(direction_sample_impl);
