//! Many samples of one disk's solid angle from one point: the inverse of
//! the spherical ellipse's sector area, tabulated once and finished by
//! Gauss–Legendre quadrature instead of Carlson's elliptic integrals.

/// Gauss–Legendre rules on [0, 1] with G = 1…8 points: (node, weight),
/// ∫₀¹ p = Σ wₖ p(yₖ) exactly for polynomials of degree ≤ 2G − 1. The
/// nodes are (1 + xₖ)/2 and the weights half of the classical rule's on
/// [−1, 1] (Abramowitz & Stegun, table 25.4), computed here by Newton's
/// method on the Legendre polynomials at 50 digits and rounded to f64.
const GAUSS_LEGENDRE: [&[(f64, f64)]; 9] = [
    &[],
    &[(0.5, 1.0)],
    &[(0.2113248654051871, 0.5), (0.7886751345948129, 0.5)],
    &[
        (0.11270166537925831, 0.2777777777777778),
        (0.5, 0.4444444444444444),
        (0.8872983346207417, 0.2777777777777778),
    ],
    &[
        (0.06943184420297371, 0.17392742256872692),
        (0.33000947820757187, 0.32607257743127305),
        (0.6699905217924281, 0.32607257743127305),
        (0.9305681557970263, 0.17392742256872692),
    ],
    &[
        (0.046910077030668004, 0.11846344252809454),
        (0.23076534494715845, 0.23931433524968324),
        (0.5, 0.28444444444444444),
        (0.7692346550528415, 0.23931433524968324),
        (0.953089922969332, 0.11846344252809454),
    ],
    &[
        (0.03376524289842399, 0.08566224618958518),
        (0.16939530676686773, 0.1803807865240693),
        (0.38069040695840156, 0.23395696728634552),
        (0.6193095930415985, 0.23395696728634552),
        (0.8306046932331322, 0.1803807865240693),
        (0.966234757101576, 0.08566224618958518),
    ],
    &[
        (0.025446043828620736, 0.06474248308443485),
        (0.12923440720030277, 0.13985269574463832),
        (0.2970774243113014, 0.19091502525255946),
        (0.5, 0.2089795918367347),
        (0.7029225756886985, 0.19091502525255946),
        (0.8707655927996972, 0.13985269574463832),
        (0.9745539561713793, 0.06474248308443485),
    ],
    &[
        (0.019855071751231884, 0.05061426814518813),
        (0.10166676129318664, 0.11119051722668724),
        (0.2372337950418355, 0.15685332293894363),
        (0.4082826787521751, 0.181341891689181),
        (0.591717321247825, 0.181341891689181),
        (0.7627662049581645, 0.15685332293894363),
        (0.8983332387068134, 0.11119051722668724),
        (0.9801449282487681, 0.05061426814518813),
    ],
];

/// [`GAUSS_LEGENDRE`] with every rule padded to 8 points by (0, 0). A
/// padding point adds 0/(1 + cos θₑ) = +0 to the rule's sum, which leaves
/// the sum as it was, so a loop over all 8 gives each rule's sum to the
/// bit without a branch on its length (the batch sampler's loop
/// vectorises across samples of different intervals).
const GAUSS_PADDED: [[(f64, f64); 8]; 9] = {
    let mut padded = [[(0.0, 0.0); 8]; 9];
    let mut g = 0;
    while g < GAUSS_LEGENDRE.len() {
        let mut k = 0;
        while k < GAUSS_LEGENDRE[g].len() {
            padded[g][k] = GAUSS_LEGENDRE[g][k];
            k += 1;
        }
        g += 1;
    }
    padded
};

/// How many samples [`f64::TabulatedDiskSolidAngle::sample_directions`]
/// takes through the table at a time (a few arrays of that length on the
/// stack).
const TABLE_LANES: usize = 64;

