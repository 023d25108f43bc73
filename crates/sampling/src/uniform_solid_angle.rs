//! What the estimator's batch loops need of a polygon's solid-angle
//! sampler once it is prepared at a point: a direction from `u` and the
//! density of a direction, both inline and branch-free.

macro_rules! uniform_solid_angle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::polygon_light::$p::SingleTriangle;
        use crate::spherical_fan::$p::SphericalFan;
        use crate::spherical_rectangle::$p::SphericalRectangle;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// A sampler of directions uniform over one solid angle Ω, seen
        /// from the point it was prepared at: density 1/Ω per steradian
        /// inside, 0 outside. The forms a polygon light takes there (one
        /// spherical triangle, a spherical rectangle, a fan of triangles in
        /// fixed lanes) implement it with their own `sample` and `pdf`, to
        /// the bit, inline and without branches on the sample, so that one
        /// loop written over this trait vectorises for each of them.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{SphericalRectangle, UniformSolidAngle};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A 2 × 2 square at height 1 seen from the origin.
        /// let square = SphericalRectangle::new(
        #[doc = concat!("    ", stringify!($v3), "::ZERO,")]
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(2.0, 0.0, 0.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 2.0, 0.0),")]
        /// )?;
        #[doc = concat!("let s = square.sample_direction(", stringify!($v2), "::new(0.3, 0.8));")]
        /// assert_eq!(square.density(s.direction), s.pdf);
        #[doc = concat!("assert_eq!(square.density(-", stringify!($v3), "::Z), 0.0);")]
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        pub trait UniformSolidAngle: Copy {
            /// A direction uniform in the solid angle and its density 1/Ω.
            fn sample_direction(&self, u: V2) -> DirectionSample;

            /// 1/Ω for unit directions `w` inside the solid angle, else 0.
            fn density(&self, w: V3) -> Real;
        }

        impl UniformSolidAngle for SingleTriangle {
            #[inline(always)]
            fn sample_direction(&self, u: V2) -> DirectionSample {
                self.sample(u)
            }

            #[inline(always)]
            fn density(&self, w: V3) -> Real {
                self.pdf(w)
            }
        }

        impl UniformSolidAngle for SphericalRectangle {
            /// [`SphericalRectangle::sample_point`]'s direction and density
            /// (the point and distance, unused, are left to the compiler
            /// to drop).
            #[inline(always)]
            fn sample_direction(&self, u: V2) -> DirectionSample {
                let s = self.sample_point(u);
                DirectionSample {
                    direction: s.direction,
                    pdf: s.pdf,
                }
            }

            #[inline(always)]
            fn density(&self, w: V3) -> Real {
                self.pdf(w)
            }
        }

        impl<const N: usize> UniformSolidAngle for SphericalFan<N> {
            #[inline(always)]
            fn sample_direction(&self, u: V2) -> DirectionSample {
                self.sample(u)
            }

            #[inline(always)]
            fn density(&self, w: V3) -> Real {
                self.pdf(w)
            }
        }
    };
}

lambert_geometry::both_precisions!(uniform_solid_angle_impl);
