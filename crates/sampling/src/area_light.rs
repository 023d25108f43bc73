//! Area sampling of lights: uniform points on the light's surface, their
//! density converted to solid angle (p_ω = p_A d²/|cos θ_l|, pbrt-v4
//! §4.2.3). Simple and unbiased, but the conversion makes the estimator's
//! variance grow without bound as the shading point approaches the light
//! (d → 0) or sees it edge-on; prefer the solid-angle samplers where they
//! exist.

macro_rules! area_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::area::$p::UniformDiskArea;
        use crate::discrete::$p::pick_by_cumulative;
        use crate::light_sample::$p::{pdf_area_to_solid_angle, LightSample, PointSample};
        use crate::light_sampler::$p::{all_below, seen_from, seen_from_or_zero, LightSampler};
        use crate::sphere::$p::sample_uniform_sphere;
        use crate::triangle::$p::UniformTriangle;
        use lambert_geometry::precision::$p::{Real, V2, V3};
        use lambert_geometry::$p::{ConvexPolygon, Disk, Intersect, Ray, Sphere, Triangle};

        /// The light sample through the first point of `shape` that the
        /// ray from `reference` along `direction` meets, with `pdf_area`
        /// per m² at that point (normal from `normal_at`); 0 if none.
        #[inline]
        fn pdf_through<S: Intersect>(
            shape: &S,
            reference: V3,
            direction: V3,
            pdf_area: Real,
            normal_at: impl Fn(V3) -> V3,
        ) -> Real {
            match shape.hit_distance(&Ray::new(reference, direction), Real::INFINITY) {
                Some(t) => {
                    let point = reference + direction * t;
                    pdf_area_to_solid_angle(pdf_area, reference, point, normal_at(point))
                }
                None => 0.0,
            }
        }

        /// Uniform points on a sphere's whole surface (density 1/(4πr²)
        /// per m²); a point on the far side, hidden by the sphere itself,
        /// gives no sample.
        ///
        /// Area sampling of lights: uniform points on the light's surface, their
        /// density converted to solid angle (p_ω = p_A d²/|cos θ_l|, pbrt-v4
        /// §4.2.3). Simple and unbiased, but the conversion makes the estimator's
        /// variance grow without bound as the shading point approaches the light
        /// (d → 0) or sees it edge-on; prefer the solid-angle samplers where they
        /// exist.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, SphereAreaSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = SphereAreaSampler::new(Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 4.0), 1.0)?);")]
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// // u₀ = 1 is the sphere's lowest point, which faces p.
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(1.0, 0.0)).unwrap();")]
        /// assert!((s.distance - 3.0).abs() < 1e-5);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphereAreaSampler {
            sphere: Sphere,
        }

        impl SphereAreaSampler {
            /// The sampler of `sphere`.
            #[inline]
            pub fn new(sphere: Sphere) -> Self {
                SphereAreaSampler { sphere }
            }

            /// The sphere.
            #[inline]
            pub fn sphere(&self) -> &Sphere {
                &self.sphere
            }

            /// [`LightSampler::sample`] without the `Option`: the same
            /// sample, or one of density 0 where that gives none (a point
            /// on the hidden side; [`seen_from_or_zero`]). Branch-free, for
            /// loops over blocks of samples.
            #[inline(always)]
            pub fn sample_or_zero(&self, reference: V3, u: V2) -> LightSample {
                let (c, r) = (self.sphere.center(), self.sphere.radius());
                let n = sample_uniform_sphere(u);
                let point = c + n * r;
                let l = seen_from_or_zero(
                    reference,
                    PointSample {
                        point,
                        normal: n,
                        pdf_area: 1.0 / self.sphere.area(),
                    },
                );
                // Hidden unless the surface faces the reference point.
                let faces = n.dot(reference - point) > 0.0;
                LightSample {
                    pdf: if faces { l.pdf } else { 0.0 },
                    ..l
                }
            }
        }

        impl LightSampler for SphereAreaSampler {
            #[inline(always)]
            fn sample(&self, reference: V3, _normal: V3, u: V2) -> Option<LightSample> {
                let l = self.sample_or_zero(reference, u);
                (l.pdf > 0.0).then_some(l)
            }

            #[inline]
            fn pdf(&self, reference: V3, _normal: V3, direction: V3) -> Real {
                let (c, r) = (self.sphere.center(), self.sphere.radius());
                pdf_through(&self.sphere, reference, direction, 1.0 / self.sphere.area(), |p| {
                    (p - c) / r
                })
            }
        }

        /// Uniform points on a disk (density 1/(πR²) per m², the
        /// concentric map).
        ///
        /// Area sampling of lights: uniform points on the light's surface, their
        /// density converted to solid angle (p_ω = p_A d²/|cos θ_l|, pbrt-v4
        /// §4.2.3). Simple and unbiased, but the conversion makes the estimator's
        /// variance grow without bound as the shading point approaches the light
        /// (d → 0) or sees it edge-on; prefer the solid-angle samplers where they
        /// exist.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Disk;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{DiskAreaSampler, LightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = DiskAreaSampler::new(Disk::new(", stringify!($v3), "::Z, -", stringify!($v3), "::Z, 1.0)?);")]
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// // The disk's centre, straight up: p_ω = p_A d²/cos θ = 1/π.
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.5, 0.5)).unwrap();")]
        #[doc = concat!("assert!((s.pdf - 1.0 / std::", stringify!($p), "::consts::PI).abs() < 1e-6);")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct DiskAreaSampler {
            disk: Disk,
            area: UniformDiskArea,
        }

        impl DiskAreaSampler {
            /// The sampler of `disk`.
            #[inline]
            pub fn new(disk: Disk) -> Self {
                DiskAreaSampler {
                    area: UniformDiskArea::new(&disk),
                    disk,
                }
            }

            /// The disk.
            #[inline]
            pub fn disk(&self) -> &Disk {
                &self.disk
            }

            /// [`LightSampler::sample`] without the `Option`: the same
            /// sample, or one of density 0 where that gives none (the disk
            /// seen edge-on; [`seen_from_or_zero`]). Branch-free, for loops
            /// over blocks of samples.
            #[inline(always)]
            pub fn sample_or_zero(&self, reference: V3, u: V2) -> LightSample {
                seen_from_or_zero(reference, self.area.sample(u))
            }
        }

        impl LightSampler for DiskAreaSampler {
            #[inline(always)]
            fn sample(&self, reference: V3, _normal: V3, u: V2) -> Option<LightSample> {
                seen_from(reference, self.area.sample(u))
            }

            #[inline]
            fn pdf(&self, reference: V3, _normal: V3, direction: V3) -> Real {
                let n = self.disk.normal();
                pdf_through(&self.disk, reference, direction, 1.0 / self.area.area(), |_| n)
            }
        }

        /// Uniform points on a triangle (density 1/A per m²).
        ///
        /// Area sampling of lights: uniform points on the light's surface, their
        /// density converted to solid angle (p_ω = p_A d²/|cos θ_l|, pbrt-v4
        /// §4.2.3). Simple and unbiased, but the conversion makes the estimator's
        /// variance grow without bound as the shading point approaches the light
        /// (d → 0) or sees it edge-on; prefer the solid-angle samplers where they
        /// exist.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Triangle;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, TriangleAreaSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let t = Triangle::new(", stringify!($v3), "::new(-1.0, -1.0, 1.0), ", stringify!($v3), "::new(1.0, -1.0, 1.0), ", stringify!($v3), "::new(0.0, 1.0, 1.0))?;")]
        /// let light = TriangleAreaSampler::new(t);
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.5, 0.5)).unwrap();")]
        /// assert!((light.pdf(p, n, s.direction) / s.pdf - 1.0).abs() < 1e-4);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct TriangleAreaSampler {
            triangle: Triangle,
            area: UniformTriangle,
        }

        impl TriangleAreaSampler {
            /// The sampler of `triangle`.
            #[inline]
            pub fn new(triangle: Triangle) -> Self {
                TriangleAreaSampler {
                    area: UniformTriangle::new(&triangle),
                    triangle,
                }
            }
        }

        impl LightSampler for TriangleAreaSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if all_below(reference, normal, &self.triangle.vertices()) {
                    return None;
                }
                seen_from(reference, self.area.sample(u))
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if all_below(reference, normal, &self.triangle.vertices()) {
                    return 0.0;
                }
                let n = self.triangle.normal();
                pdf_through(&self.triangle, reference, direction, 1.0 / self.triangle.area(), |_| n)
            }
        }

        /// Uniform points on a convex polygon: a fan triangle (v₀, vᵢ,
        /// vᵢ₊₁) chosen in proportion to its area, then a uniform point in
        /// it (density 1/A per m²). The fan is built once, with the light.
        ///
        /// Area sampling of lights: uniform points on the light's surface, their
        /// density converted to solid angle (p_ω = p_A d²/|cos θ_l|, pbrt-v4
        /// §4.2.3). Simple and unbiased, but the conversion makes the estimator's
        /// variance grow without bound as the shading point approaches the light
        /// (d → 0) or sees it edge-on; prefer the solid-angle samplers where they
        /// exist.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, PolygonAreaSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// let square = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, 1.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 1.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, -1.0, 1.0),")]
        /// ])?;
        /// let light = PolygonAreaSampler::new(square);
        /// assert_eq!(light.area(), 4.0);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct PolygonAreaSampler {
            polygon: ConvexPolygon,
            triangles: Vec<UniformTriangle>,
            cumulative: Vec<Real>,
        }

        impl PolygonAreaSampler {
            /// The sampler of `polygon`. A polygon whose area is beyond the
            /// range of the precision (0 or ∞, see
            /// [`ConvexPolygon::area`]) has no area density: the sampler
            /// then holds no triangle and gives no sample.
            pub fn new(polygon: ConvexPolygon) -> Self {
                let v = polygon.vertices();
                let mut triangles = Vec::new();
                let mut cumulative = Vec::new();
                let mut total = 0.0;
                let usable = polygon.area() > 0.0 && polygon.area().is_finite();
                for i in 1..v.len() - 1 {
                    match Triangle::new(v[0], v[i], v[i + 1]) {
                        Ok(t) if usable => {
                            total += t.area();
                            triangles.push(UniformTriangle::new(&t));
                            cumulative.push(total);
                        }
                        _ => {}
                    }
                }
                PolygonAreaSampler {
                    polygon,
                    triangles,
                    cumulative,
                }
            }

            /// The sampled area (the sum of the fan's triangles), in m².
            #[inline]
            pub fn area(&self) -> Real {
                self.cumulative.last().copied().unwrap_or(0.0)
            }

            /// The polygon.
            #[inline]
            pub fn polygon(&self) -> &ConvexPolygon {
                &self.polygon
            }

            /// This sampler seen from `reference` (with the unit normal
            /// `normal`) as a fan of exactly `N` triangles, whose samples
            /// are [`LightSampler::sample`]'s without a branch per sample
            /// (for loops over blocks); `None` unless the fan has `N`
            /// triangles.
            #[inline]
            pub fn fan<const N: usize>(
                &self,
                reference: V3,
                normal: V3,
            ) -> Option<crate::polygon_area_fan::$p::PolygonAreaFan<N>> {
                let visible = !all_below(reference, normal, self.polygon.vertices());
                crate::polygon_area_fan::$p::PolygonAreaFan::new(
                    &self.triangles,
                    &self.cumulative,
                    reference,
                    visible,
                )
            }
        }

        impl LightSampler for PolygonAreaSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if all_below(reference, normal, self.polygon.vertices()) {
                    return None;
                }
                let total = *self.cumulative.last()?;
                let (k, u0) = pick_by_cumulative(&self.cumulative, u.x)?;
                let s = self.triangles[k].sample(V2::new(u0, u.y));
                seen_from(
                    reference,
                    PointSample {
                        pdf_area: 1.0 / total,
                        ..s
                    },
                )
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if all_below(reference, normal, self.polygon.vertices()) {
                    return 0.0;
                }
                let Some(&total) = self.cumulative.last() else {
                    return 0.0;
                };
                let n = self.polygon.normal();
                pdf_through(&self.polygon, reference, direction, 1.0 / total, |_| n)
            }
        }
    };
}

