//! The light-sampling interface a path tracer calls at every shading point.

macro_rules! light_sampler_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::light_sample::$p::{pdf_area_to_solid_angle, LightSample, PointSample};
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// A light sampler: built once per light, sampled at any shading
        /// point.
        ///
        /// A light sampler is built once per light, from the light's shape, and is
        /// then asked, at any shading point (a reference point and the unit normal
        /// there), for a direction toward the light: the [`LightSample`]'s unit
        /// direction, the point it reaches on the light, the distance to that point
        /// (for the shadow ray) and the density of the direction per steradian.
        /// [`LightSampler::pdf`] gives the same density for a direction found by
        /// another technique (BSDF sampling), as multiple importance sampling needs
        /// (Veach & Guibas 1995). Neither call allocates.
        ///
        /// Samplers that draw points by area convert the density to solid angle,
        /// p_ω = p_A d²/|cos θ_l| (pbrt-v4 §4.2.3).
        ///
        /// Both methods take the shading point's unit `normal`: a sampler
        /// returns `None` (and density 0) when the light lies wholly below
        /// that point's horizon, where it cannot contribute, and is free to
        /// use the normal to sample better.
        ///
        /// When the light straddles the horizon, the polygon and triangle
        /// samplers (`PolygonLightSampler`, `TriangleLightSampler`) clip it
        /// and sample only its visible part. The sphere's cone
        /// (`SphereLightSampler`) and the area
        /// samplers do not: exact uniform sampling of a cap cut by a plane
        /// (or of a disk's circular segment by area) has no closed-form
        /// inverse — its marginal CDF is an integral of arccos terms that
        /// would need a root-finder per sample — so their samples below the
        /// horizon carry cos θ ≤ 0 and contribute nothing (an estimator
        /// counts them as misses). Projected-solid-angle samplers sample
        /// only the visible part by construction.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, SphereLightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = SphereLightSampler::new(Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 10.0), 1.0)?);")]
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.5, 0.5)).unwrap();")]
        /// // The shadow ray runs from p along s.direction for s.distance.
        /// assert!((p + s.direction * s.distance - s.point).length() < 1e-4);
        /// assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        pub trait LightSampler {
            /// A direction from `reference` toward the light, with the point
            /// it reaches, the distance, and its density per steradian;
            /// `None` when the light cannot be sampled from there (wholly
            /// below the horizon, the point inside or on the light, or the
            /// light seen edge-on).
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample>;

            /// The density per steradian with which [`LightSampler::sample`]
            /// at (`reference`, `normal`) produces the unit `direction`
            /// (0 where it never does).
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real;
        }

        /// The light sample of an area sample `s` seen from `reference`:
        /// the direction and distance to the point and the density
        /// converted to solid angle; `None` when the point subtends no
        /// solid angle (seen edge-on, or at the reference point).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{seen_from, PointSample};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let s = PointSample { point: ", stringify!($v3), "::Z * 2.0, normal: -", stringify!($v3), "::Z, pdf_area: 0.5 };")]
        #[doc = concat!("let l = seen_from(", stringify!($v3), "::ZERO, s).unwrap();")]
        #[doc = concat!("assert_eq!((l.direction, l.distance, l.pdf), (", stringify!($v3), "::Z, 2.0, 2.0));")]
        /// ```
        #[inline(always)]
        pub fn seen_from(reference: V3, s: PointSample) -> Option<LightSample> {
            let l = seen_from_or_zero(reference, s);
            (l.pdf > 0.0).then_some(l)
        }

        /// [`seen_from`] without the `Option`: the same light sample where
        /// that gives one, else one with density 0 (its other fields are
        /// then unspecified, possibly NaN). Branch-free, so that a loop over
        /// a block of samples vectorises; a caller selects on `pdf > 0`.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{seen_from_or_zero, PointSample};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // Seen edge-on: no solid angle.
        #[doc = concat!("let s = PointSample { point: ", stringify!($v3), "::X, normal: ", stringify!($v3), "::Z, pdf_area: 0.5 };")]
        #[doc = concat!("assert_eq!(seen_from_or_zero(", stringify!($v3), "::ZERO, s).pdf, 0.0);")]
        /// ```
        #[inline(always)]
        pub fn seen_from_or_zero(reference: V3, s: PointSample) -> LightSample {
            let to = s.point - reference;
            let distance = to.length();
            let pdf = pdf_area_to_solid_angle(s.pdf_area, reference, s.point, s.normal);
            LightSample {
                direction: to / distance,
                pdf: if distance > 0.0 { pdf } else { 0.0 },
                point: s.point,
                distance,
            }
        }

        /// The unit shading normal of a sampler that weights by cos θ:
        /// `normal` itself when it is already unit to 4ε (so that a caller's
        /// n·ω and the sampler's are the same bits, which the zero-variance
        /// estimators need), else `normal` normalised; errors (field
        /// `normal`) for a zero or non-finite vector.
        #[inline]
        pub(crate) fn shading_normal(normal: V3) -> Result<V3, crate::SamplingError> {
            if normal.is_finite() && (normal.length_squared() - 1.0).abs() <= 4.0 * Real::EPSILON {
                Ok(normal)
            } else {
                Ok(lambert_geometry::$p::unit_vector("normal", normal)?)
            }
        }

        /// Whether every one of `points` lies on or below the horizon of
        /// (`reference`, `normal`): n·(pᵢ − reference) ≤ 0.
        #[inline]
        pub(crate) fn all_below(reference: V3, normal: V3, points: &[V3]) -> bool {
            points.iter().all(|&p| normal.dot(p - reference) <= 0.0)
        }
    };
}

lambert_geometry::both_precisions!(light_sampler_impl);
