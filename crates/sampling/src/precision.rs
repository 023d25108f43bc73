//! The two precisions every warp is offered in, and the macro that
//! instantiates one implementation for both.
//!
//! Each warp file writes its code once, against the names `Real` (the scalar),
//! `V2` and `V3` (glam vectors of that scalar) and the constants below, inside
//! a `macro_rules!` body; [`both_precisions!`] expands that body once in a
//! `f64` module (`f64`, `DVec2`, `DVec3`) and once in a `f32` module (`f32`,
//! `Vec2`, `Vec3`). Path tracers run in f32, references run in f64, and both
//! come from the same lines of source.

/// Names used by the f64 instantiation.
pub(crate) mod f64 {
    /// The scalar.
    pub type Real = f64;
    /// A 2-vector of the scalar (the canonical sample `u`).
    pub type V2 = glam::DVec2;
    /// A 3-vector of the scalar (directions and points).
    pub type V3 = glam::DVec3;
    /// π.
    pub const PI: Real = core::f64::consts::PI;
    /// The largest value below 1.
    pub const ONE_MINUS_EPSILON: Real = 1.0 - f64::EPSILON / 2.0;
    /// The components of `v` widened to f64 (for validation messages).
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    pub fn widen(v: V3) -> [f64; 3] {
        [v.x as f64, v.y as f64, v.z as f64]
    }
    /// `w` rounded to this precision.
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    #[cfg_attr(not(test), allow(dead_code))] // the spherical-polygon tests
    pub fn narrow3(w: glam::DVec3) -> V3 {
        V3::new(w.x as Real, w.y as Real, w.z as Real)
    }
    /// `w` widened to f64 (exact).
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    #[cfg_attr(not(test), allow(dead_code))] // the spherical-polygon tests
    pub fn wide3(w: V3) -> glam::DVec3 {
        glam::DVec3::new(w.x as f64, w.y as f64, w.z as f64)
    }
    /// Taylor coefficients of sin x / x in x², to x¹⁶ (see `trig`).
    pub const SIN_TAYLOR: [Real; 9] = [
        1.0,
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362880.0,
        -1.0 / 39916800.0,
        1.0 / 6227020800.0,
        -1.0 / 1307674368000.0,
        1.0 / 355687428096000.0,
    ];
    /// Taylor coefficients of cos x in x², to x¹⁶ (see `trig`).
    pub const COS_TAYLOR: [Real; 9] = [
        1.0,
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40320.0,
        -1.0 / 3628800.0,
        1.0 / 479001600.0,
        -1.0 / 87178291200.0,
        1.0 / 20922789888000.0,
    ];
}

/// Names used by the f32 instantiation.
pub(crate) mod f32 {
    /// The scalar.
    pub type Real = f32;
    /// A 2-vector of the scalar (the canonical sample `u`).
    pub type V2 = glam::Vec2;
    /// A 3-vector of the scalar (directions and points).
    pub type V3 = glam::Vec3;
    /// π.
    pub const PI: Real = core::f32::consts::PI;
    /// The largest value below 1.
    pub const ONE_MINUS_EPSILON: Real = 1.0 - f32::EPSILON / 2.0;
    /// The components of `v` widened to f64 (for validation messages).
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    pub fn widen(v: V3) -> [f64; 3] {
        [v.x as f64, v.y as f64, v.z as f64]
    }
    /// `w` rounded to this precision.
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    #[cfg_attr(not(test), allow(dead_code))] // the spherical-polygon tests
    pub fn narrow3(w: glam::DVec3) -> V3 {
        V3::new(w.x as Real, w.y as Real, w.z as Real)
    }
    /// `w` widened to f64 (exact).
    #[inline]
    #[allow(clippy::unnecessary_cast)]
    #[cfg_attr(not(test), allow(dead_code))] // the spherical-polygon tests
    pub fn wide3(w: V3) -> glam::DVec3 {
        glam::DVec3::new(w.x as f64, w.y as f64, w.z as f64)
    }
    /// Taylor coefficients of sin x / x in x², to x⁸ (see `trig`).
    pub const SIN_TAYLOR: [Real; 5] = [1.0, -1.0 / 6.0, 1.0 / 120.0, -1.0 / 5040.0, 1.0 / 362880.0];
    /// Taylor coefficients of cos x in x², to x¹⁰ (see `trig`).
    pub const COS_TAYLOR: [Real; 6] = [
        1.0,
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40320.0,
        -1.0 / 3628800.0,
    ];
}

/// Expands a warp's implementation macro once per precision, as `pub mod f64`
/// and `pub mod f32` of the calling module.
macro_rules! both_precisions {
    ($body:ident) => {
        /// The f64 (`DVec2`, `DVec3`) instantiation.
        #[allow(clippy::unnecessary_cast)] // `x as f64` is a no-op only in this instantiation
        pub mod f64 {
            #[allow(unused_imports)]
            use crate::f64::*;
            #[allow(unused_imports)]
            use crate::precision::f64::*;
            $body!();
        }
        /// The f32 (`Vec2`, `Vec3`) instantiation.
        pub mod f32 {
            #[allow(unused_imports)]
            use crate::f32::*;
            #[allow(unused_imports)]
            use crate::precision::f32::*;
            $body!();
        }
    };
}
pub(crate) use both_precisions;
