//! Many rays against one shape: rays in structure-of-arrays form, and the
//! loops that test them.
//!
//! A tracer that follows many independent rays at once (a tile's camera
//! rays, then their reflections, then the shadow rays of all their hits)
//! can test them shape by shape instead of ray by ray. Written as a loop
//! over arrays of coordinates whose body has no branch, such a test is
//! vectorised by the compiler: with AVX-512 one instruction works on eight
//! rays. [`Intersect::nearest_in_batch`](crate::f64::Intersect::nearest_in_batch)
//! and [`Intersect::occludes_in_batch`](crate::f64::Intersect::occludes_in_batch)
//! are those loops; spheres, planes, disks and parallelograms run their
//! branch-free test in them, the other shapes their ordinary test ray by
//! ray. Either way each ray gets exactly what
//! [`Intersect::hit_distance`](crate::f64::Intersect::hit_distance) gives
//! it, to the bit: the branch-free test is the one `hit_distance` itself
//! runs, and vectorising changes how many rays an instruction works on,
//! never what it computes for each (no operation is fused or reordered).
//!
//! The loops are `#[inline(always)]`, so that a caller that compiles its
//! own code for a wider instruction set (with run-time detection, as
//! lambert's tracer does) gets them compiled for that set too.

macro_rules! batch_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{Real, V3};
        use crate::ray::$p::Ray;

        /// Rays in structure-of-arrays form: the x, y and z of their
        /// origins and directions in six arrays, for the batch tests of
        /// `Intersect`.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::{Intersect, Ray, RayBatch, Sphere};")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let ball = Sphere::new(", stringify!($v3), "::new(0.0, 0.0, 5.0), 1.0)?;")]
        /// let mut rays = RayBatch::new();
        /// for x in [-2.0, -0.5, 0.0, 0.5, 2.0] {
        #[doc = concat!("    rays.push(&Ray::new(", stringify!($v3), "::new(x, 0.0, 0.0), ", stringify!($v3), "::Z));")]
        /// }
        #[doc = concat!("let mut nearest = vec![", stringify!($p), "::INFINITY; rays.len()];")]
        /// let mut ids = vec![u32::MAX; rays.len()];
        /// ball.nearest_in_batch(&rays, 7, &mut nearest, &mut ids);
        /// assert_eq!(ids, [u32::MAX, 7, 7, 7, u32::MAX]);
        /// assert_eq!(nearest[2], 4.0);
        /// for i in 0..rays.len() {
        #[doc = concat!("    let t = ball.hit_distance(&rays.get(i), ", stringify!($p), "::INFINITY);")]
        ///     assert_eq!(t, (ids[i] == 7).then_some(nearest[i]));
        /// }
        /// # Ok::<(), lambert_geometry::GeometryError>(())
        /// ```
        #[derive(Clone, Debug, Default, PartialEq)]
        pub struct RayBatch {
            origin: [Vec<Real>; 3],
            direction: [Vec<Real>; 3],
        }

        impl RayBatch {
            /// No rays.
            pub fn new() -> Self {
                RayBatch::default()
            }

            /// No rays, with room for `n`.
            pub fn with_capacity(n: usize) -> Self {
                let v = || Vec::with_capacity(n);
                RayBatch {
                    origin: [v(), v(), v()],
                    direction: [v(), v(), v()],
                }
            }

            /// The number of rays.
            #[inline]
            pub fn len(&self) -> usize {
                self.origin[0].len()
            }

            /// Whether there are none.
            #[inline]
            pub fn is_empty(&self) -> bool {
                self.len() == 0
            }

            /// Removes every ray (keeping the room).
            #[inline]
            pub fn clear(&mut self) {
                for v in self.origin.iter_mut().chain(&mut self.direction) {
                    v.clear();
                }
            }

            /// Appends `ray`.
            #[inline]
            pub fn push(&mut self, ray: &Ray) {
                for k in 0..3 {
                    self.origin[k].push(ray.origin[k]);
                    self.direction[k].push(ray.direction[k]);
                }
            }

            /// Replaces the rays by `rays` (kept in their order): one pass
            /// per coordinate, for a caller that builds its rays as
            /// [`Ray`]s.
            #[inline]
            pub fn assign(&mut self, rays: &[Ray]) {
                for k in 0..3 {
                    let origin = &mut self.origin[k];
                    origin.clear();
                    origin.extend(rays.iter().map(|r| r.origin[k]));
                    let direction = &mut self.direction[k];
                    direction.clear();
                    direction.extend(rays.iter().map(|r| r.direction[k]));
                }
            }

            /// Ray `i`.
            ///
            /// # Panics
            /// If `i` ≥ [`RayBatch::len`].
            #[inline]
            pub fn get(&self, i: usize) -> Ray {
                let [ox, oy, oz] = &self.origin;
                let [dx, dy, dz] = &self.direction;
                Ray::new(V3::new(ox[i], oy[i], oz[i]), V3::new(dx[i], dy[i], dz[i]))
            }

            /// The x, y and z arrays of the origins.
            #[inline]
            pub fn origins(&self) -> [&[Real]; 3] {
                [&self.origin[0], &self.origin[1], &self.origin[2]]
            }

            /// The x, y and z arrays of the directions.
            #[inline]
            pub fn directions(&self) -> [&[Real]; 3] {
                [&self.direction[0], &self.direction[1], &self.direction[2]]
            }
        }

        /// The batch loop of `nearest_in_batch` over a branch-free test
        /// `lane(origin, direction) -> (hit, t)` (a hit counts when
        /// `hit` and t < nearest[i]).
        ///
        /// # Panics
        /// If `nearest` or `ids` is not as long as `rays`.
        #[inline(always)]
        pub(crate) fn nearest_lanes(
            rays: &RayBatch,
            id: u32,
            nearest: &mut [Real],
            ids: &mut [u32],
            lane: impl Fn(V3, V3) -> (bool, Real),
        ) {
            let n = rays.len();
            assert!(nearest.len() == n && ids.len() == n, "one entry per ray");
            let [ox, oy, oz] = rays.origins();
            let [dx, dy, dz] = rays.directions();
            let (ox, oy, oz, dx, dy, dz) = (&ox[..n], &oy[..n], &oz[..n], &dx[..n], &dy[..n], &dz[..n]);
            let (nearest, ids) = (&mut nearest[..n], &mut ids[..n]);
            for i in 0..n {
                let (hit, t) = lane(V3::new(ox[i], oy[i], oz[i]), V3::new(dx[i], dy[i], dz[i]));
                let closer = hit & (t < nearest[i]);
                nearest[i] = if closer { t } else { nearest[i] };
                ids[i] = if closer { id } else { ids[i] };
            }
        }

        /// The batch loop of `occludes_in_batch` over a branch-free test
        /// (see [`nearest_lanes`]).
        ///
        /// # Panics
        /// If `t_max` or `blocked` is not as long as `rays`.
        #[inline(always)]
        pub(crate) fn occludes_lanes(
            rays: &RayBatch,
            t_max: &[Real],
            blocked: &mut [bool],
            lane: impl Fn(V3, V3) -> (bool, Real),
        ) {
            let n = rays.len();
            assert!(t_max.len() == n && blocked.len() == n, "one entry per ray");
            let [ox, oy, oz] = rays.origins();
            let [dx, dy, dz] = rays.directions();
            let (ox, oy, oz, dx, dy, dz) = (&ox[..n], &oy[..n], &oz[..n], &dx[..n], &dy[..n], &dz[..n]);
            let (t_max, blocked) = (&t_max[..n], &mut blocked[..n]);
            for i in 0..n {
                let (hit, t) = lane(V3::new(ox[i], oy[i], oz[i]), V3::new(dx[i], dy[i], dz[i]));
                blocked[i] |= hit & (t < t_max[i]);
            }
        }
    };
}

crate::both_precisions!(batch_impl);