lambert_geometry::both_precisions!(area_light_impl);

#[cfg(test)]
mod tests {
    use crate::f64::{DiskAreaSampler, LightSampler, SphereAreaSampler};
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::{Disk, Sphere};

    /// `sample_or_zero` is `sample` without the `Option`: the same bits
    /// where `sample` gives a sample, density 0 where it gives none (a
    /// sphere's hidden half; a disk seen edge-on, from its own plane).
    #[test]
    fn sample_or_zero_is_sample_without_the_option() {
        let sphere = SphereAreaSampler::new(Sphere::new(DVec3::new(0.5, 0.0, 4.0), 1.0).unwrap());
        let disk = DiskAreaSampler::new(Disk::new(DVec3::Z, -DVec3::Z, 1.0).unwrap());
        let (mut some, mut none) = (0, 0);
        for (reference, n) in [
            (DVec3::ZERO, DVec3::Z),
            (DVec3::new(3.0, 0.0, 1.0), DVec3::X),
        ] {
            for i in 0..17 {
                for j in 0..17 {
                    let u = DVec2::new(i as f64 / 16.0, j as f64 / 16.0);
                    let pairs = [
                        (
                            sphere.sample(reference, n, u),
                            sphere.sample_or_zero(reference, u),
                        ),
                        (
                            disk.sample(reference, n, u),
                            disk.sample_or_zero(reference, u),
                        ),
                    ];
                    for (want, got) in pairs {
                        match want {
                            Some(w) => {
                                some += 1;
                                assert_eq!(w, got, "u {u}");
                                assert!(got.pdf > 0.0);
                            }
                            None => {
                                none += 1;
                                assert_eq!(got.pdf, 0.0, "u {u}");
                            }
                        }
                    }
                }
            }
        }
        // Both cases are exercised: the sphere's hidden half and the disk
        // seen from its plane (z = 1) give none.
        assert!(some > 289 && none > 289, "{some} {none}");
    }
}
