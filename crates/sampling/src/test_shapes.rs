//! Shapes the unit tests of several samplers share.

macro_rules! test_shapes_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use glam::$v3;
        type R = lambert_geometry::precision::$p::Real;

        /// `n` vertices of an ellipse centred at (0.2, −0.1) with semi-axes
        /// 0.9 and 0.6, in the plane at height `z`, counter-clockwise from
        /// the angle 0.3: a convex polygon off the axis, none of whose
        /// edges is parallel to a coordinate axis.
        pub(crate) fn ring(n: usize, z: R) -> Vec<$v3> {
            (0..n)
                .map(|k| {
                    let a = k as R / n as R * std::$p::consts::TAU + 0.3;
                    $v3::new(0.2 + 0.9 * a.cos(), -0.1 + 0.6 * a.sin(), z)
                })
                .collect()
        }
    };
}

lambert_geometry::both_precisions!(test_shapes_impl);
