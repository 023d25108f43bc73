//! Area sampling of a polygon light from one receiver, with the number of
//! its fan's triangles fixed at compile time: the samples of
//! [`PolygonAreaSampler`](crate::f64::PolygonAreaSampler), to the bit,
//! without a branch or a call per sample.
//!
//! [`LightSampler::sample`](crate::f64::LightSampler::sample) of a polygon
//! tests the receiver's horizon against every vertex, searches the fan's
//! cumulative areas and indexes its triangle list, all per sample; a loop
//! over a block of samples compiled to a call per sample. Here the horizon
//! test is made once (the receiver is fixed), the search is a count of the
//! `N` cumulative areas at or below the target (the index the search
//! finds, since the table increases), and the triangle is chosen by
//! selecting among the `N` candidates, so that a block's loop vectorises.
//! Sample reuse as in pbrt-v4 §A.1: one uniform number picks the triangle
//! and, rescaled, places the point in it.

macro_rules! polygon_area_fan_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::discrete::$p::rescale_within;
        use crate::light_sample::$p::{LightSample, PointSample};
        use crate::light_sampler::$p::seen_from_or_zero;
        use crate::triangle::$p::UniformTriangle;
        use glam::{$v2 as V2, $v3 as V3};
        use lambert_geometry::precision::$p::Real;

        /// A polygon light's uniform area sampler seen from one reference
        /// point, for a fan of exactly `N` triangles: built by
        /// [`PolygonAreaSampler::fan`](crate::$p::PolygonAreaSampler::fan).
        /// The point is uniform on the polygon (density 1/A per m²), its
        /// density converted to solid angle, p_ω = p_A d²/|cos θ_l|.
        #[derive(Clone, Copy, Debug)]
        pub struct PolygonAreaFan<const N: usize> {
            triangles: [UniformTriangle; N],
            /// The fan's cumulative areas, increasing; the last is A.
            cumulative: [Real; N],
            /// 1/A per m².
            pdf_area: Real,
            reference: V3,
            /// Whether some vertex lies above the reference's horizon
            /// (otherwise no sample is given).
            visible: bool,
        }

        impl<const N: usize> PolygonAreaFan<N> {
            /// The fan of `triangles` with cumulative areas `cumulative`
            /// seen from `reference`; `None` unless both hold exactly `N`
            /// entries, `N ≥ 1`.
            pub(crate) fn new(
                triangles: &[UniformTriangle],
                cumulative: &[Real],
                reference: V3,
                visible: bool,
            ) -> Option<Self> {
                let triangles: [UniformTriangle; N] = triangles.try_into().ok()?;
                let cumulative: [Real; N] = cumulative.try_into().ok()?;
                let total = *cumulative.last()?;
                Some(PolygonAreaFan {
                    triangles,
                    cumulative,
                    pdf_area: 1.0 / total,
                    reference,
                    visible,
                })
            }

            /// The light sample of `u` that
            /// [`LightSampler::sample`](crate::$p::LightSampler::sample)
            /// gives, to the bit, where it gives one; elsewhere one of
            /// density 0 (its other fields unspecified). Branch-free.
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
            #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
            /// let fan = light.fan::<2>(p, n).unwrap();
            #[doc = concat!("let u = ", stringify!($v2), "::new(0.7, 0.2);")]
            /// assert_eq!(Some(fan.sample_or_zero(u)), light.sample(p, n, u));
            /// assert!(light.fan::<3>(p, n).is_none());
            /// # Ok::<(), lambert_geometry::GeometryError>(())
            /// ```
            #[inline(always)]
            pub fn sample_or_zero(&self, u: V2) -> LightSample {
                let cumulative = &self.cumulative;
                let target = u.x * cumulative[N - 1];
                // The search's index: the count of entries ≤ target.
                let mut k = 0;
                for &c in cumulative {
                    k += usize::from(c <= target);
                }
                let k = k.min(N - 1);
                let (mut lo, mut hi) = (0.0, cumulative[0]);
                for j in 1..N {
                    if j == k {
                        (lo, hi) = (cumulative[j - 1], cumulative[j]);
                    }
                }
                let uv = V2::new(rescale_within(target, lo, hi), u.y);
                // Every candidate's point, one kept: a select per lane.
                let mut point = self.triangles[0].sample(uv);
                for (j, triangle) in self.triangles.iter().enumerate().skip(1) {
                    let candidate = triangle.sample(uv);
                    if j == k {
                        point = candidate;
                    }
                }
                let l = seen_from_or_zero(
                    self.reference,
                    PointSample {
                        pdf_area: self.pdf_area,
                        ..point
                    },
                );
                LightSample {
                    pdf: if self.visible { l.pdf } else { 0.0 },
                    ..l
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(polygon_area_fan_impl);

#[cfg(test)]
mod tests {
    macro_rules! fan_tests {
        ($name:ident, $p:ident, $v2:ident, $v3:ident) => {
            /// The fan's samples are `sample`'s to the bit (the same
            /// direction, distance, point and density where `sample` gives
            /// one, density 0 where it gives none), for polygons of 3 to 6
            /// vertices from receivers that see them face-on, obliquely,
            /// edge-on, from behind and with every vertex below the
            /// horizon; a fan of another size is refused.
            #[test]
            fn $name() {
                use glam::{$v2, $v3};
                use lambert_geometry::$p::ConvexPolygon;
                use $crate::$p::{LightSampler, PolygonAreaSampler};
                type R = lambert_geometry::precision::$p::Real;
                use $crate::test_shapes::$p::ring;
                let receivers = [
                    ($v3::ZERO, $v3::Z),
                    ($v3::new(0.5, 0.2, 0.0), $v3::new(0.6, 0.0, 0.8)),
                    ($v3::new(3.0, 0.0, 1.0), $v3::Z), // edge-on: in the plane
                    ($v3::new(0.0, 0.0, 2.0), $v3::Z), // behind
                    ($v3::ZERO, -$v3::Z),              // every vertex below
                ];
                let mut compared = [0usize; 2];
                for n in 3..=6 {
                    let polygon = ConvexPolygon::new(ring(n, 1.0)).unwrap();
                    let sampler = PolygonAreaSampler::new(polygon);
                    for &(p, normal) in &receivers {
                        let check =
                            |u: $v2, s: $crate::$p::LightSample, compared: &mut [usize; 2]| {
                                match sampler.sample(p, normal, u) {
                                    Some(want) => {
                                        compared[0] += 1;
                                        let bits = |l: $crate::$p::LightSample| {
                                            [l.direction.to_array(), l.point.to_array()]
                                                .map(|v| v.map(|x| x.to_bits()))
                                        };
                                        assert_eq!(bits(s), bits(want), "n {n} u {u}");
                                        assert_eq!(s.pdf.to_bits(), want.pdf.to_bits());
                                        assert_eq!(s.distance.to_bits(), want.distance.to_bits());
                                    }
                                    None => {
                                        compared[1] += 1;
                                        assert_eq!(s.pdf, 0.0, "n {n} u {u}");
                                    }
                                }
                            };
                        let us = (0..997u32).map(|i| {
                            let x = (i as R + 0.5) / 997.0;
                            $v2::new(x, (x * 61.8).fract())
                        });
                        let us = us.chain([$v2::ZERO, $v2::splat(ONE_BELOW as R)]);
                        let triangles = n - 2;
                        for u in us {
                            match triangles {
                                1 => check(
                                    u,
                                    sampler.fan::<1>(p, normal).unwrap().sample_or_zero(u),
                                    &mut compared,
                                ),
                                2 => check(
                                    u,
                                    sampler.fan::<2>(p, normal).unwrap().sample_or_zero(u),
                                    &mut compared,
                                ),
                                3 => check(
                                    u,
                                    sampler.fan::<3>(p, normal).unwrap().sample_or_zero(u),
                                    &mut compared,
                                ),
                                _ => check(
                                    u,
                                    sampler.fan::<4>(p, normal).unwrap().sample_or_zero(u),
                                    &mut compared,
                                ),
                            }
                        }
                        assert!(sampler.fan::<5>(p, normal).is_none());
                        assert!(n == 3 || sampler.fan::<1>(p, normal).is_none());
                    }
                }
                // Both outcomes were exercised.
                assert!(compared[0] > 5_000 && compared[1] > 5_000, "{compared:?}");
            }
        };
    }

    const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;
    fan_tests!(fan_samples_are_the_samplers_f64, f64, DVec2, DVec3);
    fan_tests!(fan_samples_are_the_samplers_f32, f32, Vec2, Vec3);
}
