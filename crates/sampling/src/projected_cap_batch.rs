//! Projected-solid-angle sampling of caps and spheres that cross the
//! horizon, many samples at a time, in loops that vectorise.
//!
//! A cap whose rim crosses the receiver's horizon with its axis above it
//! projects to a circular segment joined to an elliptical one (Ureña &
//! Georgiev 2018; [`ProjectedCap`](crate::f64::ProjectedCap)). Each sample
//! inverts one segment's area, by Halley's iteration from a fitted guess,
//! and which segment depends on u: one sample at a time that is a long
//! chain of dependent operations behind an unpredictable branch. Here every
//! sample of a batch runs the same operations — the guess and one Halley
//! step (the step the iteration stops after, for every area but NaN and
//! subnormal ones: `segment_height_branch_free`), and both segments'
//! points formed, one selected — so that the loop runs on the processor's
//! vectors, and the rare sample the single step does not answer is drawn
//! one at a time afterwards. The directions are those of `sample`, to the
//! bit. Caps wholly above the horizon take the closed form alone; caps
//! whose axis is below the horizon (the "minus" region, a bracketed solve
//! of varying length) are drawn by `sample`, one at a time.

macro_rules! projected_cap_batch_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::projected_cap::$p::ProjectedCap;
        use crate::projected_sphere::$p::ProjectedSphere;
        use lambert_geometry::precision::$p::{Real, V2, V3};

        /// How many samples the batches hold at a time (a flag per sample
        /// on the stack; the callers' direction arrays are theirs).
        const BATCH_LANES: usize = 128;

        impl ProjectedCap {
            /// The directions of [`sample`](Self::sample) for the points
            /// (`ux[i]`, `uy[i]`), to the bit, into (`dx[i]`, `dy[i]`,
            /// `dz[i]`) in the local frame (the shortest length wins);
            /// their density is cos θ/Ω⊥ = `dz[i]`/
            /// [`projected_solid_angle`](Self::projected_solid_angle).
            /// For a cap above the horizon, or across it with its axis
            /// above, branch-free loops that vectorise: run it inside
            /// [`Isa::run`](crate::isa::Isa::run).
            ///
            /// # Method
            /// Across the horizon, batches of 128: every sample takes the
            /// segment solve's first guess and one Halley step, the step
            /// that [`sample`](Self::sample)'s iteration ends with, and
            /// both segments' points, one selected; a sample for which
            /// that is not `sample`'s answer (NaN u) is drawn by `sample`
            /// afterwards. A cap whose axis is below the horizon is drawn
            /// by `sample`, one sample at a time.
            ///
            /// ```
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedCap;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            /// // A 40° cap whose axis is 70° from the normal: across the horizon.
            #[doc = concat!("let axis = ", stringify!($v3), "::new(0.939_692_6, 0.0, 0.342_020_1);")]
            /// let cap = ProjectedCap::from_theta_max(axis, 0.698_131_7)?;
            /// let (ux, uy) = ([0.1, 0.5, 0.9], [0.3, 0.8, 0.2]);
            /// let (mut x, mut y, mut z) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            /// cap.sample_directions(&ux, &uy, &mut x, &mut y, &mut z);
            #[doc = concat!("let s = cap.sample(", stringify!($v2), "::new(0.9, 0.2));")]
            /// assert_eq!((x[2], y[2], z[2]), (s.direction.x, s.direction.y, s.direction.z));
            /// # Ok::<(), lambert_sampling::SamplingError>(())
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
                // A copy: its fields stay in registers across the loops.
                let cap = &{ *self };
                if let Some(whole) = cap.whole() {
                    for i in 0..n {
                        let w = whole.sample(V2::new(ux[i], uy[i])).direction;
                        (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                    }
                    return;
                }
                if !cap.is_union() {
                    cap.directions_one_at_a_time(&ux[..n], &uy[..n], (dx, dy, dz));
                    return;
                }
                let mut unanswered = [0u32; BATCH_LANES];
                let mut start = 0;
                while start < n {
                    let m = BATCH_LANES.min(n - start);
                    let r = start..start + m;
                    start = r.end;
                    let (ux, uy) = (&ux[r.clone()], &uy[r.clone()]);
                    let (dx, dy, dz) = (&mut dx[r.clone()], &mut dy[r.clone()], &mut dz[r]);
                    for i in 0..m {
                        let (w, answered) = cap.sample_union_branch_free(V2::new(ux[i], uy[i]));
                        (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                        unanswered[i] = u32::from(!answered);
                    }
                    for i in 0..m {
                        if unanswered[i] != 0 {
                            let w = cap.direction_of(V2::new(ux[i], uy[i]));
                            (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                        }
                    }
                }
            }

            /// `sample`'s direction for one u, out of line: the batches'
            /// rare fallback, kept out of their loops (inlined, it grew
            /// them past what the compiler keeps in vector form).
            #[inline(never)]
            fn direction_of(&self, u: V2) -> V3 {
                self.sample(u).direction
            }

            /// [`sample_directions`](Self::sample_directions) by `sample`,
            /// one at a time, out of line.
            #[inline(never)]
            fn directions_one_at_a_time(
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
        }

        impl ProjectedSphere {
            /// The directions of [`sample_direction`](Self::sample_direction)
            /// for the points (`ux[i]`, `uy[i]`), to the bit, into
            /// (`dx[i]`, `dy[i]`, `dz[i]`) in world space (the shortest
            /// length wins); the density of each is
            /// [`sample_density`](Self::sample_density). The cap's
            /// directions come from
            /// [`ProjectedCap::sample_directions`] (whose loops vectorise
            /// for spheres above the horizon and across it), then each is
            /// turned into world space in a second branch-free loop.
            ///
            /// ```
            #[doc = concat!("use lambert_geometry::", stringify!($p), "::Sphere;")]
            #[doc = concat!("use lambert_sampling::", stringify!($p), "::ProjectedSphere;")]
            #[doc = concat!("use glam::{", stringify!($v2), ", ", stringify!($v3), "};")]
            /// // A unit sphere 3 away, low enough to straddle the horizon.
            #[doc = concat!("let sphere = Sphere::new(", stringify!($v3), "::new(3.0, 0.0, 0.4), 1.0)?;")]
            #[doc = concat!("let s = ProjectedSphere::new(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, &sphere)?;")]
            /// let (ux, uy) = ([0.1, 0.5, 0.9], [0.3, 0.8, 0.2]);
            /// let (mut x, mut y, mut z) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            /// s.sample_directions(&ux, &uy, &mut x, &mut y, &mut z);
            #[doc = concat!("let d = s.sample_direction(", stringify!($v2), "::new(0.5, 0.8));")]
            /// assert_eq!((x[1], y[1], z[1]), (d.direction.x, d.direction.y, d.direction.z));
            #[doc = concat!("assert_eq!(s.sample_density(", stringify!($v3), "::new(x[1], y[1], z[1])), d.pdf);")]
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
                let (dx, dy, dz) = (&mut dx[..n], &mut dy[..n], &mut dz[..n]);
                self.cap().sample_directions(ux, uy, dx, dy, dz);
                let sphere = &{ *self };
                for i in 0..n {
                    let (w, _) = sphere.world_direction_branch_free(V3::new(dx[i], dy[i], dz[i]));
                    (dx[i], dy[i], dz[i]) = (w.x, w.y, w.z);
                }
            }
        }
    };
}

