//! Projected-solid-angle sampling of a sphere light seen from a receiver
//! point with a given normal: the world-space form of
//! [`ProjectedCap`](crate::f64::ProjectedCap).
//!
//! A sphere of radius r whose center lies at distance d > r from the
//! reference point covers the cap of directions about a = (c − p)/d with
//! sin θmax = r/d and 1 − cos θmax = s²/(1 + √((d − r)(d + r))/d), s = r/d
//! (no cancellation for tiny or distant spheres, nor for receivers nearly
//! touching the sphere). Directions are drawn with density cos θ/Ω⊥ on the
//! part of that cap above the receiver's horizon (Ureña & Georgiev 2018),
//! so for a uniform sphere of radiance L the estimate L cos θ/p of every
//! sample is the irradiance L Ω⊥, exactly: the density is formed from the
//! same cos θ = n·ω (world space) that a caller multiplies by.
//!
//! The point hit on the sphere and its distance are those of
//! [`SphereSolidAngle`](crate::f64::SphereSolidAngle): the distance is the
//! near root of the ray–sphere quadratic without cancellation,
//! t = (d − r)(d + r) / (d (cos α + √(sin²θmax − sin²α))), α the angle from
//! the axis, and the point is built from the angle at the sphere's center,
//! so its error is O(r ε) even far away.

