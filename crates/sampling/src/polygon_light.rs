//! Solid-angle sampling of a convex polygon light.

macro_rules! polygon_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::discrete::$p::pick_by_cumulative;
        use crate::light_sample::$p::LightSample;
        use crate::light_sampler::$p::{all_below, LightSampler};
        use crate::spherical_rectangle::$p::SphericalRectangle;
        use crate::spherical_triangle::$p::SphericalTriangle;
        use crate::triangle_light::$p::distance_to_plane;
        use lambert_geometry::precision::$p::{Real, ONE_MINUS_EPSILON, V2, V3};
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
        #[doc = concat!("let at = PolygonLightSampler::new(square).at(", stringify!($v3), "::ZERO);")]
        /// assert!(matches!(at, PolygonSolidAngle::Rectangle(_)));
        #[doc = concat!("let s = at.sample(", stringify!($v2), "::new(0.5, 0.5)).unwrap();")]
        /// assert_eq!(at.pdf(s.direction), s.pdf);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
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

        /// Solid-angle sampling of a convex polygon light from any shading
        /// point: built once per light; [`PolygonLightSampler::at`] prepares
        /// a [`PolygonSolidAngle`] for many samples at one point, and the
        /// [`LightSampler`] methods sample one point without allocating
        /// (two passes over the fan instead of a stored table).
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
        /// let light = PolygonLightSampler::new(ConvexPolygon::new(hexagon.collect())?);
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.7, 0.2);")]
        /// let s = light.sample(p, n, u).unwrap();
        /// // The same sample as the prepared form, without its allocation.
        /// assert_eq!(Some(s), light.at(p).sample(u));
        /// assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct PolygonLightSampler {
            polygon: ConvexPolygon,
            rectangle: Option<(V3, V3, V3)>,
        }

        impl PolygonLightSampler {
            /// The sampler of `polygon`.
            pub fn new(polygon: ConvexPolygon) -> Self {
                let rectangle = polygon.as_rectangle();
                PolygonLightSampler { polygon, rectangle }
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

            /// The fan's spherical triangles at `reference`, in order,
            /// skipping those that are degenerate from there.
            #[inline]
            fn fan_at(&self, reference: V3) -> impl Iterator<Item = SphericalTriangle> + '_ {
                let v = self.polygon.vertices();
                (1..v.len() - 1)
                    .filter_map(move |i| SphericalTriangle::new(reference, v[0], v[i], v[i + 1]).ok())
            }

            /// The polygon's solid-angle sampler at `reference` (allocates
            /// the fan's table once, for many samples at one point).
            pub fn at(&self, reference: V3) -> PolygonSolidAngle {
                if let Some(r) = self.rectangle_at(reference) {
                    return PolygonSolidAngle::Rectangle(r);
                }
                let mut triangles = Vec::new();
                let mut cumulative = Vec::new();
                let mut total = 0.0;
                for t in self.fan_at(reference) {
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
            }
        }

        impl LightSampler for PolygonLightSampler {
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if all_below(reference, normal, self.polygon.vertices()) {
                    return None;
                }
                if let Some(r) = self.rectangle_at(reference) {
                    return Some(r.sample_point(u));
                }
                // First pass: Ω. Second: the same choice as
                // `pick_by_cumulative` over the same partial sums.
                let total: Real = self.fan_at(reference).map(|t| t.solid_angle()).sum();
                let target = u.x * total;
                let count = self.fan_at(reference).count();
                let (mut lo, mut chosen) = (0.0, None);
                for (k, t) in self.fan_at(reference).enumerate() {
                    let hi = lo + t.solid_angle();
                    if hi > target || k + 1 == count {
                        chosen = Some((t, lo, hi));
                        break;
                    }
                    lo = hi;
                }
                let (t, lo, hi) = chosen?;
                let u0 = ((target - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON);
                let d = t.sample(V2::new(u0, u.y));
                let (on_plane, n) = (self.polygon.vertices()[0], self.polygon.normal());
                let distance = distance_to_plane(reference, d.direction, on_plane, n);
                Some(LightSample {
                    direction: d.direction,
                    pdf: 1.0 / total,
                    point: reference + d.direction * distance,
                    distance,
                })
            }

            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if all_below(reference, normal, self.polygon.vertices()) {
                    return 0.0;
                }
                if let Some(r) = self.rectangle_at(reference) {
                    return r.pdf(direction);
                }
                if self.fan_at(reference).any(|t| t.contains(direction)) {
                    1.0 / self.fan_at(reference).map(|t| t.solid_angle()).sum::<Real>()
                } else {
                    0.0
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(polygon_light_impl);