macro_rules! disk_table_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use super::{GAUSS_LEGENDRE, GAUSS_PADDED, TABLE_LANES};
        use crate::disk_light::$p::DiskSolidAngle;
        use crate::light_sample::$p::LightSample;
        use crate::segment::$p::CBRT_EPSILON;
        use crate::trig::$p::sin_cos_quarter;
        use lambert_geometry::precision::$p::{Real, PI, V2, V3};

        /// One node τⱼ of the table: K(τⱼ) = j K(π/2)/J up to the root's
        /// rounding, and what the interval [τⱼ, τⱼ₊₁] needs.
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        struct Node {
            /// τⱼ, and sin τⱼ, cos τⱼ as the solver returned them (the
            /// quadrature rotates from these, not from τⱼ).
            tau: Real,
            sin: Real,
            cos: Real,
            /// K(τⱼ), by Carlson's integrals.
            sector: Real,
            /// dτ/dK = 1 + cos θₑ(τⱼ).
            slope: Real,
            /// Points of the Gauss–Legendre rule that meets the error
            /// bound on [τⱼ, τⱼ₊₁]; 0 if none of up to 8 does.
            gauss: u8,
        }

        /// One node per sample of a block, field by field (structure of
        /// arrays), for the batch sampler's vector passes.
        struct Lanes {
            tau: [Real; TABLE_LANES],
            sin: [Real; TABLE_LANES],
            cos: [Real; TABLE_LANES],
            sector: [Real; TABLE_LANES],
            slope: [Real; TABLE_LANES],
            gauss: [u8; TABLE_LANES],
        }

        impl Default for Lanes {
            #[inline(always)]
            fn default() -> Self {
                let zero = [0.0; TABLE_LANES];
                Lanes {
                    tau: zero,
                    sin: zero,
                    cos: zero,
                    sector: zero,
                    slope: zero,
                    gauss: [0; TABLE_LANES],
                }
            }
        }

        impl Lanes {
            /// Lane `i` takes `node`.
            #[inline(always)]
            fn set(&mut self, i: usize, node: &Node) {
                self.tau[i] = node.tau;
                self.sin[i] = node.sin;
                self.cos[i] = node.cos;
                self.sector[i] = node.sector;
                self.slope[i] = node.slope;
                self.gauss[i] = node.gauss;
            }

            /// Lane `i`'s node.
            #[inline(always)]
            fn get(&self, i: usize) -> Node {
                Node {
                    tau: self.tau[i],
                    sin: self.sin[i],
                    cos: self.cos[i],
                    sector: self.sector[i],
                    slope: self.slope[i],
                    gauss: self.gauss[i],
                }
            }
        }

        /// [`DiskSolidAngle`] prepared for many samples at its point: the
        /// same map, 1/Ω per steradian over the spherical ellipse, with the
        /// azimuth found without Carlson's integrals.
        ///
        /// # Method
        /// The sampler inverts the sector area K(τ) = ∫₀^τ dτ′/(1 + cos θₑ)
        /// (see [`DiskSolidAngle`]), each step of which costs a Carlson
        /// R_F/R_J pair. Here K is inverted once, at J + 1 = 33 nodes with
        /// K(τⱼ) = j K(π/2)/J, so the interval of a target area is found by
        /// one multiplication. Within it:
        ///
        /// 1. the cubic Hermite interpolant of the inverse τ(K), whose slope
        ///    dτ/dK = 1 + cos θₑ is known at both nodes, gives a first τ₀;
        /// 2. K(τ₀) = K(τⱼ) + ∫_{τⱼ}^{τ₀} dτ′/(1 + cos θₑ) by a G-point
        ///    Gauss–Legendre rule, sin τ′ by rotating (sin τⱼ, cos τⱼ)
        ///    through the small angle τ′ − τⱼ (Taylor polynomials);
        /// 3. one Halley step from τ₀ (as in [`DiskSolidAngle`]), taken if it
        ///    is below ¼ε^{1/3}·min(1, d) (Newton: √ε·min(1, d)), which
        ///    leaves an error of order ε; otherwise the sample falls back to
        ///    [`DiskSolidAngle`]'s own solver.
        ///
        /// # Why the quadrature is exact to rounding
        /// 1/(1 + √(cos²α + (a² − b²) sin²τ)) is analytic in τ except on the
        /// cuts Re τ = kπ, |Im τ| ≥ d, d = asinh(cos α/√(a² − b²)), where the
        /// square root's argument is real and ≤ 0; elsewhere Re √· ≥ 0, so
        /// the integrand's modulus is at most 1. For a function analytic
        /// with modulus ≤ 1 inside the Bernstein ellipse of parameter ρ of
        /// an interval of half-length ℓ, the G-point Gauss rule errs by at
        /// most ℓ (64/15) ρ^{2−2G}/(ρ² − 1) (Trefethen, "Is Gauss quadrature
        /// better than Clenshaw–Curtis?", SIAM Review 50(1), 2008, Theorem
        /// 4.5, with its (n + 1)-point rule). Each interval takes the
        /// smallest G ≤ 8 for which this is below ε/8, with ρ that of the
        /// nearest branch point 0 ± id or π ± id, and it holds for every
        /// sub-interval from τⱼ (a sub-interval's Bernstein ellipse of the
        /// same ρ lies inside the whole one's). An interval where no rule
        /// meets it (a cut within about its own length of the real axis:
        /// a nearly hemispherical, very eccentric ellipse) keeps Carlson's
        /// integrals; so do the circles of [`DiskSolidAngle`] (no solve).
        ///
        /// # Cost
        /// Building costs J − 1 solves (about 2J Carlson evaluations; tens
        /// of samples' worth), so this type is for many samples from one
        /// point (an estimate); a renderer that shades each point with a
        /// few samples keeps [`DiskSolidAngle`]. A sample costs G + 2 square
        /// roots and divisions where [`DiskSolidAngle`] evaluates Carlson's
        /// integrals once or twice (bench `projected`, rows `disk
        /// solid-angle`).
        ///
        /// Its directions agree with [`DiskSolidAngle::sample`]'s to a few
        /// ulps (both solve for the same root to rounding), not bit for bit.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Disk;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{DiskSolidAngle, TabulatedDiskSolidAngle};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A unit disk above and to the side of the receiver.
        #[doc = concat!("let disk = Disk::new(", stringify!($v3), "::new(0.6, 0.2, 0.3), -", stringify!($v3), "::Z, 0.5)?;")]
        #[doc = concat!("let plain = DiskSolidAngle::new(", stringify!($v3), "::ZERO, &disk)?;")]
        /// let table = TabulatedDiskSolidAngle::new(plain);
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.3, 0.8);")]
        /// let (a, b) = (plain.sample(u), table.sample(u));
        /// assert!((a.direction - b.direction).length() < 1e-5);
        /// assert_eq!(b.pdf, 1.0 / table.solid_angle());
        /// // Answered by the table: no evaluation of Carlson's integrals.
        /// assert_eq!(table.sector_evaluations(u), 0);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct TabulatedDiskSolidAngle {
            disk: DiskSolidAngle,
            /// J + 1 nodes, or none for a circle.
            nodes: Box<[Node]>,
            /// J / K(π/2): the interval of an area.
            per_interval: Real,
            /// The most points of any interval's rule (0 for a circle).
            most_points: usize,
            /// The largest Halley and Newton steps taken without a check.
            accept_halley: Real,
            accept_newton: Real,
        }

        impl TabulatedDiskSolidAngle {
            /// The number J of intervals of the table.
            pub const INTERVALS: usize = 32;

            /// Tabulates the inverse of `disk`'s sector area.
            pub fn new(disk: DiskSolidAngle) -> Self {
                let intervals = Self::INTERVALS;
                let quarter = disk.quarter;
                // Distance of the integrand's branch points from the real
                // axis (type docs); infinite for a circle.
                let d = if disk.ecc > 0.0 {
                    (disk.cos_a / disk.ecc.sqrt()).asinh()
                } else {
                    Real::INFINITY
                };
                let mut nodes = Vec::new();
                if disk.ecc > 0.0 {
                    nodes.reserve(intervals + 1);
                    for j in 0..=intervals {
                        let (n, m, sector) = if j == 0 {
                            (0.0, 1.0, 0.0)
                        } else if j == intervals {
                            (1.0, 0.0, quarter)
                        } else {
                            let (n, m, _) = disk.solve(quarter * j as Real / intervals as Real);
                            (n, m, disk.sector(n, m))
                        };
                        nodes.push(Node {
                            tau: if j == intervals { 0.5 * PI } else { n.atan2(m) },
                            sin: n,
                            cos: m,
                            sector,
                            slope: 1.0 + disk.rim_cos(n),
                            gauss: 0,
                        });
                    }
                    for j in 0..intervals {
                        nodes[j].gauss = gauss_points(nodes[j].tau, nodes[j + 1].tau, d);
                    }
                }
                let scale = d.min(1.0);
                let most_points = nodes.iter().map(|n| usize::from(n.gauss)).max().unwrap_or(0);
                TabulatedDiskSolidAngle {
                    disk,
                    most_points,
                    nodes: nodes.into_boxed_slice(),
                    per_interval: intervals as Real / quarter,
                    accept_halley: 0.25 * CBRT_EPSILON * scale,
                    accept_newton: Real::EPSILON.sqrt() * scale,
                }
            }

            /// The untabulated sampler.
            #[inline]
            pub fn sampler(&self) -> &DiskSolidAngle {
                &self.disk
            }

            /// The solid angle Ω the disk subtends, in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.disk.solid_angle()
            }

            /// The same direction as [`DiskSolidAngle::sample`] for u, to a
            /// few ulps, with its density 1/Ω per steradian.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                let (q, target) = self.disk.quadrant(u.x);
                let (n, m, _) = self.solve(target);
                self.disk
                    .light_sample(self.disk.local_direction(q, n, m, u.y))
            }

            /// The directions of [`sample`](Self::sample) for a block of
            /// points, to the bit: `(dx[i], dy[i], dz[i])` is the direction
            /// for u = (`ux[i]`, `uy[i]`), over the shortest of the slices.
            /// Every direction's density is 1/Ω.
            ///
            /// The table's answer is computed for every sample in
            /// branch-free passes, which vectorise across samples: the
            /// quadrature runs as many points as the table's longest rule
            /// (zero weights beyond the interval's own, which add +0), and
            /// a sample the table cannot answer (an interval without a rule, or a
            /// Halley step too long to accept) is marked and then sampled
            /// one at a time as `sample` does, by Carlson's integrals. A
            /// circle (the reference on the disk's axis) needs neither
            /// table nor solve, and is one branch-free pass.
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
                let (ux, uy) = (&ux[..n], &uy[..n]);
                let (dx, dy, dz) = (&mut dx[..n], &mut dy[..n], &mut dz[..n]);
                if self.disk.ecc == 0.0 {
                    // A circle: no table, and no solve either.
                    for i in 0..n {
                        let (q, target) = self.disk.quadrant(ux[i]);
                        let (sin, cos) = self.disk.circle_solve(target);
                        let w = self.disk.world(self.disk.local_direction(q, sin, cos, uy[i]));
                        (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                    }
                    return;
                }
                if let Some(nodes) = self.table() {
                    let mut start = 0;
                    while start < n {
                        let r = start..start + TABLE_LANES.min(n - start);
                        start = r.end;
                        let (x, y) = (&ux[r.clone()], &uy[r.clone()]);
                        let d = (&mut dx[r.clone()], &mut dy[r.clone()], &mut dz[r]);
                        self.directions_by_table(nodes, x, y, d);
                    }
                }
                // The samples the table did not answer: one at a time.
                for i in 0..n {
                    if dx[i].is_nan() || self.nodes.is_empty() {
                        let w = self.sample(V2::new(ux[i], uy[i])).direction;
                        (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                    }
                }
            }

            /// [`sample_directions`](Self::sample_directions) for at most
            /// [`TABLE_LANES`] samples, by the table; NaN in `dx` marks a
            /// sample it did not answer. Three passes over the samples,
            /// each a loop without branches that vectorises (as one loop,
            /// the body was too large for the compiler to vectorise): the
            /// interval and the Hermite guess; the rules' points, one point
            /// of every sample at a time, as many as the longest rule of
            /// the table has (each sample's sum adds its terms in the order
            /// [`solve`](Self::solve) does); the Halley step and the
            /// direction.
            #[inline(always)]
            fn directions_by_table(
                &self,
                nodes: &[Node; Self::INTERVALS + 1],
                ux: &[Real],
                uy: &[Real],
                (dx, dy, dz): (&mut [Real], &mut [Real], &mut [Real]),
            ) {
                let m = ux.len().min(uy.len()).min(TABLE_LANES);
                let (dx, dy, dz) = (&mut dx[..m], &mut dy[..m], &mut dz[..m]);
                // Each sample's interval, then its two nodes' fields copied
                // into lanes (structure of arrays): the other passes then
                // load them with plain vector loads. Indexing the table in
                // them (a gather per field per pass) kept the last pass
                // scalar in f64: 72 → 27 ns per direction in f64, 53 → 15
                // in f32, the same directions (a disk seen from the side,
                // AVX-512). The copy is the only pass that indexes.
                let mut targets = [0.0 as Real; TABLE_LANES];
                let mut intervals = [0.0 as Real; TABLE_LANES];
                for i in 0..m {
                    targets[i] = self.disk.quadrant(ux[i]).1;
                    intervals[i] = self.interval(targets[i]);
                }
                let mut first = Lanes::default();
                let mut last = Lanes::default();
                for i in 0..m {
                    let j = intervals[i] as usize;
                    first.set(i, &nodes[j]);
                    last.set(i, &nodes[j + 1]);
                }
                let mut offset = [0.0 as Real; TABLE_LANES];
                for i in 0..m {
                    offset[i] = Self::start_in(&first.get(i), &last.get(i), targets[i]);
                }
                let node = |i: usize| first.get(i);
                let mut sum = [0.0 as Real; TABLE_LANES];
                // Points beyond a sample's own rule add +0 (`GAUSS_PADDED`).
                // Each point's nodes and weights are copied into lanes
                // first, so the sum's loop loads them as vectors.
                let (mut ys, mut ws) = ([0.0 as Real; TABLE_LANES], [0.0 as Real; TABLE_LANES]);
                for k in 0..self.most_points.min(8) {
                    for i in 0..m {
                        let (y, w) = GAUSS_PADDED[usize::from(first.gauss[i]).min(8)][k];
                        (ys[i], ws[i]) = (y as Real, w as Real);
                    }
                    for i in 0..m {
                        sum[i] += self.gauss_term(&node(i), offset[i], ys[i], ws[i]);
                    }
                }
                for i in 0..m {
                    let (q, target) = self.disk.quadrant(ux[i]);
                    let a = &node(i);
                    let (sin, cos, answered) = self.halley_finish(a, offset[i], sum[i], target);
                    let w = self.disk.world(self.disk.local_direction(q, sin, cos, uy[i]));
                    // NaN marks a sample to redo (a direction is never NaN).
                    dx[i] = if answered { w.x } else { Real::NAN };
                    (dy[i], dz[i]) = (w.y, w.z);
                }
            }

            /// [`DiskSolidAngle::pdf`]: 1/Ω inside the disk's cone, else 0.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                self.disk.pdf(w)
            }

            /// How many times sampling u evaluates Carlson's integrals: 0
            /// when the table answers (for tests and benchmarks).
            pub fn sector_evaluations(&self, u: V2) -> usize {
                self.solve(self.disk.quadrant(u.x).1).2
            }

            /// For each interval: K at its end by its rule (`None` where
            /// it has none), by the one-point rule, and by Carlson's
            /// integrals (tests).
            #[cfg(test)]
            pub(crate) fn rule_residuals(&self) -> Vec<(Option<Real>, Real, Real)> {
                self.nodes
                    .windows(2)
                    .map(|w| {
                        let (a, b) = (&w[0], &w[1]);
                        let x = b.tau - a.tau;
                        let by = |g: u8| {
                            let sum: Real = GAUSS_LEGENDRE[g as usize]
                                .iter()
                                .map(|&(y, w)| self.gauss_term(a, x, y as Real, w as Real))
                                .sum();
                            a.sector + x * sum
                        };
                        ((a.gauss > 0).then(|| by(a.gauss)), by(1), b.sector)
                    })
                    .collect()
            }

            /// The table's nodes, or `None` for a circle (no table).
            #[inline(always)]
            fn table(&self) -> Option<&[Node; Self::INTERVALS + 1]> {
                (&*self.nodes).try_into().ok()
            }

            /// The interval j of `target` and the start x ∈ [0, τⱼ₊₁ − τⱼ]
            /// of the solve in it: the cubic Hermite interpolant of τ(K)
            /// on [Kⱼ, Kⱼ₊₁], less τⱼ. x is 0 in an interval without a
            /// rule (which may be longer than the rotation's polynomials
            /// allow; its sample is not answered by the table).
            #[inline(always)]
            fn table_start(&self, nodes: &[Node; Self::INTERVALS + 1], target: Real) -> (usize, Real) {
                let j = self.interval(target) as usize;
                let (a, b) = (&nodes[j], &nodes[j + 1]);
                (j, Self::start_in(a, b, target))
            }

            /// The interval j of `target`: ⌊target J/K(π/2)⌋, at most J − 1
            /// (0 for NaN), as a float: a loop over samples keeps it in
            /// vectors (see [`DiskSolidAngle::quadrant`]).
            #[inline(always)]
            fn interval(&self, target: Real) -> Real {
                let last = (Self::INTERVALS - 1) as Real;
                (target * self.per_interval).floor().max(0.0).min(last)
            }

            /// The start x of the solve in the interval from node `a` to
            /// node `b` ([`table_start`](Self::table_start)).
            #[inline(always)]
            fn start_in(a: &Node, b: &Node, target: Real) -> Real {
                let dk = b.sector - a.sector;
                let s = ((target - a.sector) / dk).clamp(0.0, 1.0);
                let r = 1.0 - s;
                let guess = (a.tau * (1.0 + 2.0 * s) + dk * a.slope * s) * r * r
                    + (b.tau * (3.0 - 2.0 * s) - dk * b.slope * r) * s * s;
                // max/min, not clamp, which panics on unordered or NaN
                // bounds (degenerate geometry).
                let x = (guess - a.tau).max(0.0).min(b.tau - a.tau);
                if a.gauss != 0 {
                    x
                } else {
                    0.0
                }
            }

            /// One point (y, w) of the rule for K(τⱼ + x) − K(τⱼ) on the
            /// interval starting at node `a`: w/(1 + cos θₑ(τⱼ + xy)).
            #[inline(always)]
            fn gauss_term(&self, a: &Node, x: Real, y: Real, w: Real) -> Real {
                let (sy, cy) = sin_cos_quarter(x * y);
                w / (1.0 + self.disk.rim_cos(a.sin * cy + a.cos * sy))
            }

            /// From K(τⱼ + x) − K(τⱼ) = x·`sum`, one Halley step (as in
            /// [`DiskSolidAngle::solve`]) to (sin τ, cos τ), and whether
            /// the table answers: the interval has a rule and the step is
            /// short enough to accept without evaluating K again.
            #[inline(always)]
            fn halley_finish(&self, a: &Node, x: Real, sum: Real, target: Real) -> (Real, Real, bool) {
                let f = a.sector + x * sum - target;
                let (sx, cx) = sin_cos_quarter(x);
                let (n, m) = (a.sin * cx + a.cos * sx, a.cos * cx - a.sin * sx);
                let c = self.disk.rim_cos(n);
                let slope = 1.0 / (1.0 + c);
                let curvature = -self.disk.ecc * n * m / c * slope * slope;
                let denominator = 2.0 * slope * slope - f * curvature;
                let halley = denominator > 0.0;
                let step = if halley {
                    2.0 * f * slope / denominator
                } else {
                    f / slope
                };
                // Both bounds compared, not one selected: the compiler made
                // a selected bound a load indexed by each lane's choice,
                // one lane at a time.
                let short = (halley & (step.abs() <= self.accept_halley))
                    | (!halley & (step.abs() <= self.accept_newton));
                let answered = (a.gauss != 0) & short;
                // A step not taken stays inside the polynomials' range.
                let step = if answered { step } else { 0.0 };
                let (sx, cx) = sin_cos_quarter(x - step);
                let n = (a.sin * cx + a.cos * sx).clamp(0.0, 1.0);
                let m = (a.cos * cx - a.sin * sx).clamp(0.0, 1.0);
                (n, m, answered)
            }

            /// (sin τ, cos τ, Carlson evaluations) with K(τ) = `target`
            /// (type docs).
            #[inline]
            fn solve(&self, target: Real) -> (Real, Real, usize) {
                let Some(nodes) = self.table() else {
                    return self.disk.solve(target);
                };
                let (j, x) = self.table_start(nodes, target);
                let a = &nodes[j];
                if a.gauss == 0 {
                    return self.disk.solve(target);
                }
                // K(τⱼ + x) by the interval's rule.
                let mut sum = 0.0;
                for &(y, w) in GAUSS_LEGENDRE[a.gauss as usize] {
                    sum += self.gauss_term(a, x, y as Real, w as Real);
                }
                match self.halley_finish(a, x, sum, target) {
                    (n, m, true) => (n, m, 0),
                    _ => self.disk.solve(target),
                }
            }
        }

        /// The fewest Gauss–Legendre points (≤ 8) whose error on every
        /// sub-interval [a, x] of [a, b] is below ε/8, or 0 (type docs):
        /// branch points at 0 ± id and π ± id, |integrand| ≤ 1. Intervals
        /// longer than 0.2 get 0 as well: the rotation's polynomials
        /// ([`sin_cos_quarter`]) need |x| ≤ π/4, and with J = 32 no interval
        /// is longer than π/J.
        fn gauss_points(a: Real, b: Real, d: Real) -> u8 {
            let half = 0.5 * (b - a);
            if !(half > 0.0 && half <= 0.1) {
                return 0;
            }
            // (ρ + 1/ρ)/2 is the sum of the distances to the interval's
            // ends over its length.
            let rho = [0.0, PI]
                .iter()
                .map(|&x| {
                    let s = 0.5 * ((x - a).hypot(d) + (x - b).hypot(d)) / half;
                    s + (s * s - 1.0).max(0.0).sqrt()
                })
                .fold(Real::INFINITY, Real::min);
            for g in 1..GAUSS_LEGENDRE.len() {
                let bound = half * (64.0 / 15.0) * rho.powi(2 - 2 * g as i32) / (rho * rho - 1.0);
                if bound <= 0.125 * Real::EPSILON {
                    return g as u8;
                }
            }
            0
        }
    };
}

