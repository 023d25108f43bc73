//! Uniform area sampling of a disk and of a parallelogram in 3-D, the
//! building blocks of area-sampled lights, built from the shapes of
//! `lambert-geometry`. Convert their densities to solid angle with
//! [`pdf_area_to_solid_angle`](crate::f64::pdf_area_to_solid_angle).

macro_rules! area_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::disk::$p::{invert_concentric_disk, sample_concentric_disk};
        use crate::light_sample::$p::PointSample;
        use lambert_geometry::precision::$p::{Real, V2, V3, PI};
        use lambert_geometry::$p::{Disk, Frame, Parallelogram};

        /// A disk (center, unit normal, radius) sampled uniformly by area
        /// through the concentric map (density 1/(πR²) per m²).
        ///
        /// Uniform area sampling of a disk and of a parallelogram in 3-D, the
        /// building blocks of area-sampled lights, built from the shapes of
        /// `lambert-geometry`. Convert their densities to solid angle with
        /// [`pdf_area_to_solid_angle`](crate::f64::pdf_area_to_solid_angle).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct UniformDiskArea {
            center: V3,
            frame: Frame,
            radius: Real,
        }

        impl UniformDiskArea {
            /// Area sampling of `disk`.
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::Disk;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformDiskArea;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            #[doc = concat!("let disk = Disk::new(", stringify!($v3), "::Z, -", stringify!($v3), "::Z, 0.5)?;")]
            /// let area = UniformDiskArea::new(&disk);
            #[doc = concat!("let s = area.sample(", stringify!($v2), "::new(0.3, 0.7));")]
            /// assert!((s.point.z - 1.0).abs() < 1e-6 && s.point.truncate().length() <= 0.5);
            /// assert_eq!(area.pdf(s.point), s.pdf_area);
            /// # Ok::<(), lambert_geometry::GeometryError>(())
            /// ```
            #[inline]
            pub fn new(disk: &Disk) -> Self {
                UniformDiskArea {
                    center: disk.center(),
                    frame: *disk.frame(),
                    radius: disk.radius(),
                }
            }

            /// The disk's area πR².
            #[inline(always)]
            pub fn area(&self) -> Real {
                PI * self.radius * self.radius
            }

            /// A point uniform on the disk, density 1/(πR²) per m².
            #[inline(always)]
            pub fn sample(&self, u: V2) -> PointSample {
                let d = sample_concentric_disk(u) * self.radius;
                PointSample {
                    point: self.center + self.frame.x * d.x + self.frame.y * d.y,
                    normal: self.frame.z,
                    pdf_area: 1.0 / self.area(),
                }
            }

            /// Density per m² of `p` (on the disk's plane): 1/(πR²) within
            /// the radius, else 0. Points within rounding of the rim,
            /// 32ε·(|p|∞ + |center|∞ + R), count as inside, so a rim sample
            /// recovered by intersecting a ray keeps its density.
            #[inline]
            pub fn pdf(&self, p: V3) -> Real {
                let l = self.frame.to_local(p - self.center);
                let slack = 32.0
                    * Real::EPSILON
                    * (p.abs().max_element() + self.center.abs().max_element() + self.radius);
                let limit = self.radius + slack;
                if l.x * l.x + l.y * l.y <= limit * limit {
                    1.0 / self.area()
                } else {
                    0.0
                }
            }

            /// The u that [`UniformDiskArea::sample`] maps to `p`.
            #[inline]
            pub fn invert(&self, p: V3) -> V2 {
                let l = self.frame.to_local(p - self.center) / self.radius;
                invert_concentric_disk(V2::new(l.x, l.y))
            }
        }

        /// A parallelogram corner + s·edge0 + t·edge1, (s, t) ∈ [0, 1]²,
        /// sampled uniformly by area (density 1/|edge0 × edge1| per m²).
        ///
        /// Uniform area sampling of a disk and of a parallelogram in 3-D, the
        /// building blocks of area-sampled lights, built from the shapes of
        /// `lambert-geometry`. Convert their densities to solid angle with
        /// [`pdf_area_to_solid_angle`](crate::f64::pdf_area_to_solid_angle).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct UniformParallelogram {
            corner: V3,
            edge0: V3,
            edge1: V3,
            normal: V3,
            area: Real,
        }

        impl UniformParallelogram {
            /// Area sampling of `parallelogram`.
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::Parallelogram;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::UniformParallelogram;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            #[doc = concat!("let quad = Parallelogram::new(", stringify!($v3), "::Z, ", stringify!($v3), "::X, ", stringify!($v3), "::Y)?;")]
            /// let area = UniformParallelogram::new(&quad);
            #[doc = concat!("let s = area.sample(", stringify!($v2), "::new(0.25, 0.5));")]
            #[doc = concat!("assert_eq!(s.point, ", stringify!($v3), "::new(0.25, 0.5, 1.0));")]
            /// assert_eq!(s.pdf_area, 1.0);
            /// # Ok::<(), lambert_geometry::GeometryError>(())
            /// ```
            #[inline]
            pub fn new(parallelogram: &Parallelogram) -> Self {
                UniformParallelogram {
                    corner: parallelogram.corner(),
                    edge0: parallelogram.edge0(),
                    edge1: parallelogram.edge1(),
                    normal: parallelogram.normal(),
                    area: parallelogram.area(),
                }
            }

            /// The corner.
            #[inline]
            pub fn corner(&self) -> V3 {
                self.corner
            }

            /// The unit normal, edge0 × edge1 normalised.
            #[inline]
            pub fn normal(&self) -> V3 {
                self.normal
            }

            /// The area |edge0 × edge1|.
            #[inline]
            pub fn area(&self) -> Real {
                self.area
            }

            /// A point uniform on the parallelogram: corner + u₀ edge0 +
            /// u₁ edge1, density 1/area per m².
            #[inline]
            pub fn sample(&self, u: V2) -> PointSample {
                PointSample {
                    point: self.corner + self.edge0 * u.x + self.edge1 * u.y,
                    normal: self.normal,
                    pdf_area: 1.0 / self.area,
                }
            }

            /// The parameters (s, t) of `p` projected on the plane.
            #[inline]
            fn parameters(&self, p: V3) -> V2 {
                let d = p - self.corner;
                let a = self.edge0.dot(self.edge0);
                let b = self.edge0.dot(self.edge1);
                let c = self.edge1.dot(self.edge1);
                let r0 = d.dot(self.edge0);
                let r1 = d.dot(self.edge1);
                let det = a * c - b * b;
                V2::new((c * r0 - b * r1) / det, (a * r1 - b * r0) / det)
            }

            /// Density per m² of `p` (on the plane): 1/area inside, else 0.
            /// Parameters within rounding of the edges,
            /// 32ε·(|p|∞ + |corner|∞)/min edge length, count as inside.
            #[inline]
            pub fn pdf(&self, p: V3) -> Real {
                let st = self.parameters(p);
                let scale = p.abs().max_element() + self.corner.abs().max_element();
                let shortest = self.edge0.length().min(self.edge1.length());
                let tol = 32.0 * Real::EPSILON * (1.0 + scale / shortest);
                if st.x >= -tol && st.x <= 1.0 + tol && st.y >= -tol && st.y <= 1.0 + tol {
                    1.0 / self.area
                } else {
                    0.0
                }
            }

            /// The u that [`UniformParallelogram::sample`] maps to `p`.
            #[inline]
            pub fn invert(&self, p: V3) -> V2 {
                self.parameters(p).clamp(V2::ZERO, V2::ONE)
            }
        }
    };
}

lambert_geometry::both_precisions!(area_impl);
