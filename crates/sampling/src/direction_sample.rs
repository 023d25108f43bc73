//! The named result of a direction sampler: a unit direction and its density.

macro_rules! direction_sample_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V3};

        /// A sampled unit direction `direction` together with the density
        /// `pdf` (per steradian) the sampler drew it with.
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
