//! Projected-solid-angle sampling of a cap or sphere wholly above the
//! horizon, without a branch on u: the form of [`ProjectedCap`] and
//! [`ProjectedSphere`] that vectorised loops call.
//!
//! A cap above the horizon projects orthographically onto the receiver's
//! disk as a whole ellipse (Ureña & Georgiev 2018), sampled in closed form
//! by the concentric map. The general samplers test per sample which region
//! (whole ellipse, union or difference of segments) the cap projects to;
//! these types make that test once, when they are built, so that a loop
//! over many u runs the closed form alone. Each gives its sampler's
//! direction and density to the bit.
//!
//! [`ProjectedCap`]: crate::f64::ProjectedCap
//! [`ProjectedSphere`]: crate::f64::ProjectedSphere

macro_rules! projected_whole_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::direction_sample::$p::DirectionSample;
        use crate::projected_cap::$p::ProjectedCap;
        use crate::projected_sphere::$p::ProjectedSphere;
        use lambert_geometry::precision::$p::V2;

        /// A [`ProjectedCap`] wholly above the horizon
        /// ([`ProjectedCap::whole`]): density cos θ/Ω⊥ per steradian on
        /// the cap, in the receiver's local frame.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedCap;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let cap = ProjectedCap::from_theta_max(", stringify!($v3), "::new(0.3, 0.0, 0.9).normalize(), 0.2)?;")]
        /// let whole = cap.whole().expect("above the horizon");
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.3, 0.7);")]
        /// assert_eq!(whole.sample(u), cap.sample(u));
        /// // A cap that crosses the horizon has no whole form.
        #[doc = concat!("let low = ProjectedCap::from_theta_max(", stringify!($v3), "::X, 0.2)?;")]
        /// assert!(low.whole().is_none());
        /// # Ok::<(), lambert_sampling::SamplingError>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct WholeProjectedCap {
            cap: ProjectedCap,
        }

        impl ProjectedCap {
            /// The branch-free form of this sampler, if the cap lies wholly
            /// above the horizon ([`ProjectedCap::is_whole`]).
            #[inline]
            pub fn whole(&self) -> Option<WholeProjectedCap> {
                self.is_whole().then_some(WholeProjectedCap { cap: *self })
            }
        }

        impl WholeProjectedCap {
            /// [`ProjectedCap::sample`] of u, to the bit.
            #[inline(always)]
            pub fn sample(&self, u: V2) -> DirectionSample {
                let w = self.cap.sample_ellipse(u);
                DirectionSample {
                    direction: w,
                    pdf: w.z / self.cap.projected_solid_angle(),
                }
            }
        }

        /// A [`ProjectedSphere`] whose sphere lies wholly above the horizon
        /// ([`ProjectedSphere::whole`]): density cos θ/Ω⊥ per steradian on
        /// the sphere's cap of directions, in world space.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedSphere;")]
        #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
        #[doc = concat!("let sphere = Sphere::new(", stringify!($v3), "::new(1.0, 0.0, 4.0), 1.0)?;")]
        #[doc = concat!("let s = ProjectedSphere::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, &sphere)?;")]
        /// let whole = s.whole().expect("above the horizon");
        #[doc = concat!("let u = ", stringify!($v2), "::new(0.8, 0.1);")]
        /// assert_eq!(whole.sample_direction(u), s.sample_direction(u));
        /// # Ok::<(), Box<dyn std::error::Error>>(())
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct WholeProjectedSphere {
            sphere: ProjectedSphere,
            cap: WholeProjectedCap,
        }

        impl ProjectedSphere {
            /// The branch-free form of this sampler, if the sphere lies
            /// wholly above the horizon.
            #[inline]
            pub fn whole(&self) -> Option<WholeProjectedSphere> {
                self.cap().whole().map(|cap| WholeProjectedSphere {
                    sphere: *self,
                    cap,
                })
            }
        }

        impl WholeProjectedSphere {
            /// [`ProjectedSphere::sample_direction`] of u, to the bit. The
            /// rare direction that the frame's rounding puts on or below
            /// the horizon is lifted as there, by a select rather than a
            /// branch (both candidates are formed; the same value).
            #[inline(always)]
            pub fn sample_direction(&self, u: V2) -> DirectionSample {
                let local = self.cap.sample(u).direction;
                let (w, cos_theta) = self.sphere.world_direction_branch_free(local);
                DirectionSample {
                    direction: w,
                    pdf: self.sphere.pdf_of(cos_theta),
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_whole_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec2, Vec3};

    /// u on a 33 × 33 grid, edges included.
    fn grid() -> impl Iterator<Item = (f64, f64)> {
        (0..=32).flat_map(|i| (0..=32).map(move |j| (i as f64 / 32.0, j as f64 / 32.0)))
    }

    #[test]
    fn whole_caps_give_the_samplers_bits() {
        use crate::f64::ProjectedCap;
        let mut compared = 0;
        // Axes from the zenith to just above the horizon, small and large caps.
        for (elevation, half_angle) in [(1.5f64, 0.1), (0.9, 0.4), (0.45, 0.4), (0.3, 1e-6)] {
            let axis = DVec3::new(elevation.cos(), 0.2, elevation.sin()).normalize();
            let cap = ProjectedCap::from_theta_max(axis, half_angle).unwrap();
            let whole = cap.whole().expect("above the horizon");
            for (x, y) in grid() {
                let u = DVec2::new(x, y);
                assert_eq!(whole.sample(u), cap.sample(u), "axis {axis} u {u}");
                compared += 1;
            }
            // f32, the same cap.
            let cap32 = crate::f32::ProjectedCap::from_theta_max(axis.as_vec3(), half_angle as f32)
                .unwrap();
            let whole32 = cap32.whole().expect("above the horizon");
            for (x, y) in grid() {
                let u = Vec2::new(x as f32, y as f32);
                assert_eq!(whole32.sample(u), cap32.sample(u));
            }
        }
        assert_eq!(compared, 4 * 33 * 33);
        // Caps across the horizon have no whole form.
        let low = ProjectedCap::from_theta_max(DVec3::new(0.94, 0.0, 0.34), 0.7).unwrap();
        assert!(low.whole().is_none());
    }

    #[test]
    fn whole_spheres_give_the_samplers_bits() {
        use crate::f64::ProjectedSphere;
        use lambert_geometry::f64::Sphere;
        let normals = [
            DVec3::Z,
            DVec3::new(0.3, -0.2, 1.0),
            DVec3::new(-1.0, 0.5, 0.2),
        ];
        let mut compared = 0;
        for normal in normals {
            // A sphere 30° off the normal, and one just clearing the horizon.
            let n = normal.normalize();
            let side = n.any_orthonormal_vector();
            for (center, radius) in [(n * 8.66 + side * 5.0, 1.0), (n * 1.05 + side * 6.0, 1.0)] {
                let sphere = Sphere::new(center, radius).unwrap();
                let s = ProjectedSphere::new(DVec3::ZERO, normal, &sphere).unwrap();
                let Some(whole) = s.whole() else {
                    continue;
                };
                for (x, y) in grid() {
                    let u = DVec2::new(x, y);
                    assert_eq!(whole.sample_direction(u), s.sample_direction(u));
                    let full = s.sample(u);
                    assert_eq!(whole.sample_direction(u).direction, full.direction);
                    assert_eq!(whole.sample_direction(u).pdf, full.pdf);
                    compared += 1;
                }
                let s32 = crate::f32::ProjectedSphere::new(
                    Vec3::ZERO,
                    normal.as_vec3(),
                    &lambert_geometry::f32::Sphere::new(center.as_vec3(), radius as f32).unwrap(),
                )
                .unwrap();
                if let Some(whole32) = s32.whole() {
                    for (x, y) in grid() {
                        let u = Vec2::new(x as f32, y as f32);
                        assert_eq!(whole32.sample_direction(u), s32.sample_direction(u));
                    }
                }
            }
        }
        // Every normal's 30° sphere is whole; the grazing ones may not be.
        assert!(compared >= 3 * 33 * 33, "compared {compared}");
        // A sphere across the horizon has no whole form.
        let across = Sphere::new(DVec3::new(3.0, 0.0, 0.4), 1.0).unwrap();
        let s = ProjectedSphere::new(DVec3::ZERO, DVec3::Z, &across).unwrap();
        assert!(s.whole().is_none());
    }
}
