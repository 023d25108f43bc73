//! Every direction warp behind one object-safe trait, in either precision,
//! for tools that choose the warp at run time: the `lambert sample` and
//! `lambert validate` commands and the validation suites.
//!
//! Geometry-dependent warps are seen from the origin. Inputs and outputs are
//! f64; an f32 warp receives its parameters converted once (a cone by
//! 1 − cos θmax, so tiny cones survive the conversion) and its results are
//! widened, so f32 and f64 can be compared sample by sample.

use glam::{DVec2, DVec3};

use crate::error::SamplingError;

/// Which implementation of a warp to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Precision {
    /// f32 (`Vec2`, `Vec3`).
    F32,
    /// f64 (`DVec2`, `DVec3`).
    F64,
}

impl Precision {
    /// Both precisions, f64 first.
    pub const ALL: [Precision; 2] = [Precision::F64, Precision::F32];

    /// "f32" or "f64".
    pub fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        }
    }
}

/// A direction warp and its parameters (lights seen from the origin).
#[derive(Clone, Debug, PartialEq)]
pub enum DirectionWarpSpec {
    /// Uniform on the hemisphere about +z.
    UniformHemisphere,
    /// Cosine-weighted on the hemisphere about +z.
    CosineHemisphere,
    /// Uniform on the sphere.
    UniformSphere,
    /// Uniform in the cone about +z with 1 − cos θmax given.
    UniformCone {
        /// 1 − cos θmax ∈ (0, 2].
        one_minus_cos_theta_max: f64,
    },
    /// Solid-angle sampling of a sphere seen from the origin.
    SphereLight {
        /// The sphere's center.
        center: DVec3,
        /// Its radius.
        radius: f64,
    },
}

/// The cap of directions that contains a warp's support, used to bin
/// chi-square tests within it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingCap {
    /// Unit axis of the cap.
    pub axis: DVec3,
    /// 1 − cos of its half-angle.
    pub one_minus_cos: f64,
}

/// A direction warp chosen at run time: sample, density (per steradian)
/// and inverse, with f64 inputs and outputs whatever the precision inside.
pub trait DirectionWarp: Send + Sync {
    /// The direction for `u` and the density the sampler reports for it.
    fn sample(&self, u: DVec2) -> crate::f64::DirectionSample;
    /// The density per steradian of the unit direction `w`.
    fn pdf(&self, w: DVec3) -> f64;
    /// The u that maps to `w`.
    fn invert(&self, w: DVec3) -> DVec2;
}

impl DirectionWarpSpec {
    /// The warp's name, as `lambert sample` spells it.
    pub fn name(&self) -> &'static str {
        match self {
            DirectionWarpSpec::UniformHemisphere => "uniform-hemisphere",
            DirectionWarpSpec::CosineHemisphere => "cosine-hemisphere",
            DirectionWarpSpec::UniformSphere => "uniform-sphere",
            DirectionWarpSpec::UniformCone { .. } => "uniform-cone",
            DirectionWarpSpec::SphereLight { .. } => "sphere-light",
        }
    }

    /// Builds the warp in the given precision, validating its parameters.
    pub fn build(&self, precision: Precision) -> Result<Box<dyn DirectionWarp>, SamplingError> {
        match precision {
            Precision::F64 => f64::build(self),
            Precision::F32 => f32::build(self),
        }
    }

    /// The smallest convenient cap containing the support, or `None` when
    /// the support is best binned over the whole sphere.
    pub fn bounding_cap(&self) -> Option<BoundingCap> {
        match self {
            DirectionWarpSpec::UniformHemisphere
            | DirectionWarpSpec::CosineHemisphere
            | DirectionWarpSpec::UniformSphere => None,
            DirectionWarpSpec::UniformCone {
                one_minus_cos_theta_max,
            } => Some(BoundingCap {
                axis: DVec3::Z,
                one_minus_cos: *one_minus_cos_theta_max,
            }),
            DirectionWarpSpec::SphereLight { center, radius } => {
                let d = center.length();
                let s2 = (radius / d).powi(2);
                let cos = ((d - radius) * (d + radius)).max(0.0).sqrt() / d;
                Some(BoundingCap {
                    axis: *center / d,
                    one_minus_cos: s2 / (1.0 + cos),
                })
            }
        }
    }
}

