//! Projected-solid-angle sampling of convex polygon lights.

macro_rules! projected_polygon_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::error::SamplingError;
        use crate::light_sample::$p::LightSample;
        use crate::light_sampler::$p::{shading_normal, LightSampler};
        use crate::projected_sector::$p::{cross2, cut as cut_edge, Corner, Sector};
        use crate::segment::$p::CBRT_EPSILON;
        use crate::trig::$p::sin_cos;
        use lambert_geometry::precision::$p::{wide3, Real, ONE_MINUS_EPSILON, V2, V3};
        use lambert_geometry::$p::{ConvexPolygon, Frame};

        /// Capacity for the clipped polygon: at most 8 input vertices, plus
        /// the one that clipping at the horizon can add. Kept small because
        /// a sampler is prepared per shading point and its arrays are
        /// initialised each time (2 KB in f64).
        const CAP: usize = 9;
        /// No inner edge in a sector (the zenith lies on the polygon's
        /// boundary).
        const NONE: usize = usize::MAX;

        /// Projected-solid-angle (cosine-weighted) sampling of a convex planar
        /// polygon light, clipped to the receiver's hemisphere: density
        /// p(ω) = cos θ/Ω⊥ per steradian over the directions in which the receiver
        /// sees the polygon above its horizon, with Ω⊥ = ∫ cos θ dω. For a uniform
        /// polygon of radiance L every sample's estimate L cos θ/p is the irradiance
        /// L Ω⊥ (zero variance), up to the accuracy of Ω⊥ and of one iteration,
        /// stated below.
        ///
        /// # Choice of method: Peters 2021 over Arvo 2001
        /// Two published methods sample the projected solid angle of a polygon
        /// exactly. Arvo ("Stratified sampling of 2-manifolds", SIGGRAPH 2001 course
        /// notes) fans the polygon into spherical triangles and, per triangle,
        /// inverts two nested one-dimensional CDFs by Newton's method: the projected
        /// solid angle of a growing sub-triangle (Lambert's formula, a sum of edge
        /// terms of alternating sign) and the cosine-weighted position along an arc.
        /// Peters ("BRDF importance sampling for polygonal lights", ACM TOG 40(4),
        /// 2021) works in the orthographic projection onto the receiver's disk
        /// (Nusselt's analogue: cos θ dω is its area element), where each great-circle
        /// edge becomes an ellipse centered on the disk's center O. Cutting the
        /// projected polygon into sectors about O at its vertices' azimuths leaves,
        /// in each sector, the region between at most two ellipses; the area of a
        /// central ellipse sector is closed-form and so is its inverse, so if the
        /// polygon contains the zenith ("central case") sampling needs no iteration
        /// at all, and otherwise one one-dimensional inversion per sample, and the
        /// radial coordinate is exact (r² uniform between the two ellipses).
        ///
        /// We chose Peters' decomposition, measured against a prototype of Arvo's
        /// method on this crate's cases (`lambert_benches::arvo`, its test and the
        /// `projected` bench, one run, f64):
        ///
        /// * **Iterations.** Arvo: 6–11 Newton steps per sample on average over its
        ///   two nested inversions (up to 30 on a grazing triangle). Sectors: none
        ///   when the polygon contains the zenith, otherwise one inversion of ≤ 4
        ///   Halley steps (≤ 3 in f32; mean 1–3).
        /// * **Accuracy.** Both of Arvo's inversions evaluate Lambert's formula on
        ///   nearly parallel unit vectors: for a triangle 3e-5 rad across they left
        ///   residuals of 1.4e-7 (relative to Ω⊥) in the sampled CDF, and Ω⊥ itself
        ///   was off by 4.5e-9. Ours agrees with the planar limit to 2e-15 for a
        ///   polygon 1e-6 rad across (the tests) and stops at its rounding floor.
        /// * **Cost.** Per sample, Arvo took 17× the time of the central sector
        ///   method on a triangle and 1.5× that of the non-central one on a square.
        ///   The central case costs about what uniform spherical-triangle sampling
        ///   does (0.8× on the bench's triangle, 0.7× of a spherical rectangle); the
        ///   non-central case about 10× a spherical rectangle (each Halley step
        ///   evaluates the moment formula below: two corner cuts, two arc lengths).
        ///   Preparing a sampler for a shading point costs 2–4× preparing a
        ///   spherical triangle or rectangle.
        #[doc = concat!("  For many samples from one point, [`TabulatedProjectedPolygon`](crate::", stringify!($p), "::TabulatedProjectedPolygon)")]
        ///   starts each solve from a tabulated inverse and evaluates the area
        ///   about half as often, and its `sample_directions` draws them in
        ///   vectorised passes, a sector at a time.
        ///
        /// The one weakness we found in Peters' formulation is numerical: away from
        /// the zenith a sector's area is the difference of two elliptic-sector areas
        /// of size ~r²Δφ for a region of size ~r Δr Δφ, so a polygon of angular size
        /// ℓ loses about 2 log₁₀(1/ℓ) digits (ε/ℓ² relative: 1e-3 in f32 for a light
        /// 1e-2 rad across). We therefore evaluate the non-central sectors
        /// differently (below), keeping Peters' structure.
        ///
        /// # Non-central sectors without cancellation (our formulation)
        /// The part of a sector between azimuths φₐ (at a vertex) and φ is a
        /// spherical quadrilateral Q with corners îₐ, ôₐ on the meridian at φₐ and
        /// î, ô on the meridian at φ (inner and outer edge). Its projected solid
        /// angle is n·m(Q), where m(Q) = ∫_Q ω dω = ½ Σₑ (Θₑ/sin Θₑ)(cₑ × cₑ₊₁)
        /// (Lambert's vector form over the edges, Θₑ their arc lengths). Splitting
        /// Θ/sin Θ = 1 + g(Θ), g = (Θ − sin Θ)/sin Θ, and using
        /// Σ cₑ × cₑ₊₁ = (c₃ − c₁) × (c₄ − c₂) for a quadrilateral,
        ///
        /// Ω⊥(Q) = ½ [ ((ô − îₐ) × (î − ôₐ))_z + g(Θₒ)(ôₐ × ô)_z + g(Θᵢ)(î × îₐ)_z ]
        ///
        /// (the meridian edges contribute nothing: their cross products are
        /// horizontal). The first term is the triple product of the diagonals, of
        /// the size of the result; the corrections are smaller by Θ², so nothing
        /// cancels (Θ comes from this crate's branch-free
        #[doc = concat!("[`atan2`](crate::", stringify!($p), "::atan2), which the batch's loops can inline).")]
        /// The corners are points of the planar polygon (the meridian
        /// plane through φ cut with an edge), kept as offsets from the sector's
        /// vertex so that differences of nearby unit directions, Q̂₁ − Q̂₂ =
        /// [(Q₁ − Q₂) − Q̂₂(|Q₁| − |Q₂|)]/|Q₁| with |Q₁| − |Q₂| =
        /// (Q₁ − Q₂)·(Q₁ + Q₂)/(|Q₁| + |Q₂|), come from exact edge vectors; and the
        /// meridian plane at φ = φₐ + δ is cut as cross(d, P) = −|Pₐ,xy| sin δ +
        /// cross(d, P − Pₐ), relative to the vertex. The offsets themselves are the
        /// world edge vectors turned into the receiver's frame, not differences of
        /// turned positions, so a light 10⁶ times farther than its size keeps full
        /// precision. The sector's area A(δ) is inverted by Halley's method
        /// (A′ = ½(zᵢ² − zₒ²), also from corner differences; A″ from the edges'
        /// ellipses) from a quadratic model of A fitted at the sector's nearer end
        /// (exact when the radial thickness varies linearly, as it does where the
        /// inner and outer edges meet at a zero slope, a double root that Newton's
        /// method alone approaches only linearly), inside a bisection bracket. It
        /// stops when the residual reaches the rounding floor of A and of the target
        /// (8ε times the terms summed), or takes a last Halley step below ¼ε^{1/3} Δ
        /// without evaluating A again (its error is then ~step³/Δ² ≲ ε Δ/64; a
        /// Newton fallback step must be below √ε Δ), after at most
        /// [`ProjectedPolygon::MAX_ITERATIONS`] steps (measured: ≤ 4 in f64, ≤ 3 in
        /// f32 over the tests' cases). The sample is then placed on the meridian with
        /// r² uniform between the two edges, z² = (1 − u₁) zᵢ² + u₁ zₒ².
        ///
        /// Central sectors (one ellipse, about O) are sampled exactly as Peters
        /// does: with m̂ the edge's unit normal, μ = m̂_z and L the map that shrinks
        /// the unit circle by μ along m̂_xy onto the ellipse, a sector's area is
        /// (μ/2)·∠(L⁻¹dₛ, L⁻¹d), so the angle in L's preimage is 2T/μ for a
        /// target area T, and a point at distance √u₁ along the ellipse point Lg has
        /// z² = (1 − u₁) + u₁ (m̂_xy·g)² (no cancellation).
        ///
        /// # Clipping and accuracy
        /// The polygon is clipped at the receiver's plane (Sutherland & Hodgman
        /// 1974) before anything else, so no sample is wasted below the horizon.
        /// Ω⊥ is the sum of the sector areas: a few ulps relative for polygons of
        /// any size and distance, except where the problem itself is ill-conditioned
        /// (a polygon seen nearly edge-on or grazing the horizon). Directions within
        /// 4ε of the horizon are raised to cos θ = 4ε, so every sample has a
        /// positive density.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedPolygon;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A unit square 1 above the receiver, offset so the zenith is outside.
        /// let square = ConvexPolygon::new(vec![
        #[doc = concat!("    ", stringify!($v3), "::new(0.5, -0.5, 1.0), ", stringify!($v3), "::new(1.5, -0.5, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.5, 0.5, 1.0), ", stringify!($v3), "::new(0.5, 0.5, 1.0),")]
        /// ])?;
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// let sampler = ProjectedPolygon::new(p, n, &square)?;
        #[doc = concat!("let s = sampler.sample(", stringify!($v2), "::new(0.4, 0.6));")]
        /// // Zero variance: cos θ / pdf is Ω⊥ for every sample.
        /// let omega = sampler.projected_solid_angle();
        /// assert!((s.direction.z / s.pdf - omega).abs() < 1e-6 * omega);
        /// assert!((s.point.z - 1.0).abs() < 1e-6 && sampler.pdf(s.direction) == s.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ProjectedPolygon {
            frame: Frame,
            /// The reference point, and the polygon's plane: unit normal and
            /// signed distance from the reference point.
            reference: V3,
            plane_normal: V3,
            plane_offset: Real,
            count: usize,
            /// Clipped vertices (local frame): offsets from vertex 0,
            /// positions, lengths, unit directions; unit inward edge normals.
            offset: [V3; CAP],
            position: [V3; CAP],
            length: [Real; CAP],
            direction: [V3; CAP],
            edge_normal: [V3; CAP],
            central: bool,
            sectors: usize,
            /// Per sector: cumulative area at its end.
            cumulative: [Real; CAP],
            /// Central: start direction in L's preimage (unit, 2-D in xy),
            /// its angle, and the edge (its normal gives μ and m_xy).
            /// Non-central: start vertex, outer and inner edge, angular
            /// width, unit start azimuth, and the corners at the start.
            start: [usize; CAP],
            outer: [usize; CAP],
            inner: [usize; CAP],
            width: [Real; CAP],
            /// Non-central: the slopes of the sector's area at its start and
            /// end relative to its mean slope, clamped to [0, 3] (the
            /// quadratic models of the initial guess).
            shape: [Real; CAP],
            shape_end: [Real; CAP],
            /// Non-central: the largest final Halley step taken without
            /// evaluating the area again, ¼ε^{1/3} times the sector's width.
            accept: [Real; CAP],
            azimuth: [V3; CAP],
            outer_corner: [Corner; CAP],
            inner_corner: [Corner; CAP],
            projected_solid_angle: Real,
            /// Σ over the sectors of the size of the terms their areas sum.
            area_scale: Real,
        }

        impl ProjectedPolygon {
            /// The most vertices the polygon may have.
            pub const MAX_VERTICES: usize = CAP - 1;

            /// The most Newton steps of a non-central sample (see the type's docs).
            pub const MAX_ITERATIONS: usize = 64;

            /// Prepares sampling of `polygon` (at most
            /// [`Self::MAX_VERTICES`] vertices; the light is treated as
            /// two-sided) seen from `reference` with surface normal `normal`
            /// (any non-zero length). The polygon is clipped at the
            /// receiver's plane. [`ProjectedPolygonSampler`] takes polygons
            /// of any size.
            ///
            /// Errors: non-finite input, a zero normal, more than
            /// [`Self::MAX_VERTICES`] vertices, a vertex at the reference
            /// point, a polygon seen edge-on (the reference point in its
            /// plane), one wholly below the horizon, or one whose visible
            /// part is too small for its density to be representable.
            pub fn new(
                reference: V3,
                normal: V3,
                polygon: &ConvexPolygon,
            ) -> Result<Self, SamplingError> {
                let vertices = polygon.vertices();
                if vertices.len() > Self::MAX_VERTICES {
                    return Err(SamplingError::OutOfRange {
                        field: "polygon.vertices().len()",
                        value: vertices.len() as f64,
                        range: "[3, 8] (ProjectedPolygonSampler takes any polygon)",
                    });
                }
                Self::from_vertices(reference, normal, vertices, polygon.normal())
            }

            /// [`ProjectedPolygon::new`] for the vertices of a valid convex
            /// polygon (3 to [`Self::MAX_VERTICES`] of them) whose unit
            /// normal is `plane_normal`.
            pub(crate) fn from_vertices(
                reference: V3,
                normal: V3,
                vertices: &[V3],
                plane_normal: V3,
            ) -> Result<Self, SamplingError> {
                debug_assert!((3..=Self::MAX_VERTICES).contains(&vertices.len()));
                crate::error::finite3("reference", wide3(reference))?;
                let frame = Frame::from_normal(shading_normal(normal)?);
                let base = frame.to_local(vertices[0] - reference);
                // Clip at z ≥ 0, keeping offsets from vertex 0 exact.
                let k = vertices.len();
                let mut offset = [V3::ZERO; CAP];
                let mut position = [V3::ZERO; CAP];
                let mut count = 0usize;
                let local_offset = |i: usize| frame.to_local(vertices[i] - vertices[0]);
                for i in 0..k {
                    let (ea, eb) = (local_offset(i), local_offset((i + 1) % k));
                    let (pa, pb) = (base + ea, base + eb);
                    if pa.z >= 0.0 {
                        offset[count] = ea;
                        position[count] = pa;
                        count += 1;
                    }
                    if (pa.z > 0.0 && pb.z < 0.0) || (pa.z < 0.0 && pb.z > 0.0) {
                        let t = pa.z / (pa.z - pb.z);
                        let e = ea + (eb - ea) * t;
                        let mut p = base + e;
                        p.z = 0.0;
                        offset[count] = e;
                        position[count] = p;
                        count += 1;
                    }
                }
                let below = SamplingError::Degenerate {
                    what: "the polygon lies below the receiver's horizon",
                };
                if count < 3 {
                    return Err(below);
                }
                // Orientation: inward edge normals need the vertices
                // counter-clockwise seen from the receiver looking out.
                let mut newell = V3::ZERO;
                for i in 0..count {
                    newell += offset[i].cross(offset[(i + 1) % count]);
                }
                let side = newell.dot(position[0]);
                if !(side.abs() > 0.0) || !side.is_finite() {
                    return Err(SamplingError::Degenerate {
                        what: "the polygon is seen edge-on (the reference point lies in its \
                               plane) or has zero area",
                    });
                }
                if side < 0.0 {
                    offset[..count].reverse();
                    position[..count].reverse();
                }
                let mut length = [0.0 as Real; CAP];
                let mut direction = [V3::ZERO; CAP];
                let mut edge_normal = [V3::ZERO; CAP];
                for i in 0..count {
                    length[i] = position[i].length();
                    if !(length[i] > 0.0) || !length[i].is_finite() {
                        return Err(SamplingError::Degenerate {
                            what: "a polygon vertex coincides with the reference point",
                        });
                    }
                    direction[i] = position[i] / length[i];
                }
                for i in 0..count {
                    let j = (i + 1) % count;
                    // Pᵢ × Pⱼ = Pᵢ × (Eⱼ − Eᵢ), from the exact edge vector.
                    let m = position[i].cross(offset[j] - offset[i]);
                    edge_normal[i] = m.normalize_or_zero();
                }
                let plane_offset = plane_normal.dot(vertices[0] - reference);
                let mut poly = ProjectedPolygon {
                    frame,
                    reference,
                    plane_normal,
                    plane_offset,
                    count,
                    offset,
                    position,
                    length,
                    direction,
                    edge_normal,
                    central: false,
                    sectors: 0,
                    cumulative: [0.0; CAP],
                    start: [0; CAP],
                    outer: [NONE; CAP],
                    inner: [NONE; CAP],
                    width: [0.0; CAP],
                    shape: [0.0; CAP],
                    shape_end: [0.0; CAP],
                    accept: [0.0; CAP],
                    azimuth: [V3::ZERO; CAP],
                    outer_corner: [Corner::ZENITH; CAP],
                    inner_corner: [Corner::ZENITH; CAP],
                    projected_solid_angle: 0.0,
                    area_scale: 0.0,
                };
                poly.central = (0..count).all(|i| poly.edge_normal[i].z > 0.0);
                if poly.central {
                    poly.prepare_central();
                } else {
                    poly.prepare_sectors();
                }
                let total = if poly.sectors > 0 {
                    poly.cumulative[poly.sectors - 1]
                } else {
                    0.0
                };
                poly.projected_solid_angle = total;
                if !(total > 0.0) || !(1.0 / total).is_finite() {
                    return Err(SamplingError::Degenerate {
                        what: "the polygon's projected solid angle above the horizon is too \
                               small for its density to be representable",
                    });
                }
                Ok(poly)
            }

            /// The projected solid angle Ω⊥ of the visible part of the
            /// polygon, in steradians: irradiance from a uniform polygon of
            /// radiance L is L Ω⊥.
            #[inline]
            pub fn projected_solid_angle(&self) -> Real {
                self.projected_solid_angle
            }

            /// A bound on the rounding error of
            /// [`projected_solid_angle`](Self::projected_solid_angle), in
            /// steradians: 8ε times the sum, over the sectors, of the
            /// magnitudes of the terms each sector's area is formed from
            /// (½|d₁||d₂| for the diagonals' cross product, plus the arc
            /// corrections), and 8ε Ω⊥ when the zenith is inside the polygon
            /// (each sector's area is then a product, exact to a few ulps).
            /// It is a few ulps of Ω⊥ except where the sector areas cancel:
            /// a polygon grazing the horizon, whose Ω⊥ is the small
            /// difference of sectors of the unit disk (for a wall clipped to
            /// a 1e-4 sliver, Ω⊥ ≈ 1e-9 from sectors of ≈ 0.1, so about
            /// 1e-7 of Ω⊥). Every sample's value L cos θ/p is L Ω⊥ and
            /// carries this error, which no number of samples averages away;
            /// estimators add it to their error.
            #[inline]
            pub fn projected_solid_angle_error(&self) -> Real {
                let terms = if self.central {
                    self.projected_solid_angle
                } else {
                    self.area_scale.max(self.projected_solid_angle)
                };
                8.0 * Real::EPSILON * terms
            }

            /// Whether the zenith lies inside the polygon (no iteration is
            /// needed to sample it).
            #[inline]
            pub fn is_central(&self) -> bool {
                self.central
            }

            /// The number of vertices after clipping at the horizon.
            #[inline]
            pub fn clipped_vertex_count(&self) -> usize {
                self.count
            }

            /// μ L⁻¹ d for the ellipse of unit normal m (direction only).
            #[inline(always)]
            fn preimage(m: V3, d: V3) -> V3 {
                let mu = m.z;
                let mxy = V3::new(m.x, m.y, 0.0);
                V3::new(d.x, d.y, 0.0) * mu + mxy * (mxy.dot(d) / (1.0 + mu))
            }

            /// Central case: one sector per edge, about the zenith.
            fn prepare_central(&mut self) {
                let mut total: Real = 0.0;
                for i in 0..self.count {
                    let j = (i + 1) % self.count;
                    let m = self.edge_normal[i];
                    let gs = Self::preimage(m, self.direction[i]).normalize_or_zero();
                    let ge = Self::preimage(m, self.direction[j]).normalize_or_zero();
                    let angle = cross2(gs, ge).atan2(gs.dot(ge)).max(0.0);
                    total += 0.5 * m.z * angle;
                    self.cumulative[i] = total;
                    self.azimuth[i] = gs;
                    self.width[i] = angle;
                    self.start[i] = i;
                }
                self.sectors = self.count;
            }

            /// The azimuth of vertex i relative to `g`, in (−π, π].
            #[inline]
            fn relative_azimuth(&self, g: V3, i: usize) -> Real {
                let d = self.direction[i];
                cross2(g, d).atan2(g.x * d.x + g.y * d.y)
            }

            /// Non-central case: sectors between consecutive vertex azimuths.
            fn prepare_sectors(&mut self) {
                let n = self.count;
                // A reference azimuth inside the polygon's azimuth range.
                let mut g = V3::ZERO;
                for i in 0..n {
                    let d = self.direction[i];
                    let r = (d.x * d.x + d.y * d.y).sqrt();
                    if r > 0.0 {
                        g += V3::new(d.x / r, d.y / r, 0.0);
                    }
                }
                let g = g.normalize_or_zero();
                let mut order = [0usize; CAP];
                let mut angle = [0.0 as Real; CAP];
                let mut m = 0;
                for i in 0..n {
                    let d = self.direction[i];
                    if d.x != 0.0 || d.y != 0.0 {
                        angle[i] = self.relative_azimuth(g, i);
                        order[m] = i;
                        m += 1;
                    }
                }
                // Insertion sort by azimuth.
                for x in 1..m {
                    let mut y = x;
                    while y > 0 && angle[order[y - 1]] > angle[order[y]] {
                        order.swap(y - 1, y);
                        y -= 1;
                    }
                }
                let mut total: Real = 0.0;
                let mut sectors = 0;
                for s in 0..m.saturating_sub(1) {
                    let (a, b) = (order[s], order[s + 1]);
                    let mid = 0.5 * (angle[a] + angle[b]);
                    if !(angle[b] > angle[a]) {
                        continue;
                    }
                    // The edges whose azimuth range covers the sector.
                    let (mut outer, mut inner) = (NONE, NONE);
                    for e in 0..n {
                        let f = (e + 1) % n;
                        let de = self.direction[e];
                        let df = self.direction[f];
                        let zen = |d: V3| d.x == 0.0 && d.y == 0.0;
                        if zen(de) || zen(df) {
                            continue;
                        }
                        let (lo, hi) = if angle[e] <= angle[f] {
                            (angle[e], angle[f])
                        } else {
                            (angle[f], angle[e])
                        };
                        if lo <= mid && mid <= hi {
                            let z = self.edge_normal[e].z;
                            if z > 0.0 {
                                outer = e;
                            } else if z < 0.0 {
                                inner = e;
                            }
                        }
                    }
                    if outer == NONE {
                        continue;
                    }
                    let pa = self.position[a];
                    let pb = self.position[b];
                    let ra = V3::new(pa.x, pa.y, 0.0);
                    let da = ra / ra.length();
                    // Angular width from the exact edge vector (no
                    // cancellation between nearby azimuths).
                    let fb = self.offset[b] - self.offset[a];
                    let width = cross2(pa, fb).atan2(pa.x * pb.x + pa.y * pb.y);
                    let k = sectors;
                    self.start[k] = a;
                    self.outer[k] = outer;
                    self.inner[k] = inner;
                    self.width[k] = width;
                    self.azimuth[k] = da;
                    let radius = (pa.x * pa.x + pa.y * pa.y).sqrt();
                    self.outer_corner[k] = cut_edge(pa, radius, da, 0.0, self.edge_ends(a, outer));
                    if inner != NONE {
                        self.inner_corner[k] =
                            cut_edge(pa, radius, da, 0.0, self.edge_ends(a, inner));
                    }
                    let sector = self.sector(k);
                    let (ib, ob, _) = sector.corners(width);
                    let (area, scale) = sector.area_and_scale::<false>(&ib, &ob);
                    self.area_scale += scale;
                    let (oa, ia) = (sector.outer_start, sector.inner_start);
                    let mean = if area > 0.0 { width / area } else { 0.0 };
                    let start_slope = (0.5 * sector.height_gap(&ia, &oa) * mean).clamp(0.0, 3.0);
                    let end_slope = (0.5 * sector.height_gap(&ib, &ob) * mean).clamp(0.0, 3.0);
                    self.shape[k] = start_slope;
                    self.shape_end[k] = end_slope;
                    self.accept[k] = 0.25 * CBRT_EPSILON * width;
                    total += area;
                    self.cumulative[k] = total;
                    sectors += 1;
                }
                self.sectors = sectors;
            }

            /// The ends of edge `e` as offsets from vertex `a`.
            #[inline(always)]
            fn edge_ends(&self, a: usize, e: usize) -> (V3, V3) {
                let t = (e + 1) % self.count;
                (self.offset[e] - self.offset[a], self.offset[t] - self.offset[a])
            }

            /// Non-central sector k, copied out (see [`Sector`]).
            #[inline]
            pub(crate) fn sector(&self, k: usize) -> Sector {
                let a = self.start[k];
                let pa = self.position[a];
                let (outer, inner) = (self.outer[k], self.inner[k]);
                let has_inner = inner != NONE;
                let before = if k > 0 { self.cumulative[k - 1] } else { 0.0 };
                Sector {
                    start: pa,
                    start_radius: (pa.x * pa.x + pa.y * pa.y).sqrt(),
                    azimuth: self.azimuth[k],
                    outer_ends: self.edge_ends(a, outer),
                    inner_ends: if has_inner {
                        self.edge_ends(a, inner)
                    } else {
                        (V3::ZERO, V3::ZERO)
                    },
                    has_inner,
                    outer_start: self.outer_corner[k],
                    inner_start: if has_inner {
                        self.inner_corner[k]
                    } else {
                        Corner::ZENITH
                    },
                    outer_normal: self.edge_normal[outer],
                    inner_normal: if has_inner {
                        self.edge_normal[inner]
                    } else {
                        V3::ZERO
                    },
                    width: self.width[k],
                    before,
                    accept: self.accept[k],
                    size: self.cumulative[k] - before,
                    shape: self.shape[k],
                    shape_end: self.shape_end[k],
                }
            }

            /// The sector and the area target within it for u₀.
            #[inline]
            pub(crate) fn locate(&self, u0: Real) -> (usize, Real) {
                let target = u0.clamp(0.0, 1.0) * self.projected_solid_angle;
                // The first sector whose cumulative area exceeds the target
                // (the last if none): as the cumulative areas never
                // decrease, the number of sectors before the last that do
                // not, counted without a branch (the sector is random, and
                // a search loop's exit mispredicted).
                let mut k = 0;
                for s in 0..self.sectors.saturating_sub(1).min(CAP) {
                    k += usize::from(self.cumulative[s] <= target);
                }
                let before = if k > 0 { self.cumulative[k - 1] } else { 0.0 };
                let size = self.cumulative[k] - before;
                (k, (target - before).clamp(0.0, size))
            }

            /// The local direction for u, and the Newton steps taken.
            #[inline]
            fn sample_local(&self, u: V2) -> (V3, usize) {
                let (k, target) = self.locate(u.x);
                if self.central {
                    (self.central_local(k, target, u.y), 0)
                } else {
                    let sector = self.sector(k);
                    let guess = sector.initial_guess(target);
                    let (_, i, o, d, steps) = sector.solve_from(target, guess, Self::MAX_ITERATIONS);
                    (sector.local(d, &i, &o, u.y), steps)
                }
            }

            /// Whether the sectors are central (no solve: see the type's
            /// docs).
            #[inline]
            pub(crate) fn central(&self) -> bool {
                self.central
            }

            /// The number of sectors, and sector k's angular width and area.
            #[inline]
            pub(crate) fn sector_shape(&self, k: usize) -> (usize, Real, Real) {
                let before = if k > 0 { self.cumulative[k - 1] } else { 0.0 };
                (self.sectors, self.width[k], self.cumulative[k] - before)
            }

            /// The light sample for area `target` in non-central `sector`
            /// and u₁, solving from the first azimuth `delta`, and the
            /// Newton steps taken.
            #[inline]
            pub(crate) fn sample_sector(
                &self,
                sector: &Sector,
                target: Real,
                delta: Real,
                u1: Real,
            ) -> (LightSample, usize) {
                let (_, i, o, d, steps) = sector.solve_from(target, delta, Self::MAX_ITERATIONS);
                (self.light_sample(sector.local(d, &i, &o, u1)), steps)
            }

            /// The azimuth δ past the start of non-central sector k where
            /// its area is `target`, and the area's slope dA/dδ there.
            pub(crate) fn root_and_slope(&self, k: usize, target: Real) -> (Real, Real) {
                let sector = self.sector(k);
                let guess = sector.initial_guess(target);
                let (delta, i, o, _, _) = sector.solve_from(target, guess, Self::MAX_ITERATIONS);
                (delta, 0.5 * sector.height_gap(&i, &o))
            }

            /// The slope dA/dδ of non-central sector k's area at δ.
            pub(crate) fn slope_at(&self, k: usize, delta: Real) -> Real {
                let sector = self.sector(k);
                let (i, o, _) = sector.corners(delta);
                0.5 * sector.height_gap(&i, &o)
            }

            /// The local direction in central sector k at area `target`
            /// past its start, a fraction u₁ of the way out.
            #[inline]
            fn central_local(&self, k: usize, target: Real, u1: Real) -> V3 {
                let u1 = u1.clamp(0.0, 1.0);
                let m = self.edge_normal[self.start[k]];
                let mu = m.z;
                let gs = self.azimuth[k];
                let theta = (2.0 * target / mu).min(self.width[k]);
                let (s, c) = sin_cos(theta);
                let g = gs * c + V3::new(-gs.y, gs.x, 0.0) * s;
                let mxy = V3::new(m.x, m.y, 0.0);
                let mg = mxy.dot(g);
                let on_ellipse = g - mxy * (mg / (1.0 + mu));
                let r = u1.sqrt();
                let z2 = (1.0 - u1) + u1 * mg * mg;
                let p = on_ellipse * r;
                V3::new(p.x, p.y, z2.sqrt())
            }

            /// The receiver's frame (local z its normal).
            #[inline(always)]
            pub(crate) fn frame(&self) -> Frame {
                self.frame
            }

            /// The world direction of the local direction `l` of a sample,
            /// raised to cos θ ≥ 4ε (see the type's docs) first.
            #[inline(always)]
            pub(crate) fn world_direction(frame: &Frame, mut l: V3) -> V3 {
                l.z = l.z.max(4.0 * Real::EPSILON);
                frame.from_local(l)
            }

            /// The density [`ProjectedPolygon::sample`] gives its direction
            /// `w`: cos θ/Ω⊥ (cos θ = n·w), or 0 for cos θ ≤ 0. Unlike
            /// [`ProjectedPolygon::pdf`] it does not test whether `w`
            /// points into the polygon (a sample's direction does).
            #[inline(always)]
            pub fn sample_density(&self, w: V3) -> Real {
                self.pdf_of(self.frame.z.dot(w))
            }

            /// The light sample of the local direction `l`.
            #[inline]
            fn light_sample(&self, l: V3) -> LightSample {
                let w = Self::world_direction(&self.frame, l);
                let distance = self.plane_offset / self.plane_normal.dot(w);
                LightSample {
                    direction: w,
                    pdf: self.pdf_of(self.frame.z.dot(w)),
                    point: self.reference + w * distance,
                    distance,
                }
            }

            /// The number of Newton steps [`ProjectedPolygon::sample`] takes
            /// for u (0 in the central case).
            #[inline]
            pub fn newton_steps(&self, u: V2) -> usize {
                self.sample_local(u).1
            }

            /// A direction with density cos θ/Ω⊥ on the visible polygon, that
            /// density (formed from cos θ = n·ω of the returned direction), the
            /// point it hits on the polygon's plane and its distance. Every
            /// u ∈ [0, 1]² gives a finite unit vector for which
            /// [`ProjectedPolygon::pdf`] returns the same density.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                self.light_sample(self.sample_local(u).0)
            }

            /// cos θ = n·w of the unit world direction `w`, n the
            /// receiver's unit normal.
            #[inline]
            pub(crate) fn cos_theta(&self, w: V3) -> Real {
                self.frame.z.dot(w)
            }

            #[inline(always)]
            fn pdf_of(&self, cos_theta: Real) -> Real {
                if cos_theta > 0.0 {
                    cos_theta / self.projected_solid_angle
                } else {
                    0.0
                }
            }

            /// Whether the unit world direction `w` points into the visible
            /// polygon: w·m ≥ −32ε for every inward edge normal m (a band of
            /// 32ε rad along the boundary, for the samples' rounding).
            #[inline]
            pub fn contains(&self, w: V3) -> bool {
                let l = self.frame.to_local(w);
                let tol = -32.0 * Real::EPSILON;
                (0..self.count).all(|i| l.dot(self.edge_normal[i]) >= tol)
            }

            /// The density cos θ/Ω⊥ per steradian (cos θ = n·w) of the unit
            /// world direction `w` if it points into the visible polygon (see
            /// [`ProjectedPolygon::contains`]) above the horizon; 0 otherwise.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if self.contains(w) {
                    self.pdf_of(self.frame.z.dot(w))
                } else {
                    0.0
                }
            }

            /// The u that [`ProjectedPolygon::sample`] maps to the direction
            /// `w` of the visible polygon.
            pub fn invert(&self, w: V3) -> V2 {
                let l = self.frame.to_local(w);
                let total = self.projected_solid_angle;
                let clamp01 = |v: Real| v.clamp(0.0, 1.0);
                let r2 = l.x * l.x + l.y * l.y;
                if self.central {
                    // The sector whose azimuth range holds w.
                    let mut k = 0;
                    for i in 0..self.count {
                        let j = (i + 1) % self.count;
                        if cross2(self.direction[i], l) >= 0.0
                            && cross2(l, self.direction[j]) >= 0.0
                        {
                            k = i;
                            break;
                        }
                    }
                    let m = self.edge_normal[k];
                    let gs = self.azimuth[k];
                    let gw = Self::preimage(m, l).normalize_or_zero();
                    let angle = cross2(gs, gw).atan2(gs.dot(gw)).clamp(0.0, self.width[k]);
                    let before = if k > 0 { self.cumulative[k - 1] } else { 0.0 };
                    let u0 = (before + 0.5 * m.z * angle) / total;
                    let mxy = V3::new(m.x, m.y, 0.0);
                    // Ellipse radius² along w: μ²/(μ² + (m_xy·ŵ)²).
                    let mw = mxy.dot(l);
                    let rim2 = if r2 > 0.0 {
                        m.z * m.z * r2 / (m.z * m.z * r2 + mw * mw)
                    } else {
                        1.0
                    };
                    V2::new(clamp01(u0), clamp01(r2 / rim2))
                } else {
                    // The sector whose azimuth range holds w (or, for a w
                    // just outside by rounding, the nearest one).
                    let mut k = 0;
                    let mut best = Real::INFINITY;
                    for s in 0..self.sectors {
                        let pa = self.position[self.start[s]];
                        let delta = cross2(pa, l).atan2(pa.x * l.x + pa.y * l.y);
                        let miss = (-delta).max(delta - self.width[s]).max(0.0);
                        if miss < best {
                            best = miss;
                            k = s;
                        }
                        if miss == 0.0 {
                            break;
                        }
                    }
                    let pa = self.position[self.start[k]];
                    let delta = cross2(pa, l)
                        .atan2(pa.x * l.x + pa.y * l.y)
                        .clamp(0.0, self.width[k]);
                    let sector = self.sector(k);
                    let (i, o, _) = sector.corners(delta);
                    let (area, _) = sector.area_and_scale::<false>(&i, &o);
                    let before = sector.before;
                    let gap = sector.height_gap(&i, &o);
                    let ri2 = i.direction.x * i.direction.x + i.direction.y * i.direction.y;
                    let u1 = if gap > 0.0 { (r2 - ri2) / gap } else { 0.0 };
                    V2::new(clamp01((before + area) / total), clamp01(u1))
                }
            }
        }

        /// Projected-solid-angle sampling of a convex polygon light from
        /// any shading point: built once per light, a [`ProjectedPolygon`]
        /// at each point (density cos θ/Ω⊥ on the part of the polygon above
        /// the point's horizon; Peters 2021), no allocation. For an
        /// unoccluded uniform polygon every sample's L cos θ/p is the
        /// irradiance (to the accuracy stated on [`ProjectedPolygon`]), and
        /// no sample is drawn below the horizon.
        ///
        /// Polygons of more than [`ProjectedPolygon::MAX_VERTICES`] vertices
        /// are cut, once, into a fan of convex pieces of at most that many
        /// vertices sharing vertex 0; a sample chooses a piece in proportion
        /// to its Ω⊥ and samples it, so the density is still cos θ/Ω⊥ of the
        /// whole (each piece is prepared twice per sample: once to sum Ω⊥,
        /// once to sample). [`ProjectedPolygonSampler::at`] prepares one
        /// piece-free sampler for many samples at a point.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::ConvexPolygon;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, ProjectedPolygonSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A 12-gon straddling the horizon of the shading point.
        /// let dodecagon = (0..12).map(|k| {
        #[doc = concat!("    let a = k as ", stringify!($p), " * std::", stringify!($p), "::consts::PI / 6.0;")]
        #[doc = concat!("    ", stringify!($v3), "::new(2.0, a.cos(), 0.5 + a.sin())")]
        /// });
        /// let light = ProjectedPolygonSampler::new(ConvexPolygon::new(dodecagon.collect())?);
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let a = light.sample(p, n, ", stringify!($v2), "::new(0.2, 0.3)).unwrap();")]
        #[doc = concat!("let b = light.sample(p, n, ", stringify!($v2), "::new(0.9, 0.6)).unwrap();")]
        /// // Above the horizon, and cos θ / p the same for every sample.
        /// assert!(a.direction.z > 0.0 && b.direction.z > 0.0);
        /// assert!((a.direction.z / a.pdf - b.direction.z / b.pdf).abs() < 1e-5);
        /// assert_eq!(light.pdf(p, n, a.direction), a.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Debug, PartialEq)]
        pub struct ProjectedPolygonSampler {
            polygon: ConvexPolygon,
            /// The fan pieces: vertex 0 and `vertices[first..=last]`.
            pieces: Vec<(usize, usize)>,
        }

        impl ProjectedPolygonSampler {
            /// The sampler of `polygon`.
            pub fn new(polygon: ConvexPolygon) -> Self {
                let n = polygon.vertices().len();
                let span = ProjectedPolygon::MAX_VERTICES - 2;
                let mut pieces = Vec::new();
                let mut first = 1;
                while first + 1 < n {
                    let last = (first + span).min(n - 1);
                    pieces.push((first, last));
                    first = last;
                }
                ProjectedPolygonSampler { polygon, pieces }
            }

            /// The polygon.
            #[inline]
            pub fn polygon(&self) -> &ConvexPolygon {
                &self.polygon
            }

            /// The sampler at (`reference`, `normal`), for many samples at
            /// one point; see [`ProjectedPolygon::new`] for the errors
            /// (including polygons of more than
            /// [`ProjectedPolygon::MAX_VERTICES`] vertices, which only the
            /// [`LightSampler`] methods take).
            #[inline]
            pub fn at(&self, reference: V3, normal: V3) -> Result<ProjectedPolygon, SamplingError> {
                ProjectedPolygon::new(reference, normal, &self.polygon)
            }

            /// The sampler of fan piece `k` at (`reference`, `normal`), or
            /// `None` where that piece shows nothing above the horizon.
            #[inline]
            fn piece(&self, k: usize, reference: V3, normal: V3) -> Option<ProjectedPolygon> {
                let v = self.polygon.vertices();
                let (first, last) = self.pieces[k];
                let mut corners = [V3::ZERO; ProjectedPolygon::MAX_VERTICES];
                corners[0] = v[0];
                corners[1..=last - first + 1].copy_from_slice(&v[first..=last]);
                let count = last - first + 2;
                ProjectedPolygon::from_vertices(
                    reference,
                    normal,
                    &corners[..count],
                    self.polygon.normal(),
                )
                .ok()
            }

            /// Ω⊥ of the whole polygon at (`reference`, `normal`), the sum
            /// over the fan pieces.
            #[inline]
            fn total(&self, reference: V3, normal: V3) -> Real {
                (0..self.pieces.len())
                    .filter_map(|k| self.piece(k, reference, normal))
                    .map(|p| p.projected_solid_angle())
                    .sum()
            }
        }

        impl LightSampler for ProjectedPolygonSampler {
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if self.pieces.len() == 1 {
                    return self.piece(0, reference, normal).map(|p| p.sample(u));
                }
                let total = self.total(reference, normal);
                if !(total > 0.0) {
                    return None;
                }
                // Choose a piece in proportion to its Ω⊥, reusing u₀.
                let target = u.x * total;
                let mut lo = 0.0;
                let mut chosen = None;
                for k in 0..self.pieces.len() {
                    let Some(piece) = self.piece(k, reference, normal) else {
                        continue;
                    };
                    let hi = lo + piece.projected_solid_angle();
                    chosen = Some((piece, lo, hi));
                    if hi > target {
                        break;
                    }
                    lo = hi;
                }
                let (piece, lo, hi) = chosen?;
                let u0 = ((target - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON);
                let s = piece.sample(V2::new(u0, u.y));
                Some(LightSample {
                    pdf: piece.cos_theta(s.direction) / total,
                    ..s
                })
            }

            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if self.pieces.len() == 1 {
                    return self
                        .piece(0, reference, normal)
                        .map_or(0.0, |p| p.pdf(direction));
                }
                let mut total = 0.0;
                let mut inside = None;
                for k in 0..self.pieces.len() {
                    if let Some(piece) = self.piece(k, reference, normal) {
                        total += piece.projected_solid_angle();
                        if inside.is_none() && piece.pdf(direction) > 0.0 {
                            inside = Some(piece.cos_theta(direction));
                        }
                    }
                }
                match inside {
                    Some(cos_theta) if total > 0.0 => cos_theta / total,
                    _ => 0.0,
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_polygon_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::ConvexPolygon;

    /// Sampled points lie in the polygon's plane, inside it, along the
    /// direction at the reported distance.
    #[test]
    fn points_lie_on_the_polygon_at_the_reported_distance() {
        let p = DVec3::new(0.1, -0.2, 0.3);
        // A parallelogram (planar by construction).
        let (a, b, c) = (
            DVec3::new(1.0, 0.0, 2.0),
            DVec3::new(2.0, 0.5, 2.5),
            DVec3::new(1.5, 1.5, 2.0),
        );
        let v = [a, b, c, a + c - b];
        let polygon = ConvexPolygon::new(v.to_vec()).unwrap();
        let poly =
            super::f64::ProjectedPolygon::new(p, DVec3::new(0.2, 0.1, 1.0), &polygon).unwrap();
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        for i in 0..16 {
            for j in 0..16 {
                let u = DVec2::new((i as f64 + 0.5) / 16.0, (j as f64 + 0.5) / 16.0);
                let l = poly.sample(u);
                // A few ulps of the scene's size (≈ 3).
                assert!(n.dot(l.point - v[0]).abs() < 1e-14, "{u}");
                assert!(
                    (p + l.direction * l.distance - l.point).length() < 1e-14,
                    "{u}"
                );
                // Inside: on the inner side of every edge.
                for k in 0..4 {
                    let (a, b) = (v[k], v[(k + 1) % 4]);
                    assert!((b - a).cross(l.point - a).dot(n) > -1e-14, "{u}");
                }
            }
        }
    }
}
