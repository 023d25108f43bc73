//! Every direction warp behind one object-safe trait, in either precision,
//! for tools that choose the warp at run time: the `lambert sample` and
//! `lambert validate` commands and the validation suites.
//!
//! Geometry-dependent warps are seen from the origin. Inputs and outputs are
//! f64; an f32 warp receives its parameters converted once (a cone by
//! 1 − cos θmax, so tiny cones survive the conversion) and its results are
//! widened, so f32 and f64 can be compared sample by sample.

use glam::{DVec2, DVec3};

use lambert_sampling::SamplingError;

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
    /// Uniform sampling of the spherical triangle a planar triangle
    /// subtends at the origin (Arvo 1995).
    SphericalTriangle {
        /// The vertices.
        vertices: [DVec3; 3],
    },
    /// Uniform sampling of the spherical rectangle a rectangle subtends at
    /// the origin (Ureña, Fajardo and King 2013).
    SphericalRectangle {
        /// One corner.
        corner: DVec3,
        /// First edge from the corner.
        edge0: DVec3,
        /// Second edge, perpendicular to the first.
        edge1: DVec3,
    },
    /// Area sampling of a triangle, seen from the origin (density converted
    /// to solid angle).
    TriangleArea {
        /// The vertices.
        vertices: [DVec3; 3],
    },
    /// Area sampling of a disk, seen from the origin.
    DiskArea {
        /// The disk's center.
        center: DVec3,
        /// Its normal (any length).
        normal: DVec3,
        /// Its radius.
        radius: f64,
    },
    /// Area sampling of a parallelogram, seen from the origin.
    ParallelogramArea {
        /// One corner.
        corner: DVec3,
        /// First edge from the corner.
        edge0: DVec3,
        /// Second edge from the corner.
        edge1: DVec3,
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
    fn sample(&self, u: DVec2) -> lambert_sampling::f64::DirectionSample;
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
            DirectionWarpSpec::SphericalTriangle { .. } => "spherical-triangle",
            DirectionWarpSpec::SphericalRectangle { .. } => "spherical-rectangle",
            DirectionWarpSpec::TriangleArea { .. } => "triangle-area",
            DirectionWarpSpec::DiskArea { .. } => "disk-area",
            DirectionWarpSpec::ParallelogramArea { .. } => "parallelogram-area",
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
            DirectionWarpSpec::TriangleArea { vertices }
            | DirectionWarpSpec::SphericalTriangle { vertices } => cap_of_points(vertices),
            DirectionWarpSpec::ParallelogramArea {
                corner,
                edge0,
                edge1,
            }
            | DirectionWarpSpec::SphericalRectangle {
                corner,
                edge0,
                edge1,
            } => cap_of_points(&[
                *corner,
                *corner + *edge0,
                *corner + *edge0 + *edge1,
                *corner + *edge1,
            ]),
            DirectionWarpSpec::DiskArea {
                center,
                normal,
                radius,
            } => {
                let (x, y) = normal.normalize().any_orthonormal_pair();
                let rim: Vec<DVec3> = (0..256)
                    .map(|k| {
                        let phi = std::f64::consts::TAU * k as f64 / 256.0;
                        *center + (x * phi.cos() + y * phi.sin()) * *radius
                    })
                    .collect();
                cap_of_points(&rim)
            }
        }
    }
}

/// A cap about the normalised mean direction of `points` (seen from the
/// origin) that contains them all, widened by 2 % in 1 − cos so that a
/// boundary sampled between the points (a disk's rim) stays inside; `None`
/// when that cap would exceed a hemisphere (bin over the sphere instead).
fn cap_of_points(points: &[DVec3]) -> Option<BoundingCap> {
    let axis = points
        .iter()
        .map(|p| p.normalize())
        .sum::<DVec3>()
        .normalize();
    let frame = lambert_geometry::f64::Frame::from_normal(axis);
    let h = points
        .iter()
        .map(|p| lambert_sampling::f64::one_minus_cos_theta(frame.to_local(p.normalize())))
        .fold(0.0, f64::max);
    let h = h * 1.02;
    (h < 1.0).then_some(BoundingCap {
        axis,
        one_minus_cos: h,
    })
}

