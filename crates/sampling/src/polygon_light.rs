//! Solid-angle sampling of a convex polygon light.

macro_rules! polygon_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::discrete::$p::{pick_by_cumulative, rescale_within};
        use crate::error::SamplingError;
        use crate::horizon_clip::$p::{horizon, Clipped, Horizon};
        use crate::horizon_clip::MAX_POLYGON_VERTICES;
        use crate::light_sample::$p::LightSample;
        use crate::light_sampler::$p::LightSampler;
        use crate::spherical_rectangle::$p::SphericalRectangle;
        use crate::spherical_triangle::$p::SphericalTriangle;
        use crate::triangle_light::$p::distance_to_plane;
        use lambert_geometry::precision::$p::{Real, V2, V3};
        use lambert_geometry::$p::ConvexPolygon;

        /// A convex polygon seen from one reference point, sampled
        /// uniformly in solid angle: its spherical rectangle when it is a
        /// rectangle (Ureña, Fajardo & King 2013), otherwise the fan of
        /// spherical triangles (v₀, vᵢ, vᵢ₊₁), one chosen in proportion to
        /// its solid angle and sampled by Arvo's method (1995) with the
        /// choosing number reused. Fan triangles that are degenerate seen
        /// from the point are skipped.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{PolygonLightSampler, PolygonSolidAngle};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// let square = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 2.0), ", stringify!($v3), "::new(1.0, -1.0, 2.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 1.0, 2.0), ", stringify!($v3), "::new(-1.0, 1.0, 2.0),")]
        /// ])?;
        #[doc = concat!("let at = PolygonLightSampler::new(square)?.at(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// assert!(matches!(at, PolygonSolidAngle::Rectangle(_)));
        #[doc = concat!("let s = at.sample(", stringify!($v2), "::new(0.5, 0.5)).unwrap();")]
        /// assert_eq!(at.pdf(s.direction), s.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub enum PolygonSolidAngle {
            /// A rectangle's spherical rectangle.
            Rectangle(SphericalRectangle),
            /// A fan of spherical triangles.
            Fan {
                /// The fan's spherical triangles.
                triangles: Vec<SphericalTriangle>,
                /// Their cumulative solid angles (the last is Ω).
                cumulative: Vec<Real>,
                /// The reference point.
                reference: V3,
                /// A point of the polygon's plane.
                on_plane: V3,
                /// The polygon's unit normal.
                normal: V3,
            },
        }

        impl PolygonSolidAngle {
            /// The subtended solid angle Ω, in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                match self {
                    PolygonSolidAngle::Rectangle(r) => r.solid_angle(),
                    PolygonSolidAngle::Fan { cumulative, .. } => {
                        cumulative.last().copied().unwrap_or(0.0)
                    }
                }
            }

            /// A direction uniform in the subtended solid angle (density
            /// 1/Ω per steradian), with the point it reaches and the
            /// distance.
            #[inline]
            pub fn sample(&self, u: V2) -> Option<LightSample> {
                match self {
                    PolygonSolidAngle::Rectangle(r) => Some(r.sample_point(u)),
                    PolygonSolidAngle::Fan {
                        triangles,
                        cumulative,
                        reference,
                        on_plane,
                        normal,
                    } => {
                        let total = *cumulative.last()?;
                        let (k, u0) = pick_by_cumulative(cumulative, u.x)?;
                        let d = triangles[k].sample(V2::new(u0, u.y));
                        let distance = distance_to_plane(*reference, d.direction, *on_plane, *normal);
                        Some(LightSample {
                            direction: d.direction,
                            pdf: 1.0 / total,
                            point: *reference + d.direction * distance,
                            distance,
                        })
                    }
                }
            }

            /// The fan's one spherical triangle, when the polygon is seen
            /// as a single triangle (a triangle wholly above the horizon):
            /// it samples as [`sample`](Self::sample) and
            /// [`pdf`](Self::pdf) do, to the bit, without the table lookup,
            /// so a batch of samples runs as one vectorised loop.
            #[inline]
            pub fn single_triangle(&self) -> Option<SingleTriangle> {
                match self {
                    PolygonSolidAngle::Fan {
                        triangles,
                        cumulative,
                        ..
                    } if triangles.len() == 1 => Some(SingleTriangle {
                        triangle: triangles[0],
                        solid_angle: cumulative[0],
                    }),
                    _ => None,
                }
            }

            /// 1/Ω for unit directions inside the subtended solid angle,
            /// else 0.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                match self {
                    PolygonSolidAngle::Rectangle(r) => r.pdf(w),
                    PolygonSolidAngle::Fan {
                        triangles,
                        cumulative,
                        ..
                    } => {
                        if triangles.iter().any(|t| t.contains(w)) {
                            1.0 / cumulative.last().copied().unwrap_or(Real::INFINITY)
                        } else {
                            0.0
                        }
                    }
                }
            }
        }

        /// A [`PolygonSolidAngle`] that is one spherical triangle
        /// ([`PolygonSolidAngle::single_triangle`]).
        ///
        /// It holds a copy of the triangle, not a reference: a batch loop
        /// then keeps the triangle's values in registers (through a
        /// reference, the compiler reloaded them and did not vectorise).
        #[derive(Clone, Copy, Debug)]
        pub struct SingleTriangle {
            triangle: SphericalTriangle,
            solid_angle: Real,
        }

        impl SingleTriangle {
            /// [`PolygonSolidAngle::sample`]'s direction and density (1/Ω
            /// per steradian): the one-entry table's pick, u₀ = u·Ω/Ω
            /// rescaled as [`pick_by_cumulative`] does, then the triangle's
            /// warp.
            #[inline(always)]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let u0 = rescale_within(u.x * self.solid_angle, 0.0, self.solid_angle);
                DirectionSample {
                    direction: self.triangle.sample(V2::new(u0, u.y)).direction,
                    pdf: 1.0 / self.solid_angle,
                }
            }

            /// [`PolygonSolidAngle::pdf`]: 1/Ω inside the triangle, else 0.
            #[inline(always)]
            pub fn pdf(&self, w: V3) -> Real {
                if self.triangle.contains(w) {
                    1.0 / self.solid_angle
                } else {
                    0.0
                }
            }
        }

        /// Solid-angle sampling of a convex polygon light from any shading
        /// point: built once per light; [`PolygonLightSampler::at`] prepares
        /// a [`PolygonSolidAngle`] for many samples at one point, and the
        /// [`LightSampler`] methods sample one point without allocating
        /// (two passes over the fan instead of a stored table). Only the
        /// part of the polygon above the shading point's horizon is
        /// sampled: a straddling polygon is cut by the plane
        /// n·(x − p) = 0 (one Sutherland–Hodgman step, 1974) into a fixed
        /// buffer on the stack, hence at most [`MAX_POLYGON_VERTICES`]
        /// vertices, checked by [`PolygonLightSampler::new`].
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, PolygonLightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A hexagon at height 2.
        /// let hexagon = (0..6).map(|k| {
        #[doc = concat!("    let a = k as ", stringify!($p), " * std::", stringify!($p), "::consts::PI / 3.0;")]
        #[doc = concat!("    ", stringify!($v3), "::new(a.cos(), a.sin(), 2.0)")]
        /// });
        /// let light = PolygonLightSampler::new(ConvexPolygon::new(hexagon.collect())?)?;
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.7, 0.2);")]
        /// let s = light.sample(p, n, u).unwrap();
        /// // The same sample as the prepared form, without its allocation.
        /// assert_eq!(Some(s), light.at(p, n).sample(u));
        /// assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        /// // A shading point facing +y sees only the hexagon's half with
        /// // y > 0: every sample lands there.
        #[doc = concat!("let m = ", stringify!($v3), "::Y;")]
        /// let s = light.sample(p, m, u).unwrap();
        /// assert!(s.direction.y > 0.0 && light.pdf(p, m, s.direction) == s.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct PolygonLightSampler {
            polygon: ConvexPolygon,
            rectangle: Option<(V3, V3, V3)>,
        }

        impl PolygonLightSampler {
            /// The sampler of `polygon`.
            ///
            /// Errors: [`SamplingError::TooManyVertices`] for a polygon of
            /// more than [`MAX_POLYGON_VERTICES`] vertices (its part above a
            /// shading point's horizon is clipped into a fixed buffer, see
            /// the [`LightSampler`] impl).
            pub fn new(polygon: ConvexPolygon) -> Result<Self, SamplingError> {
                let count = polygon.vertices().len();
                if count > MAX_POLYGON_VERTICES {
                    return Err(SamplingError::TooManyVertices {
                        count,
                        limit: MAX_POLYGON_VERTICES,
                    });
                }
                let rectangle = polygon.as_rectangle();
                Ok(PolygonLightSampler { polygon, rectangle })
            }

            /// The polygon.
            #[inline]
            pub fn polygon(&self) -> &ConvexPolygon {
                &self.polygon
            }

            /// The spherical rectangle at `reference`, when the polygon is a
            /// rectangle that it can be built for from there.
            #[inline]
            fn rectangle_at(&self, reference: V3) -> Option<SphericalRectangle> {
                let (corner, e0, e1) = self.rectangle?;
                SphericalRectangle::new(reference, corner, e0, e1).ok()
            }

            /// The polygon's solid-angle sampler at (`reference`, `normal`),
            /// for many samples at one point (allocates the fan's table
            /// once): the whole polygon when it lies on or above the
            /// horizon (its spherical rectangle if it is a rectangle), the
            /// part above the horizon when it straddles it (always a fan),
            /// and an empty fan when it lies wholly below. It samples exactly
            /// as [`LightSampler::sample`] does.
            pub fn at(&self, reference: V3, normal: V3) -> PolygonSolidAngle {
                let vertices = self.polygon.vertices();
                let fan = |vertices: &[V3]| {
                    let mut triangles = Vec::new();
                    let mut cumulative = Vec::new();
                    let mut total = 0.0;
                    for t in fan_at(reference, vertices) {
                        total += t.solid_angle();
                        triangles.push(t);
                        cumulative.push(total);
                    }
                    PolygonSolidAngle::Fan {
                        triangles,
                        cumulative,
                        reference,
                        on_plane: self.polygon.vertices()[0],
                        normal: self.polygon.normal(),
                    }
                };
                match horizon(reference, normal, vertices) {
                    Horizon::Below => fan(&[]),
                    Horizon::Above => match self.rectangle_at(reference) {
                        Some(r) => PolygonSolidAngle::Rectangle(r),
                        None => fan(vertices),
                    },
                    Horizon::Straddles => fan(Clipped::above(reference, normal, vertices).vertices()),
                }
            }
        }

        /// The fan's spherical triangles (v₀, vᵢ, vᵢ₊₁) of the convex
        /// polygon `vertices` at `reference`, in order, skipping those that
        /// are degenerate from there.
        #[inline]
        fn fan_at(reference: V3, vertices: &[V3]) -> impl Iterator<Item = SphericalTriangle> + '_ {
            (1..vertices.len().saturating_sub(1)).filter_map(move |i| {
                SphericalTriangle::new(reference, vertices[0], vertices[i], vertices[i + 1]).ok()
            })
        }

        /// A direction uniform in the solid angle of the convex polygon
        /// `vertices` (in the plane through `on_plane` with unit normal
        /// `plane_normal`) seen from `reference`, by its fan of spherical
        /// triangles, one chosen in proportion to its solid angle with the
        /// choosing number reused; without allocating (two passes over the
        /// fan, the same partial sums as [`pick_by_cumulative`]). `None` if
        /// every fan triangle is degenerate.
        #[inline]
        pub(crate) fn sample_fan(
            reference: V3,
            vertices: &[V3],
            on_plane: V3,
            plane_normal: V3,
            u: V2,
        ) -> Option<LightSample> {
            let total: Real = fan_at(reference, vertices).map(|t| t.solid_angle()).sum();
            let target = u.x * total;
            let count = fan_at(reference, vertices).count();
            let (mut lo, mut chosen) = (0.0, None);
            for (k, t) in fan_at(reference, vertices).enumerate() {
                let hi = lo + t.solid_angle();
                if hi > target || k + 1 == count {
                    chosen = Some((t, lo, hi));
                    break;
                }
                lo = hi;
            }
            let (t, lo, hi) = chosen?;
            let u0 = rescale_within(target, lo, hi);
            let d = t.sample(V2::new(u0, u.y));
            let distance = distance_to_plane(reference, d.direction, on_plane, plane_normal);
            Some(LightSample {
                direction: d.direction,
                pdf: 1.0 / total,
                point: reference + d.direction * distance,
                distance,
            })
        }

        /// The density of [`sample_fan`] at the unit `direction`: 1/Ω inside
        /// the fan's spherical triangles, else 0.
        #[inline]
        pub(crate) fn pdf_fan(reference: V3, vertices: &[V3], direction: V3) -> Real {
            if fan_at(reference, vertices).any(|t| t.contains(direction)) {
                1.0 / fan_at(reference, vertices).map(|t| t.solid_angle()).sum::<Real>()
            } else {
                0.0
            }
        }

        /// Samples only what the shading point can see: a polygon wholly
        /// below the horizon gives `None`, one wholly on or above it is
        /// sampled whole (its spherical rectangle if it is a rectangle,
        /// else its fan), and one that straddles the horizon is first
        /// clipped to its part above it ([`MAX_POLYGON_VERTICES`] + 1
        /// vertices on the stack: no allocation), whose fan is sampled with
        /// density 1/Ω_visible.
        impl LightSampler for PolygonLightSampler {
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                let vertices = self.polygon.vertices();
                let (on_plane, n) = (vertices[0], self.polygon.normal());
                match horizon(reference, normal, vertices) {
                    Horizon::Below => None,
                    Horizon::Above => match self.rectangle_at(reference) {
                        Some(r) => Some(r.sample_point(u)),
                        None => sample_fan(reference, vertices, on_plane, n, u),
                    },
                    Horizon::Straddles => {
                        let clipped = Clipped::above(reference, normal, vertices);
                        sample_fan(reference, clipped.vertices(), on_plane, n, u)
                    }
                }
            }

            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                let vertices = self.polygon.vertices();
                match horizon(reference, normal, vertices) {
                    Horizon::Below => 0.0,
                    Horizon::Above => match self.rectangle_at(reference) {
                        Some(r) => r.pdf(direction),
                        None => pdf_fan(reference, vertices, direction),
                    },
                    Horizon::Straddles => {
                        // The clipped fan lies above the horizon (to the
                        // spherical triangles' rounding slack, which keeps
                        // pdf(sample) equal to the sample's density).
                        let clipped = Clipped::above(reference, normal, vertices);
                        pdf_fan(reference, clipped.vertices(), direction)
                    }
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(polygon_light_impl);

#[cfg(test)]
mod tests {
    use super::f64::{PolygonLightSampler, PolygonSolidAngle};
    use crate::f64::{LightSampler, TriangleLightSampler};
    use crate::SamplingError;
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::{convex_polygon_solid_angle, ConvexPolygon, Triangle};

    /// A hexagon in the plane x = 2 centred at height 0.3: a shading point
    /// at the origin facing +z sees its part above z = 0.
    fn hexagon() -> Vec<DVec3> {
        (0..6)
            .map(|k| {
                let a = -(k as f64) * std::f64::consts::PI / 3.0;
                DVec3::new(2.0, a.cos(), 0.3 + a.sin())
            })
            .collect()
    }

    fn grid() -> impl Iterator<Item = DVec2> {
        (0..=12).flat_map(|i| (0..=12).map(move |j| DVec2::new(i as f64, j as f64) / 12.0))
    }

    /// A triangle above the horizon is a one-triangle fan, and its
    /// `single_triangle` view samples and evaluates the density exactly as
    /// the fan does (bits compared, on a grid with its edges and on
    /// directions inside and outside); a straddling hexagon (a fan of
    /// several) and a rectangle have no such view.
    #[test]
    fn a_single_triangle_samples_as_its_fan_does() {
        let (p, n) = (DVec3::ZERO, DVec3::Z);
        let triangle = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(0.0, 1.5, 2.5),
            DVec3::new(2.0, -0.5, 2.2),
        ])
        .unwrap();
        let fan = PolygonLightSampler::new(triangle).unwrap().at(p, n);
        let single = fan.single_triangle().expect("one triangle");
        for u in grid() {
            let (a, b) = (fan.sample(u).unwrap(), single.sample(u));
            assert_eq!(
                a.direction.to_array().map(f64::to_bits),
                b.direction.to_array().map(f64::to_bits)
            );
            assert_eq!(a.pdf.to_bits(), b.pdf.to_bits());
            for w in [a.direction, -a.direction, DVec3::X] {
                assert_eq!(fan.pdf(w).to_bits(), single.pdf(w).to_bits());
            }
        }
        let hexagon = PolygonLightSampler::new(ConvexPolygon::new(hexagon()).unwrap()).unwrap();
        assert!(hexagon.at(p, n).single_triangle().is_none());
        let rectangle = ConvexPolygon::new(vec![
            DVec3::new(-1.0, -1.0, 1.0),
            DVec3::new(1.0, -1.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(-1.0, 1.0, 1.0),
        ])
        .unwrap();
        let rectangle = PolygonLightSampler::new(rectangle).unwrap().at(p, n);
        assert!(matches!(rectangle, PolygonSolidAngle::Rectangle(_)));
        assert!(rectangle.single_triangle().is_none());
    }

    /// Every sample of a straddling polygon lies above the horizon (to
    /// rounding, 1e-15 in cos θ), on the polygon's plane; its density is
    /// 1/Ω of the visible part (the solid angle of the clipped polygon,
    /// computed independently, to 1e-12 relative), pdf() returns it, and
    /// the prepared form gives the same sample.
    #[test]
    fn straddling_polygons_are_sampled_above_the_horizon_only() {
        let (p, n) = (DVec3::ZERO, DVec3::Z);
        let light = PolygonLightSampler::new(ConvexPolygon::new(hexagon()).unwrap()).unwrap();
        let visible: Vec<DVec3> = hexagon()
            .windows(2)
            .chain(std::iter::once(&[hexagon()[5], hexagon()[0]][..]))
            .flat_map(|e| {
                let (a, b) = (e[0], e[1]);
                let mut out = Vec::new();
                if a.z >= 0.0 {
                    out.push(a);
                }
                if (a.z > 0.0) != (b.z > 0.0) {
                    out.push(a + (b - a) * (a.z / (a.z - b.z)));
                }
                out
            })
            .collect();
        let omega = convex_polygon_solid_angle(p, &visible);
        let whole = convex_polygon_solid_angle(p, &hexagon());
        assert!(omega < 0.9 * whole);
        let prepared = light.at(p, n);
        assert!(matches!(prepared, PolygonSolidAngle::Fan { .. }));
        assert!((prepared.solid_angle() - omega).abs() <= 1e-12 * omega);
        for u in grid() {
            let s = light.sample(p, n, u).unwrap();
            assert!(s.direction.dot(n) >= -1e-15, "{u}: {}", s.direction);
            assert!((s.point.x - 2.0).abs() < 1e-12, "{u}: {}", s.point);
            assert!((s.pdf * omega - 1.0).abs() < 1e-12, "{u}");
            assert_eq!(light.pdf(p, n, s.direction), s.pdf);
            assert_eq!(prepared.sample(u), Some(s));
        }
        // Below the horizon: density 0.
        assert_eq!(light.pdf(p, n, DVec3::new(1.0, 0.0, -0.1).normalize()), 0.0);
        // Wholly below: nothing.
        assert!(light.sample(p, -DVec3::X, DVec2::splat(0.5)).is_none());
        assert_eq!(light.at(p, -DVec3::X).solid_angle(), 0.0);
    }

    #[test]
    fn straddling_triangles_are_sampled_above_the_horizon_only() {
        let (p, n) = (DVec3::ZERO, DVec3::Z);
        let [a, b, c] = [
            DVec3::new(2.0, -1.0, -0.5),
            DVec3::new(2.0, 1.0, -0.5),
            DVec3::new(2.0, 0.0, 1.0),
        ];
        let light = TriangleLightSampler::new(Triangle::new(a, b, c).unwrap());
        // The part above z = 0: the apex and the two crossings at t = 1/3.
        let visible = [b + (c - b) / 3.0, c, a + (c - a) / 3.0];
        let omega = convex_polygon_solid_angle(p, &visible);
        for u in grid() {
            let s = light.sample(p, n, u).unwrap();
            assert!(s.direction.dot(n) >= -1e-15, "{u}");
            assert!((s.pdf * omega - 1.0).abs() < 1e-12, "{u}");
            assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        }
    }

    #[test]
    fn polygons_beyond_the_vertex_limit_are_rejected() {
        let many: Vec<DVec3> = (0..65)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 65.0;
                DVec3::new(a.cos(), a.sin(), 2.0)
            })
            .collect();
        let e = PolygonLightSampler::new(ConvexPolygon::new(many).unwrap()).unwrap_err();
        assert_eq!(
            e,
            SamplingError::TooManyVertices {
                count: 65,
                limit: 64
            }
        );
        assert!(e.to_string().contains("at most 64 vertices"), "{e}");
    }
}