macro_rules! projected_sphere_impl {
    () => {
        /// Projected-solid-angle sampling of the sphere (`center`,
        /// `radius`) seen from `reference` with unit `normal`: density
        /// cos θ/Ω⊥ per steradian on the part of the subtended cap above the
        /// receiver's horizon (module docs).
        ///
        /// ```
        /// use glam::{DVec2, DVec3};
        /// use lambert_sampling::f64::ProjectedSphere;
        /// // A unit sphere 3 away, tilted so that it straddles the horizon.
        /// let s = ProjectedSphere::new(DVec3::ZERO, DVec3::Z, DVec3::new(3.0, 0.0, 0.2), 1.0).unwrap();
        /// for u in [DVec2::new(0.1, 0.2), DVec2::new(0.9, 0.5)] {
        ///     let l = s.sample(u);
        ///     // L cos θ / p is the irradiance L Ω⊥ for every sample.
        ///     let estimate = DVec3::Z.dot(l.direction) / l.pdf;
        ///     assert!((estimate - s.projected_solid_angle()).abs() < 1e-15);
        /// }
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct ProjectedSphere {
            frame: Frame,
            cap: ProjectedCap,
            axis: V3,
            center: V3,
            radius: Real,
            distance: Real,
            sin_theta_max: Real,
            sin2_theta_max: Real,
            inside_limit: Real,
        }

        impl ProjectedSphere {
            /// Prepares sampling of the sphere seen from `reference` whose
            /// surface normal is `normal` (any length; it is normalised).
            ///
            /// Errors: non-finite input, a zero normal, radius ≤ 0, a
            /// reference point inside or on the sphere
            /// ([`SamplingError::InsideLight`]), or a sphere wholly below the
            /// receiver's horizon ([`SamplingError::Degenerate`]).
            pub fn new(
                reference: V3,
                normal: V3,
                center: V3,
                radius: Real,
            ) -> Result<Self, SamplingError> {
                crate::error::finite3("reference", widen(reference))?;
                crate::error::finite3("normal", widen(normal))?;
                crate::error::finite3("center", widen(center))?;
                crate::error::positive("radius", radius as f64)?;
                let n_len = normal.length();
                crate::error::nonzero("normal", n_len as f64)?;
                let to_center = center - reference;
                let distance = to_center.length();
                if !(distance > radius) || !distance.is_finite() {
                    return Err(SamplingError::InsideLight {
                        distance: distance as f64,
                        radius: radius as f64,
                    });
                }
                let sin_theta_max = radius / distance;
                let sin2_theta_max = sin_theta_max * sin_theta_max;
                let cos_theta_max = ((distance - radius) * (distance + radius)).sqrt() / distance;
                let h = sin2_theta_max / (1.0 + cos_theta_max);
                let axis = to_center / distance;
                let frame = Frame::from_normal(normal / n_len);
                let cap = ProjectedCap::new(frame.to_local(axis), h)?;
                // The frame's rotation moves a direction by a few ε more
                // than the cap's own band allows for (see SphereSolidAngle).
                let inside_limit =
                    h * (1.0 + 8.0 * Real::EPSILON) + 32.0 * Real::EPSILON * (sin_theta_max + h);
                Ok(ProjectedSphere {
                    frame,
                    cap,
                    axis,
                    center,
                    radius,
                    distance,
                    sin_theta_max,
                    sin2_theta_max,
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
                let local = self.cap.sample(u).direction;
                let mut w = self.frame.from_local(local);
                let mut cos_theta = self.frame.z.dot(w);
                if !(cos_theta > 0.0) {
                    // A local cos θ of a few ε turned ≤ 0 by the frame's
                    // rounding: lift it to ε (a move of ~ε rad, inside the
                    // rim band).
                    w = (w + self.frame.z * (Real::EPSILON - cos_theta)).normalize();
                    cos_theta = self.frame.z.dot(w);
                }
                // Angle α from the axis: 1 − cos α = |w − a|²/2.
                let one_minus_cos = (0.5 * (w - self.axis).length_squared()).min(2.0);
                let cos_alpha = 1.0 - one_minus_cos;
                let sin2_alpha = one_minus_cos * (2.0 - one_minus_cos);
                let below_rim = (self.sin2_theta_max - sin2_alpha).max(0.0);
                let root = below_rim.sqrt();
                let (d, r) = (self.distance, self.radius);
                let t = (d - r) * (d + r) / (d * (cos_alpha + root));
                // Angle at the center α_c = γ₀ − α, sin γ₀ = sin α/sin θmax.
                let sin_alpha = sin2_alpha.sqrt();
                let sin_g = (sin_alpha / self.sin_theta_max).min(1.0);
                let cos_g = root / self.sin_theta_max;
                let sin_c = sin_g * cos_alpha - cos_g * sin_alpha;
                let cos_c = cos_g * cos_alpha + sin_g * sin_alpha;
                let lateral = (w - self.axis * w.dot(self.axis)).normalize_or_zero();
                let normal = (lateral * sin_c.max(0.0) - self.axis * cos_c).normalize();
                LightSample {
                    direction: w,
                    pdf: self.pdf_of(cos_theta),
                    point: self.center + normal * r,
                    distance: t,
                }
            }

            #[inline]
            fn pdf_of(&self, cos_theta: Real) -> Real {
                if cos_theta > 0.0 {
                    cos_theta / self.cap.projected_solid_angle()
                } else {
                    0.0
                }
            }

            /// The density cos θ/Ω⊥ per steradian (cos θ = n·w) of the unit
            /// world direction `w` if it points into the sphere's cap (with a
            /// band of about 32ε rad beyond the rim for rounding) above the
            /// horizon; 0 otherwise.
            #[inline]
            pub fn pdf(&self, w: V3) -> Real {
                if 0.5 * (w - self.axis).length_squared() <= self.inside_limit {
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
    };
}

crate::precision::both_precisions!(projected_sphere_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec2};

    /// Value stability: fixed u → fixed bits of (x, y, z, pdf), in both
    /// precisions, so that any change to the samples is deliberate. The
    /// values depend on the platform's libm for sin, cos, atan2, asin and
    /// cbrt (they were taken with glibc's); regenerate them if a change in
    /// the algorithm is intended.
    /// Points lie on the sphere's near side, along the direction at the
    /// reported distance (as for `SphereSolidAngle`), above the horizon.
    #[test]
    fn points_lie_on_the_near_side_at_the_reported_distance() {
        let (p, n) = (
            DVec3::new(0.5, -0.2, 0.1),
            DVec3::new(0.1, 0.3, 1.0).normalize(),
        );
        for center in [DVec3::new(3.0, -1.0, 8.0), DVec3::new(4.0, 1.0, 0.3)] {
            let s = super::f64::ProjectedSphere::new(p, n, center, 1.5).unwrap();
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
    fn fixed_u_gives_fixed_bits() {
        let (p, n, c, r) = (
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.2, -0.1, 1.0).normalize(),
            DVec3::new(2.0, 1.0, 1.5),
            0.5,
        );
        let s = super::f64::ProjectedSphere::new(p, n, c, r)
            .unwrap()
            .sample(DVec2::new(0.3, 0.7));
        let w = s.direction;
        assert_eq!(
            [w.x.to_bits(), w.y.to_bits(), w.z.to_bits(), s.pdf.to_bits()],
            [
                0x3fe77ca6c2e48f7f,
                0x3fd69e5aa311ee26,
                0x3fe28f4c6778c300,
                0x401fdd42d95bd7cd
            ]
        );
        let s = super::f32::ProjectedSphere::new(p.as_vec3(), n.as_vec3(), c.as_vec3(), r as f32)
            .unwrap()
            .sample(Vec2::new(0.3, 0.7));
        let w = s.direction;
        assert_eq!(
            [w.x.to_bits(), w.y.to_bits(), w.z.to_bits(), s.pdf.to_bits()],
            [0x3f3be536, 0x3eb4f2d4, 0x3f147a66, 0x40feea1b]
        );
    }
}
