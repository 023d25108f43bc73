//! Many samples of one polygon's projected solid angle from one point: the
//! inverse of each sector's area, tabulated once, as the first guess of the
//! sector's solve.

macro_rules! projected_table_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::light_sample::$p::LightSample;
        use crate::projected_polygon::$p::ProjectedPolygon;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// One node δⱼ of a sector's table: A(δⱼ) = j A_k/J (the sector's
        /// area A_k), and the slope dA/dδ there.
        #[derive(Clone, Copy, Debug, PartialEq)]
        struct Node {
            delta: Real,
            area: Real,
            slope: Real,
        }

        /// [`ProjectedPolygon`] prepared for many samples at its point: the
        /// same map (density cos θ/Ω⊥ over the visible polygon), with a
        /// better first guess for each sample's solve.
        ///
        /// # Method
        /// A non-central sample solves A(δ) = target for the azimuth δ in
        /// one sector (Halley's method inside a bisection bracket, see
        /// [`ProjectedPolygon`]); from the quadratic first guess it takes
        /// two evaluations of A for most samples. Here each non-central
        /// sector's A is inverted once at J + 1 = 17 nodes of equal area,
        /// with its slope dA/dδ = ½(r_o² − r_i²) there, and a sample starts
        /// from the cubic Hermite interpolant of the inverse δ(A) (slopes
        /// 1/(dA/dδ) at the nodes). Its error, of order (A_k/J)⁴, is below
        /// the solve's threshold for a last Halley step taken without
        /// evaluating A again, so most samples evaluate A once. The solve
        /// and its stopping rules are [`ProjectedPolygon`]'s own, so the
        /// result is the same root to rounding (a few ulps: the iterates
        /// differ). Where the inverse is not smooth on an interval (a slope
        /// that vanishes, at a sector's end where its inner and outer
        /// edges meet, or that varies by more than 4× across it), the
        /// sample starts from [`ProjectedPolygon`]'s quadratic guess, which
        /// is made for those ends. Central polygons need no solve and are
        /// sampled as they are.
        ///
        /// # Cost
        /// Building costs 15 solves per non-central sector (a few hundred
        /// samples' worth for a quadrilateral), so this type is for many
        /// samples from one point (an estimate); a renderer shading each
        /// point with a few samples keeps [`ProjectedPolygon`] (bench
        /// `projected`, rows `projected square`).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{ProjectedPolygon, TabulatedProjectedPolygon};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A square off to the side of the receiver's normal (non-central).
        /// let square = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(-2.0, -1.0, 3.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 3.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(-1.0, 1.0, 3.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(-2.0, 1.0, 3.0),")]
        /// ])?;
        #[doc = concat!("let plain = ProjectedPolygon::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, &square)?;")]
        /// let table = TabulatedProjectedPolygon::new(plain);
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.3, 0.8);")]
        /// let (a, b) = (plain.sample(u), table.sample(u));
        /// assert!((a.direction - b.direction).length() < 1e-5);
        /// assert!(table.newton_steps(u) <= plain.newton_steps(u));
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct TabulatedProjectedPolygon {
            polygon: ProjectedPolygon,
            /// J + 1 nodes per sector (none when central).
            nodes: Box<[Node]>,
        }

        impl TabulatedProjectedPolygon {
            /// The number J of intervals per sector.
            pub const INTERVALS: usize = 16;

            /// Tabulates the inverse of each of `polygon`'s non-central
            /// sectors' areas.
            pub fn new(polygon: ProjectedPolygon) -> Self {
                let intervals = Self::INTERVALS;
                let mut nodes = Vec::new();
                if !polygon.central() {
                    let sectors = polygon.sector_shape(0).0;
                    nodes.reserve(sectors * (intervals + 1));
                    for k in 0..sectors {
                        let (_, width, size) = polygon.sector_shape(k);
                        for j in 0..=intervals {
                            let area = size * j as Real / intervals as Real;
                            let (delta, slope) = if j == 0 {
                                (0.0, polygon.slope_at(k, 0.0))
                            } else if j == intervals {
                                (width, polygon.slope_at(k, width))
                            } else {
                                polygon.root_and_slope(k, area)
                            };
                            nodes.push(Node { delta, area, slope });
                        }
                    }
                }
                TabulatedProjectedPolygon {
                    polygon,
                    nodes: nodes.into_boxed_slice(),
                }
            }

            /// The untabulated sampler.
            #[inline]
            pub fn sampler(&self) -> &ProjectedPolygon {
                &self.polygon
            }

            /// [`ProjectedPolygon::projected_solid_angle`].
            #[inline]
            pub fn projected_solid_angle(&self) -> Real {
                self.polygon.projected_solid_angle()
            }

            /// [`ProjectedPolygon::projected_solid_angle_error`].
            #[inline]
            pub fn projected_solid_angle_error(&self) -> Real {
                self.polygon.projected_solid_angle_error()
            }

            /// [`ProjectedPolygon::pdf`].
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                self.polygon.pdf(w)
            }

            /// The same direction as [`ProjectedPolygon::sample`] for u, to
            /// a few ulps, with its density cos θ/Ω⊥.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                self.sample_and_steps(u).0
            }

            /// The Newton steps the sample of u takes (tests, benchmarks).
            pub fn newton_steps(&self, u: V2) -> usize {
                self.sample_and_steps(u).1
            }

            #[inline]
            fn sample_and_steps(&self, u: V2) -> (LightSample, usize) {
                if self.nodes.is_empty() {
                    // Central: no solve, no steps.
                    return (self.polygon.sample(u), 0);
                }
                let (k, target) = self.polygon.locate(u.x);
                let guess = self.guess(k, target);
                self.polygon.sample_sector(k, target, guess, u.y)
            }

            /// The first azimuth for area `target` in sector k (type docs).
            #[inline]
            fn guess(&self, k: usize, target: Real) -> Real {
                let intervals = Self::INTERVALS;
                let (_, _, size) = self.polygon.sector_shape(k);
                let row = &self.nodes[k * (intervals + 1)..(k + 1) * (intervals + 1)];
                let j = if size > 0.0 {
                    ((target / size * intervals as Real) as usize).min(intervals - 1)
                } else {
                    0
                };
                let (a, b) = (&row[j], &row[j + 1]);
                let smooth = a.slope > 0.0
                    && b.slope > 0.0
                    && a.slope <= 4.0 * b.slope
                    && b.slope <= 4.0 * a.slope;
                if !smooth {
                    return self.polygon.initial_guess(k, target);
                }
                let da = b.area - a.area;
                let s = ((target - a.area) / da).clamp(0.0, 1.0);
                let r = 1.0 - s;
                let guess = (a.delta * (1.0 + 2.0 * s) + da / a.slope * s) * r * r
                    + (b.delta * (3.0 - 2.0 * s) - da / b.slope * r) * s * s;
                // max/min, not clamp: degenerate geometry (fuzz case
                // `projected-table-unordered-nodes`) may leave the nodes
                // unordered or NaN, which clamp would panic on.
                guess.max(a.delta).min(b.delta)
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_table_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec2, Vec3};
    use lambert_geometry::f64::ConvexPolygon;

    /// Non-central polygons: a wall at grazing elevation, a square off to
    /// the side overhead, and a triangle crossing the horizon (clipped).
    fn polygons() -> Vec<Vec<DVec3>> {
        vec![
            vec![
                DVec3::new(3.0, -1.0, 0.05),
                DVec3::new(3.0, 1.0, 0.05),
                DVec3::new(3.0, 1.0, 1.05),
                DVec3::new(3.0, -1.0, 1.05),
            ],
            vec![
                DVec3::new(-2.0, -1.0, 3.0),
                DVec3::new(-1.0, -1.0, 3.0),
                DVec3::new(-1.0, 1.0, 3.0),
                DVec3::new(-2.0, 1.0, 3.0),
            ],
            vec![
                DVec3::new(1.0, -1.0, -0.5),
                DVec3::new(1.5, 0.0, 2.0),
                DVec3::new(1.0, 1.0, -0.5),
            ],
        ]
    }

    fn convex(v: &[DVec3]) -> ConvexPolygon {
        ConvexPolygon::new(v.to_vec())
            .or_else(|_| ConvexPolygon::new(v.iter().rev().copied().collect()))
            .unwrap()
    }

    /// The table's samples are the plain sampler's to the solve's own
    /// tolerance, with the same density, and take fewer area evaluations.
    /// Both solves stop at a computed residual of at most 8ε times the
    /// area's terms (`ProjectedPolygon`'s solve; the terms are ≲ 2 in
    /// these sectors), and the computed area itself carries a rounding
    /// error of that size (that is what the floor is set from), so the
    /// true residual is within 2 · 8ε · 2 = 32ε; divided by the slope
    /// dA/dδ (≥ 1/2 on these smooth intervals), each azimuth is within
    /// 64ε of the root and two within 128ε; the direction moves by at
    /// most that per unit azimuth: 128ε. (Measured: ≤ 41ε in f64; ≤ 72ε
    /// in f32, whose sines, `sin_cos`, are good to about 2 ulps where
    /// libm's were within half of one, and gave ≤ 50ε.) In f32 the same
    /// argument gives 128ε of f32. The steps: over
    /// 4097 u, the table's total is at most 60 % of the plain sampler's,
    /// and for no u of the first two polygons more than the plain one's.
    /// Negative control for the comparison: the plain sampler at u shifted
    /// by 1e-9 lies farther than the tolerance for most u.
    #[test]
    fn table_gives_the_plain_directions_with_fewer_steps() {
        for (k, v) in polygons().iter().enumerate() {
            let plain =
                crate::f64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &convex(v)).unwrap();
            assert!(!plain.is_central());
            let table = super::f64::TabulatedProjectedPolygon::new(plain);
            assert_eq!(table.projected_solid_angle(), plain.projected_solid_angle());
            let (mut steps_plain, mut steps_table, mut shifted_far) = (0, 0, 0);
            for i in 0..=4096 {
                let u = DVec2::new(i as f64 / 4096.0, (i % 7) as f64 / 6.0);
                let (a, b) = (plain.sample(u), table.sample(u));
                let error = (a.direction - b.direction).abs().max_element();
                assert!(
                    error <= 128.0 * f64::EPSILON,
                    "polygon {k}, u {u}: {error:e}"
                );
                // cos θ/Ω⊥ moves with the direction's z: 128ε/Ω⊥.
                let omega = plain.projected_solid_angle();
                assert!(
                    (a.pdf - b.pdf).abs() <= 128.0 * f64::EPSILON * (1.0 / omega + a.pdf),
                    "polygon {k}, u {u}"
                );
                let shifted = plain.sample(u + DVec2::new(1e-9, 0.0)).direction;
                shifted_far +=
                    usize::from((shifted - a.direction).abs().max_element() > 128.0 * f64::EPSILON);
                let (p, t) = (plain.newton_steps(u), table.newton_steps(u));
                if k < 2 {
                    assert!(t <= p, "polygon {k}, u {u}: {t} steps against {p}");
                }
                steps_plain += p;
                steps_table += t;
            }
            assert!(shifted_far > 2000, "polygon {k}: {shifted_far}");
            assert!(
                10 * steps_table <= 6 * steps_plain,
                "polygon {k}: {steps_table} steps against {steps_plain}"
            );
            // f32.
            let v32: Vec<Vec3> = v.iter().map(|p| p.as_vec3()).collect();
            let poly32 = lambert_geometry::f32::ConvexPolygon::new(v32.clone())
                .or_else(|_| {
                    lambert_geometry::f32::ConvexPolygon::new(v32.iter().rev().copied().collect())
                })
                .unwrap();
            let plain = crate::f32::ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &poly32).unwrap();
            let table = super::f32::TabulatedProjectedPolygon::new(plain);
            for i in 0..=4096 {
                let u = Vec2::new(i as f32 / 4096.0, (i % 7) as f32 / 6.0);
                let (a, b) = (plain.sample(u), table.sample(u));
                let error = (a.direction - b.direction).abs().max_element();
                assert!(
                    error <= 128.0 * f32::EPSILON,
                    "f32 polygon {k}, u {u}: {error:e}"
                );
            }
        }
    }

    /// A central polygon (the receiver's normal through it) needs no
    /// solve: the table is empty and the samples are the plain ones, bit
    /// for bit.
    #[test]
    fn central_polygons_are_sampled_as_they_are() {
        let square = [
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ];
        let plain =
            crate::f64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &convex(&square)).unwrap();
        assert!(plain.is_central());
        let table = super::f64::TabulatedProjectedPolygon::new(plain);
        for i in 0..=64 {
            let u = DVec2::new(i as f64 / 64.0, 0.3);
            assert_eq!(plain.sample(u), table.sample(u));
            assert_eq!(table.newton_steps(u), 0);
        }
    }
}