macro_rules! catalog_impl {
    () => {
        use glam::{DVec2, DVec3};

        #[inline]
        fn narrow2(u: DVec2) -> V2 {
            V2::new(u.x as Real, u.y as Real)
        }

        #[inline]
        fn narrow3(w: DVec3) -> V3 {
            V3::new(w.x as Real, w.y as Real, w.z as Real)
        }

        #[inline]
        fn wide2(u: V2) -> DVec2 {
            DVec2::new(u.x as f64, u.y as f64)
        }

        #[inline]
        fn wide3(w: V3) -> DVec3 {
            DVec3::new(w.x as f64, w.y as f64, w.z as f64)
        }

        enum Built {
            UniformHemisphere,
            CosineHemisphere,
            UniformSphere,
            UniformCone(UniformCone),
            SphereLight(SphereSolidAngle),
        }

        pub(crate) fn build(
            spec: &crate::catalog::DirectionWarpSpec,
        ) -> Result<Box<dyn crate::catalog::DirectionWarp>, SamplingError> {
            use crate::catalog::DirectionWarpSpec as S;
            let built = match spec {
                S::UniformHemisphere => Built::UniformHemisphere,
                S::CosineHemisphere => Built::CosineHemisphere,
                S::UniformSphere => Built::UniformSphere,
                S::UniformCone {
                    one_minus_cos_theta_max,
                } => Built::UniformCone(UniformCone::from_one_minus_cos(
                    *one_minus_cos_theta_max as Real,
                )?),
                S::SphereLight { center, radius } => Built::SphereLight(SphereSolidAngle::new(
                    V3::ZERO,
                    narrow3(*center),
                    *radius as Real,
                )?),
            };
            Ok(Box::new(built))
        }

        impl crate::catalog::DirectionWarp for Built {
            fn sample(&self, u: DVec2) -> crate::f64::DirectionSample {
                let u = narrow2(u);
                let (direction, pdf) = match self {
                    Built::UniformHemisphere => {
                        let w = sample_uniform_hemisphere(u);
                        (w, pdf_uniform_hemisphere(w))
                    }
                    Built::CosineHemisphere => {
                        let w = sample_cosine_hemisphere(u);
                        (w, pdf_cosine_hemisphere(w))
                    }
                    Built::UniformSphere => {
                        let w = sample_uniform_sphere(u);
                        (w, pdf_uniform_sphere(w))
                    }
                    Built::UniformCone(c) => {
                        let w = c.sample(u);
                        (w, 1.0 / c.solid_angle())
                    }
                    Built::SphereLight(s) => {
                        let l = s.sample(u);
                        (l.direction, l.pdf)
                    }
                };
                crate::f64::DirectionSample {
                    direction: wide3(direction),
                    pdf: pdf as f64,
                }
            }

            fn pdf(&self, w: DVec3) -> f64 {
                let w = narrow3(w);
                (match self {
                    Built::UniformHemisphere => pdf_uniform_hemisphere(w),
                    Built::CosineHemisphere => pdf_cosine_hemisphere(w),
                    Built::UniformSphere => pdf_uniform_sphere(w),
                    Built::UniformCone(c) => c.pdf(w),
                    Built::SphereLight(s) => s.pdf(w),
                }) as f64
            }

            fn invert(&self, w: DVec3) -> DVec2 {
                let w = narrow3(w);
                wide2(match self {
                    Built::UniformHemisphere => invert_uniform_hemisphere(w),
                    Built::CosineHemisphere => invert_cosine_hemisphere(w),
                    Built::UniformSphere => invert_uniform_sphere(w),
                    Built::UniformCone(c) => c.invert(w),
                    Built::SphereLight(s) => s.invert(w),
                })
            }
        }
    };
}

// The instantiations are private: they are reached through the trait.
mod instantiations {
    crate::precision::both_precisions!(catalog_impl);
}
use instantiations::{f32, f64};
