//! Solid-angle sampling of a sphere seen from a point outside it.

macro_rules! sphere_light_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, V2, V3, wide3};
        use crate::cone::$p::UniformCone;
        use crate::light_sample::$p::LightSample;
        use crate::spherical::$p::one_minus_cos_theta;
        use lambert_geometry::$p::Frame;
        use crate::error::SamplingError;
        use crate::light_sampler::$p::LightSampler;
        use lambert_geometry::$p::Sphere;

        /// Solid-angle sampling of the sphere (`center`, `radius`) as seen
        /// from `reference`; see the module docs for the formulas.
        ///
        /// A sphere of radius r whose center is at distance d from the reference
        /// point subtends the cone sin²θmax = (r/d)², so directions are sampled
        /// uniformly in that cone ([`UniformCone`](crate::f64::UniformCone)), density 1/(2π(1 − cos θmax))
        /// per steradian (Shirley, Wang and Zimmerman 1996, "Monte Carlo techniques
        /// for direct lighting calculations"; pbrt-v4 §6.2.4). 1 − cos θmax is
        /// formed as s²/(1 + cos θmax) with cos θmax = √((d − r)(d + r))/d, so
        /// neither tiny, distant spheres nor nearly touching ones lose precision.
        ///
        /// The point on the sphere follows from the triangle (reference, center,
        /// point): the angle γ₀ = asin(sin θ / sin θmax) gives the angle at the
        /// center α = γ₀ − θ, and the point is center + r·(sin α, cos α) in the
        /// frame pointing back to the reference (all absolute errors O(r ε), even
        /// 1e6 radii away). The distance along the direction is
        /// t = (d − r)(d + r) / (d (cos θ + √(sin²θmax − sin²θ))), the near root of
        /// the ray–sphere quadratic written without cancellation.
        ///
        /// **The horizon.** The whole cone is sampled even when a shading
        /// point's horizon cuts it (a sphere straddling the receiver's
        /// plane); directions below the horizon carry cos θ ≤ 0 and score
        /// zero. Sampling only the visible part uniformly would need the
        /// inverse of its marginal CDF in θ, ∫ 2β(θ) sin θ dθ with β(θ) the
        /// half-width of the visible azimuth arc, an arccos: no closed form,
        /// so a root-finder per sample. The fraction of samples wasted is
        /// 1 − Ω_visible/Ω, which matters only when the horizon leaves a
        /// sliver; projected-solid-angle sampling of the cap handles that
        /// case exactly, and estimators that use this cone report how many
        /// of their samples saw the light.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::SphereSolidAngle;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        /// // A sphere 1e6 away: its cone is 1e-6 rad, sampled exactly.
        #[doc = concat!("let far = Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 1e6), 1.0)?;")]
        #[doc = concat!("let cone = SphereSolidAngle::new(", stringify!($v3), "::ZERO, &far)?;")]
        #[doc = concat!("let s = cone.sample(", stringify!($v2), "::new(1.0, 0.25));")]
        /// assert!(s.direction.z > 0.0 && cone.pdf(s.direction) == s.pdf);
        /// assert!(((s.point - far.center()).length() - 1.0).abs() < 1e-1);
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphereSolidAngle {
            frame: Frame,
            cone: UniformCone,
            center: V3,
            radius: Real,
            distance: Real,
            sin_theta_max: Real,
            sin2_theta_max: Real,
            inside_limit: Real,
        }

        impl SphereSolidAngle {
            /// Prepares sampling of `sphere` seen from `reference`.
            ///
            /// Errors: a non-finite reference point, or one inside or on
            /// the sphere ([`SamplingError::InsideLight`]: there the sphere
            /// covers at least a hemisphere of directions and cone sampling
            /// does not apply).
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::SphereSolidAngle;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            /// // A sphere of radius 1 at distance 10, 30° from +z.
            #[doc = concat!("let sphere = Sphere::new(", stringify!($v3), "::new(5.0, 0.0, 8.660254), 1.0)?;")]
            #[doc = concat!("let cone = SphereSolidAngle::new(", stringify!($v3), "::ZERO, &sphere)?;")]
            #[doc = concat!("let s = cone.sample(", stringify!($v2), "::new(0.25, 0.5));")]
            /// assert!((s.pdf * cone.solid_angle() - 1.0).abs() < 1e-6);
            /// assert!(((s.point - sphere.center()).length() - 1.0).abs() < 1e-5);
            /// assert_eq!(cone.pdf(s.direction), s.pdf);
            /// # Ok::<(), Box<dyn std::error::Error>>(())
            /// ```
            pub fn new(reference: V3, sphere: &Sphere) -> Result<Self, SamplingError> {
                crate::error::finite3("reference", wide3(reference))?;
                let (center, radius) = (sphere.center(), sphere.radius());
                let axis = center - reference;
                // |axis|² overflows beyond ≈ 1e154 (f64) or 1e19 (f32): the
                // scaled length then (the same value where both are finite,
                // so ordinary spheres keep their bits).
                let mut distance = axis.length();
                if distance == Real::INFINITY {
                    distance = sphere.distance_to_center(reference);
                }
                if !(distance > radius) {
                    return Err(SamplingError::InsideLight {
                        distance: distance as f64,
                        radius: radius as f64,
                    });
                }
                let sin_theta_max = radius / distance;
                let sin2_theta_max = sin_theta_max * sin_theta_max;
                let mut cos_theta_max = ((distance - radius) * (distance + radius)).sqrt() / distance;
                if !cos_theta_max.is_finite() {
                    // (d − r)(d + r) overflowed: the same cos θmax from
                    // s = r/d, √((1 − s)(1 + s)).
                    cos_theta_max = ((1.0 - sin_theta_max) * (1.0 + sin_theta_max)).sqrt();
                }
                let cone = UniformCone::from_one_minus_cos(sin2_theta_max / (1.0 + cos_theta_max))?;
                // Rotating a direction into the cone's frame and back moves it
                // by up to ~16ε in angle (each frame axis and each dot product
                // carries a few ulps), which changes 1 − cos θ at the rim by
                // sin θmax · 16ε. Directions within that of the rim count as
                // inside, so pdf(sample(u)) is the sampled density. For an
                // axis along ±z the frame is exact (Duff et al.'s basis is
                // then (±1, 0, 0), (0, 1, 0)) and only the cone's own
                // relative rounding remains; the rotation term is scaled by
                // the axis's off-z components, which vanish there.
                let h = cone.one_minus_cos_theta_max();
                let n = axis / distance;
                let tilt = n.x.abs() + n.y.abs();
                let inside_limit = h * (1.0 + 8.0 * Real::EPSILON)
                    + 16.0 * Real::EPSILON * tilt * (sin_theta_max + h);
                Ok(SphereSolidAngle {
                    inside_limit,
                    frame: Frame::from_normal(axis / distance),
                    cone,
                    center,
                    radius,
                    distance,
                    sin_theta_max,
                    sin2_theta_max,
                })
            }

            /// The cone of directions the sphere subtends (about the axis
            /// toward the center).
            #[inline]
            pub fn cone(&self) -> &UniformCone {
                &self.cone
            }

            /// The frame whose z axis points at the sphere's center.
            #[inline]
            pub fn frame(&self) -> &Frame {
                &self.frame
            }

            /// The subtended solid angle 2π(1 − cos θmax), in steradians.
            #[inline]
            pub fn solid_angle(&self) -> Real {
                self.cone.solid_angle()
            }

            /// A direction uniform in the subtended cone, with its density
            /// per steradian, the point it hits on the near side of the
            /// sphere, and the distance to that point.
            #[inline]
            pub fn sample(&self, u: V2) -> LightSample {
                let local = self.cone.sample(u);
                let direction = self.frame.from_local(local);
                // 1 − cos θ from the cone's own h·u₀.
                let (sin_c, cos_c, t) = self.near_hit(u.x * self.cone.one_minus_cos_theta_max());
                // In the frame pointing back at the reference (−z), the point
                // lies at polar angle α_c, azimuth opposite to the direction's.
                let horizontal = V3::new(local.x, local.y, 0.0);
                let h_len = horizontal.length();
                let lateral = if h_len > 0.0 {
                    horizontal / h_len
                } else {
                    V3::new(1.0, 0.0, 0.0)
                };
                let normal_local = lateral * sin_c.max(0.0) - V3::new(0.0, 0.0, cos_c);
                let normal = self.frame.from_local(normal_local).normalize();
                LightSample {
                    direction,
                    pdf: 1.0 / self.cone.solid_angle(),
                    point: self.center + normal * self.radius,
                    distance: t,
                }
            }

            /// Where a direction at angle θ from the axis (given as
            /// 1 − cos θ ≤ 1 − cos θmax) meets the near side of the sphere:
            /// (sin α_c, cos α_c, t), with α_c the angle at the center
            /// between the point and the direction back to the reference,
            /// and t the distance. The point is center + r·(lateral·sin α_c
            /// − axis·cos α_c), lateral the unit direction of the sample's
            /// offset from the axis (the type's docs give the formulas).
            #[inline]
            pub(crate) fn near_hit(&self, one_minus_cos: Real) -> (Real, Real, Real) {
                let cos_theta = 1.0 - one_minus_cos;
                let sin2_theta = one_minus_cos * (2.0 - one_minus_cos);
                let below_rim = (self.sin2_theta_max - sin2_theta).max(0.0);
                let root = below_rim.sqrt();
                let d = self.distance;
                let r = self.radius;
                let t = (d - r) * (d + r) / (d * (cos_theta + root));
                // Angle at the center: α = γ₀ − θ, sin γ₀ = sin θ / sin θmax,
                // cos γ₀ = √(sin²θmax − sin²θ) / sin θmax.
                let sin_theta = sin2_theta.sqrt();
                let sin_g = (sin_theta / self.sin_theta_max).min(1.0);
                let cos_g = root / self.sin_theta_max;
                let sin_alpha = sin_g * cos_theta - cos_g * sin_theta;
                let cos_alpha = cos_g * cos_theta + sin_g * sin_theta;
                (sin_alpha, cos_alpha, t)
            }

            /// The sphere's radius.
            #[inline]
            pub(crate) fn radius(&self) -> Real {
                self.radius
            }

            /// The distance from the reference point to the center.
            #[inline]
            pub(crate) fn distance(&self) -> Real {
                self.distance
            }

            /// The density per steradian of direction `w` (unit): 1/Ω inside
            /// the subtended cone, 0 outside. "Inside" includes a band of
            /// 16ε in angle beyond the rim, the rounding of the frame
            /// rotation: in f32 a direction off the coordinate axes is only
            /// located to ~1e-7 rad, so for spheres under ~1e-5 rad the f32
            /// pdf is a blurred indicator (its integral exceeds 1 by about
            /// 32ε/θmax); f64 resolves spheres down to ~1e-12 rad.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if one_minus_cos_theta(self.frame.to_local(w)) <= self.inside_limit {
                    1.0 / self.cone.solid_angle()
                } else {
                    0.0
                }
            }

            /// The sphere's center.
            #[inline]
            pub fn center(&self) -> V3 {
                self.center
            }

            /// The u that [`SphereSolidAngle::sample`] maps to `w`.
            #[inline]
            pub fn invert(&self, w: V3) -> V2 {
                self.cone.invert(self.frame.to_local(w))
            }
        }

        /// Solid-angle sampling of a sphere light from any shading point:
        /// built once per light, [`SphereSolidAngle`] at each point (uniform
        /// in the subtended cone, Shirley, Wang & Zimmerman 1996), no
        /// allocation.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::{LightSampler, SphereLightSampler};")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let light = SphereLightSampler::new(Sphere::new(", stringify!($v3), "::new(3.0, 0.0, 4.0), 1.0)?);")]
        #[doc = concat!("let s = light.sample(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, ", stringify!($v2), "::new(0.1, 0.9)).unwrap();")]
        /// assert!(s.distance > 3.9 && s.distance < 5.0);
        /// // A shading point whose horizon hides the whole sphere gets none.
        #[doc = concat!("assert!(light.sample(", stringify!($v3), "::ZERO, -", stringify!($v3), "::Z, ", stringify!($v2), "::new(0.1, 0.9)).is_none());")]
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SphereLightSampler {
            sphere: Sphere,
        }

        impl SphereLightSampler {
            /// The sampler of `sphere`.
            #[inline]
            pub fn new(sphere: Sphere) -> Self {
                SphereLightSampler { sphere }
            }

            /// The sphere.
            #[inline]
            pub fn sphere(&self) -> &Sphere {
                &self.sphere
            }

            /// The cone sampler at `reference` (for many samples at one
            /// point); see [`SphereSolidAngle::new`] for the errors.
            #[inline]
            pub fn at(&self, reference: V3) -> Result<SphereSolidAngle, SamplingError> {
                SphereSolidAngle::new(reference, &self.sphere)
            }

            /// Whether the sphere lies wholly on or below the horizon of
            /// (`reference`, `normal`).
            #[inline]
            fn below(&self, reference: V3, normal: V3) -> bool {
                normal.dot(self.sphere.center() - reference) + self.sphere.radius() <= 0.0
            }
        }

        impl LightSampler for SphereLightSampler {
            #[inline]
            fn sample(&self, reference: V3, normal: V3, u: V2) -> Option<LightSample> {
                if self.below(reference, normal) {
                    return None;
                }
                self.at(reference).ok().map(|cone| cone.sample(u))
            }

            #[inline]
            fn pdf(&self, reference: V3, normal: V3, direction: V3) -> Real {
                if self.below(reference, normal) {
                    return 0.0;
                }
                self.at(reference).map_or(0.0, |cone| cone.pdf(direction))
            }
        }
    };
}

