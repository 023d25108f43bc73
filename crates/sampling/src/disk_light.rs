//! Uniform sampling of the solid angle a disk subtends, and the disk's
//! light sampler.

macro_rules! disk_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::carlson::$p::carlson_rf_rj;
        use crate::error::SamplingError;
        use crate::light_sample::$p::LightSample;
        use crate::light_sampler::$p::LightSampler;
        use crate::segment::$p::CBRT_EPSILON;
        use crate::trig::$p::sin_cos;
        use lambert_geometry::precision::$p::{wide3, Real, ONE_MINUS_EPSILON, PI, V2, V3};
        use lambert_geometry::$p::Disk;

        /// Uniform sampling of the solid angle a disk subtends at a point: density
        /// 1/Ω per steradian over the directions that hit the disk.
        ///
        /// Area sampling a disk light has density d²/(cos θ_l A) per steradian,
        /// which is unbounded as the receiver approaches the disk's plane, so its
        /// variance explodes (and is infinite for a receiver on the disk's rim
        /// plane). Sampling the subtended solid angle uniformly removes both factors.
        ///
        /// # The spherical ellipse
        /// Guillén, Ureña, King, Fajardo, Georgiev, López-Moreno & Jarabo,
        /// "Area-preserving parameterizations for spherical ellipses", Computer
        /// Graphics Forum 36(4) (EGSR), 2017: the directions from p to a disk form
        /// an elliptic cone, whose intersection with the unit sphere is a
        /// *spherical ellipse*, symmetric about two perpendicular planes. With h the
        /// distance from p to the disk's plane, ρ the offset of p's foot point from
        /// the disk's center and R the radius, the cone is
        /// (h x − ρ z)² + h² y² ≤ R² z² in a frame (x toward the offset, y, z along
        /// the disk's normal); its principal frame follows from the 2 × 2 block
        /// [[h², −hρ], [−hρ, ρ² − R²]], whose positive eigenvalue is
        /// μ = T/2 + √(T²/4 + h²R²), T = h² + ρ² − R² (evaluated as h²R²/(√… − T/2)
        /// when T < 0). The cone's axis is along ρμ x̂ + h(μ + R²) ẑ, its semi-angles
        /// are tan α = R/√μ (major, along ŷ) and tan β = hR/μ (minor), and
        /// a² − b² = sin²α − sin²β = a² μ(μ − h²)/(μ² + h²R²), with
        /// μ − h² = q + √(q² + h²ρ²), q = (ρ² − R² − h²)/2 — every quantity a
        /// product or sum of non-negative terms, so tiny, huge, edge-on and nearly
        /// touching disks keep their precision.
        ///
        /// # Parameterization (polar, after Guillén et al.'s Booth/polar variant)
        /// Guillén et al. sample the spherical ellipse by a polar map about its
        /// axis: the azimuth from the area of the sector it bounds (an incomplete
        /// elliptic integral of the third kind, inverted by Newton's method), then
        /// 1 − cos θ uniformly along it. We keep that structure with two changes
        /// for robustness. (1) The sector is parameterised by the *orthographic*
        /// parametric angle τ (the boundary's orthographic projection is the ellipse
        /// (a cos τ, b sin τ), a = sin α, b = sin β), in which the sector area is
        ///
        /// Ω(τ) = ab K(τ),  K(τ) = ∫₀^τ dτ′ / (1 + cos θₑ(τ′)),
        /// cos θₑ = √(cos²α + (a² − b²) sin²τ),
        ///
        /// an integrand between ½ and 1 for every ellipse, so K is within a factor
        /// 2 of linear (tiny, edge-on and near-hemisphere ellipses alike) and
        /// Newton's method from the linear guess converges in a few steps. (2) K is
        /// written in Carlson's symmetric form with only positive terms (our
        /// derivation via DLMF 19.29.8 with the numerator factor c − cos α, checked
        /// against quadrature in the tests): with n = sin τ, m = cos τ, c = cos θₑ,
        /// cₐ = cos α, c_b = cos β, E = a² − b²,
        ///
        /// K = [ (4/3) cₐE/(1 + cₐ) n³ R_J(W₁, W₂, W₃, W₄) + 2cₐ n R_F(W₁, W₂, W₃) ] / (1 + cₐ),
        /// W₁ = (c + cₐ)², W₂ = m² 2cₐ(c_b + cₐ)(c + cₐ)/(c_b + c),
        /// W₃ = 2cₐ(c_b + c)(c + cₐ)/(c_b + cₐ), W₄ = W₂ + 2cₐ(cₐ + c_b)(1 + c_b) n²/(1 + cₐ).
        ///
        /// The usual form ψ(τ) − c·Π(n; τ | k) (Guillén et al.'s) is a difference
        /// of two nearly equal terms for small ellipses; this one is not. The four
        /// quadrants are mapped from u₀ by reflection (u₀ ∈ [0, ¼) → τ ∈ [0, π/2],
        /// the next quarter mirrored, and so on), continuous across quadrants.
        /// K is concave and K′ = 1/(1 + c) is within a factor 2 of constant, so
        /// Halley's method (K″ = −c′/(1 + c)² is cheap) from the linear guess
        /// converges in a few steps; a Halley step below ¼ε^{1/3} is taken without
        /// evaluating K again (its error after the step is ~step³ ≲ ε/64; a
        /// Newton fallback step must be below √ε), and the iteration is kept
        /// inside a bisection bracket and stopped after at most
        /// [`DiskSolidAngle::MAX_ITERATIONS`] steps (measured: ≤ 3 in f64, ≤ 2 in
        /// f32 over the tests' hard cases).
        ///
        /// When the reference lies on the disk's axis, a² − b² is exactly 0
        /// (μ − h² = q + |q| with q < 0): the ellipse is a circle, K is
        /// linear, and the azimuth is uniform with no evaluation of K at all
        /// (the cone map of a spherical cap, about a tenth of the cost).
        ///
        /// # Cost
        /// Per sample, a few Halley steps, each a Carlson R_F/R_J pair (five or so
        /// duplication steps): about 10× area sampling of the disk (bench
        /// `projected`, both precisions), and preparing the sampler costs about one
        /// sample (the quarter area K(π/2)). Area sampling's per-sample density
        /// d²/(cos θ_l A) is unbounded as the receiver approaches the disk's plane,
        /// so there the solid-angle sampler wins by far more than its cost; far
        /// from a disk that faces the receiver, area sampling is nearly uniform in
        /// solid angle already and is the cheaper choice.
        #[doc = concat!("For many samples from one point, [`TabulatedDiskSolidAngle`](crate::", stringify!($p), "::TabulatedDiskSolidAngle)")]
        /// gives the same directions to a few ulps at a fraction of the
        /// per-sample cost.
        ///
        /// # Disks below the horizon
        /// This sampler does not know the receiver's normal: a disk that crosses
        /// the receiver's plane is sampled over its whole spherical ellipse, and
        /// the samples below the horizon contribute nothing (cos θ ≤ 0), so the
        /// fraction of samples wasted is the fraction of the disk's solid angle
        /// below the horizon. We know no area-preserving map of a spherical ellipse
        /// cut by a great circle (its area is an incomplete elliptic integral in two
        /// variables); a caller that needs to waste nothing there can combine this
        /// sampler with cosine-weighted sampling by multiple importance sampling.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Disk;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::DiskSolidAngle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A unit disk 1 above the receiver, facing it: Ω = 2π(1 − 1/√2).
        #[doc = concat!("let disk = Disk::new(", stringify!($v3), "::Z, -", stringify!($v3), "::Z, 1.0)?;")]
        #[doc = concat!("let sampler = DiskSolidAngle::new(", stringify!($v3), "::ZERO, &disk)?;")]
        #[doc = concat!("let omega = 2.0 * std::", stringify!($p), "::consts::PI * (1.0 - 0.5", stringify!($p), ".sqrt());")]
        /// assert!((sampler.solid_angle() - omega).abs() < 1e-6);
        #[doc = concat!("let s = sampler.sample(", stringify!($v2), "::new(0.3, 0.8));")]
        /// assert!((s.point.z - 1.0).abs() < 1e-6 && s.point.truncate().length() <= 1.0);
        /// assert_eq!(sampler.pdf(s.direction), s.pdf);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct DiskSolidAngle {
            reference: V3,
            /// Unit normal of the disk's plane, pointing away from the
            /// reference point, and the plane's distance.
            normal: V3,
            height: Real,
            /// Principal frame: major axis, minor axis, cone axis.
            x_axis: V3,
            y_axis: V3,
            z_axis: V3,
            /// sin α, sin β, cos α, cos β, a² − b².
            a: Real,
            b: Real,
            pub(crate) cos_a: Real,
            cos_b: Real,
            pub(crate) ecc: Real,
            /// K(π/2) and Ω = 4ab K(π/2).
            pub(crate) quarter: Real,
            solid_angle: Real,
        }

        impl DiskSolidAngle {
            /// The most Newton steps one sample takes (see the type's docs).
            pub const MAX_ITERATIONS: usize = 40;

            /// Prepares sampling of `disk` seen from `reference`. The disk
            /// is treated as two-sided: only its outline matters here.
            ///
            /// Errors: a non-finite reference point, one in the disk's
            /// plane (seen edge-on, or on the disk itself: no solid angle to
            /// sample), or a solid angle too small for its density 1/Ω to be
            /// representable.
            pub fn new(reference: V3, disk: &Disk) -> Result<Self, SamplingError> {
                crate::error::finite3("reference", wide3(reference))?;
                let (center, radius) = (disk.center(), disk.radius());
                let mut n = disk.normal();
                let v = center - reference;
                let mut height = n.dot(v);
                if height < 0.0 {
                    n = -n;
                    height = -height;
                }
                let edge_on = SamplingError::Degenerate {
                    what: "the reference point lies in the disk's plane (the disk is seen \
                           edge-on and subtends no solid angle)",
                };
                if !(height > 0.0) {
                    return Err(edge_on);
                }
                // `v − n·h` rounds by a few ε|v| in every direction, along
                // n̂ too. Seen from on or near the disk's axis that rounding
                // is much or all of the offset: ê_ρ would lean into n̂, the
                // frame below would not be orthonormal, samples would come
                // out squashed and `contains` would reject directions that
                // hit the disk (MIS then weighted those cosine samples 1,
                // about twice the irradiance). So what is left along n̂ is
                // projected out, and an offset within the rounding of |v|
                // is none: the disk is seen from its axis, a circle. Both
                // act only where the offset is within rounding of n̂ or of
                // nothing, so other disks keep their values to the bit.
                let mut lateral = v - n * height;
                let along = n.dot(lateral);
                if along.abs() > 4.0 * Real::EPSILON * overflow_free_length(lateral) {
                    lateral -= n * along;
                }
                let rho = overflow_free_length(lateral);
                let rho = if rho > 8.0 * Real::EPSILON * overflow_free_length(v) {
                    rho
                } else {
                    0.0
                };
                let e_rho = if rho > 0.0 {
                    lateral / rho
                } else {
                    disk.frame().x
                };
                // Lengths scaled to ≤ 1 so that squares and products of
                // four lengths neither overflow nor underflow.
                let scale = height.max(rho).max(radius);
                if !scale.is_finite() {
                    return Err(SamplingError::Degenerate {
                        what: "the reference point is so far from the disk that its \
                               distance overflows",
                    });
                }
                let (h, rh, r) = (height / scale, rho / scale, radius / scale);
                let t = h * h + (rh - r) * (rh + r);
                let g = (0.5 * t).hypot(h * r);
                let mu = if t >= 0.0 {
                    0.5 * t + g
                } else {
                    (h * r) * (h * r) / (g - 0.5 * t)
                };
                let q = 0.5 * ((rh - r) * (rh + r) - h * h);
                let gq = q.hypot(h * rh);
                let mu_minus_h2 = if q >= 0.0 {
                    q + gq
                } else {
                    (h * rh) * (h * rh) / (gq - q)
                };
                let sqrt_mu = mu.sqrt();
                let ra = sqrt_mu.hypot(r);
                let (a, cos_a) = (r / ra, sqrt_mu / ra);
                let rb = mu.hypot(h * r);
                let (b, cos_b) = (h * r / rb, mu / rb);
                let ecc = a * a * (mu / rb) * (mu_minus_h2 / rb);
                // The cone's axis ∝ ρμ ê_ρ + h(μ + R²) n̂; the minor axis is
                // the perpendicular direction in that plane.
                let (zc, zs) = (rh * mu, h * (mu + r * r));
                let zl = zc.hypot(zs);
                let (zc, zs) = (zc / zl, zs / zl);
                let z_axis = e_rho * zc + n * zs;
                let y_axis = e_rho * zs - n * zc;
                let x_axis = e_rho.cross(n);
                if !(cos_a > 0.0 && cos_b > 0.0) {
                    // The height underflowed against the radius: the cone
                    // is the hemisphere to within rounding, and the
                    // elliptic integrals leave their domain.
                    return Err(SamplingError::Degenerate {
                        what: "the disk's height is below the rounding of its size (its \
                               cone of directions is the hemisphere to within rounding)",
                    });
                }
                let mut disk = DiskSolidAngle {
                    reference,
                    normal: n,
                    height,
                    x_axis,
                    y_axis,
                    z_axis,
                    a,
                    b,
                    cos_a,
                    cos_b,
                    ecc,
                    quarter: 0.0,
                    solid_angle: 0.0,
                };
                disk.quarter = disk.sector(1.0, 0.0);
                disk.solid_angle = 4.0 * a * b * disk.quarter;
                let omega = disk.solid_angle;
                if !(omega > 0.0) || !(1.0 / omega).is_finite() || !x_axis.is_finite() {
                    return Err(if b > 0.0 {
                        SamplingError::Degenerate {
                            what: "the disk's solid angle is too small for its density 1/Ω \
                                   to be representable",
                        }
                    } else {
                        edge_on
                    });
                }
                Ok(disk)
            }

            /// The solid angle Ω the disk subtends, in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.solid_angle
            }

            /// sin of the spherical ellipse's semi-major and semi-minor
            /// arcs (a ≥ b), the semi-axes of its orthographic projection.
            #[inline]
            pub fn semi_axes(&self) -> (Real, Real) {
                (self.a, self.b)
            }

            /// The unit axis of the disk's cone of directions.
            #[inline]
            pub fn axis(&self) -> V3 {
                self.z_axis
            }

            /// K(τ) for n = sin τ, m = cos τ (see the type's docs): the area of the
            /// sector from the major axis to τ, over ab.
            #[inline]
            pub(crate) fn sector(&self, n: Real, m: Real) -> Real {
                if n <= 0.0 {
                    return 0.0;
                }
                let (ca, cb, e) = (self.cos_a, self.cos_b, self.ecc);
                let c = (ca * ca + e * n * n).sqrt();
                let w1 = (c + ca) * (c + ca);
                let w2 = m * m * (2.0 * ca * (cb + ca) * (c + ca) / (cb + c));
                let w3 = 2.0 * ca * (cb + c) * (c + ca) / (cb + ca);
                let w4 = w2 + 2.0 * ca * (ca + cb) * (1.0 + cb) * n * n / (1.0 + ca);
                let (rf, rj) = carlson_rf_rj(w1, w2, w3, w4);
                let third = (4.0 / 3.0) * (ca * e / (1.0 + ca)) * n * n * n * rj;
                (third + 2.0 * ca * n * rf) / (1.0 + ca)
            }

            /// cos θₑ at the parametric angle with sin τ = n.
            #[inline]
            pub(crate) fn rim_cos(&self, n: Real) -> Real {
                (self.cos_a * self.cos_a + self.ecc * n * n).sqrt()
            }

            /// (sin τ, cos τ, steps) with K(τ) = `target` ∈ [0, K(π/2)], by
            /// Newton's method inside a bisection bracket (see the type's docs).
            #[inline]
            pub(crate) fn solve(&self, target: Real) -> (Real, Real, usize) {
                let half_pi = 0.5 * PI;
                let (mut lo, mut hi) = (0.0 as Real, half_pi);
                if self.ecc == 0.0 {
                    let (n, m) = self.circle_solve(target);
                    return (n, m, 0);
                }
                // The linear guess lies right of the root (K is concave).
                let mut tau = (target / self.quarter).clamp(0.0, 1.0) * half_pi;
                let (mut n, mut m) = tau.sin_cos();
                let mut steps = 0;
                while steps < Self::MAX_ITERATIONS {
                    steps += 1;
                    let f = self.sector(n, m) - target;
                    if f > 0.0 {
                        hi = tau;
                    } else if f < 0.0 {
                        lo = tau;
                    } else {
                        break;
                    }
                    // Halley's step: K′ = 1/(1 + c), K″ = −c′/(1 + c)² with
                    // c′ = (a² − b²) sin τ cos τ / c.
                    let c = self.rim_cos(n);
                    let slope = 1.0 / (1.0 + c);
                    let curvature = if c > 0.0 {
                        -self.ecc * n * m / c * slope * slope
                    } else {
                        0.0
                    };
                    let denominator = 2.0 * slope * slope - f * curvature;
                    let halley = denominator > 0.0;
                    let step = if halley {
                        2.0 * f * slope / denominator
                    } else {
                        f / slope
                    };
                    if step.abs() <= 4.0 * Real::EPSILON * tau {
                        break;
                    }
                    let next = tau - step;
                    // A Halley step s leaves an error of about s³ (cubic
                    // convergence; K varies on the scale of τ ∈ [0, π/2]),
                    // a Newton step s²: below ¼ε^{1/3} resp. √ε that is
                    // ≲ ε, so the step is taken without evaluating K again.
                    let accept = if halley {
                        0.25 * CBRT_EPSILON
                    } else {
                        Real::EPSILON.sqrt()
                    };
                    if next > lo && next < hi && step.abs() <= accept {
                        tau = next;
                        (n, m) = tau.sin_cos();
                        break;
                    }
                    let next = if next > lo && next < hi {
                        next
                    } else {
                        0.5 * (lo + hi)
                    };
                    let done = hi - lo <= 4.0 * Real::EPSILON * hi;
                    tau = next;
                    (n, m) = tau.sin_cos();
                    if done {
                        break;
                    }
                }
                (n, m, steps)
            }

            /// (sin τ, cos τ) with K(τ) = `target` for a circle (the
            /// reference on the disk's axis, a = b): cos θₑ = cos α for
            /// every τ, so K(τ) = τ/(1 + cos α) is linear and its linear
            /// guess is the root. The sines are our own
            /// ([`crate::trig`]), which vectorise in a loop over samples.
            #[inline(always)]
            pub(crate) fn circle_solve(&self, target: Real) -> (Real, Real) {
                sin_cos((target / self.quarter).clamp(0.0, 1.0) * (0.5 * PI))
            }

            /// The quadrant and in-quadrant area target for u₀.
            #[inline]
            pub(crate) fn quadrant(&self, u0: Real) -> (Real, Real) {
                let four = 4.0 * u0.clamp(0.0, 1.0);
                // In floating point, not as an integer: a loop over samples
                // keeps it in vectors, where AVX2's saturating conversions
                // run a lane at a time. `max` takes NaN to 0, as `as usize`
                // did.
                let q = four.floor().max(0.0).min(3.0);
                let f = four - q;
                let f = if (q == 1.0) | (q == 3.0) { 1.0 - f } else { f };
                (q, f * self.quarter)
            }

            /// The local direction (principal frame) for u, and the Newton
            /// steps taken.
            #[inline]
            fn sample_local(&self, u: V2) -> (V3, usize) {
                let (q, target) = self.quadrant(u.x);
                let (n, m, steps) = self.solve(target);
                (self.local_direction(q, n, m, u.y), steps)
            }

            /// The local direction (principal frame) in quadrant `q` at the
            /// parametric angle with sin τ = n, cos τ = m, and 1 − cos θ a
            /// fraction u₁ of its value on the rim.
            #[inline]
            pub(crate) fn local_direction(&self, q: Real, n: Real, m: Real, u1: Real) -> V3 {
                // The signs of quadrants 0 (+, +), 1 (−, +), 2 (−, −) and
                // 3 (+, −), as selects: a `match` is a switch, which keeps
                // a loop over many samples from vectorising.
                let sx = if (q == 1.0) | (q == 2.0) { -1.0 } else { 1.0 };
                let sy = if q >= 2.0 { -1.0 } else { 1.0 };
                let (px, py) = (self.a * m, self.b * n);
                let re2 = px * px + py * py;
                let re = re2.sqrt();
                let ce = self.rim_cos(n);
                let one_minus_cos = u1.clamp(0.0, 1.0) * (re2 / (1.0 + ce));
                let cos_t = 1.0 - one_minus_cos;
                let sin_t = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
                let (lx, ly) = if re > 0.0 {
                    (px / re, py / re)
                } else {
                    (1.0, 0.0)
                };
                V3::new(sx * sin_t * lx, sy * sin_t * ly, cos_t)
            }

            /// The local direction `l` (principal frame) in world space.
            #[inline(always)]
            pub(crate) fn world(&self, l: V3) -> V3 {
                self.x_axis * l.x + self.y_axis * l.y + self.z_axis * l.z
            }

            /// The light sample of the local direction `l`.
            #[inline]
            pub(crate) fn light_sample(&self, l: V3) -> LightSample {
                let w = self.world(l);
                let distance = self.height / self.normal.dot(w);
                LightSample {
                    direction: w,
                    pdf: 1.0 / self.solid_angle,
                    point: self.reference + w * distance,
                    distance,
                }
            }

            /// The number of Newton steps [`DiskSolidAngle::sample`] takes
            /// for u (for tests and benchmarks of the iteration).
            #[inline]
            pub fn newton_steps(&self, u: V2) -> usize {
                self.sample_local(u).1
            }

            /// A direction uniform in the solid angle of the disk, with its
            /// density 1/Ω per steradian, the point it hits on the disk and
            /// that point's distance. Every u ∈ [0, 1]² gives a finite unit
            /// vector for which [`DiskSolidAngle::pdf`] returns 1/Ω.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                self.light_sample(self.sample_local(u).0)
            }

            /// Whether the unit direction `w` points into the disk: inside
            /// the cone x² cos²α b² + y² cos²β a² ≤ z² a² b² (principal frame),
            /// with a band of about 32ε rad beyond the rim for rounding.
            #[inline]
            pub fn contains(&self, w: V3) -> bool {
                let (x, y, z) = (w.dot(self.x_axis), w.dot(self.y_axis), w.dot(self.z_axis));
                let (a2, b2) = (self.a * self.a, self.b * self.b);
                let fx = self.cos_a * self.cos_a * b2;
                let fy = self.cos_b * self.cos_b * a2;
                let fz = a2 * b2;
                let f = x * x * fx + y * y * fy - z * z * fz;
                let gradient = 2.0 * (x.abs() * fx + y.abs() * fy + z.abs() * fz);
                z > 0.0 && f <= 32.0 * Real::EPSILON * gradient
            }

            /// The density 1/Ω per steradian of the unit direction `w` if it
            /// points into the disk (see [`DiskSolidAngle::contains`]), else 0.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if self.contains(w) {
                    1.0 / self.solid_angle
                } else {
                    0.0
                }
            }

            /// The u that [`DiskSolidAngle::sample`] maps to the direction
            /// `w` into the disk.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                let (x, y, z) = (w.dot(self.x_axis), w.dot(self.y_axis), w.dot(self.z_axis));
                let q = match (x >= 0.0, y >= 0.0) {
                    (true, true) => 0,
                    (false, true) => 1,
                    (false, false) => 2,
                    (true, false) => 3,
                };
                let tau = (self.a * y.abs()).atan2(self.b * x.abs());
                let (n, m) = tau.sin_cos();
                let f = (self.sector(n, m) / self.quarter).clamp(0.0, 1.0);
                let f = if q % 2 == 1 { 1.0 - f } else { f };
                let u0 = ((q as Real + f) * 0.25).min(ONE_MINUS_EPSILON);
                let one_minus_cos = (x * x + y * y) / (1.0 + z.max(0.0));
                let (px, py) = (self.a * m, self.b * n);
                let rim = (px * px + py * py) / (1.0 + self.rim_cos(n));
                let u1 = if rim > 0.0 { one_minus_cos / rim } else { 0.0 };
                V2::new(u0, u1.clamp(0.0, 1.0))
            }
        }

        /// |v| without overflow or underflow of its squares: glam's
        /// `length` (√(v·v)) where v·v is a normal number, else the length
        /// of v over its largest component, scaled back. A receiver ~1e200
        /// from a disk (f64; ~1e20 in f32) has a finite distance whose
        /// square overflows; ordinary distances keep glam's bits.
        #[inline]
        fn overflow_free_length(v: V3) -> Real {
            let l = v.length();
            if l.is_finite() && l >= Real::MIN_POSITIVE.sqrt() {
                return l;
            }
            let m = v.abs().max_element();
            if m > 0.0 && m.is_finite() {
                (v / m).length() * m
            } else {
                l
            }
        }

        /// Solid-angle sampling of a disk light from any shading point:
        /// built once per light, a [`DiskSolidAngle`] at each point
        /// (uniform over the spherical ellipse the disk subtends; Guillén et
        /// al. 2017), no allocation. Unlike area sampling, whose density
        /// d²/(A |cos θ_l|) per steradian is unbounded as the shading point
        /// approaches the disk's plane, its density 1/Ω is bounded by the
        /// disk's own solid angle.
        ///
        /// A disk wholly on or below the shading point's horizon gives
        /// `None`. One that crosses the horizon is sampled over its whole
        /// ellipse (see [`DiskSolidAngle`] for why): the samples below carry
        /// cos θ ≤ 0 and contribute nothing, and the fraction wasted is the
        /// fraction of the disk's solid angle below the horizon.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Disk;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{DiskLightSampler, LightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A disk just above the shading point: area sampling's density
        /// // reaches 1e6 times the mean here, this one's is 1/Ω everywhere.
        #[doc = concat!("let disk = Disk::new(", stringify!($v3), "::new(0.3, 0.0, 1e-3), -", stringify!($v3), "::Z, 1.0)?;")]
        /// let light = DiskLightSampler::new(disk);
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.4, 0.6)).unwrap();")]
        /// assert_eq!(s.pdf, 1.0 / light.at(p)?.solid_angle());
        /// assert_eq!(light.pdf(p, n, s.direction), s.pdf);
        /// assert!((s.point.z - 1e-3).abs() < 1e-6);
        /// // Seen from below the disk's plane with the normal pointing away.
        #[doc = concat!("assert!(light.sample(p, -", stringify!($v3), "::Z, ", stringify!($v2), "::new(0.4, 0.6)).is_none());")]
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct DiskLightSampler {
            disk: Disk,
        }

        impl DiskLightSampler {
            /// The sampler of `disk`.
            #[inline]
            pub fn new(disk: Disk) -> Self {
                DiskLightSampler { disk }
            }

            /// The disk.
            #[inline]
            pub fn disk(&self) -> &Disk {
                &self.disk
            }

            /// The solid-angle sampler at `reference` (for many samples at
            /// one point); see [`DiskSolidAngle::new`] for the errors.
            #[inline]
            pub fn at(&self, reference: V3) -> Result<DiskSolidAngle, SamplingError> {
                DiskSolidAngle::new(reference, &self.disk)
            }

            /// Whether the disk lies wholly on or below the horizon of
            /// (`reference`, `normal`): its highest point, the center raised
            /// by R √(1 − (n·n_d)²), is not above the plane.
            #[inline]
            fn below(&self, reference: V3, normal: V3) -> bool {
                let c = normal.dot(self.disk.normal());
                let reach = self.disk.radius() * ((1.0 - c) * (1.0 + c)).max(0.0).sqrt();
                normal.dot(self.disk.center() - reference) + reach <= 0.0
            }
        }

        impl LightSampler for DiskLightSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if self.below(reference, normal) {
                    return None;
                }
                self.at(reference).ok().map(|d| d.sample(u))
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if self.below(reference, normal) {
                    return 0.0;
                }
                self.at(reference).map_or(0.0, |d| d.pdf(direction))
            }
        }
    };
}

