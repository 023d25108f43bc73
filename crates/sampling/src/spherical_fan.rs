//! A fan of spherical triangles in a fixed number of lanes: solid-angle
//! sampling of a polygon seen as several triangles, branch-free, so that a
//! batch of samples runs as one vectorised loop.

macro_rules! spherical_fan_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::discrete::$p::rescale_within;
        use crate::polygon_light::$p::PolygonSolidAngle;
        use crate::spherical_triangle::$p::SphericalTriangle;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// The fan of a [`PolygonSolidAngle`] of 1 to `N` spherical
        /// triangles in a loop of exactly `N`: the triangles and their
        /// cumulative solid angles, padded with copies of the last triangle
        /// and of the total Ω. It samples as
        /// [`PolygonSolidAngle::sample`] and [`PolygonSolidAngle::pdf`] do,
        /// to the bit, where those look the fan's triangle up per sample
        /// (a binary search and an indexed load, which keep a loop from
        /// vectorising): here the pick is a count over the `N` entries,
        /// and the picked triangle's constants a select per entry.
        ///
        /// Why padding leaves the values alone: the pick is the number of
        /// entries `≤ u₀·Ω`, clamped to the last real one. A padded entry
        /// is Ω, counted only when `u₀·Ω` rounds up to Ω, when the real
        /// entries are all counted too and the clamp picks the last real
        /// triangle, as the search does; and a copy of the last triangle
        /// adds no direction to the union that [`SphericalFan::pdf`] tests.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{PolygonLightSampler, SphericalFan};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A pentagon at height 2: three triangles seen from the origin.
        /// let pentagon = (0..5).map(|k| {
        #[doc = concat!("    let a = k as ", stringify!($p), " * std::", stringify!($p), "::consts::TAU / 5.0;")]
        #[doc = concat!("    ", stringify!($v3), "::new(a.cos(), a.sin(), 2.0)")]
        /// });
        /// let light = PolygonLightSampler::new(ConvexPolygon::new(pentagon.collect())?)?;
        #[doc = concat!("let at = light.at(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// let fan = SphericalFan::<6>::new(&at).unwrap();
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.7, 0.2);")]
        /// let (s, want) = (fan.sample(u), at.sample(u).unwrap());
        /// assert_eq!((s.direction, s.pdf), (want.direction, want.pdf));
        /// assert_eq!(fan.pdf(s.direction), at.pdf(s.direction));
        /// // Three triangles do not fit in two lanes.
        /// assert!(SphericalFan::<2>::new(&at).is_none());
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug)]
        pub struct SphericalFan<const N: usize> {
            /// The fan's triangles, then copies of the last.
            pub(crate) triangles: [SphericalTriangle; N],
            /// Their cumulative solid angles, then copies of Ω.
            pub(crate) cumulative: [Real; N],
            /// The index of the last real triangle.
            last: usize,
            /// Ω, the last real cumulative solid angle.
            total: Real,
        }

        impl<const N: usize> SphericalFan<N> {
            /// The fan of `seen`, if it is a fan (not a spherical
            /// rectangle) of 1 to `N` triangles.
            pub fn new(seen: &PolygonSolidAngle) -> Option<Self> {
                let PolygonSolidAngle::Fan {
                    triangles,
                    cumulative,
                    ..
                } = seen
                else {
                    return None;
                };
                if triangles.is_empty() || triangles.len() > N || cumulative.len() != triangles.len()
                {
                    return None;
                }
                let last = triangles.len() - 1;
                Some(SphericalFan {
                    triangles: std::array::from_fn(|j| triangles[j.min(last)]),
                    cumulative: std::array::from_fn(|j| cumulative[j.min(last)]),
                    last,
                    total: cumulative[last],
                })
            }

            /// [`PolygonSolidAngle::sample`]'s direction and density
            /// (1/Ω per steradian), to the bit: the triangle `k` whose
            /// cumulative interval holds `u₀·Ω`, sampled by Arvo's method
            /// at `((u₀·Ω − Ω_{k−1})/(Ω_k − Ω_{k−1}), u₁)`.
            #[inline(always)]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let total = self.total;
                let target = u.x * total;
                // The search's index: the count of entries ≤ target.
                let mut k = 0;
                for &c in &self.cumulative {
                    k += usize::from(c <= target);
                }
                let k = k.min(self.last);
                let (mut lo, mut hi) = (0.0, self.cumulative[0]);
                let mut triangle = self.triangles[0];
                for j in 1..N {
                    if j == k {
                        (lo, hi) = (self.cumulative[j - 1], self.cumulative[j]);
                        triangle = self.triangles[j];
                    }
                }
                let u0 = rescale_within(target, lo, hi);
                DirectionSample {
                    direction: triangle.sample(V2::new(u0, u.y)).direction,
                    pdf: 1.0 / total,
                }
            }

            /// [`PolygonSolidAngle::pdf`]: 1/Ω for unit directions in
            /// some triangle of the fan, else 0.
            #[inline(always)]
            pub fn pdf(&self, w: V3) -> Real {
                let mut inside = false;
                for triangle in &self.triangles {
                    inside |= triangle.contains(w);
                }
                if inside {
                    1.0 / self.total
                } else {
                    0.0
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(spherical_fan_impl);

#[cfg(test)]
mod tests {
    macro_rules! fan_tests {
        ($name:ident, $control:ident, $p:ident, $v2:ident, $v3:ident) => {
            /// The fan's samples and densities are the polygon sampler's to
            /// the bit, for polygons seen as 2 to 6 triangles (a triangle
            /// and a square cut by the horizon, a pentagon, a hexagon and
            /// an octagon, face-on and tilted), at the ends of the unit
            /// square and between; a rectangle (no fan) and a fan larger
            /// than `N` are refused.
            #[test]
            fn $name() {
                use glam::{$v2, $v3};
                use lambert_geometry::$p::ConvexPolygon;
                use $crate::$p::{PolygonLightSampler, PolygonSolidAngle, SphericalFan};
                type R = lambert_geometry::precision::$p::Real;
                use $crate::test_shapes::$p::ring;
                let tilted = $v3::new(0.8, 0.0, 0.6);
                let cases = [
                    (3, $v3::new(0.0, 0.0, 0.5), tilted), // cut: a quadrilateral
                    (4, $v3::new(0.0, 0.0, 0.5), tilted), // cut: five vertices
                    (5, $v3::ZERO, $v3::Z),
                    (5, $v3::new(0.3, 0.1, 0.0), tilted),
                    (6, $v3::ZERO, $v3::Z),
                    (8, $v3::ZERO, $v3::Z),
                ];
                let mut sizes = Vec::new();
                for (n, p, normal) in cases {
                    let light = PolygonLightSampler::new(ConvexPolygon::new(ring(n, 1.0)).unwrap())
                        .unwrap();
                    let at = light.at(p, normal);
                    let PolygonSolidAngle::Fan { triangles, .. } = &at else {
                        panic!("n {n}: not a fan");
                    };
                    let size = triangles.len();
                    sizes.push(size);
                    assert!(SphericalFan::<1>::new(&at).is_none() || size == 1);
                    let fan = SphericalFan::<6>::new(&at).unwrap();
                    let us = (0..997u32).map(|i| {
                        let x = (i as R + 0.5) / 997.0;
                        $v2::new(x, (x * 61.8).fract())
                    });
                    let one_below = 1.0 - R::EPSILON / 2.0;
                    for u in us.chain([$v2::ZERO, $v2::splat(one_below), $v2::new(one_below, 0.0)])
                    {
                        let (s, want) = (fan.sample(u), at.sample(u).unwrap());
                        let bits = |v: $v3| v.to_array().map(|x| x.to_bits());
                        assert_eq!(bits(s.direction), bits(want.direction), "n {n} u {u}");
                        assert_eq!(s.pdf.to_bits(), want.pdf.to_bits(), "n {n} u {u}");
                        // Inside (the sample) and, mirrored, mostly outside.
                        for w in [
                            s.direction,
                            -s.direction,
                            $v3::new(s.direction.x, s.direction.y, 0.1).normalize(),
                        ] {
                            assert_eq!(fan.pdf(w).to_bits(), at.pdf(w).to_bits(), "n {n} w {w}");
                        }
                    }
                }
                // The cases cover fans of 2 to 6 triangles.
                sizes.sort_unstable();
                sizes.dedup();
                assert_eq!(sizes, vec![2, 3, 4, 6], "fan sizes");
                let square = ConvexPolygon::new(vec![
                    $v3::new(-1.0, -1.0, 2.0),
                    $v3::new(1.0, -1.0, 2.0),
                    $v3::new(1.0, 1.0, 2.0),
                    $v3::new(-1.0, 1.0, 2.0),
                ])
                .unwrap();
                let at = PolygonLightSampler::new(square)
                    .unwrap()
                    .at($v3::ZERO, $v3::Z);
                assert!(
                    SphericalFan::<6>::new(&at).is_none(),
                    "a rectangle is no fan"
                );
            }

            /// Negative control: padding with anything but Ω breaks the
            /// pick, and the test above would see it. A fan whose padded
            /// entries are 0 counts them for every `u`, and picks the last
            /// triangle where the search picks an earlier one.
            #[test]
            fn $control() {
                use glam::{$v2, $v3};
                use lambert_geometry::$p::ConvexPolygon;
                use $crate::$p::PolygonLightSampler;
                type R = lambert_geometry::precision::$p::Real;
                let pentagon = (0..5)
                    .map(|k| {
                        let a = k as R * std::$p::consts::TAU / 5.0;
                        $v3::new(a.cos(), a.sin(), 2.0)
                    })
                    .collect();
                let light =
                    PolygonLightSampler::new(ConvexPolygon::new(pentagon).unwrap()).unwrap();
                let at = light.at($v3::ZERO, $v3::Z);
                let fan = $crate::$p::SphericalFan::<6>::new(&at).unwrap();
                let mut wrong = fan;
                wrong.cumulative[3..].fill(0.0);
                let u = $v2::new(0.1, 0.5);
                let want = at.sample(u).unwrap().direction;
                assert_eq!(fan.sample(u).direction, want);
                assert_ne!(wrong.sample(u).direction, want);
            }
        };
    }

    fan_tests!(
        fan_samples_as_the_polygon_sampler_f64,
        zero_padding_is_seen_f64,
        f64,
        DVec2,
        DVec3
    );
    fan_tests!(
        fan_samples_as_the_polygon_sampler_f32,
        zero_padding_is_seen_f32,
        f32,
        Vec2,
        Vec3
    );
}
