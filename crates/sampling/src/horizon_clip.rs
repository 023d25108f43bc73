//! Clipping a convex polygon light to the hemisphere a shading point can
//! see, without allocating.
//!
//! A shading point (p, n) receives light only from directions with
//! n·ω > 0. A planar polygon that straddles the plane n·(x − p) = 0 is cut
//! by that plane into the part above it — still a convex polygon, with at
//! most one vertex more — and the solid-angle samplers draw directions only
//! toward that part, so no sample is wasted below the horizon and the
//! density 1/Ω is that of the visible part. (A light cut to a sliver by the
//! horizon would otherwise be hit by a vanishing fraction of its samples:
//! an estimate that is all zeros, with a standard error of zero.)
//!
//! The cut is one step of Sutherland–Hodgman clipping (Sutherland & Hodgman,
//! "Reentrant polygon clipping", CACM 17(1), 1974; `lambert_geometry`'s
//! `clip_to_half_space`): with
//! dᵢ = n·(vᵢ − p), keep every vertex with dᵢ ≥ 0 and insert, on every edge
//! whose ends lie strictly on opposite sides, the crossing
//! vᵢ + (vⱼ − vᵢ)·dᵢ/(dᵢ − dⱼ).
//! The vertices go into a fixed-capacity array on the stack, which is why
//! polygon lights have at most [`MAX_POLYGON_VERTICES`] vertices (checked
//! when the light's sampler is built).

/// The most vertices a polygon light may have: its clipped part (at most
/// one vertex more) is held in a fixed array on the stack, so that sampling
/// at a shading point never allocates.
pub const MAX_POLYGON_VERTICES: usize = 64;

macro_rules! horizon_clip_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use super::MAX_POLYGON_VERTICES;
        use lambert_geometry::precision::$p::V3;
        use lambert_geometry::$p::clip_to_half_space;

        /// Where a light's vertices lie relative to a shading point's
        /// horizon plane n·(x − p) = 0.
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub(crate) enum Horizon {
            /// Every vertex on or below: nothing can be seen.
            Below,
            /// Every vertex on or above: the whole light can be seen.
            Above,
            /// Vertices strictly on both sides: only a part can be seen.
            Straddles,
        }

        /// Classifies `vertices` against the horizon of (`reference`,
        /// `normal`).
        #[inline]
        pub(crate) fn horizon(reference: V3, normal: V3, vertices: &[V3]) -> Horizon {
            let (mut above, mut below) = (false, false);
            for &v in vertices {
                let d = normal.dot(v - reference);
                above |= d > 0.0;
                below |= d < 0.0;
            }
            match (above, below) {
                (false, _) => Horizon::Below,
                (true, false) => Horizon::Above,
                (true, true) => Horizon::Straddles,
            }
        }

        /// A convex polygon clipped to the half-space above a horizon, in a
        /// fixed-capacity buffer.
        #[derive(Clone, Copy, Debug)]
        pub(crate) struct Clipped {
            vertices: [V3; MAX_POLYGON_VERTICES + 1],
            len: usize,
        }

        impl Clipped {
            /// The part of the convex polygon `vertices` (at most
            /// [`MAX_POLYGON_VERTICES`], in order) on or above the plane
            /// n·(x − p) = 0 (module docs).
            ///
            /// # Panics
            /// In debug builds, if `vertices` has more than
            /// [`MAX_POLYGON_VERTICES`] vertices (the samplers check this
            /// when they are built).
            #[inline]
            pub(crate) fn above(reference: V3, normal: V3, vertices: &[V3]) -> Clipped {
                debug_assert!(vertices.len() <= MAX_POLYGON_VERTICES);
                let mut out = Clipped {
                    vertices: [V3::ZERO; MAX_POLYGON_VERTICES + 1],
                    len: 0,
                };
                clip_to_half_space(reference, normal, vertices, |v| out.push(v));
                out
            }

            #[inline]
            fn push(&mut self, v: V3) {
                // A convex polygon crosses a plane at most twice, so at most
                // one vertex is added: the capacity is never exceeded.
                if self.len < self.vertices.len() {
                    self.vertices[self.len] = v;
                    self.len += 1;
                }
            }

            /// The clipped polygon's vertices, in order.
            #[inline]
            pub(crate) fn vertices(&self) -> &[V3] {
                &self.vertices[..self.len]
            }
        }
    };
}

lambert_geometry::both_precisions!(horizon_clip_impl);

#[cfg(test)]
mod tests {
    use super::f64::{horizon, Clipped, Horizon};
    use glam::DVec3;

    #[test]
    fn classifies_and_clips_a_straddling_square() {
        // A vertical unit square x = 1, z ∈ [−0.25, 0.75]: the horizon z = 0
        // cuts off its lower quarter.
        let square = [
            DVec3::new(1.0, -0.5, -0.25),
            DVec3::new(1.0, 0.5, -0.25),
            DVec3::new(1.0, 0.5, 0.75),
            DVec3::new(1.0, -0.5, 0.75),
        ];
        let (p, n) = (DVec3::ZERO, DVec3::Z);
        assert_eq!(horizon(p, n, &square), Horizon::Straddles);
        assert_eq!(horizon(p, -n, &square), Horizon::Straddles);
        assert_eq!(horizon(p + DVec3::Z, n, &square), Horizon::Below);
        assert_eq!(horizon(p - DVec3::Z, n, &square), Horizon::Above);
        let c = Clipped::above(p, n, &square);
        // Exact here: the crossings are at t = 1/4 of edges of length 1.
        assert_eq!(
            c.vertices(),
            [
                DVec3::new(1.0, 0.5, 0.0),
                DVec3::new(1.0, 0.5, 0.75),
                DVec3::new(1.0, -0.5, 0.75),
                DVec3::new(1.0, -0.5, 0.0),
            ]
        );
    }

    #[test]
    fn a_vertex_on_the_horizon_is_kept_once() {
        let triangle = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, 1.0, -1.0),
        ];
        let c = Clipped::above(DVec3::ZERO, DVec3::Z, &triangle);
        assert_eq!(
            c.vertices(),
            [
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(1.0, 1.0, 1.0),
                DVec3::new(1.0, 1.0, 0.0),
            ]
        );
    }
}