macro_rules! catalog_impl {
    ($p:ident) => {
        use glam::{DVec2, DVec3};
        use lambert_geometry::precision::$p::{narrow2, narrow3, wide2, wide3, Real, V3};
        use lambert_geometry::$p::{Disk, Intersect, Parallelogram, Plane, Ray, Sphere, Triangle};
        use lambert_sampling::$p::{
            invert_cosine_hemisphere, invert_uniform_hemisphere, invert_uniform_sphere,
            pdf_area_to_solid_angle, pdf_cosine_hemisphere, pdf_uniform_hemisphere,
            pdf_uniform_sphere, sample_cosine_hemisphere, sample_uniform_hemisphere,
            sample_uniform_sphere, PointSample, SphereSolidAngle, SphericalRectangle,
            SphericalTriangle, UniformCone, UniformDiskArea, UniformParallelogram, UniformTriangle,
        };
        use lambert_sampling::SamplingError;

        enum Built {
            UniformHemisphere,
            CosineHemisphere,
            UniformSphere,
            UniformCone(UniformCone),
            SphereLight(SphereSolidAngle),
            SphericalTriangle(SphericalTriangle),
            SphericalRectangle(SphericalRectangle),
            TriangleArea(UniformTriangle, Plane),
            DiskArea(UniformDiskArea, Plane),
            ParallelogramArea(UniformParallelogram, Plane),
        }

        /// The point where the ray from the origin along `w` meets the
        /// area light's plane, if in front. The area samplers' own densities
        /// decide whether it lies on the light (with their rounding slack at
        /// the rim, which an exact containment test would not have).
        #[inline]
        fn hit_plane(w: V3, plane: &Plane) -> Option<V3> {
            plane
                .hit_distance(&Ray::new(V3::ZERO, w), Real::INFINITY)
                .map(|t| w * t)
        }

        /// The solid-angle density at the origin of direction `w` toward an
        /// area light of density `pdf_area` (per m², at the point hit).
        #[inline]
        fn area_pdf(w: V3, plane: &Plane, pdf_area: impl Fn(V3) -> Real) -> Real {
            match hit_plane(w, plane) {
                Some(p) => pdf_area_to_solid_angle(pdf_area(p), V3::ZERO, p, plane.normal()),
                None => 0.0,
            }
        }

        /// Direction and solid-angle density of an area sample seen from
        /// the origin.
        #[inline]
        fn seen_from_origin(s: PointSample) -> (V3, Real) {
            let w = s.point.normalize();
            (
                w,
                pdf_area_to_solid_angle(s.pdf_area, V3::ZERO, s.point, s.normal),
            )
        }

        /// The plane of an area light, which must not contain the origin
        /// (the light would be seen edge-on, with no solid angle).
        fn plane_seen_from_origin(on_plane: V3, normal: V3) -> Result<Plane, SamplingError> {
            let plane = Plane::new(on_plane, normal)?;
            if plane.signed_distance(V3::ZERO) == 0.0 {
                Err(SamplingError::Degenerate {
                    what: "the origin lies in the light's plane (seen edge-on)",
                })
            } else {
                Ok(plane)
            }
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
                    &Sphere::new(narrow3(*center), *radius as Real)?,
                )?),
                S::SphericalTriangle { vertices } => {
                    Built::SphericalTriangle(SphericalTriangle::new(
                        V3::ZERO,
                        narrow3(vertices[0]),
                        narrow3(vertices[1]),
                        narrow3(vertices[2]),
                    )?)
                }
                S::SphericalRectangle {
                    corner,
                    edge0,
                    edge1,
                } => Built::SphericalRectangle(SphericalRectangle::new(
                    V3::ZERO,
                    narrow3(*corner),
                    narrow3(*edge0),
                    narrow3(*edge1),
                )?),
                S::TriangleArea { vertices } => {
                    let tri = Triangle::new(
                        narrow3(vertices[0]),
                        narrow3(vertices[1]),
                        narrow3(vertices[2]),
                    )?;
                    let plane = plane_seen_from_origin(tri.vertices()[0], tri.normal())?;
                    Built::TriangleArea(UniformTriangle::new(&tri), plane)
                }
                S::DiskArea {
                    center,
                    normal,
                    radius,
                } => {
                    let disk = Disk::new(narrow3(*center), narrow3(*normal), *radius as Real)?;
                    let plane = plane_seen_from_origin(disk.center(), disk.normal())?;
                    Built::DiskArea(UniformDiskArea::new(&disk), plane)
                }
                S::ParallelogramArea {
                    corner,
                    edge0,
                    edge1,
                } => {
                    let par =
                        Parallelogram::new(narrow3(*corner), narrow3(*edge0), narrow3(*edge1))?;
                    let plane = plane_seen_from_origin(par.corner(), par.normal())?;
                    Built::ParallelogramArea(UniformParallelogram::new(&par), plane)
                }
            };
            Ok(Box::new(built))
        }

        impl crate::catalog::DirectionWarp for Built {
            fn sample(&self, u: DVec2) -> lambert_sampling::f64::DirectionSample {
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
                    Built::SphericalTriangle(s) => {
                        let d = s.sample(u);
                        (d.direction, d.pdf)
                    }
                    Built::SphericalRectangle(s) => {
                        let d = s.sample(u);
                        (d.direction, d.pdf)
                    }
                    Built::TriangleArea(a, _) => seen_from_origin(a.sample(u)),
                    Built::DiskArea(a, _) => seen_from_origin(a.sample(u)),
                    Built::ParallelogramArea(a, _) => seen_from_origin(a.sample(u)),
                };
                lambert_sampling::f64::DirectionSample {
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
                    Built::SphericalTriangle(s) => s.pdf(w),
                    Built::SphericalRectangle(s) => s.pdf(w),
                    Built::TriangleArea(a, plane) => area_pdf(w, plane, |p| a.pdf(p)),
                    Built::DiskArea(a, plane) => area_pdf(w, plane, |p| a.pdf(p)),
                    Built::ParallelogramArea(a, plane) => area_pdf(w, plane, |p| a.pdf(p)),
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
                    Built::SphericalTriangle(s) => s.invert(w),
                    Built::SphericalRectangle(s) => s.invert(w),
                    Built::TriangleArea(a, plane) => {
                        a.invert(hit_plane(w, plane).unwrap_or(plane.point()))
                    }
                    Built::DiskArea(a, plane) => {
                        a.invert(hit_plane(w, plane).unwrap_or(plane.point()))
                    }
                    Built::ParallelogramArea(a, plane) => {
                        a.invert(hit_plane(w, plane).unwrap_or(plane.point()))
                    }
                })
            }
        }
    };
}

// The instantiations are private: they are reached through the trait.
mod instantiations {
    /// The f64 instantiation.
    #[allow(clippy::unnecessary_cast)]
    pub(super) mod f64 {
        catalog_impl!(f64);
    }
    /// The f32 instantiation.
    pub(super) mod f32 {
        catalog_impl!(f32);
    }
}
use instantiations::{f32, f64};