lambert_geometry::both_precisions!(projected_cap_batch_impl);

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3, Vec2, Vec3};

    /// The bits of a direction's coordinates (f32 ones widened exactly).
    fn bits_of(w: [f64; 3]) -> [u64; 3] {
        w.map(f64::to_bits)
    }

    /// u in [0, 1]² from a fixed-seed generator, the square's corners and
    /// edges, subnormal u₀ (the batches' fallback) and NaN.
    fn points() -> Vec<(f64, f64)> {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let mut u: Vec<(f64, f64)> = (0..4_000).map(|_| (rng.random(), rng.random())).collect();
        for a in [0.0, 5e-324, 1e-310, 1e-300, 0.5, 1.0 - 1e-16, 1.0] {
            for b in [0.0, 0.5, 1.0] {
                u.push((a, b));
                u.push((b, a));
            }
        }
        u.extend([(f64::NAN, 0.5), (0.5, f64::NAN)]);
        u
    }

    /// Caps of every region: above the horizon, across it with the axis
    /// above (the vectorised solve), the whole-disk case, and across it
    /// with the axis below (one at a time).
    fn caps() -> Vec<(DVec3, f64)> {
        let from_normal = |deg: f64| {
            let g = deg.to_radians();
            DVec3::new(g.sin(), 0.3 * g.sin(), g.cos())
        };
        vec![
            (from_normal(30.0), 0.3),
            (from_normal(70.0), 0.7),
            (from_normal(89.0), 1e-3),
            (from_normal(88.0), 0.2),
            (from_normal(20.0), 2.5),
            (from_normal(100.0), 0.5),
        ]
    }

    #[test]
    fn cap_batches_are_the_samples_directions() {
        let u = points();
        let (ux, uy): (Vec<f64>, Vec<f64>) = u.iter().copied().unzip();
        let (ux32, uy32): (Vec<f32>, Vec<f32>) =
            u.iter().map(|&(a, b)| (a as f32, b as f32)).unzip();
        let mut fallbacks = 0;
        for (axis, theta) in caps() {
            let cap = crate::f64::ProjectedCap::from_theta_max(axis, theta).unwrap();
            let n = u.len();
            let (mut x, mut y, mut z) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            cap.sample_directions(&ux, &uy, &mut x, &mut y, &mut z);
            for i in 0..n {
                let w = cap.sample(DVec2::new(ux[i], uy[i])).direction;
                assert_eq!(
                    bits_of([x[i], y[i], z[i]]),
                    bits_of(w.to_array()),
                    "f64 cap {axis} {theta}, u = {:?}",
                    u[i]
                );
            }
            // The vectorised step answers every sample but those whose
            // area's cube root is the library's (u₀ subnormal in f64; the
            // f32 areas reach it in f64): the batch must not match by
            // falling back, one at a time. The f64 fallback is exercised.
            if cap.is_union() {
                for &(a, b) in &u {
                    let (_, answered) = cap.sample_union_branch_free(DVec2::new(a, b));
                    assert!(answered || a < 1e-300, "u = {a}, {b}");
                    fallbacks += usize::from(!answered);
                }
            }
            let cap =
                crate::f32::ProjectedCap::from_theta_max(axis.as_vec3(), theta as f32).unwrap();
            if cap.is_union() {
                for &(a, b) in &u {
                    let (_, answered) = cap.sample_union_branch_free(Vec2::new(a as f32, b as f32));
                    assert!(answered, "f32 u = {a}, {b}");
                }
            }
            let (mut x, mut y, mut z) = (vec![0.0f32; n], vec![0.0; n], vec![0.0; n]);
            // A cut-short output: the shortest length wins.
            cap.sample_directions(&ux32, &uy32, &mut x, &mut y, &mut z[..n - 3]);
            for i in 0..n {
                let w = cap.sample(Vec2::new(ux32[i], uy32[i])).direction;
                let got = if i < n - 3 {
                    [x[i], y[i], z[i]]
                } else {
                    [0.0; 3]
                };
                let expected = if i < n - 3 { w.to_array() } else { [0.0; 3] };
                assert_eq!(
                    bits_of(got.map(f64::from)),
                    bits_of(expected.map(f64::from)),
                    "f32 cap {axis} {theta}, u = {:?}",
                    u[i]
                );
            }
        }
        assert!(fallbacks > 0, "no sample took the fallback");
    }

    #[test]
    fn sphere_batches_are_the_samples_directions_and_densities() {
        let u = points();
        let (ux, uy): (Vec<f64>, Vec<f64>) = u.iter().copied().unzip();
        let (ux32, uy32): (Vec<f32>, Vec<f32>) =
            u.iter().map(|&(a, b)| (a as f32, b as f32)).unzip();
        // Above the horizon, straddling it, centre below it; a tilted
        // receiver normal, so that the frame turns every direction.
        let normal = DVec3::new(0.1, -0.2, 1.0).normalize();
        for center in [
            DVec3::new(1.0, 0.5, 4.0),
            DVec3::new(3.0, 0.0, 0.4),
            DVec3::new(3.0, 1.0, -0.5),
        ] {
            let sphere = lambert_geometry::f64::Sphere::new(center, 1.0).unwrap();
            let s = crate::f64::ProjectedSphere::new(DVec3::ZERO, normal, &sphere).unwrap();
            let n = u.len();
            let (mut x, mut y, mut z) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            s.sample_directions(&ux, &uy, &mut x, &mut y, &mut z);
            for i in 0..n {
                let d = s.sample_direction(DVec2::new(ux[i], uy[i]));
                let w = DVec3::new(x[i], y[i], z[i]);
                assert_eq!(
                    bits_of(w.to_array()),
                    bits_of(d.direction.to_array()),
                    "f64 {center}"
                );
                assert_eq!(
                    s.sample_density(w).to_bits(),
                    d.pdf.to_bits(),
                    "f64 {center}"
                );
            }
            let sphere = lambert_geometry::f32::Sphere::new(center.as_vec3(), 1.0).unwrap();
            let s =
                crate::f32::ProjectedSphere::new(Vec3::ZERO, normal.as_vec3(), &sphere).unwrap();
            let (mut x, mut y, mut z) = (vec![0.0f32; n], vec![0.0; n], vec![0.0; n]);
            s.sample_directions(&ux32, &uy32, &mut x, &mut y, &mut z);
            for i in 0..n {
                let d = s.sample_direction(Vec2::new(ux32[i], uy32[i]));
                let w = Vec3::new(x[i], y[i], z[i]);
                assert_eq!(
                    bits_of(w.to_array().map(f64::from)),
                    bits_of(d.direction.to_array().map(f64::from)),
                    "f32 {center}"
                );
                assert_eq!(
                    s.sample_density(w).to_bits(),
                    d.pdf.to_bits(),
                    "f32 {center}"
                );
            }
        }
    }
}
