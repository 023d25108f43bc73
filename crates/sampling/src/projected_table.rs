//! Many samples of one polygon's projected solid angle from one point: the
//! inverse of each sector's area, tabulated once, as the first guess of the
//! sector's solve.

macro_rules! projected_table_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::light_sample::$p::LightSample;
        use crate::projected_polygon::$p::ProjectedPolygon;
        use crate::projected_sector::$p::{Bracket, Sector};
        use lambert_geometry::$p::Frame;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// One node δⱼ of a sector's table: A(δⱼ) = j A_k/J (the sector's
        /// area A_k), and the slope dA/dδ there.
        #[derive(Clone, Copy, Debug, PartialEq)]
        struct Node {
            delta: Real,
            area: Real,
            slope: Real,
        }

        /// Table nodes, one per sample of a batch (structure of arrays).
        struct NodeLanes {
            delta: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            area: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            slope: [Real; TabulatedProjectedPolygon::BATCH_LANES],
        }

        impl Default for NodeLanes {
            fn default() -> Self {
                const ZERO: [Real; TabulatedProjectedPolygon::BATCH_LANES] =
                    [0.0; TabulatedProjectedPolygon::BATCH_LANES];
                NodeLanes {
                    delta: ZERO,
                    area: ZERO,
                    slope: ZERO,
                }
            }
        }

        impl NodeLanes {
            #[inline(always)]
            fn set(&mut self, j: usize, n: &Node) {
                (self.delta[j], self.area[j], self.slope[j]) = (n.delta, n.area, n.slope);
            }

            #[inline(always)]
            fn get(&self, j: usize) -> Node {
                Node {
                    delta: self.delta[j],
                    area: self.area[j],
                    slope: self.slope[j],
                }
            }
        }

        /// The samples of one sector in the batch, structure of arrays:
        /// each sample's target and u₁, its solve's state, and what its
        /// last step gave (the direction, if it answered).
        struct Lanes {
            sample: [usize; TabulatedProjectedPolygon::BATCH_LANES],
            first: NodeLanes,
            last: NodeLanes,
            target: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            u1: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            delta: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            lo: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            hi: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            steps: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            answered: [bool; TabulatedProjectedPolygon::BATCH_LANES],
            x: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            y: [Real; TabulatedProjectedPolygon::BATCH_LANES],
            z: [Real; TabulatedProjectedPolygon::BATCH_LANES],
        }

        impl Default for Lanes {
            fn default() -> Self {
                const ZERO: [Real; TabulatedProjectedPolygon::BATCH_LANES] =
                    [0.0; TabulatedProjectedPolygon::BATCH_LANES];
                Lanes {
                    sample: [0; TabulatedProjectedPolygon::BATCH_LANES],
                    first: NodeLanes::default(),
                    last: NodeLanes::default(),
                    target: ZERO,
                    u1: ZERO,
                    delta: ZERO,
                    lo: ZERO,
                    hi: ZERO,
                    steps: ZERO,
                    answered: [false; TabulatedProjectedPolygon::BATCH_LANES],
                    x: ZERO,
                    y: ZERO,
                    z: ZERO,
                }
            }
        }

        impl Lanes {
            #[inline(always)]
            fn get(&self, j: usize) -> Bracket {
                Bracket {
                    delta: self.delta[j],
                    lo: self.lo[j],
                    hi: self.hi[j],
                    steps: self.steps[j],
                }
            }

            #[inline(always)]
            fn set(&mut self, j: usize, b: Bracket) {
                (self.delta[j], self.lo[j], self.hi[j], self.steps[j]) = (b.delta, b.lo, b.hi, b.steps);
            }

            /// One step of the solve for the first `n` samples, all of
            /// `sector` (a loop without branches, which vectorises): each
            /// sample's direction where the step answers, else its next
            /// state.
            #[inline(always)]
            fn step(&mut self, sector: &Sector, frame: &Frame, n: usize, max_iterations: Real) {
                for j in 0..n.min(TabulatedProjectedPolygon::BATCH_LANES) {
                    let (_, i, o, d, answered, next) =
                        sector.step(self.target[j], self.get(j), max_iterations);
                    let l = sector.local(d, &i, &o, self.u1[j]);
                    let v = ProjectedPolygon::world_direction(frame, l);
                    (self.x[j], self.y[j], self.z[j]) = (v.x, v.y, v.z);
                    self.answered[j] = answered;
                    self.set(j, next);
                }
            }
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

            /// How many samples [`sample_directions`](Self::sample_directions)
            /// sorts by sector at a time (its arrays take 17 KB in f64).
            pub const BATCH_LANES: usize = 128;

            /// How many steps of the solve [`sample_directions`](Self::sample_directions)
            /// takes in vectors; a sample that needs more (none in the
            /// tests' polygons) is drawn by [`sample`](Self::sample).
            const BATCH_STEPS: usize = 4;

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
                let sector = self.polygon.sector(k);
                let row = self.row(k);
                let j = Self::interval(sector.size, target);
                let (a, b) = (&row[j], &row[j + 1]);
                // One sample: only the guess it takes is formed.
                let guess = if Self::smooth(a, b) {
                    Self::hermite(a, b, target)
                } else {
                    sector.initial_guess(target)
                };
                self.polygon.sample_sector(&sector, target, guess, u.y)
            }

            /// The directions of [`sample`](Self::sample) for the points
            /// (`ux[i]`, `uy[i]`), to the bit, into (`dx[i]`, `dy[i]`,
            /// `dz[i]`) (the shortest length wins); their density is
            /// [`sample_density`](Self::sample_density). Branch-free loops
            /// that vectorise: run it inside
            /// [`Isa::run`](crate::isa::Isa::run).
            ///
            /// # Method
            /// [`BATCH_LANES`](Self::BATCH_LANES) samples at a time: each
            /// sample's sector, area target and first guess (a search and a
            /// table lookup, one sample at a time), then the samples sorted
            /// by sector, so that each sector's samples run one loop with
            /// that sector's data in registers: one evaluation of the area
            /// and one Halley step, which answers the samples for which
            /// [`sample`](Self::sample) stops there (most of them); the
            /// others, and every sample of a central polygon, are drawn by
            /// [`sample`](Self::sample) one at a time.
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::{ProjectedPolygon, TabulatedProjectedPolygon};")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            /// let square = ConvexPolygon::new(vec![
            #[doc = concat!("    ", stringify!($v3), "::new(-2.0, -1.0, 3.0),")]
            #[doc = concat!("    ", stringify!($v3), "::new(-1.0, -1.0, 3.0),")]
            #[doc = concat!("    ", stringify!($v3), "::new(-1.0, 1.0, 3.0),")]
            #[doc = concat!("    ", stringify!($v3), "::new(-2.0, 1.0, 3.0),")]
            /// ])?;
            #[doc = concat!("let plain = ProjectedPolygon::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, &square)?;")]
            /// let table = TabulatedProjectedPolygon::new(plain);
            /// let (ux, uy) = ([0.1, 0.5, 0.9], [0.3, 0.8, 0.2]);
            /// let (mut x, mut y, mut z) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            /// table.sample_directions(&ux, &uy, &mut x, &mut y, &mut z);
            #[doc = concat!("let s = table.sample(", stringify!($v2), "::new(0.5, 0.8));")]
            /// assert_eq!((x[1], y[1], z[1]), (s.direction.x, s.direction.y, s.direction.z));
            /// assert_eq!(table.sample_density(s.direction), s.pdf);
            /// # Ok::<(), Box<dyn std::error::Error>>(())
            /// ```
            #[inline(always)]
            pub fn sample_directions(
                &self,
                ux: &[Real],
                uy: &[Real],
                dx: &mut [Real],
                dy: &mut [Real],
                dz: &mut [Real],
            ) {
                let n = crate::soa::common_len(ux, uy, dx, dy, dz);
                if self.nodes.is_empty() {
                    self.central_directions(&ux[..n], &uy[..n], (dx, dy, dz));
                    return;
                }
                let mut start = 0;
                while start < n {
                    let r = start..start + Self::BATCH_LANES.min(n - start);
                    start = r.end;
                    let d = (&mut dx[r.clone()], &mut dy[r.clone()], &mut dz[r.clone()]);
                    self.directions_by_sector(&ux[r.clone()], &uy[r], d);
                }
            }

            /// [`sample_directions`](Self::sample_directions) of a central
            /// polygon (no solve): `sample` one at a time, out of line (see
            /// [`direction_of`](Self::direction_of)).
            #[inline(never)]
            fn central_directions(
                &self,
                ux: &[Real],
                uy: &[Real],
                (dx, dy, dz): (&mut [Real], &mut [Real], &mut [Real]),
            ) {
                let n = crate::soa::common_len(ux, uy, dx, dy, dz);
                for i in 0..n {
                    let w = self.sample(V2::new(ux[i], uy[i])).direction;
                    (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                }
            }

            /// [`sample_directions`](Self::sample_directions) for at most
            /// [`BATCH_LANES`](Self::BATCH_LANES) samples of a non-central
            /// polygon.
            #[inline(always)]
            fn directions_by_sector(
                &self,
                ux: &[Real],
                uy: &[Real],
                (dx, dy, dz): (&mut [Real], &mut [Real], &mut [Real]),
            ) {
                const LANES: usize = TabulatedProjectedPolygon::BATCH_LANES;
                let m = crate::soa::common_len(ux, uy, dx, dy, dz).min(LANES);
                // Each sample's sector and target, then the samples listed
                // by sector (a counting sort: sector k's are
                // `order[start[k]..start[k + 1]]`).
                let mut sector_of = [0usize; LANES];
                let mut target = [0.0 as Real; LANES];
                let mut start = [0usize; ProjectedPolygon::MAX_VERTICES + 2];
                for i in 0..m {
                    let (k, t) = self.polygon.locate(ux[i]);
                    (sector_of[i], target[i]) = (k, t);
                    start[k + 1] += 1;
                }
                let sectors = self.polygon.sector_shape(0).0;
                for k in 0..sectors {
                    start[k + 1] += start[k];
                }
                let mut next = start;
                let mut order = [0usize; LANES];
                for i in 0..m {
                    let at = &mut next[sector_of[i]];
                    order[*at] = i;
                    *at += 1;
                }
                let frame = &{ self.polygon.frame() };
                let max_iterations = ProjectedPolygon::MAX_ITERATIONS as Real;
                let mut lanes = Lanes::default();
                for k in 0..sectors {
                    let samples = &order[start[k]..start[k + 1]];
                    if samples.is_empty() {
                        continue;
                    }
                    // A copy (see `Sector`): its data stay in registers.
                    let sector = &{ self.polygon.sector(k) };
                    let row = self.row(k);
                    // The samples' targets, u₁ and table nodes copied into
                    // lanes (the only pass that indexes), then their first
                    // guesses in one loop.
                    let mut pending = samples.len();
                    for (j, &i) in samples.iter().enumerate() {
                        (lanes.sample[j], lanes.target[j], lanes.u1[j]) = (i, target[i], uy[i]);
                        let n = Self::interval(sector.size, target[i]);
                        lanes.first.set(j, &row[n]);
                        lanes.last.set(j, &row[n + 1]);
                    }
                    for j in 0..pending.min(LANES) {
                        let (a, b) = (lanes.first.get(j), lanes.last.get(j));
                        let guess = Self::guess_between(sector, &a, &b, lanes.target[j]);
                        lanes.set(j, Bracket::start(guess, sector.width));
                    }
                    for _ in 0..Self::BATCH_STEPS {
                        lanes.step(sector, frame, pending, max_iterations);
                        // Answered samples out, the others moved up.
                        let mut kept = 0;
                        for j in 0..pending {
                            let i = lanes.sample[j];
                            if lanes.answered[j] {
                                (dx[i], dy[i], dz[i]) = (lanes.x[j], lanes.y[j], lanes.z[j]);
                            } else {
                                lanes.sample[kept] = i;
                                lanes.target[kept] = lanes.target[j];
                                lanes.u1[kept] = lanes.u1[j];
                                let state = lanes.get(j);
                                lanes.set(kept, state);
                                kept += 1;
                            }
                        }
                        pending = kept;
                        if pending == 0 {
                            break;
                        }
                    }
                    // The rest (none in the tests' polygons but NaN u), one
                    // at a time.
                    for &i in &lanes.sample[..pending] {
                        let v = self.direction_of(V2::new(ux[i], uy[i]));
                        (dx[i], dy[i], dz[i]) = (v.x, v.y, v.z);
                    }
                }
            }

            /// The density [`sample`](Self::sample) gives its direction
            /// `w` ([`ProjectedPolygon::sample_density`]).
            #[inline(always)]
            pub fn sample_density(&self, w: V3) -> Real {
                self.polygon.sample_density(w)
            }

            /// [`sample`](Self::sample)'s direction, out of line: the
            /// batch's rare fallback. Inlined there, the one-sample solve
            /// made the estimator's kernel so large that the compiler
            /// stopped inlining other strategies' calls, and their loops
            /// went scalar (f64 uniform-hemisphere sampling of a polygon
            /// light 10.8 → 51 ns a sample).
            #[inline(never)]
            #[cold]
            fn direction_of(&self, u: V2) -> V3 {
                self.sample(u).direction
            }

            /// Sector k's J + 1 nodes.
            #[inline(always)]
            fn row(&self, k: usize) -> &[Node] {
                let intervals = Self::INTERVALS;
                &self.nodes[k * (intervals + 1)..(k + 1) * (intervals + 1)]
            }

            /// The interval j < J of a sector of area `size` that holds
            /// area `target` (0 for NaN).
            #[inline(always)]
            fn interval(size: Real, target: Real) -> usize {
                let intervals = Self::INTERVALS;
                if size > 0.0 {
                    ((target / size * intervals as Real) as usize).min(intervals - 1)
                } else {
                    0
                }
            }

            /// The first azimuth for area `target` in `sector`'s interval
            /// between nodes `a` and `b`: the Hermite interpolant of the
            /// inverse where it is smooth, else the sector's quadratic
            /// guess. Branch-free (both formed, one selected), so that the
            /// batch's loop over a sector's samples vectorises.
            #[inline(always)]
            fn guess_between(sector: &Sector, a: &Node, b: &Node, target: Real) -> Real {
                let hermite = Self::hermite(a, b, target);
                let quadratic = sector.initial_guess(target);
                if Self::smooth(a, b) {
                    hermite
                } else {
                    quadratic
                }
            }

            /// Whether the inverse is smooth between nodes `a` and `b`:
            /// both slopes positive and within 4× of each other.
            #[inline(always)]
            fn smooth(a: &Node, b: &Node) -> bool {
                (a.slope > 0.0)
                    & (b.slope > 0.0)
                    & (a.slope <= 4.0 * b.slope)
                    & (b.slope <= 4.0 * a.slope)
            }

            /// The cubic Hermite interpolant of the inverse δ(A) between
            /// nodes `a` and `b` at area `target`, kept within [a.δ, b.δ].
            #[inline(always)]
            fn hermite(a: &Node, b: &Node, target: Real) -> Real {
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

    /// The batch gives `sample`'s directions to the bit, and
    /// `sample_density` its densities, in both precisions: over 4097 u of
    /// each non-central polygon and a central one, in batches cut short
    /// and across the batch's lanes. Some samples take two or more steps
    /// (the batch's later passes), and a NaN u, which no step answers,
    /// takes the one-at-a-time solve (the batch's fallback).
    #[test]
    fn batch_directions_are_the_sample_directions() {
        let central = vec![
            DVec3::new(-1.0, -1.0, 2.0),
            DVec3::new(1.0, -1.0, 2.0),
            DVec3::new(1.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 2.0),
        ];
        let mut redone = 0;
        for (k, v) in polygons().iter().chain([&central]).enumerate() {
            let plain =
                crate::f64::ProjectedPolygon::new(DVec3::ZERO, DVec3::Z, &convex(v)).unwrap();
            let table = super::f64::TabulatedProjectedPolygon::new(plain);
            let mut us: Vec<DVec2> = (0..=4096)
                .map(|i| DVec2::new(i as f64 / 4096.0, ((i * 37) % 4097) as f64 / 4096.0))
                .collect();
            us[1000].x = f64::NAN;
            let (ux, uy): (Vec<f64>, Vec<f64>) = us.iter().map(|u| (u.x, u.y)).unzip();
            let n = us.len();
            let (mut dx, mut dy, mut dz) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            table.sample_directions(&ux, &uy, &mut dx, &mut dy, &mut dz);
            for (i, &u) in us.iter().enumerate() {
                let want = table.sample(u);
                assert_eq!(
                    [dx[i], dy[i], dz[i]].map(f64::to_bits),
                    want.direction.to_array().map(f64::to_bits),
                    "polygon {k}, u {u}"
                );
                assert_eq!(table.sample_density(want.direction), want.pdf);
                redone += usize::from(table.newton_steps(u) >= 2);
            }
            let v32: Vec<Vec3> = v.iter().map(|p| p.as_vec3()).collect();
            let poly32 = lambert_geometry::f32::ConvexPolygon::new(v32.clone())
                .or_else(|_| {
                    lambert_geometry::f32::ConvexPolygon::new(v32.iter().rev().copied().collect())
                })
                .unwrap();
            let plain = crate::f32::ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &poly32).unwrap();
            let table = super::f32::TabulatedProjectedPolygon::new(plain);
            let (ux, uy): (Vec<f32>, Vec<f32>) =
                us.iter().map(|u| (u.x as f32, u.y as f32)).unzip();
            let (mut dx, mut dy, mut dz) = (vec![0.0; n], vec![0.0; n], vec![0.0; 300]);
            // A shorter output cuts the batch (300: two full batches and
            // part of a third).
            table.sample_directions(&ux, &uy, &mut dx, &mut dy, &mut dz);
            for i in 0..n {
                let want = table.sample(Vec2::new(ux[i], uy[i]));
                if i < 300 {
                    assert_eq!(
                        [dx[i], dy[i], dz[i]].map(f32::to_bits),
                        want.direction.to_array().map(f32::to_bits),
                        "f32 polygon {k}, u {}",
                        us[i]
                    );
                    assert_eq!(table.sample_density(want.direction), want.pdf);
                } else {
                    assert_eq!(
                        (dx[i], dy[i]),
                        (0.0, 0.0),
                        "f32 polygon {k}: written past the end"
                    );
                }
            }
        }
        assert!(redone > 0, "no sample took the fallback");
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
