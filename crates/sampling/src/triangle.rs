//! Uniform sampling of a planar triangle by area.

macro_rules! triangle_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V2, V3};
        use crate::light_sample::$p::PointSample;
        use lambert_geometry::$p::Triangle;

        /// A planar triangle sampled uniformly by area (density 1/A per m²).
        ///
        /// Barycentrics b₀ = 1 − √u₀, b₁ = u₁√u₀ (Osada, Funkhouser, Chazelle and
        /// Dobkin 2002, "Shape Distributions", eq. 1; Turk 1990), density 1/A per
        /// unit area, inverse u₀ = (1 − b₀)², u₁ = b₁/(1 − b₀).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformTriangle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let area = UniformTriangle::new(&Triangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X * 2.0, ", stringify!($v3), "::Y)?);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.36, 0.5);")]
        /// let s = area.sample(u);
        /// assert_eq!(area.pdf(s.point), 1.0);
        /// assert!((area.invert(s.point) - u).length() < 1e-5);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct UniformTriangle {
            v0: V3,
            e1: V3,
            e2: V3,
            normal: V3,
            area: Real,
        }

        impl UniformTriangle {
            /// Area sampling of `triangle`.
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformTriangle;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            #[doc = concat!("let t = Triangle::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::X, ", stringify!($v3), "::Y)?;")]
            /// let area = UniformTriangle::new(&t);
            #[doc = concat!("let s = area.sample(", stringify!($v2), "::new(0.5, 0.5));")]
            /// assert!(s.point.x + s.point.y <= 1.0 && s.pdf_area == 2.0);
            /// assert_eq!(area.pdf(s.point), 2.0);
            /// # Ok::<(), lambert_geometry::GeometryError>(())
            /// ```
            #[inline]
            pub fn new(triangle: &Triangle) -> Self {
                let [v0, v1, v2] = triangle.vertices();
                UniformTriangle {
                    v0,
                    e1: v1 - v0,
                    e2: v2 - v0,
                    normal: triangle.normal(),
                    area: triangle.area(),
                }
            }

            /// The triangle's area.
            #[inline]
            pub fn area(&self) -> Real {
                self.area
            }

            /// The first vertex.
            #[inline]
            pub fn vertex0(&self) -> V3 {
                self.v0
            }

            /// The triangle's unit normal (right-hand rule).
            #[inline]
            pub fn normal(&self) -> V3 {
                self.normal
            }

            /// Barycentrics (b₀, b₁, b₂) of a uniform point:
            /// b₀ = 1 − √u₀, b₁ = u₁√u₀, b₂ = 1 − b₀ − b₁.
            #[inline(always)]
            pub fn sample_barycentrics(u: V2) -> V3 {
                let s = u.x.sqrt();
                let b0 = 1.0 - s;
                let b1 = u.y * s;
                V3::new(b0, b1, (1.0 - b0 - b1).max(0.0))
            }

            /// A point uniform on the triangle, density 1/A per m².
            #[inline(always)]
            pub fn sample(&self, u: V2) -> PointSample {
                let b = Self::sample_barycentrics(u);
                PointSample {
                    point: self.v0 + self.e1 * b.y + self.e2 * b.z,
                    normal: self.normal,
                    pdf_area: 1.0 / self.area,
                }
            }

            /// Barycentrics (b₀, b₁, b₂) of `p` projected on the plane.
            #[inline]
            pub fn barycentrics(&self, p: V3) -> V3 {
                // Solve p − v0 = b₁ e1 + b₂ e2 by the normal equations.
                let d = p - self.v0;
                let d11 = self.e1.dot(self.e1);
                let d12 = self.e1.dot(self.e2);
                let d22 = self.e2.dot(self.e2);
                let r1 = d.dot(self.e1);
                let r2 = d.dot(self.e2);
                let det = d11 * d22 - d12 * d12;
                let b1 = (d22 * r1 - d12 * r2) / det;
                let b2 = (d11 * r2 - d12 * r1) / det;
                V3::new(1.0 - b1 - b2, b1, b2)
            }

            /// Density per m² of the point `p` (on the triangle's plane):
            /// 1/A inside, 0 outside. Barycentrics down to
            /// −32ε·(1 + (|p|∞ + |v0|∞)/√A), the rounding of a point
            /// recovered by intersecting a ray, count as inside.
            #[inline]
            pub fn pdf(&self, p: V3) -> Real {
                let b = self.barycentrics(p);
                let scale = p.abs().max_element() + self.v0.abs().max_element();
                let tol = -32.0 * Real::EPSILON * (1.0 + scale / self.area.sqrt());
                if b.x >= tol && b.y >= tol && b.z >= tol {
                    1.0 / self.area
                } else {
                    0.0
                }
            }

            /// The u that [`UniformTriangle::sample`] maps to `p`:
            /// u₀ = (1 − b₀)², u₁ = b₁/(1 − b₀).
            #[inline]
            pub fn invert(&self, p: V3) -> V2 {
                let b = self.barycentrics(p);
                let s = (1.0 - b.x).clamp(0.0, 1.0);
                let u1 = if s > 0.0 {
                    (b.y / s).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                V2::new(s * s, u1)
            }
        }
    };
}

lambert_geometry::both_precisions!(triangle_impl);
