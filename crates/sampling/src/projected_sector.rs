//! One non-central sector of a projected polygon (see
//! [`ProjectedPolygon`](crate::f64::ProjectedPolygon)): its corners at an
//! azimuth, its area, the area's slope and curvature, the solve for an
//! area, and the direction a sample takes in it.
//!
//! A sector is copied out of its sampler as a value, so that a loop over
//! many samples of one sector keeps its data in registers: read through a
//! reference into the sampler, the data were reloaded lane by lane and
//! the loop stayed scalar (as in the estimator's kernels; see
//! docs/ARCHITECTURE.md). Every function here is branch-free but for the
//! solve's iteration, so that such loops vectorise.

macro_rules! projected_sector_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::atan::$p::atan2;
        use crate::segment::$p::{v_minus_sin, v_minus_sin_branch_free};
        use crate::trig::$p::sin_cos;
        use lambert_geometry::precision::$p::{Real, V3};

        /// z of the cross product of the xy parts.
        #[inline(always)]
        pub(crate) fn cross2(a: V3, b: V3) -> Real {
            a.x * b.y - a.y * b.x
        }

        /// Q̂₁ − Q̂₂ from the exact difference `diff` = Q₁ − Q₂, the
        /// positions and their lengths (see `ProjectedPolygon`'s docs).
        #[inline(always)]
        fn unit_diff(diff: V3, p1: V3, p2: V3, l1: Real, l2: Real) -> V3 {
            let dl = diff.dot(p1 + p2) / (l1 + l2);
            (diff - p2 * (dl / l2)) / l1
        }

        /// g(Θ) = Θ/sin Θ − 1 for the arc between unit directions a and
        /// a + d (d = b − a), times (a × b)_z; 0 for a zero arc. With
        /// `BRANCH_FREE`, Θ − sin Θ by [`v_minus_sin_branch_free`] (for the
        /// batch's loops), else by [`v_minus_sin`] (one sample at a time:
        /// one of its two forms evaluated); the same bits either way.
        #[inline(always)]
        fn arc_correction<const BRANCH_FREE: bool>(a: V3, d: V3) -> Real {
            let c = a.cross(d);
            let s = c.length();
            let cos = 1.0 - 0.5 * d.length_squared();
            // s = sin Θ already (a unit): g = (Θ − sin Θ)/sin Θ.
            let theta = atan2(s, cos);
            let v = if BRANCH_FREE {
                v_minus_sin_branch_free(theta)
            } else {
                v_minus_sin(theta)
            };
            let g = v / s * c.z;
            if s > 0.0 {
                g
            } else {
                0.0
            }
        }

        /// A corner: a point of the planar polygon, as its offset from a
        /// reference vertex, its position, length and unit direction.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub(crate) struct Corner {
            pub(crate) offset: V3,
            pub(crate) position: V3,
            pub(crate) length: Real,
            pub(crate) direction: V3,
        }

        impl Corner {
            /// The zenith as a corner (the inner boundary of a sector
            /// without an inner edge).
            pub(crate) const ZENITH: Corner = Corner {
                offset: V3::ZERO,
                position: V3::Z,
                length: 1.0,
                direction: V3::Z,
            };

            /// Q̂₁ − Q̂₂ for two corners (offsets from the same vertex).
            #[inline(always)]
            fn diff(&self, other: &Corner) -> V3 {
                unit_diff(
                    self.offset - other.offset,
                    self.position,
                    other.position,
                    self.length,
                    other.length,
                )
            }
        }

        /// The corner where the meridian plane at azimuth δ past a vertex
        /// (position `start`, distance `start_radius` from the axis) cuts
        /// the edge whose ends are `ends` (offsets from that vertex); `d`
        /// is the azimuth's unit direction and `sin_d` = sin δ.
        #[inline(always)]
        pub(crate) fn cut(
            start: V3,
            start_radius: Real,
            d: V3,
            sin_d: Real,
            (fs, ft): (V3, V3),
        ) -> Corner {
            // cross(d, P) relative to the start vertex.
            let cs = -start_radius * sin_d + cross2(d, fs);
            let ct = -start_radius * sin_d + cross2(d, ft);
            let denom = cs - ct;
            // The cut from the end nearer to the plane: u ≈ 1 would lose
            // 1 − u's relative precision (and the corner's). The end and
            // the numerator are selected first, so one division serves
            // both cases (and a branch would mispredict between samples).
            let s_nearer = cs.abs() <= ct.abs();
            let (near, far, num) = if s_nearer {
                (fs, ft, cs)
            } else {
                (ft, fs, -ct)
            };
            let cut = near + (far - near) * (num / denom).clamp(0.0, 1.0);
            let offset = if denom == 0.0 { fs } else { cut };
            let position = start + offset;
            let length = position.length();
            Corner {
                offset,
                position,
                length,
                direction: position / length,
            }
        }

        /// A sample's solve between steps: the azimuth to evaluate next,
        /// the bracket [lo, hi] known to hold the root, and the steps taken
        /// (a whole number, kept as a float so that the batch's loops stay
        /// in one kind of vector).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub(crate) struct Bracket {
            pub(crate) delta: Real,
            pub(crate) lo: Real,
            pub(crate) hi: Real,
            pub(crate) steps: Real,
        }

        impl Bracket {
            /// The first state: the guess `delta` moved into [0, `width`]
            /// (by max and min, not clamp: a NaN width must not panic).
            #[inline(always)]
            pub(crate) fn start(delta: Real, width: Real) -> Bracket {
                Bracket {
                    delta: delta.max(0.0).min(width),
                    lo: 0.0,
                    hi: width,
                    steps: 0.0,
                }
            }
        }

        /// One non-central sector, copied out of its sampler (module docs).
        #[derive(Clone, Copy, Debug)]
        pub(crate) struct Sector {
            /// The start vertex's position and its distance from the axis.
            pub(crate) start: V3,
            pub(crate) start_radius: Real,
            /// The unit azimuth of the start vertex.
            pub(crate) azimuth: V3,
            /// The outer and inner edges' ends, as offsets from the start
            /// vertex (the inner's unused without an inner edge).
            pub(crate) outer_ends: (V3, V3),
            pub(crate) inner_ends: (V3, V3),
            pub(crate) has_inner: bool,
            /// The corners at the start (the zenith for no inner edge).
            pub(crate) outer_start: Corner,
            pub(crate) inner_start: Corner,
            /// The outer and inner edges' unit inward normals.
            pub(crate) outer_normal: V3,
            pub(crate) inner_normal: V3,
            /// Angular width, the area of the sectors before, and the
            /// largest last Halley step taken without evaluating the area.
            pub(crate) width: Real,
            pub(crate) before: Real,
            pub(crate) accept: Real,
            /// The sector's area, and its slopes at the start and the end
            /// relative to its mean slope (the quadratic first guess).
            pub(crate) size: Real,
            pub(crate) shape: Real,
            pub(crate) shape_end: Real,
        }

        impl Sector {
            /// The first azimuth of the solve for area `target`, from a
            /// quadratic model of A/A_k in x = δ/Δ fitted at the nearer end:
            /// τ ≈ αx + (1 − α)x² with α the start slope over the mean
            /// slope, or, for τ > ½, the same in 1 − x and 1 − τ with the
            /// end slope β. Exact for a sector whose radial thickness varies
            /// linearly, such as one that starts or ends at a vertex where
            /// its inner and outer edges meet (a zero slope there, i.e. a
            /// double root that Newton's method on A itself would approach
            /// only linearly). Branch-free (both ends' models formed, one
            /// selected).
            #[inline(always)]
            pub(crate) fn initial_guess(&self, target: Real) -> Real {
                let size = self.size;
                let fraction = if size > 0.0 {
                    (target / size).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let quadratic = |slope: Real, tau: Real| {
                    let slope = slope.min(2.0);
                    let root = (slope * slope + 4.0 * (1.0 - slope) * tau).max(0.0).sqrt();
                    let x = (2.0 * tau / (slope + root)).clamp(0.0, 1.0);
                    if slope + root > 0.0 {
                        x
                    } else {
                        0.0
                    }
                };
                let near_start = quadratic(self.shape, fraction);
                let near_end = 1.0 - quadratic(self.shape_end, 1.0 - fraction);
                let x = if fraction <= 0.5 {
                    near_start
                } else {
                    near_end
                };
                self.width * x.clamp(0.0, 1.0)
            }

            /// The inner and outer corners at azimuth δ past the start, and
            /// the azimuth's unit direction.
            #[inline(always)]
            pub(crate) fn corners(&self, delta: Real) -> (Corner, Corner, V3) {
                let da = self.azimuth;
                let (sin_d, cos_d) = sin_cos(delta);
                let d = da * cos_d + V3::new(-da.y, da.x, 0.0) * sin_d;
                let o = cut(self.start, self.start_radius, d, sin_d, self.outer_ends);
                let i = if self.has_inner {
                    cut(self.start, self.start_radius, d, sin_d, self.inner_ends)
                } else {
                    Corner::ZENITH
                };
                (i, o, d)
            }

            /// The area from the start to azimuth δ and the size of the
            /// terms it sums (|diagonal₁||diagonal₂|/2 and the arc
            /// corrections), which bounds its rounding error, for the
            /// corners `i`, `o` at δ.
            #[inline(always)]
            pub(crate) fn area_and_scale<const BRANCH_FREE: bool>(
                &self,
                i: &Corner,
                o: &Corner,
            ) -> (Real, Real) {
                let (oa, ia) = (&self.outer_start, &self.inner_start);
                let has_inner = self.has_inner;
                let diff = |c1: &Corner, c2: &Corner| {
                    if has_inner {
                        c1.diff(c2)
                    } else {
                        c1.direction - c2.direction
                    }
                };
                let d1 = diff(o, ia);
                let d2 = diff(i, oa);
                let main = (d1.cross(d2)).z;
                let outer_term = arc_correction::<BRANCH_FREE>(oa.direction, o.diff(oa));
                let inner_term = if has_inner {
                    arc_correction::<BRANCH_FREE>(i.direction, ia.diff(i))
                } else {
                    0.0
                };
                let scale = 0.5 * (d1.length() * d2.length() + outer_term.abs() + inner_term.abs());
                (0.5 * (main + outer_term + inner_term).max(0.0), scale)
            }

            /// z_i² − z_o² (≥ 0) for the corners at one azimuth, without
            /// cancellation: twice the area's slope dA/dδ there.
            #[inline(always)]
            pub(crate) fn height_gap(&self, i: &Corner, o: &Corner) -> Real {
                let dz = if self.has_inner {
                    i.diff(o).z
                } else {
                    1.0 - o.direction.z
                };
                (dz * (i.direction.z + o.direction.z)).max(0.0)
            }

            /// A″(δ) = ½ d(r_o² − r_i²)/dφ at the azimuth of the outer
            /// corner `o`: on an edge's great circle of unit normal m̂,
            /// r² = μ²/(μ² + (m·d)²) (μ = |m̂_z|, m = m̂_xy, d the unit
            /// azimuth), so dr²/dφ = −2μ²(m·d)(m·d⊥)/(μ² + (m·d)²)².
            #[inline(always)]
            pub(crate) fn curvature(&self, o: &Corner) -> Real {
                let d = V3::new(o.direction.x, o.direction.y, 0.0).normalize_or_zero();
                let dp = V3::new(-d.y, d.x, 0.0);
                let rate = |m: V3| {
                    let mu2 = m.z * m.z;
                    let (md, mp) = (m.x * d.x + m.y * d.y, m.x * dp.x + m.y * dp.y);
                    let q = mu2 + md * md;
                    let r = -2.0 * mu2 * md * mp / (q * q);
                    if q > 0.0 {
                        r
                    } else {
                        0.0
                    }
                };
                let inner = if self.has_inner {
                    rate(self.inner_normal)
                } else {
                    0.0
                };
                0.5 * (rate(self.outer_normal) - inner)
            }

            /// The local direction at azimuth δ (unit direction `d`,
            /// corners `i`, `o` there), a fraction u₁ of the projected area
            /// from the inner to the outer edge: r² uniform between them.
            #[inline(always)]
            pub(crate) fn local(&self, d: V3, i: &Corner, o: &Corner, u1: Real) -> V3 {
                let u1 = u1.clamp(0.0, 1.0);
                let gap = self.height_gap(i, o);
                let zi2 = i.direction.z * i.direction.z;
                let ri2 = i.direction.x * i.direction.x + i.direction.y * i.direction.y;
                let r2 = ri2 + u1 * gap;
                let z2 = (zi2 - u1 * gap).max(0.0);
                let r = r2.sqrt();
                V3::new(d.x * r, d.y * r, z2.sqrt())
            }

            /// δ with A(δ) = `target` from the first azimuth `delta`
            /// (Halley's method in a bisection bracket; `ProjectedPolygon`'s
            /// docs give the stopping rules), the corners and unit azimuth
            /// there, and the steps taken (at most `max_iterations`). With
            /// branches, for one sample at a time: [`step`](Self::step) is
            /// one pass of this loop without them (the same values; a test
            /// compares them).
            #[inline]
            pub(crate) fn solve_from(
                &self,
                target: Real,
                delta: Real,
                max_iterations: usize,
            ) -> (Real, Corner, Corner, V3, usize) {
                let Bracket {
                    mut delta,
                    mut lo,
                    mut hi,
                    ..
                } = Bracket::start(delta, self.width);
                let mut steps = 0;
                loop {
                    let (i, o, d) = self.corners(delta);
                    let (area, scale) = self.area_and_scale::<false>(&i, &o);
                    let f = area - target;
                    if self.converged(f, scale, target) || steps >= max_iterations {
                        return (delta, i, o, d, steps);
                    }
                    steps += 1;
                    if f > 0.0 {
                        hi = delta;
                    } else {
                        lo = delta;
                    }
                    let (slope, step, accept) = self.halley_step(f, &i, &o);
                    if slope > 0.0 && step.abs() <= 4.0 * Real::EPSILON * delta.abs() {
                        return (delta, i, o, d, steps);
                    }
                    let next = delta - step;
                    let inside = slope > 0.0 && next > lo && next < hi;
                    if inside && step.abs() <= accept {
                        let (i, o, d) = self.corners(next);
                        return (next, i, o, d, steps);
                    }
                    delta = if inside { next } else { 0.5 * (lo + hi) };
                    if hi - lo <= 4.0 * Real::EPSILON * hi {
                        let (i, o, d) = self.corners(delta);
                        return (delta, i, o, d, steps);
                    }
                }
            }

            /// One step of the solve, without a branch (so that a loop over
            /// many samples' steps vectorises): A evaluated at the state's
            /// azimuth, then either an answer (the azimuth, its corners and
            /// unit direction, and `true`) or the next state (`false`).
            /// Where the step answers, the next state's `steps` is the
            /// number of steps the solve took.
            ///
            /// The answer is the state's azimuth when the residual there is
            /// at its rounding floor, when `max_iterations` steps have been
            /// taken, or when the step is below 4ε relative; the step's
            /// target when it is taken without evaluating A again; the
            /// bracket's midpoint or the step's target when the bracket has
            /// shrunk to 4ε relative.
            #[inline(always)]
            pub(crate) fn step(
                &self,
                target: Real,
                state: Bracket,
                max_iterations: Real,
            ) -> (Real, Corner, Corner, V3, bool, Bracket) {
                let Bracket {
                    delta,
                    lo,
                    hi,
                    steps,
                } = state;
                let (i, o, d) = self.corners(delta);
                let (area, scale) = self.area_and_scale::<true>(&i, &o);
                let f = area - target;
                let done = self.converged(f, scale, target) | (steps >= max_iterations);
                let (lo, hi) = if f > 0.0 { (lo, delta) } else { (delta, hi) };
                let (slope, step, accept) = self.halley_step(f, &i, &o);
                let stays = (slope > 0.0) & (step.abs() <= 4.0 * Real::EPSILON * delta.abs());
                let next = delta - step;
                let inside = (slope > 0.0) & (next > lo) & (next < hi);
                let moves = inside & (step.abs() <= accept);
                let then = if inside { next } else { 0.5 * (lo + hi) };
                let narrow = hi - lo <= 4.0 * Real::EPSILON * hi;
                // Both the step taken without evaluating A and the narrow
                // bracket end at `then` (the step's target when inside).
                let (i2, o2, d2) = self.corners(then);
                let keep = done | stays;
                let answered = keep | moves | narrow;
                let next_state = Bracket {
                    delta: then,
                    lo,
                    hi,
                    steps: if done { steps } else { steps + 1.0 },
                };
                if keep {
                    (delta, i, o, d, answered, next_state)
                } else {
                    (then, i2, o2, d2, answered, next_state)
                }
            }

            /// Whether the residual f = A(δ) − target is at the rounding
            /// floor of the area's evaluation (a few ε times its terms,
            /// `scale`) and of the target (formed as u₀Ω⊥ minus the
            /// sectors before).
            #[inline(always)]
            fn converged(&self, f: Real, scale: Real, target: Real) -> bool {
                f.abs() <= 8.0 * Real::EPSILON * (scale + target + self.before)
            }

            /// One step from the residual f at corners `i`, `o`: the slope
            /// dA/dδ there, the step (Halley's, with A″ from the edges'
            /// ellipses: cubic convergence, one evaluation of A fewer than
            /// Newton's from the same guess; Newton's where Halley's
            /// denominator is not positive), and the largest such step
            /// taken without evaluating A again. A Halley step of size s
            /// leaves an error of about s³/Δ² (A varying on the sector's
            /// scale Δ), a Newton step s²/Δ: below ¼ε^{1/3}Δ resp. √ε Δ
            /// that is ≲ ε Δ (tested against the converged root).
            #[inline(always)]
            fn halley_step(&self, f: Real, i: &Corner, o: &Corner) -> (Real, Real, Real) {
                let slope = 0.5 * self.height_gap(i, o);
                let curvature = self.curvature(o);
                let denominator = 2.0 * slope * slope - f * curvature;
                let halley = denominator > 0.0;
                let halley_step = 2.0 * f * slope / denominator;
                let newton_step = f / slope;
                if halley {
                    (slope, halley_step, self.accept)
                } else {
                    (slope, newton_step, Real::EPSILON.sqrt() * self.width)
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_sector_impl);
