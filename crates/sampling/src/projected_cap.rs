//! Projected-solid-angle sampling of a spherical cap of directions.

macro_rules! projected_cap_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::disk::$p::{concentric_polar, invert_concentric_disk};
        use crate::error::SamplingError;
        use crate::segment::$p::{segment_area, segment_height, segment_height_branch_free};
        use lambert_geometry::precision::$p::{Real, ONE_MINUS_EPSILON, PI, V2, V3};
        use lambert_geometry::$p::unit_vector;

        /// Which part of the unit disk the visible cap projects to.
        #[derive(Clone, Copy, Debug, PartialEq)]
        enum Region {
            /// The whole ellipse (cap above the horizon).
            Ellipse,
            /// The circular segment ξ ∈ [0, ξ_t] joined to the ellipse's
            /// left segment of height k ∈ [0, k_t] (k = 1 + η); ξ_t = 2,
            /// k_t = 0 for the whole disk.
            Union,
            /// The circular segment ξ ∈ [0, ξ_t] minus the ellipse's right
            /// segment of height k ∈ [0, k_t] (k = 1 − η).
            Difference,
        }

        /// Projected-solid-angle sampling of a spherical cap of directions, clipped
        /// to the receiver's hemisphere: density p(ω) = cos θ/Ω⊥ per steradian on
        /// the visible part of the cap (θ from the receiver's normal, +z of the
        /// local frame), where Ω⊥ = ∫ cos θ dω over that part is the cap's
        /// projected solid angle. For a uniform light of radiance L filling the cap
        /// (a sphere light seen from a point, or a sky cap), every sample's estimate
        /// L cos θ/p equals the irradiance L Ω⊥ exactly: one sample suffices.
        ///
        /// # Method
        /// Ureña & Georgiev, "Stratified sampling of projected spherical caps",
        /// Computer Graphics Forum 37(4) (EGSR), 2018: by Nusselt's analogue,
        /// cos θ dω is the area element of the orthographic projection of the
        /// hemisphere onto the unit disk of its base, so sampling the cap's
        /// *projection* uniformly by area and lifting each point to
        /// z = √(1 − x² − y²) gives density cos θ/Ω⊥, with Ω⊥ the projection's
        /// area. In a frame turned about +z so that the cap's axis is
        /// a = (sin γ, 0, cos γ), with θm the cap's half-angle, the rim projects to
        /// the ellipse of center (cos θm sin γ, 0) and semi-axes sin θm |cos γ|
        /// (along x) and sin θm (along y), internally tangent to the unit circle
        /// where the rim crosses the horizon. The visible part projects to:
        ///
        /// * the whole ellipse, if the cap lies above the horizon (the common
        ///   sphere-light case; sampled in closed form by the concentric map,
        ///   Ω⊥ = π sin²θm cos γ);
        /// * if the rim crosses the horizon, at x = x_t = cos θm / sin γ: the disk's
        ///   circular segment x ≥ x_t *plus* the ellipse's segment x ≤ x_t when the
        ///   axis is above the horizon, *minus* the ellipse's segment x ≥ x_t when
        ///   it is below;
        /// * the whole disk (cosine sampling) or the disk minus the ellipse, for
        ///   caps wider than a hemisphere that contain the zenith or whose
        ///   complement lies above the horizon; nothing if the cap is below.
        ///
        /// Ureña & Georgiev slice the region by lines parallel to the chord; we do
        /// the same, with our own cancellation-free formulation: the slice
        /// coordinate is the height ξ = 1 − x of the circular segment (and
        /// k = 1 ± η of the elliptical one, η the ellipse's normalised x), so thin
        /// segments near the horizon (tiny caps near the horizon have ξ ≈ θm²) keep
        /// full relative precision, and the cumulative area is a sum of segment
        /// areas (S, the area of a segment of the unit disk, summed as a series
        /// where it is thin). u₀ picks the slice by inverting the cumulative area
        /// (a closed form per segment inverted by Halley's method, or for the
        /// "minus" case a bracketed Newton iteration on the difference of two
        /// segment areas), u₁ places the point uniformly along the slice. The height
        /// of each point is formed without cancellation: on the circular segment
        /// z = 2 Y √(u₁(1 − u₁)) with Y the half-chord; inside the ellipse
        /// z² = z_rim² + sin²θm (1 − η² − ζ²) (η, ζ the ellipse's normalised
        /// coordinates, z_rim the height of the rim's plane there), a sum of two
        /// non-negative terms that follows from the ellipse's equation.
        ///
        /// Ω⊥ is the region's area: π sin²θm cos γ, or S(ξ_t) ± sin²θm |cos γ| S(k_t)
        /// with S the unit-disk segment area (the same closed form as Snyder 1996,
        /// term by term without its cancellation); sin θm = √(h(2 − h)) from
        /// h = 1 − cos θm, so caps of θm = 1e-8 rad keep full precision in f64.
        /// When the cap's center is below the horizon the two segments are
        /// subtracted, and a cap that barely peeks above it loses about
        /// log₁₀(θm/Δ) digits (Δ the angular height of the visible sliver), the
        /// conditioning of the problem in the inputs (axis, h).
        ///
        /// Every sample, including those from u on the square's edge, has
        /// cos θ > 0 and so a positive density: u₁ is kept ε/2 off the ends of a
        /// slice that reaches the horizon, and cos θ is never rounded below the
        /// smallest normal number.
        ///
        /// The inverse recovers the ellipse coordinate η from x − x_c =
        /// [h − (1 − w·a) + cos γ (cos θm cos γ − z)]/sin γ, with 1 − w·a = |w − a|²/2,
        /// rather than from x − x_c directly: near the horizon x ≈ 1 carries only
        /// absolute precision, while y and z locate the direction relatively.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedCap;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("use std::", stringify!($p), "::consts::PI;")]
        /// // A sphere of angular radius 0.3 rad whose center is 1 rad from the normal.
        #[doc = concat!("let axis = ", stringify!($v3), "::new(0.841_470_98, 0.0, 0.540_302_3);")]
        /// let cap = ProjectedCap::from_theta_max(axis, 0.3)?;
        /// // Wholly above the horizon: Ω⊥ = π sin²θmax cos γ.
        #[doc = concat!("let omega = PI * 0.3", stringify!($p), ".sin().powi(2) * axis.z;")]
        /// assert!((cap.projected_solid_angle() - omega).abs() < 1e-6 * omega);
        #[doc = concat!("let s = cap.sample(", stringify!($v2), "::new(0.3, 0.7));")]
        /// // Zero variance: cos θ / pdf is Ω⊥ for every sample.
        /// assert!((s.direction.z / s.pdf - cap.projected_solid_angle()).abs() < 1e-6 * omega);
        /// assert_eq!(cap.pdf(s.direction), s.pdf);
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ProjectedCap {
            axis: V3,
            one_minus_cos: Real,
            /// Azimuth of the axis: (cos φa, sin φa).
            cos_az: Real,
            sin_az: Real,
            sin_m: Real,
            cos_m: Real,
            sin_g: Real,
            cos_g: Real,
            /// Ellipse center x and semi-axes.
            x_c: Real,
            a_x: Real,
            a_y: Real,
            region: Region,
            /// Circular segment height (Union, Difference).
            xi_t: Real,
            /// Elliptical segment height (Union, Difference).
            k_t: Real,
            /// Difference: ξ of the ellipse's right tip.
            xi_e0: Real,
            /// The rim crosses the horizon (else the chord is absent).
            straddles: bool,
            /// Ellipse: cos(γ + θm)/(sin θm sin γ) · sin θm sin γ, the rim's
            /// lowest height, formed without cancellation.
            rim_low: Real,
            /// Areas of the elliptical and circular pieces, and the total.
            area_ellipse: Real,
            area_circle: Real,
            projected_solid_angle: Real,
            inside_limit: Real,
        }

        impl ProjectedCap {
            /// The most iterations of the bracketed Newton search used when a
            /// cap whose axis is below the horizon peeks above it (it stops
            /// when the bracket is within 4ε relative; each step at least
            /// halves the bracket when Newton's step would leave it).
            pub const MAX_ITERATIONS: usize = 96;

            /// The cap about the unit `axis` (any length; it is normalised),
            /// given in the receiver's local frame (+z the normal), with
            /// 1 − cos θmax = `one_minus_cos_theta_max` ∈ (0, 2] (pass it
            /// computed without cancellation: s²/(1 + √(1 − s²)) from
            /// s = sin θmax, e.g. s = r/d for a sphere; it keeps caps of
            /// θmax = 1e-8 rad exact in f64).
            ///
            /// Errors: non-finite input, a zero axis, h outside (0, 2], a cap
            /// wholly below the horizon (or touching it from below), or a
            /// visible part too small for its density to be representable.
            pub fn new(axis: V3, one_minus_cos_theta_max: Real) -> Result<Self, SamplingError> {
                let h = one_minus_cos_theta_max;
                crate::error::finite("one_minus_cos_theta_max", h as f64)?;
                if !(h > 0.0 && h <= 2.0) {
                    return Err(SamplingError::OutOfRange {
                        field: "one_minus_cos_theta_max",
                        value: h as f64,
                        range: "(0, 2]",
                    });
                }
                let a = unit_vector("axis", axis)?;
                let sin_g = (a.x * a.x + a.y * a.y).sqrt().min(1.0);
                let cos_g = a.z.clamp(-1.0, 1.0);
                let (cos_az, sin_az) = if sin_g > 0.0 {
                    (a.x / sin_g, a.y / sin_g)
                } else {
                    (1.0, 0.0)
                };
                let cos_m = 1.0 - h;
                let sin_m = (h * (2.0 - h)).max(0.0).sqrt();
                let x_c = cos_m * sin_g;
                let a_x = sin_m * cos_g.abs();
                let a_y = sin_m;
                let abs_g = cos_g.abs();
                // W² = sin²θm − cos²γ > 0 iff the rim crosses the horizon.
                let w2 = (sin_m - abs_g) * (sin_m + abs_g);
                let straddles = w2 > 0.0;
                let below = SamplingError::Degenerate {
                    what: "the cap lies below the receiver's horizon",
                };
                // ξ_t = 1 − cos θm / sin γ, the chord's distance from x = 1.
                let chord = || {
                    if cos_m > 0.0 {
                        w2 / (sin_g * (sin_g + cos_m))
                    } else {
                        1.0 - cos_m / sin_g
                    }
                };
                // s_g s_m ± cos θm |cos γ| with (s_g s_m)² − (c_m c_g)² = W².
                let ss = sin_g * sin_m;
                let cc = cos_m * abs_g;
                let plus = || if cc >= 0.0 { ss + cc } else { w2 / (ss - cc) };
                let minus = || if cc <= 0.0 { ss - cc } else { w2 / (ss + cc) };
                let mut cap = ProjectedCap {
                    axis: a,
                    one_minus_cos: h,
                    cos_az,
                    sin_az,
                    sin_m,
                    cos_m,
                    sin_g,
                    cos_g,
                    x_c,
                    a_x,
                    a_y,
                    region: Region::Ellipse,
                    xi_t: 0.0,
                    k_t: 0.0,
                    xi_e0: 0.0,
                    straddles,
                    rim_low: 0.0,
                    area_ellipse: 0.0,
                    area_circle: 0.0,
                    projected_solid_angle: 0.0,
                    inside_limit: 0.0,
                };
                if straddles && cos_g >= 0.0 {
                    // Circular segment beyond the chord, plus the ellipse's
                    // segment of height 1 + η_t = (s_g s_m + c_m|c_g|)/(s_g s_m).
                    cap.region = Region::Union;
                    cap.xi_t = chord();
                    cap.k_t = if a_x > 0.0 { plus() / ss } else { 0.0 };
                } else if straddles {
                    // Circular segment minus the ellipse's segment of height
                    // 1 − η_t; the ellipse's right tip at ξ = 1 − sin(γ − θm).
                    cap.region = Region::Difference;
                    cap.xi_t = chord();
                    cap.k_t = minus() / ss;
                    let sin_nu = cos_m * sin_g + sin_m * abs_g;
                    cap.xi_e0 = if cos_m > 0.0 {
                        let cos_nu = w2 / (ss + cc);
                        cos_nu * cos_nu / (1.0 + sin_nu)
                    } else {
                        1.0 - sin_nu
                    };
                } else if cos_g > 0.0 && cos_m >= 0.0 {
                    cap.region = Region::Ellipse;
                    // Lowest rim height cos(γ + θm) = (c_g² − s_m²)/(c_m c_g + s_m s_g).
                    cap.rim_low = ((cos_g - sin_m) * (cos_g + sin_m)) / (cos_m * cos_g + ss);
                } else if cos_m < 0.0 && cos_g > 0.0 || h == 2.0 {
                    // The cap contains the whole upper hemisphere.
                    cap.region = Region::Union;
                    cap.xi_t = 2.0;
                    cap.k_t = 0.0;
                } else if cos_m < 0.0 && cos_g < 0.0 {
                    // The complement cap lies above the horizon: disk minus
                    // the whole ellipse.
                    cap.region = Region::Difference;
                    cap.xi_t = 2.0;
                    cap.k_t = 2.0;
                    cap.xi_e0 = 1.0 - (cos_m * sin_g + sin_m * abs_g);
                } else {
                    return Err(below);
                }
                let ellipse_scale = a_x * a_y;
                match cap.region {
                    Region::Ellipse => {
                        cap.area_ellipse = PI * ellipse_scale;
                        cap.projected_solid_angle = cap.area_ellipse;
                    }
                    Region::Union => {
                        cap.area_circle = segment_area(cap.xi_t);
                        cap.area_ellipse = ellipse_scale * segment_area(cap.k_t);
                        cap.projected_solid_angle = cap.area_circle + cap.area_ellipse;
                    }
                    Region::Difference => {
                        cap.area_circle = segment_area(cap.xi_t);
                        cap.area_ellipse = ellipse_scale * segment_area(cap.k_t);
                        cap.projected_solid_angle = (cap.area_circle - cap.area_ellipse).max(0.0);
                    }
                }
                let omega = cap.projected_solid_angle;
                if !(omega > 0.0) || !(1.0 / omega).is_finite() {
                    return Err(if cap.region == Region::Difference {
                        SamplingError::Degenerate {
                            what: "the part of the cap above the receiver's horizon is too \
                                   small for its density to be representable",
                        }
                    } else {
                        below
                    });
                }
                // A sample carries an absolute direction error of a few ε
                // (the slice construction and the turn by the azimuth), which
                // moves |w − a|²/2 by ≤ 16ε (sin θm + h); allow that, plus
                // h's own rounding.
                cap.inside_limit =
                    h * (1.0 + 8.0 * Real::EPSILON) + 16.0 * Real::EPSILON * (sin_m + h);
                Ok(cap)
            }

            /// The cap of half-angle `theta_max` ∈ (0, π] radians about
            /// `axis` (local frame, any non-zero length), as a sky cap is
            /// given: 1 − cos θmax = 2 sin²(θmax/2), without cancellation.
            /// Errors as [`ProjectedCap::new`], and for θmax outside (0, π].
            pub fn from_theta_max(axis: V3, theta_max: Real) -> Result<Self, SamplingError> {
                crate::error::finite("theta_max", theta_max as f64)?;
                if !(theta_max > 0.0 && theta_max <= PI) {
                    return Err(SamplingError::OutOfRange {
                        field: "theta_max",
                        value: theta_max as f64,
                        range: "(0, π]",
                    });
                }
                let s = (0.5 * theta_max).sin();
                Self::new(axis, (2.0 * s * s).min(2.0))
            }

            /// The unit axis of the cap, in the local frame.
            #[inline]
            pub fn axis(&self) -> V3 {
                self.axis
            }

            /// h = 1 − cos θmax.
            #[inline]
            pub fn one_minus_cos_theta_max(&self) -> Real {
                self.one_minus_cos
            }

            /// The projected solid angle Ω⊥ = ∫ cos θ dω of the cap's part
            /// above the horizon, in steradians (closed form).
            /// Irradiance from a uniform cap of radiance L is L Ω⊥.
            #[inline]
            pub fn projected_solid_angle(&self) -> Real {
                self.projected_solid_angle
            }

            /// The cap-frame point (x, y, z) turned back by the axis azimuth.
            #[inline]
            fn turn_back(&self, x: Real, y: Real, z: Real) -> V3 {
                // Never exactly on the horizon (density 0 there).
                let z = z.max(Real::MIN_POSITIVE);
                V3::new(
                    self.cos_az * x - self.sin_az * y,
                    self.sin_az * x + self.cos_az * y,
                    z,
                )
            }

            /// Whether the cap lies wholly above the horizon, so that
            /// [`ProjectedCap::sample`] samples the whole ellipse
            /// (closed form, no solve, no branch on u).
            #[inline]
            pub fn is_whole(&self) -> bool {
                self.region == Region::Ellipse
            }

            /// A direction with density cos θ/Ω⊥ on the visible cap, and
            /// that density. Every u ∈ [0, 1]² gives a finite unit vector
            /// with z > 0 for which [`ProjectedCap::pdf`] returns the same
            /// density.
            #[inline]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let w = match self.region {
                    Region::Ellipse => self.sample_ellipse(u),
                    Region::Union => self.sample_union(u),
                    Region::Difference => self.sample_difference(u),
                };
                DirectionSample {
                    direction: w,
                    pdf: w.z / self.projected_solid_angle,
                }
            }

            /// The whole ellipse, by the concentric map.
            #[inline(always)]
            pub(crate) fn sample_ellipse(&self, u: V2) -> V3 {
                let (r, s, c) = concentric_polar(u);
                let r = r.min(ONE_MINUS_EPSILON);
                let (eta, zeta) = (r * c, r * s);
                // 1 − η = (1 − r) + r (1 − cos φ), both ≥ 0.
                let one_minus_cos = if c >= 0.0 { s * s / (1.0 + c) } else { 1.0 - c };
                let one_minus_eta = (1.0 - r) + r * one_minus_cos;
                let z_rim = self.rim_low + self.sin_m * self.sin_g * one_minus_eta;
                let inside = self.sin_m * self.sin_m * ((1.0 - r) * (1.0 + r));
                let z = (z_rim * z_rim + inside).sqrt();
                self.turn_back(self.x_c + self.a_x * eta, self.a_y * zeta, z)
            }

            /// u₁ kept off the slice's ends by ε/2, so that no sample lies
            /// exactly on the horizon.
            #[inline]
            fn along(u1: Real) -> Real {
                u1.clamp(0.5 * Real::EPSILON, ONE_MINUS_EPSILON)
            }

            /// The circular segment joined to the ellipse's left segment.
            #[inline]
            fn sample_union(&self, u: V2) -> V3 {
                let target = u.x * self.projected_solid_angle;
                let v = Self::along(u.y);
                let t = 2.0 * v - 1.0;
                let spread = 2.0 * (v * (1.0 - v)).sqrt();
                if target < self.area_ellipse {
                    // Height k = 1 + η from the ellipse's left tip.
                    let k = segment_height(target / (self.a_x * self.a_y)).min(self.k_t);
                    let half = (k * (2.0 - k)).max(0.0).sqrt();
                    let eta = k - 1.0;
                    let z_rim = self.sin_m * self.sin_g * (self.k_t - k);
                    let across = self.sin_m * half * spread;
                    let z = (z_rim * z_rim + across * across).sqrt();
                    self.turn_back(self.x_c + self.a_x * eta, self.a_y * half * t, z)
                } else {
                    // Height ξ from the circle's tip at x = 1, measured from
                    // that end so thin segments keep their precision.
                    let rest = ((1.0 - u.x) * self.projected_solid_angle)
                        .max(0.5 * Real::EPSILON * self.projected_solid_angle)
                        .min(self.area_circle);
                    let xi = segment_height(rest).min(self.xi_t);
                    let half = (xi * (2.0 - xi)).max(0.0).sqrt();
                    self.turn_back(1.0 - xi, half * t, half * spread)
                }
            }

            /// [`sample_union`](Self::sample_union) without a branch on u,
            /// for loops that vectorise: the segment solve of whichever
            /// piece u falls in, run once
            /// ([`segment_height_branch_free`]), then both pieces' points
            /// formed and one selected. Returns the direction and whether
            /// it is `sample_union`'s to the bit (false only where the
            /// solve is, NaN u; the caller sends those to `sample`).
            #[inline(always)]
            pub(crate) fn sample_union_branch_free(&self, u: V2) -> (V3, bool) {
                let target = u.x * self.projected_solid_angle;
                let v = Self::along(u.y);
                let t = 2.0 * v - 1.0;
                let spread = 2.0 * (v * (1.0 - v)).sqrt();
                let in_ellipse = target < self.area_ellipse;
                let rest = ((1.0 - u.x) * self.projected_solid_angle)
                    .max(0.5 * Real::EPSILON * self.projected_solid_angle)
                    .min(self.area_circle);
                let area = if in_ellipse {
                    target / (self.a_x * self.a_y)
                } else {
                    rest
                };
                let (height, answered) = segment_height_branch_free(area);
                // The ellipse's slice at k = 1 + η (as `sample_union`).
                let k = height.min(self.k_t);
                let half = (k * (2.0 - k)).max(0.0).sqrt();
                let z_rim = self.sin_m * self.sin_g * (self.k_t - k);
                let across = self.sin_m * half * spread;
                let in_ellipse_point = (
                    self.x_c + self.a_x * (k - 1.0),
                    self.a_y * half * t,
                    (z_rim * z_rim + across * across).sqrt(),
                );
                // The circle's slice at ξ.
                let xi = height.min(self.xi_t);
                let half = (xi * (2.0 - xi)).max(0.0).sqrt();
                let in_circle_point = (1.0 - xi, half * t, half * spread);
                let (x, y, z) = if in_ellipse {
                    in_ellipse_point
                } else {
                    in_circle_point
                };
                (self.turn_back(x, y, z), answered)
            }

            /// Whether the visible cap is a circular segment joined to an
            /// elliptical one (its axis above the horizon, its rim across
            /// it), the region [`sample_union_branch_free`](Self::sample_union_branch_free) draws.
            #[inline]
            pub(crate) fn is_union(&self) -> bool {
                self.region == Region::Union
            }

            /// Area of the "minus" region up to the slice at height ξ from
            /// x = 1, and the ellipse's segment height k at ξ (0 where the
            /// slice misses the ellipse).
            #[inline]
            fn difference_area(&self, xi: Real) -> (Real, Real) {
                if !(self.a_x > 0.0) {
                    return (segment_area(xi), 0.0);
                }
                let raw = (xi - self.xi_e0) / self.a_x;
                let k = raw.clamp(0.0, self.k_t);
                let area = segment_area(xi) - self.a_x * self.a_y * segment_area(k);
                // The slice crosses the ellipse only for 0 < k < 2 (past its
                // far tip, when the whole ellipse is removed, it is a full
                // chord again).
                (area, if raw > 0.0 && raw < 2.0 { k } else { 0.0 })
            }

            /// Height of the rim's plane above the slice at ξ (the gap
            /// between the circle and the ellipse: Y_c² − Y_e² = z_rim²).
            #[inline]
            fn rim_height(&self, xi: Real) -> Real {
                let abs_g = self.cos_g.abs();
                if self.straddles {
                    self.sin_g * (self.xi_t - xi).max(0.0) / abs_g
                } else {
                    ((1.0 - xi) * self.sin_g - self.cos_m) / abs_g
                }
            }

            /// The circular segment minus the ellipse's right segment.
            #[inline]
            fn sample_difference(&self, u: V2) -> V3 {
                let total = self.projected_solid_angle;
                let target = ((1.0 - u.x) * total).clamp(0.5 * Real::EPSILON * total, total);
                let xi = self.solve_difference(target);
                let v = Self::along(u.y);
                let t = 2.0 * v - 1.0;
                let y_c = (xi * (2.0 - xi)).max(0.0).sqrt();
                let (_, k) = self.difference_area(xi);
                let (y, z) = if k > 0.0 {
                    let y_e = self.a_y * (k * (2.0 - k)).max(0.0).sqrt();
                    let z_rim = self.rim_height(xi);
                    let gap = z_rim * z_rim / (y_c + y_e);
                    let y = t.signum() * (y_e + t.abs() * gap).min(y_c);
                    let z = ((1.0 - t.abs()) * gap * (y_c + y.abs())).max(0.0).sqrt();
                    (y, z)
                } else {
                    (t * y_c, y_c * 2.0 * (v * (1.0 - v)).sqrt())
                };
                self.turn_back(1.0 - xi, y, z)
            }

            /// The ξ whose "minus" area is `target`: Newton's iteration on
            /// A(ξ) = S(ξ) − a_x a_y S(k(ξ)), A′ = 2(Y_c − Y_e), kept inside
            /// a bracket (bisection when a step would leave it).
            #[inline]
            fn solve_difference(&self, target: Real) -> Real {
                // A ≤ S, so the circle-only solution is a lower bound.
                let mut lo = segment_height(target).min(self.xi_t);
                let mut hi = self.xi_t;
                let mut xi = lo;
                for _ in 0..Self::MAX_ITERATIONS {
                    let (area, k) = self.difference_area(xi);
                    let f = area - target;
                    // The area is a difference of two segment areas: stop at
                    // its rounding floor (a few ε times the larger).
                    let floor = 8.0 * Real::EPSILON * (segment_area(xi) + target);
                    if f.abs() <= floor {
                        break;
                    }
                    if f < 0.0 {
                        lo = xi;
                    } else {
                        hi = xi;
                    }
                    if hi - lo <= 4.0 * Real::EPSILON * hi {
                        break;
                    }
                    // A′ = 2(Y_c − Y_e) = 2 z_rim²/(Y_c + Y_e) inside the
                    // ellipse's range (no cancellation in the crescent).
                    let y_c = (xi * (2.0 - xi)).max(0.0).sqrt();
                    let slope = if k > 0.0 {
                        let y_e = self.a_y * (k * (2.0 - k)).max(0.0).sqrt();
                        let z_rim = self.rim_height(xi);
                        2.0 * z_rim * z_rim / (y_c + y_e)
                    } else {
                        2.0 * y_c
                    };
                    let step = f / slope;
                    if slope > 0.0 && step.abs() <= 4.0 * Real::EPSILON * xi {
                        break;
                    }
                    let next = xi - step;
                    xi = if slope > 0.0 && next > lo && next < hi {
                        next
                    } else {
                        0.5 * (lo + hi)
                    };
                }
                xi
            }

            /// Whether the unit direction `w` lies in the cap, with a band of
            /// about 16ε rad beyond the rim for the samples' rounding.
            #[inline]
            pub fn contains(&self, w: V3) -> bool {
                0.5 * (w - self.axis).length_squared() <= self.inside_limit
            }

            /// The density cos θ/Ω⊥ per steradian of the unit direction `w`
            /// (local frame) if it lies in the cap (see
            /// [`ProjectedCap::contains`]) with cos θ = w_z > 0; 0 otherwise.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if w.z > 0.0 && self.contains(w) {
                    w.z / self.projected_solid_angle
                } else {
                    0.0
                }
            }

            /// The u that [`ProjectedCap::sample`] maps to the direction `w`
            /// of the visible cap.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                // Into the cap frame (axis azimuth 0).
                let x = self.cos_az * w.x + self.sin_az * w.y;
                let y = -self.sin_az * w.x + self.cos_az * w.y;
                let z = w.z.max(0.0);
                // ξ = 1 − x without cancellation near x = 1.
                let xi = if x > 0.0 {
                    (y * y + z * z) / (1.0 + x)
                } else {
                    1.0 - x
                };
                let total = self.projected_solid_angle;
                let clamp01 = |v: Real| v.clamp(0.0, 1.0);
                // x − x_c from the angle to the axis when the cap is near the
                // horizon point (1, 0, 0) (see the type's docs).
                let dx = if self.sin_g > 0.5 {
                    let from_axis = 0.5 * (w - self.axis).length_squared();
                    (self.one_minus_cos - from_axis + self.cos_g * (self.cos_m * self.cos_g - z))
                        / self.sin_g
                } else {
                    x - self.x_c
                };
                match self.region {
                    Region::Ellipse => {
                        let p = V2::new(dx / self.a_x, y / self.a_y);
                        let p = if p.length_squared() > 1.0 {
                            p.normalize()
                        } else {
                            p
                        };
                        invert_concentric_disk(p)
                    }
                    Region::Union => {
                        if xi <= self.xi_t || self.area_ellipse == 0.0 {
                            let xi = xi.min(self.xi_t);
                            let half = (xi * (2.0 - xi)).max(0.0).sqrt();
                            let u1 = if half > 0.0 {
                                0.5 * (y / half + 1.0)
                            } else {
                                0.5
                            };
                            V2::new(clamp01(1.0 - segment_area(xi) / total), clamp01(u1))
                        } else {
                            let k = (1.0 + dx / self.a_x).clamp(0.0, self.k_t);
                            let half = (k * (2.0 - k)).max(0.0).sqrt();
                            let u0 = self.a_x * self.a_y * segment_area(k) / total;
                            let u1 = if half > 0.0 {
                                0.5 * (y / (self.a_y * half) + 1.0)
                            } else {
                                0.5
                            };
                            V2::new(clamp01(u0), clamp01(u1))
                        }
                    }
                    Region::Difference => {
                        let xi = xi.min(self.xi_t);
                        let (area, k) = self.difference_area(xi);
                        let y_c = (xi * (2.0 - xi)).max(0.0).sqrt();
                        let t = if k > 0.0 {
                            let y_e = self.a_y * (k * (2.0 - k)).max(0.0).sqrt();
                            let z_rim = self.rim_height(xi);
                            let gap = z_rim * z_rim / (y_c + y_e);
                            let along = if gap > 0.0 {
                                ((y.abs() - y_e) / gap).clamp(0.0, 1.0)
                            } else {
                                0.0
                            };
                            y.signum() * along
                        } else if y_c > 0.0 {
                            y / y_c
                        } else {
                            0.0
                        };
                        V2::new(clamp01(1.0 - area / total), clamp01(0.5 * (t + 1.0)))
                    }
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_cap_impl);