lambert_geometry::both_precisions!(disk_light_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::Disk;

    /// The Carlson form of K(τ) against a direct quadrature of
    /// ∫₀^τ dτ′/(1 + √(cos²α + (a² − b²) sin²τ′)) (composite Simpson, 20000
    /// intervals: error ≲ 1e-15 for these smooth integrands), for a tilted,
    /// a near-hemisphere (receiver close under the disk), an edge-on-ish and
    /// a tiny disk.
    #[test]
    fn sector_area_matches_quadrature() {
        use super::f64::DiskSolidAngle;
        for (c, n, r) in [
            (DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 0.4), 0.7),
            (DVec3::new(0.2, 0.1, 1e-2), DVec3::Z, 1.0),
            (DVec3::new(2.0, 0.0, 1e-3), DVec3::Z, 1.0),
            (DVec3::new(1.0, 2.0, 2.0), DVec3::Z, 1e-4),
        ] {
            let d = DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c, n, r).unwrap()).unwrap();
            let e = d.ecc;
            let f = |t: f64| 1.0 / (1.0 + (d.cos_a * d.cos_a + e * t.sin().powi(2)).sqrt());
            for &tau in &[1e-3, 0.4, 1.0, std::f64::consts::FRAC_PI_2] {
                let m = 20_000;
                let h = tau / m as f64;
                let mut sum = f(0.0) + f(tau);
                for i in 1..m {
                    sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
                }
                let quadrature = sum * h / 3.0;
                let (sn, cs) = tau.sin_cos();
                let carlson = d.sector(sn, cs);
                let rel = (carlson - quadrature).abs() / quadrature;
                assert!(
                    rel < 1e-13,
                    "τ = {tau}: {carlson} vs {quadrature} ({rel:e})"
                );
            }
        }
    }

    /// On the disk's axis the spherical ellipse is a circle: no Newton
    /// step, and the direction is the cone map's, azimuth 2πu₀ and
    /// 1 − cos θ = u₁(1 − cos α), to a few ulps (4ε allowed: the sine and
    /// cosine of τ and the products that rotate them into the principal
    /// frame each round once). Negative control: a disk off the axis by
    /// 10⁻³ of its height needs at least one step for every u₀ inside a
    /// quadrant.
    #[test]
    fn a_circle_is_sampled_without_newton_steps() {
        use super::f64::DiskSolidAngle;
        let (h, r) = (2.0, 0.7);
        let on_axis = DiskSolidAngle::new(
            DVec3::ZERO,
            &Disk::new(DVec3::new(0.0, 0.0, h), -DVec3::Z, r).unwrap(),
        )
        .unwrap();
        assert_eq!(on_axis.ecc, 0.0);
        let off_axis = DiskSolidAngle::new(
            DVec3::ZERO,
            &Disk::new(DVec3::new(2e-3, 0.0, h), -DVec3::Z, r).unwrap(),
        )
        .unwrap();
        let one_minus_cos_alpha = 1.0 - h / (h * h + r * r).sqrt();
        // The principal frame of a circle is any frame about the axis: its
        // horizontal axes are those of the samples at azimuths 0 and π/2.
        let horizontal = |u0: f64| {
            let w = on_axis.sample(DVec2::new(u0, 1.0)).direction;
            DVec3::new(w.x, w.y, 0.0).normalize()
        };
        let (e1, e2) = (horizontal(0.0), horizontal(0.25));
        assert!(e1.dot(e2).abs() <= 4.0 * f64::EPSILON);
        for i in 0..64 {
            for j in 0..=8 {
                let u = DVec2::new((i as f64 + 0.5) / 64.0, j as f64 / 8.0);
                assert_eq!(on_axis.newton_steps(u), 0, "u {u}");
                assert!(off_axis.newton_steps(u) >= 1, "u {u}");
                let w = on_axis.sample(u).direction;
                let one_minus_cos = u.y * one_minus_cos_alpha;
                let sin_t = (one_minus_cos * (2.0 - one_minus_cos)).sqrt();
                let phi = 2.0 * std::f64::consts::PI * u.x;
                let want = sin_t * (phi.cos() * e1 + phi.sin() * e2)
                    + DVec3::new(0.0, 0.0, 1.0 - one_minus_cos);
                assert!(
                    (w - want).abs().max_element() <= 4.0 * f64::EPSILON,
                    "u {u}: {w} against {want}"
                );
            }
        }
    }

    /// A disk seen from its axis off the receiver's normal (the axis
    /// through the receiver, tilted 30°–75°), or from within 10⁻¹³ (f64)
    /// or 10⁻⁶ (f32) radians of it: its samples are unit directions inside
    /// the circular cone of half-angle α (sin α = R/√(h² + R²)) that
    /// `contains` accepts, with density `pdf(w) = 1/Ω`, the reported one.
    /// Before the fix, `v − n·h` left rounding along n̂ as the offset, the
    /// frame was not orthonormal, and `contains` rejected most directions
    /// that hit the disk (MIS on such a disk came out 2× its irradiance).
    /// Tolerances: |w| within 8ε of 1 (a few roundings of the frame's
    /// products); inside the cone to within 64ε of cos α (the direction's
    /// rounding against a cone whose edge is a sum of rounded terms); the
    /// density exactly 1/Ω, as `pdf` returns it. Negative control: the
    /// cone's axis tilted 3α away is rejected.
    #[test]
    fn a_disk_seen_from_its_axis_off_the_normal_is_sampled_inside_its_cone() {
        for degrees in [30.0f64, 45.0, 60.0, 75.0] {
            for radius in [0.01f64, 0.1, 0.5] {
                for tilt in [0.0, 1e-13, 1e-6] {
                    let t = degrees.to_radians();
                    let axis = DVec3::new(t.sin(), 0.0, t.cos());
                    let normal = -(axis + DVec3::new(0.0, tilt, 0.0)).normalize();
                    let cos_alpha = 1.0 / (1.0 + radius * radius).sqrt();
                    let case = format!("{degrees}° R {radius} tilt {tilt}");
                    if tilt < 1e-6 {
                        let d = super::f64::DiskSolidAngle::new(
                            DVec3::ZERO,
                            &Disk::new(axis, normal, radius).unwrap(),
                        )
                        .unwrap();
                        let outside = DVec3::new((t + 3.0 * cos_alpha.acos()).sin(), 0.0, 0.0);
                        let outside = (outside
                            + DVec3::new(0.0, 0.0, (t + 3.0 * cos_alpha.acos()).cos()))
                        .normalize();
                        assert!(!d.contains(outside), "{case}: control");
                        for i in 0..16 {
                            for j in 0..=8 {
                                let u = DVec2::new((i as f64 + 0.5) / 16.0, j as f64 / 8.0);
                                let w = d.sample(u).direction;
                                assert!(
                                    (w.length() - 1.0).abs() <= 8.0 * f64::EPSILON,
                                    "{case} {u}: |w| {}",
                                    w.length()
                                );
                                assert!(
                                    w.dot(axis) >= cos_alpha - 64.0 * f64::EPSILON,
                                    "{case} {u}: outside the cone"
                                );
                                assert!(d.contains(w), "{case} {u}: rejected");
                                assert_eq!(d.pdf(w), 1.0 / d.solid_angle(), "{case} {u}");
                            }
                        }
                    }
                    if tilt == 0.0 || tilt >= 1e-6 {
                        let d = super::f32::DiskSolidAngle::new(
                            glam::Vec3::ZERO,
                            &lambert_geometry::f32::Disk::new(
                                axis.as_vec3(),
                                normal.as_vec3(),
                                radius as f32,
                            )
                            .unwrap(),
                        )
                        .unwrap();
                        for i in 0..16 {
                            for j in 0..=8 {
                                let u = glam::Vec2::new((i as f32 + 0.5) / 16.0, j as f32 / 8.0);
                                let w = d.sample(u).direction;
                                assert!(
                                    (w.length() - 1.0).abs() <= 8.0 * f32::EPSILON,
                                    "f32 {case} {u}: |w| {}",
                                    w.length()
                                );
                                let inside = f64::from(w.dot(axis.as_vec3()));
                                assert!(
                                    inside >= cos_alpha - 64.0 * f64::from(f32::EPSILON),
                                    "f32 {case} {u}: outside the cone"
                                );
                                assert!(d.contains(w), "f32 {case} {u}: rejected");
                                assert_eq!(d.pdf(w), 1.0 / d.solid_angle(), "f32 {case} {u}");
                            }
                        }
                    }
                }
            }
        }
    }

    /// A receiver so far from a disk that squared distances overflow
    /// (fuzz corpus `giant-disk-no-light-sampler`: a disk of radius 2e199
    /// about 1e200 away) is sampled as the same geometry at unit scale:
    /// solid angles are invariant under scaling about the receiver, and
    /// scaling by 2^k is exact, so the sampler at 2^660 (f64) and 2^66 (f32)
    /// must give the solid angle and directions of the sampler at scale 1,
    /// up to the rounding of the one length formed differently (|ρ| from
    /// the scaled vector: a few ulps, 8ε allowed). Before the fix the
    /// sampler refused these geometries ("distance overflows").
    #[test]
    fn far_geometry_whose_squares_overflow_is_sampled_as_at_unit_scale() {
        use glam::{Vec2, Vec3};
        let (c, n, r) = (
            DVec3::new(-7.4, -6.6, 0.85),
            DVec3::new(0.2, -0.1, -1.0),
            2.17,
        );
        let near = super::f64::DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c, n, r).unwrap());
        let s = 2f64.powi(660);
        let far =
            super::f64::DiskSolidAngle::new(DVec3::ZERO, &Disk::new(c * s, n, r * s).unwrap());
        let (near, far) = (near.unwrap(), far.expect("built although |c|² overflows"));
        let eps = 8.0 * f64::EPSILON;
        assert!((far.solid_angle() / near.solid_angle() - 1.0).abs() <= eps);
        for u in [
            DVec2::new(0.1, 0.2),
            DVec2::new(0.7, 0.9),
            DVec2::new(0.5, 0.0),
        ] {
            let (a, b) = (near.sample(u), far.sample(u));
            assert!(
                (a.direction - b.direction).abs().max_element() <= eps,
                "{u}"
            );
            assert!(b.point.is_finite() && b.distance.is_finite(), "{u}");
        }
        let c32 = c.as_vec3();
        let (n32, r32) = (n.as_vec3(), r as f32);
        let near = super::f32::DiskSolidAngle::new(
            Vec3::ZERO,
            &lambert_geometry::f32::Disk::new(c32, n32, r32).unwrap(),
        )
        .unwrap();
        let s = 2f32.powi(66);
        let far = super::f32::DiskSolidAngle::new(
            Vec3::ZERO,
            &lambert_geometry::f32::Disk::new(c32 * s, n32, r32 * s).unwrap(),
        )
        .expect("built although |c|² overflows f32");
        let eps = 8.0 * f32::EPSILON;
        assert!((far.solid_angle() / near.solid_angle() - 1.0).abs() <= eps);
        for u in [Vec2::new(0.1, 0.2), Vec2::new(0.7, 0.9)] {
            let (a, b) = (near.sample(u), far.sample(u));
            assert!(
                (a.direction - b.direction).abs().max_element() <= eps,
                "{u}"
            );
        }
    }

    /// Points lie on the disk, along the direction at the reported
    /// distance, for a tilted disk and one seen from close under its rim.
    #[test]
    fn points_lie_on_the_disk_at_the_reported_distance() {
        use super::f64::DiskSolidAngle;
        let p = DVec3::new(0.2, -0.1, 0.3);
        for (c, n, r) in [
            (DVec3::new(1.0, 0.5, 2.0), DVec3::new(0.3, -1.0, 0.4), 0.7),
            (DVec3::new(1.2, -0.1, 0.31), DVec3::Z, 1.0),
        ] {
            let d = DiskSolidAngle::new(p, &Disk::new(c, n, r).unwrap()).unwrap();
            let n = n.normalize();
            for i in 0..=16 {
                for j in 0..=16 {
                    let u = DVec2::new(i as f64 / 16.0, j as f64 / 16.0);
                    let l = d.sample(u);
                    assert!(n.dot(l.point - c).abs() < 1e-14, "{u}");
                    assert!((l.point - c).length() <= r * (1.0 + 1e-12), "{u}");
                    assert!(
                        (p + l.direction * l.distance - l.point).length() < 1e-13,
                        "{u}"
                    );
                }
            }
        }
    }
}
