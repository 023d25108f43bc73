//! Solid-angle sampling of a triangle light.

macro_rules! triangle_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::error::SamplingError;
        use crate::light_sample::$p::LightSample;
        use crate::horizon_clip::$p::{horizon, Clipped, Horizon};
        use crate::light_sampler::$p::LightSampler;
        use crate::polygon_light::$p::{pdf_fan, sample_fan};
        use crate::spherical_triangle::$p::SphericalTriangle;
        use lambert_geometry::precision::$p::{Real, V2, V3};
        use lambert_geometry::$p::Triangle;

        /// The distance from `reference` along the unit `direction` to the
        /// plane through `on_plane` with unit `normal` (the plane the
        /// direction was sampled toward).
        #[inline]
        pub(crate) fn distance_to_plane(reference: V3, direction: V3, on_plane: V3, normal: V3) -> Real {
            normal.dot(on_plane - reference) / normal.dot(direction)
        }

        /// A triangle's spherical triangle seen from one reference point,
        /// with the plane needed to turn a direction into the point it
        /// reaches: uniform in solid angle (Arvo 1995, see
        /// [`SphericalTriangle`]).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::TriangleSolidAngle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let t = Triangle::new(", stringify!($v3), "::new(-1.0, -1.0, 1.0), ", stringify!($v3), "::new(1.0, -1.0, 1.0), ", stringify!($v3), "::new(0.0, 1.0, 1.0))?;")]
        #[doc = concat!("let at = TriangleSolidAngle::new(", stringify!($v3), "::ZERO, &t)?;")]
        #[doc = concat!("let s = at.sample(", stringify!($v2), "::new(0.5, 0.5));")]
        /// assert!((s.point.z - 1.0).abs() < 1e-6 && at.pdf(s.direction) == s.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct TriangleSolidAngle {
            spherical: SphericalTriangle,
            reference: V3,
            on_plane: V3,
            normal: V3,
        }

        impl TriangleSolidAngle {
            /// The spherical triangle that `triangle` subtends at
            /// `reference`; errors as [`SphericalTriangle::new`] (the point
            /// in the triangle's plane, a solid angle too small for its
            /// density).
            pub fn new(reference: V3, triangle: &Triangle) -> Result<Self, SamplingError> {
                let [a, b, c] = triangle.vertices();
                Ok(TriangleSolidAngle {
                    spherical: SphericalTriangle::new(reference, a, b, c)?,
                    reference,
                    on_plane: a,
                    normal: triangle.normal(),
                })
            }

            /// The subtended solid angle Ω, in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.spherical.solid_angle()
            }

            /// The spherical triangle.
            #[inline]
            pub fn spherical(&self) -> &SphericalTriangle {
                &self.spherical
            }

            /// A direction uniform in the spherical triangle (density 1/Ω
            /// per steradian), with the point it reaches on the triangle and
            /// the distance.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                let d = self.spherical.sample(u);
                let distance = distance_to_plane(self.reference, d.direction, self.on_plane, self.normal);
                LightSample {
                    direction: d.direction,
                    pdf: d.pdf,
                    point: self.reference + d.direction * distance,
                    distance,
                }
            }

            /// 1/Ω for unit directions inside the spherical triangle, else 0.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                self.spherical.pdf(w)
            }
        }

        /// Solid-angle sampling of a triangle light from any shading point
        /// (built once; a [`TriangleSolidAngle`] at each point; no
        /// allocation). The light of a mesh is a set of these.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, TriangleLightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// let light = TriangleLightSampler::new(Triangle::new(
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 1.0, 2.0),")]
        /// )?);
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.3, 0.6)).unwrap();")]
        /// assert!((s.point.z - 2.0).abs() < 1e-5);
        /// assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct TriangleLightSampler {
            triangle: Triangle,
        }

        impl TriangleLightSampler {
            /// The sampler of `triangle`.
            #[inline]
            pub fn new(triangle: Triangle) -> Self {
                TriangleLightSampler { triangle }
            }

            /// The triangle.
            #[inline]
            pub fn triangle(&self) -> &Triangle {
                &self.triangle
            }

            /// The sampler of the whole triangle at `reference` (no
            /// horizon: the [`LightSampler`] methods clip); see
            /// [`TriangleSolidAngle::new`].
            #[inline]
            pub fn at(&self, reference: V3) -> Result<TriangleSolidAngle, SamplingError> {
                TriangleSolidAngle::new(reference, &self.triangle)
            }
        }

        /// Samples only what the shading point can see: `None` for a
        /// triangle wholly below the horizon, the whole spherical triangle
        /// for one wholly on or above it, and for one that straddles it the
        /// part above the horizon (a triangle or quadrilateral, clipped on
        /// the stack, sampled as a fan of spherical triangles with density
        /// 1/Ω_visible).
        impl LightSampler for TriangleLightSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                let vertices = self.triangle.vertices();
                match horizon(reference, normal, &vertices) {
                    Horizon::Below => None,
                    Horizon::Above => self.at(reference).ok().map(|s| s.sample(u)),
                    Horizon::Straddles => {
                        let clipped = Clipped::above(reference, normal, &vertices);
                        let n = self.triangle.normal();
                        sample_fan(reference, clipped.vertices(), vertices[0], n, u)
                    }
                }
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                let vertices = self.triangle.vertices();
                match horizon(reference, normal, &vertices) {
                    Horizon::Below => 0.0,
                    Horizon::Above => self.at(reference).map_or(0.0, |s| s.pdf(direction)),
                    Horizon::Straddles => {
                        // The clipped fan lies above the horizon (to the
                        // spherical triangles' rounding slack, which keeps
                        // pdf(sample) equal to the sample's density).
                        let clipped = Clipped::above(reference, normal, &vertices);
                        pdf_fan(reference, clipped.vertices(), direction)
                    }
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(triangle_light_impl);
