//! Clipping a convex polygon to a half-space (one step of Sutherland &
//! Hodgman, "Reentrant polygon clipping", CACM 17(1), 1974).
//!
//! The part of a convex polygon on the side n·(x − p) ≥ 0 of a plane is a
//! convex polygon with at most one vertex more: with dᵢ = n·(vᵢ − p), keep
//! every vertex with dᵢ ≥ 0 and insert, on every edge whose ends lie
//! strictly on opposite sides, the crossing vᵢ + (vⱼ − vᵢ)·dᵢ/(dᵢ − dⱼ).
//! The light samplers clip a polygon light at a shading point's horizon
//! this way, into a buffer on the stack, so the vertices are handed to a
//! callback. (The closed forms clip with heights computed exactly, in
//! double-double, so that the cut does not depend on rounding however far
//! the polygon; a sampler needs no more than the rounding of its own
//! arithmetic.)

macro_rules! clip_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::V3;

        /// Calls `emit` with the vertices, in order, of the part of the
        /// convex polygon `vertices` on the side n·(x − p) ≥ 0 of the plane
        /// through `point` with normal `normal` (module docs): at most
        /// `vertices.len() + 1` of them, none if the polygon lies wholly on
        /// the other side.
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::clip_to_half_space;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        /// // A square from z = −1 to z = 1, cut at z = 0.
        /// let square = [
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 0.0, -1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 0.0, -1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(1.0, 0.0, 1.0),")]
        #[doc = concat!("    ", stringify!($v3), "::new(0.0, 0.0, 1.0),")]
        /// ];
        /// let mut upper = Vec::new();
        #[doc = concat!("clip_to_half_space(", stringify!($v3), "::ZERO, ", stringify!($v3), "::Z, &square, |v| upper.push(v));")]
        /// assert_eq!(upper.len(), 4);
        /// assert!(upper.iter().all(|v| v.z >= 0.0));
        /// ```
        #[inline]
        pub fn clip_to_half_space(point: V3, normal: V3, vertices: &[V3], mut emit: impl FnMut(V3)) {
            let k = vertices.len();
            for i in 0..k {
                let (a, b) = (vertices[i], vertices[(i + 1) % k]);
                let (da, db) = (normal.dot(a - point), normal.dot(b - point));
                if da >= 0.0 {
                    emit(a);
                }
                if (da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0) {
                    emit(a + (b - a) * (da / (da - db)));
                }
            }
        }
    };
}

crate::both_precisions!(clip_impl);
