//! Orthonormal frames built from a single normal.
//!
//! The frame follows Duff, Burgess, Christensen, Hery, Kensler, Liani and
//! Villemin, "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017:
//! with s = sign(n_z) (+1 for n_z = +0), a = −1/(s + n_z), b = n_x n_y a,
//! x = (1 + s n_x² a, s b, −s n_x) and y = (b, s + n_y² a, −n_y). It has no
//! branch on a threshold, is continuous except across n_z = 0, and is
//! orthonormal to rounding for every unit n (glam's `any_orthonormal_pair`
//! implements the same construction; we call it).
//!
//! Convention: in the local frame +z is the normal, θ is measured from +z
//! and φ from +x.

macro_rules! frame_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::V3;

        /// A right-handed orthonormal frame (x, y, z) whose z is a given unit
        /// normal (Duff et al. 2017, "Building an Orthonormal Basis,
        /// Revisited", JCGT 6(1)).
        ///
        /// ```
        #[doc = concat!("use lambert_geometry::", stringify!($p), "::Frame;")]
        #[doc = concat!("use glam::", stringify!($v3), ";")]
        #[doc = concat!("let n = ", stringify!($v3), "::new(1.0, 2.0, -3.0).normalize();")]
        /// let frame = Frame::from_normal(n);
        /// // The normal is the local +z, and the frame is right-handed.
        #[doc = concat!("assert!((frame.to_local(n) - ", stringify!($v3), "::Z).length() < 1e-6);")]
        /// assert!((frame.x.cross(frame.y) - frame.z).length() < 1e-6);
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Frame {
            /// First tangent.
            pub x: V3,
            /// Second tangent, `z × x`.
            pub y: V3,
            /// The normal.
            pub z: V3,
        }

        impl Frame {
            /// The frame whose z axis is the unit vector `normal`.
            ///
            /// # Panics
            /// In debug builds, if `normal` is not unit length to 1e-3.
            #[inline]
            pub fn from_normal(normal: V3) -> Self {
                debug_assert!(
                    (normal.length_squared() - 1.0).abs() < 1e-3,
                    "Frame::from_normal needs a unit normal"
                );
                let (x, y) = normal.any_orthonormal_pair();
                Frame { x, y, z: normal }
            }

            /// Components of the world vector `v` in this frame.
            // Always inlined: three dot products, which every kernel loop
            // needs in registers. Left to the compiler's judgement they
            // became an out-of-line call (and the loop scalar) once the
            // estimator's kernel had grown past its inlining budget.
            #[inline(always)]
            pub fn to_local(&self, v: V3) -> V3 {
                V3::new(v.dot(self.x), v.dot(self.y), v.dot(self.z))
            }

            /// The world vector whose components in this frame are `v`.
            // Always inlined (see `to_local`): f64 uniform-hemisphere
            // sampling of a polygon light took 10 → 51 ns a sample when a
            // larger projected-polygon kernel left this a call.
            #[inline(always)]
            pub fn from_local(&self, v: V3) -> V3 {
                self.x * v.x + self.y * v.y + self.z * v.z
            }
        }
    };
}

crate::both_precisions!(frame_impl);

#[cfg(test)]
mod tests {
    use super::f32::Frame as Frame32;
    use super::f64::Frame;
    use glam::{DVec3, Vec3};

    #[test]
    fn frames_are_orthonormal_and_right_handed() {
        let normals = [
            DVec3::Z,
            -DVec3::Z,
            DVec3::X,
            DVec3::new(1.0, 2.0, -3.0).normalize(),
            DVec3::new(1e-9, 0.0, -1.0).normalize(),
            DVec3::new(0.0, 0.0, -0.0),
        ];
        for n in normals {
            let n = if n.length() == 0.0 { DVec3::Z } else { n };
            let f = Frame::from_normal(n);
            // Orthonormal to a few ulps: each product is a handful of roundings.
            for (a, b) in [(f.x, f.y), (f.y, f.z), (f.z, f.x)] {
                assert!(a.dot(b).abs() < 1e-15);
            }
            for v in [f.x, f.y, f.z] {
                assert!((v.length() - 1.0).abs() < 1e-15);
            }
            assert!((f.x.cross(f.y) - f.z).length() < 1e-15);
            let v = DVec3::new(0.3, -0.7, 0.2);
            assert!((f.from_local(f.to_local(v)) - v).length() < 1e-15);
            let g = Frame32::from_normal(n.as_vec3());
            assert!((g.x.cross(g.y) - g.z).length() < 1e-6);
            let w = Vec3::new(0.3, -0.7, 0.2);
            assert!((g.from_local(g.to_local(w)) - w).length() < 1e-6);
        }
    }
}