lambert_geometry::both_precisions!(disk_table_impl);

#[cfg(test)]
mod tests {
    use super::f64::TabulatedDiskSolidAngle;
    use glam::{DVec2, DVec3, Vec2, Vec3};
    use lambert_geometry::f64::Disk;

    /// Disks seen at a slant, from close under, from afar, tiny, and
    /// nearly edge-on from just outside the rim (a nearly hemispherical,
    /// very eccentric ellipse, whose first intervals no rule covers).
    const DISKS: [(DVec3, DVec3, f64); 7] = [
        (DVec3::new(0.6, 0.2, 0.3), DVec3::NEG_Z, 0.5),
        (DVec3::new(0.3, 0.0, 0.01), DVec3::NEG_Z, 1.0),
        (DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 0.4), 0.7),
        (DVec3::new(1.01, 0.0, 1e-3), DVec3::Z, 1.0),
        (DVec3::new(1.0, 2.0, 2.0), DVec3::Z, 1e-4),
        (DVec3::new(0.99, 0.0, 1e-9), DVec3::Z, 1.0),
        (DVec3::new(1.0001, 0.0, 1e-6), DVec3::Z, 1.0),
    ];

    /// The u grid: 256 azimuths (inside quadrants and at their ends) by
    /// 5 heights.
    fn grid() -> impl Iterator<Item = DVec2> {
        (0..=256).flat_map(|i| (0..=4).map(move |j| DVec2::new(i as f64 / 256.0, j as f64 / 4.0)))
    }

    /// The table gives the untabulated sampler's directions to a few
    /// ulps: both solve K(τ) = target to rounding, K to a few ulps each
    /// (Carlson's ~4 ulps; the rule's bound ε/8 plus the node's ~4 ulps),
    /// and the direction moves by at most |Δτ| per unit τ (see
    /// `DiskSolidAngle`'s principal frame), so 16ε per component in f64,
    /// 16ε in f32. Every u of the first five disks is answered by the
    /// table; the last is the negative control, where some u must fall
    /// back to Carlson's integrals and still agree.
    #[test]
    fn table_gives_the_untabulated_directions() {
        for (k, &(c, n, r)) in DISKS.iter().enumerate() {
            let plain =
                crate::f64::DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c, n, r).unwrap()).unwrap();
            let table = TabulatedDiskSolidAngle::new(plain);
            assert_eq!(table.solid_angle(), plain.solid_angle());
            let mut fallbacks = 0;
            for u in grid() {
                let (a, b) = (plain.sample(u), table.sample(u));
                let error = (a.direction - b.direction).abs().max_element();
                assert!(error <= 16.0 * f64::EPSILON, "disk {k}, u {u}: {error:e}");
                assert_eq!(a.pdf, b.pdf);
                assert_eq!(table.pdf(b.direction), b.pdf, "disk {k}, u {u}");
                fallbacks += usize::from(table.sector_evaluations(u) > 0);
            }
            if k + 1 < DISKS.len() {
                assert_eq!(fallbacks, 0, "disk {k}");
            } else {
                assert!(fallbacks > 0, "the negative control never fell back");
            }
            // f32, from the same geometry, for the first five disks. The
            // last two are 1e-9 and 1e-6 under a unit disk's plane: in f32
            // both samplers differ from f64 by ~3e-4 there (the geometry
            // itself rounds), so the comparison would test f32's rounding
            // of the geometry, not the table.
            if k >= 5 {
                continue;
            }
            let disk = lambert_geometry::f32::Disk::new(c.as_vec3(), n.as_vec3(), r as f32);
            let plain = crate::f32::DiskSolidAngle::new(Vec3::ZERO, &disk.unwrap()).unwrap();
            let table = super::f32::TabulatedDiskSolidAngle::new(plain);
            for u in grid() {
                let u: Vec2 = u.as_vec2();
                let (a, b) = (plain.sample(u), table.sample(u));
                let error = (a.direction - b.direction).abs().max_element();
                assert!(
                    error <= 16.0 * f32::EPSILON,
                    "f32 disk {k}, u {u}: {error:e}"
                );
                assert_eq!(table.sector_evaluations(u), 0, "f32 disk {k}, u {u}");
            }
        }
    }

    /// The batch gives `sample`'s directions to the bit, in both
    /// precisions, for every disk (the circle seen from its axis too, and
    /// the last disk, whose samples partly fall back to Carlson's
    /// integrals: the marked lanes are redone). Negative control: the
    /// comparison is exact, so a batch that returned the fast path's value
    /// for a fallen-back sample would fail; the fallback count shows the
    /// last disk has such samples.
    #[test]
    fn batch_directions_are_the_sample_directions() {
        let coaxial = (DVec3::new(0.0, 0.0, 2.0), DVec3::NEG_Z, 0.5);
        for (k, &(c, n, r)) in DISKS.iter().chain([&coaxial]).enumerate() {
            let plain =
                crate::f64::DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c, n, r).unwrap()).unwrap();
            let table = TabulatedDiskSolidAngle::new(plain);
            let us: Vec<DVec2> = grid().collect();
            let (ux, uy): (Vec<f64>, Vec<f64>) = us.iter().map(|u| (u.x, u.y)).unzip();
            let mut d = [
                vec![0.0; us.len()],
                vec![0.0; us.len()],
                vec![0.0; us.len()],
            ];
            let [dx, dy, dz] = &mut d;
            table.sample_directions(&ux, &uy, dx, dy, dz);
            let mut fallbacks = 0;
            for (i, &u) in us.iter().enumerate() {
                let want = table.sample(u).direction;
                assert_eq!(
                    [dx[i], dy[i], dz[i]].map(f64::to_bits),
                    want.to_array().map(f64::to_bits),
                    "disk {k}, u {u}"
                );
                fallbacks += usize::from(table.sector_evaluations(u) > 0);
            }
            assert_eq!(fallbacks > 0, k + 1 == DISKS.len(), "disk {k}");
            if k >= 5 {
                continue;
            }
            let disk = lambert_geometry::f32::Disk::new(c.as_vec3(), n.as_vec3(), r as f32);
            let plain = crate::f32::DiskSolidAngle::new(Vec3::ZERO, &disk.unwrap()).unwrap();
            let table = super::f32::TabulatedDiskSolidAngle::new(plain);
            let (ux, uy): (Vec<f32>, Vec<f32>) =
                us.iter().map(|u| (u.x as f32, u.y as f32)).unzip();
            let mut d = [
                vec![0.0; us.len()],
                vec![0.0; us.len()],
                vec![0.0; us.len()],
            ];
            let [dx, dy, dz] = &mut d;
            // A shorter output cuts the batch.
            table.sample_directions(&ux, &uy, dx, dy, &mut dz[..100]);
            for i in 0..us.len() {
                let want = table.sample(Vec2::new(ux[i], uy[i])).direction;
                let got = if i < 100 {
                    [dx[i], dy[i], dz[i]]
                } else {
                    want.to_array()
                };
                assert_eq!(got.map(f32::to_bits), want.to_array().map(f32::to_bits));
                if i >= 100 {
                    assert_eq!(dx[i], 0.0, "written beyond the batch");
                }
            }
        }
    }

    /// Each interval's rule reaches the next node's area, computed by
    /// Carlson's integrals, within the rule's bound ε/8 plus the two
    /// nodes' rounding (4 ulps of K each, `carlson` module docs): the
    /// bound is a real error bound, not a formality. Negative control:
    /// the one-point rule (midpoint) misses on some intervals of every
    /// disk (on at least half of them but for the tiny disk, whose
    /// integrand is nearly constant), so the comparison can fail.
    #[test]
    fn every_rule_reaches_the_next_node() {
        for (k, &(c, n, r)) in DISKS.iter().enumerate() {
            let plain =
                crate::f64::DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c, n, r).unwrap()).unwrap();
            let table = TabulatedDiskSolidAngle::new(plain);
            let mut midpoint_missed = 0;
            for (j, (rule, midpoint, carlson)) in table.rule_residuals().into_iter().enumerate() {
                let allowed = 0.125 * f64::EPSILON + 8.0 * f64::EPSILON * carlson.abs();
                if let Some(rule) = rule {
                    assert!((rule - carlson).abs() <= allowed, "disk {k}, interval {j}");
                }
                midpoint_missed += usize::from((midpoint - carlson).abs() > allowed);
            }
            // And in f32, for the well-conditioned disks (see above).
            if k < 5 {
                let disk = lambert_geometry::f32::Disk::new(c.as_vec3(), n.as_vec3(), r as f32);
                let plain = crate::f32::DiskSolidAngle::new(Vec3::ZERO, &disk.unwrap()).unwrap();
                let table = super::f32::TabulatedDiskSolidAngle::new(plain);
                for (j, (rule, _, carlson)) in table.rule_residuals().into_iter().enumerate() {
                    let allowed = 0.125 * f32::EPSILON + 8.0 * f32::EPSILON * carlson.abs();
                    let rule = rule.expect("every f32 interval of these disks has a rule");
                    assert!(
                        (rule - carlson).abs() <= allowed,
                        "f32 disk {k}, interval {j}"
                    );
                }
            }
            let least = if k == 4 {
                1
            } else {
                TabulatedDiskSolidAngle::INTERVALS / 2
            };
            assert!(midpoint_missed >= least, "disk {k}: {midpoint_missed}");
        }
    }
}