lambert_geometry::both_precisions!(sphere_light_impl);

#[cfg(test)]
mod tests {
    use super::f64::SphereSolidAngle;
    use crate::SamplingError;
    use glam::{DVec2, DVec3};
    use lambert_geometry::f64::Sphere;

    fn cone(
        reference: DVec3,
        center: DVec3,
        radius: f64,
    ) -> Result<SphereSolidAngle, SamplingError> {
        SphereSolidAngle::new(reference, &Sphere::new(center, radius)?)
    }

    #[test]
    fn points_lie_on_the_near_side_at_the_reported_distance() {
        let center = DVec3::new(3.0, -1.0, 8.0);
        let s = cone(DVec3::ZERO, center, 1.5).unwrap();
        for i in 0..=16 {
            for j in 0..=16 {
                let u = DVec2::new(i as f64 / 16.0, j as f64 / 16.0);
                let l = s.sample(u);
                // On the sphere and along the direction, to a few ulps of
                // the scene's size (|center| ≈ 8.6).
                assert!(((l.point - center).length() - 1.5).abs() < 1e-13, "{u}");
                assert!((l.direction * l.distance - l.point).length() < 1e-12, "{u}");
                // The near side: the surface faces the reference point.
                assert!((l.point - center).dot(-l.point) >= -1e-12, "{u}");
            }
        }
    }

    #[test]
    fn inside_or_on_the_sphere_is_a_clear_error() {
        let on = cone(DVec3::ZERO, DVec3::new(0.0, 0.0, 2.0), 2.0);
        assert!(matches!(on, Err(SamplingError::InsideLight { .. })));
        let inside = cone(DVec3::ZERO, DVec3::new(0.0, 0.0, 1.0), 2.0);
        let e = inside.unwrap_err();
        assert!(
            e.to_string().contains("inside or on the sphere light"),
            "{e}"
        );
        assert!(cone(DVec3::ZERO, DVec3::Z * 5.0, -1.0).is_err());
        assert!(cone(DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 5.0), 1.0).is_err());
        let unit = Sphere::new(DVec3::Z * 5.0, 1.0).unwrap();
        let e = SphereSolidAngle::new(DVec3::new(0.0, f64::INFINITY, 0.0), &unit).unwrap_err();
        assert!(e.to_string().contains("reference"), "{e}");
    }
}
