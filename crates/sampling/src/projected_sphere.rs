//! Projected-solid-angle sampling of a sphere light seen from a shading
//! point: the world-space form of `ProjectedCap`, and its light sampler.

macro_rules! projected_sphere_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::error::SamplingError;
        use crate::light_sample::$p::LightSample;
        use crate::light_sampler::$p::{shading_normal, LightSampler};
        use crate::projected_cap::$p::ProjectedCap;
        use crate::sphere_light::$p::SphereSolidAngle;
        use lambert_geometry::precision::$p::{Real, V2, V3};
        use lambert_geometry::$p::{Frame, Sphere};

        /// Projected-solid-angle sampling of a sphere seen from a receiver
        /// point with a given normal: density cos θ/Ω⊥ per steradian on the
        /// part of the subtended cap above the receiver's horizon.
        ///
        /// A sphere of radius r whose center lies at distance d > r from the
        /// reference point covers the cap of directions about a = (c − p)/d with
        /// sin θmax = r/d and 1 − cos θmax = s²/(1 + √((d − r)(d + r))/d),
        /// s = r/d (no cancellation for tiny or distant spheres, nor for
        /// receivers nearly touching the sphere; the cap is that of
        /// [`SphereSolidAngle`]). Directions are drawn with density cos θ/Ω⊥ on
        /// the part of that cap above the receiver's horizon by
        /// [`ProjectedCap`] in the receiver's frame (Ureña & Georgiev 2018,
        /// "Stratified sampling of projected spherical caps"), so for a uniform
        /// sphere of radiance L the estimate L cos θ/p of every sample is the
        /// irradiance L Ω⊥, exactly: the density is formed from the same
        /// cos θ = n·ω (world space) that a caller multiplies by.
        ///
        /// The point hit on the sphere and its distance are those of
        /// [`SphereSolidAngle`] for the sample's angle α from the axis
        /// (1 − cos α = |ω − a|²/2): the near root of the ray–sphere quadratic
        /// without cancellation, t = (d − r)(d + r) / (d (cos α + √(sin²θmax −
        /// sin²α))), and the point built from the angle at the sphere's
        /// center, so its error is O(r ε) even far away.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedSphere;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A unit sphere 3 away, low enough to straddle the horizon.
        #[doc = concat!("let sphere = Sphere::new(", stringify!($v3), "::new(3.0, 0.0, 0.2), 1.0)?;")]
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        /// let s = ProjectedSphere::new(p, n, &sphere)?;
        #[doc = concat!("for u in [", stringify!($v2), "::new(0.1, 0.2), ", stringify!($v2), "::new(0.9, 0.5)] {")]
        ///     let l = s.sample(u);
        ///     // L cos θ / p is the irradiance L Ω⊥ for every sample.
        ///     let estimate = n.dot(l.direction) / l.pdf;
        ///     assert!((estimate - s.projected_solid_angle()).abs() < 1e-6);
        ///     assert!(((l.point - sphere.center()).length() - 1.0).abs() < 1e-5);
        /// }
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ProjectedSphere {
            /// The sphere's cone of directions from the reference point
            /// (its frame's z is the axis toward the center).
            cone: SphereSolidAngle,
            /// The receiver's frame (z the unit normal).
            frame: Frame,
            cap: ProjectedCap,
            inside_limit: Real,
        }

        impl ProjectedSphere {
            /// Prepares sampling of `sphere` seen from `reference` whose
            /// surface normal is `normal` (any non-zero length; it is
            /// normalised).
            ///
            /// Errors: a non-finite or zero normal, a non-finite reference
            /// point or one inside or on the sphere
            /// ([`SamplingError::InsideLight`]), or a sphere wholly below
            /// the receiver's horizon ([`SamplingError::Degenerate`]).
            pub fn new(reference: V3, normal: V3, sphere: &Sphere) -> Result<Self, SamplingError> {
                let normal = shading_normal(normal)?;
                let cone = SphereSolidAngle::new(reference, sphere)?;
                let frame = Frame::from_normal(normal);
                let h = cone.cone().one_minus_cos_theta_max();
                let cap = ProjectedCap::new(frame.to_local(cone.frame().z), h)?;
                // The receiver frame's rotation moves a direction by a few ε
                // more than the cap's own band allows for (see
                // SphereSolidAngle): allow 32ε rad beyond the rim.
                let sin_theta_max = sphere.radius() / cone.distance();
                let inside_limit =
                    h * (1.0 + 8.0 * Real::EPSILON) + 32.0 * Real::EPSILON * (sin_theta_max + h);
                Ok(ProjectedSphere {
                    cone,
                    frame,
                    cap,
                    inside_limit,
                })
            }

            /// The projected solid angle Ω⊥ of the visible part of the
            /// sphere, in steradians: irradiance from a uniform sphere of
            /// radiance L is L Ω⊥.
            #[inline]
            pub fn projected_solid_angle(&self) -> Real {
                self.cap.projected_solid_angle()
            }

            /// The sampler in the receiver's local frame.
            #[inline]
            pub fn cap(&self) -> &ProjectedCap {
                &self.cap
            }

            /// The receiver's frame (z the unit normal).
            #[inline]
            pub fn frame(&self) -> &Frame {
                &self.frame
            }

            /// A direction with density cos θ/Ω⊥, that density (formed from
            /// cos θ = n·ω of the returned direction), the point it hits on
            /// the near side of the sphere and its distance.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                let (w, cos_theta) = self.world_direction(self.cap.sample(u).direction);
                let axis = self.cone.frame().z;
                // Angle α from the axis: 1 − cos α = |w − a|²/2.
                let one_minus_cos = (0.5 * (w - axis).length_squared())
                    .min(self.cone.cone().one_minus_cos_theta_max());
                let (sin_c, cos_c, t) = self.cone.near_hit(one_minus_cos);
                let lateral = (w - axis * w.dot(axis)).normalize_or_zero();
                let normal = (lateral * sin_c.max(0.0) - axis * cos_c).normalize();
                LightSample {
                    direction: w,
                    pdf: self.pdf_of(cos_theta),
                    point: self.cone.center() + normal * self.cone.radius(),
                    distance: t,
                }
            }

            /// [`ProjectedSphere::sample`]'s direction and density alone,
            /// to the bit, without the point on the sphere and its
            /// distance (for estimators, which need neither).
            #[inline]
            pub fn sample_direction(&self, u: V2) -> DirectionSample {
                let (w, cos_theta) = self.world_direction(self.cap.sample(u).direction);
                DirectionSample {
                    direction: w,
                    pdf: self.pdf_of(cos_theta),
                }
            }

            /// The world direction of the cap's local direction `local` and
            /// its cos θ = n·ω.
            #[inline(always)]
            fn world_direction(&self, local: V3) -> (V3, Real) {
                let w = self.frame.from_local(local);
                let cos_theta = self.frame.z.dot(w);
                if cos_theta > 0.0 {
                    (w, cos_theta)
                } else {
                    self.lifted(w, cos_theta)
                }
            }

            /// [`world_direction`](Self::world_direction) by a select
            /// rather than a branch, for loops that vectorise: both the
            /// direction and its lifted form are formed, one kept (the
            /// same value).
            #[inline(always)]
            pub(crate) fn world_direction_branch_free(&self, local: V3) -> (V3, Real) {
                let w = self.frame.from_local(local);
                let cos_theta = self.frame.z.dot(w);
                let (lifted, lifted_cos) = self.lifted(w, cos_theta);
                if cos_theta > 0.0 {
                    (w, cos_theta)
                } else {
                    (lifted, lifted_cos)
                }
            }

            /// The density [`sample_direction`](Self::sample_direction)
            /// gives the direction `w` it drew: cos θ/Ω⊥ with cos θ = n·w
            /// (0 if that is not positive). Unlike [`pdf`](Self::pdf) it
            /// does not test that `w` lies in the cap: the batches
            /// ([`sample_directions`](Self::sample_directions)) pair their
            /// directions with it.
            #[inline(always)]
            pub fn sample_density(&self, w: V3) -> Real {
                self.pdf_of(self.frame.z.dot(w))
            }

            /// A direction `w` whose cos θ (a local cos θ of a few ε) the
            /// frame's rounding turned ≤ 0, lifted to cos θ ≈ ε (a move of
            /// ~ε rad, inside the rim band), and its new cos θ.
            #[inline(always)]
            pub(crate) fn lifted(&self, w: V3, cos_theta: Real) -> (V3, Real) {
                let w = (w + self.frame.z * (Real::EPSILON - cos_theta)).normalize();
                (w, self.frame.z.dot(w))
            }

            #[inline(always)]
            pub(crate) fn pdf_of(&self, cos_theta: Real) -> Real {
                if cos_theta > 0.0 {
                    cos_theta / self.cap.projected_solid_angle()
                } else {
                    0.0
                }
            }

            /// The density cos θ/Ω⊥ per steradian (cos θ = n·w) of the unit
            /// world direction `w` if it points into the sphere's cap (with
            /// a band of about 32ε rad beyond the rim for rounding) above
            /// the horizon; 0 otherwise.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if 0.5 * (w - self.cone.frame().z).length_squared() <= self.inside_limit {
                    self.pdf_of(self.frame.z.dot(w))
                } else {
                    0.0
                }
            }

            /// The u that [`ProjectedSphere::sample`] maps to `w`.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                self.cap.invert(self.frame.to_local(w))
            }
        }

        /// Projected-solid-angle sampling of a sphere light from any
        /// shading point: built once per light, a [`ProjectedSphere`] at
        /// each point (density cos θ/Ω⊥ on the part of the sphere above the
        /// point's horizon; Ureña & Georgiev 2018), no allocation. For an
        /// unoccluded uniform sphere every sample's L cos θ/p is the
        /// irradiance; nothing is drawn below the horizon.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, ProjectedSphereSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = ProjectedSphereSampler::new(Sphere::new(", stringify!($v3), "::new(3.0, 0.0, 1.0), 1.0)?);")]
        #[doc = concat!("let (p, n) = (", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z);")]
        #[doc = concat!("let s = light.sample(p, n, ", stringify!($v2), "::new(0.1, 0.9)).unwrap();")]
        /// assert!(n.dot(s.direction) > 0.0 && light.pdf(p, n, s.direction) == s.pdf);
        /// // Every sample's cos θ / p is the same: Ω⊥.
        /// let omega = light.at(p, n)?.projected_solid_angle();
        /// assert!((n.dot(s.direction) / s.pdf - omega).abs() < 1e-6 * omega);
        /// // A shading point whose horizon hides the whole sphere gets none.
        #[doc = concat!("assert!(light.sample(p, -", stringify!($v3), "::Z, ", stringify!($v2), "::new(0.1, 0.9)).is_none());")]
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ProjectedSphereSampler {
            sphere: Sphere,
        }

        impl ProjectedSphereSampler {
            /// The sampler of `sphere`.
            #[inline]
            pub fn new(sphere: Sphere) -> Self {
                ProjectedSphereSampler { sphere }
            }

            /// The sphere.
            #[inline]
            pub fn sphere(&self) -> &Sphere {
                &self.sphere
            }

            /// The sampler at (`reference`, `normal`), for many samples at
            /// one point; see [`ProjectedSphere::new`] for the errors.
            #[inline]
            pub fn at(&self, reference: V3, normal: V3) -> Result<ProjectedSphere, SamplingError> {
                ProjectedSphere::new(reference, normal, &self.sphere)
            }
        }

        impl LightSampler for ProjectedSphereSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                self.at(reference, normal).ok().map(|s| s.sample(u))
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                self.at(reference, normal).map_or(0.0, |s| s.pdf(direction))
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_sphere_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::Sphere;

    /// Points lie on the sphere's near side, along the direction at the
    /// reported distance (as for `SphereSolidAngle`), above the horizon.
    #[test]
    fn points_lie_on_the_near_side_at_the_reported_distance() {
        let (p, n) = (
            DVec3::new(0.5, -0.2, 0.1),
            DVec3::new(0.1, 0.3, 1.0).normalize(),
        );
        for center in [DVec3::new(3.0, -1.0, 8.0), DVec3::new(4.0, 1.0, 0.3)] {
            let sphere = Sphere::new(center, 1.5).unwrap();
            let s = super::f64::ProjectedSphere::new(p, n, &sphere).unwrap();
            for i in 0..=16 {
                for j in 0..=16 {
                    let u = DVec2::new(i as f64 / 16.0, j as f64 / 16.0);
                    let l = s.sample(u);
                    // A few ulps of the scene's size (≈ 10).
                    assert!(((l.point - center).length() - 1.5).abs() < 1e-13, "{u}");
                    assert!(
                        (p + l.direction * l.distance - l.point).length() < 1e-12,
                        "{u}"
                    );
                    assert!((l.point - center).dot(p - l.point) >= -1e-12, "{u}");
                    assert!(n.dot(l.direction) > 0.0, "{u}");
                }
            }
        }
    }

    #[test]
    fn bad_input_names_the_field() {
        use super::f64::ProjectedSphere;
        let sphere = Sphere::new(DVec3::new(0.0, 0.0, 3.0), 1.0).unwrap();
        let e = ProjectedSphere::new(DVec3::ZERO, DVec3::ZERO, &sphere).unwrap_err();
        assert!(e.to_string().contains("normal"), "{e}");
        let e =
            ProjectedSphere::new(DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 1.0), &sphere).unwrap_err();
        assert!(e.to_string().contains("normal"), "{e}");
        let e = ProjectedSphere::new(DVec3::new(0.0, 0.0, 2.5), DVec3::Z, &sphere).unwrap_err();
        assert!(e.to_string().contains("inside or on"), "{e}");
        let e = ProjectedSphere::new(DVec3::ZERO, -DVec3::Z, &sphere).unwrap_err();
        assert!(e.to_string().contains("below"), "{e}");
    }
}
