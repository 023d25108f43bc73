//! The two precisions every type of lambert's geometry and sampling crates
//! is offered in, and the macro that writes one implementation for both.
//!
//! A file writes its code once, inside a `macro_rules!` body that takes the
//! precision as `($p:ident, $v2:ident, $v3:ident)` and imports by name what
//! it uses: `use lambert_geometry::precision::$p::{Real, V2, V3};` for the
//! scalar and glam vectors, `use crate::frame::$p::Frame;` for another
//! file's item. [`both_precisions!`](crate::both_precisions) expands that
//! body once as `pub mod f64` (`f64`, `DVec2`, `DVec3`) and once as
//! `pub mod f32` (`f32`, `Vec2`, `Vec3`). The crate root then re-exports each
//! public item once per precision (`lambert_geometry::f64::Sphere`,
//! `lambert_geometry::f32::Sphere`), so every item has exactly one public
//! path per precision and its own documentation page.
//!
//! Why a macro and not generics: glam's `DVec3` and `Vec3` share no trait,
//! and a generic scalar would turn every literal of the numerics into a
//! conversion call; the macro keeps the code as written and monomorphic.

/// Names used by the f64 instantiation.
#[doc(hidden)]
pub mod f64 {
    /// The scalar.
    pub type Real = f64;
    /// A 2-vector of the scalar (the canonical sample `u`, surface parameters).
    pub type V2 = glam::DVec2;
    /// A 3-vector of the scalar (points and directions).
    pub type V3 = glam::DVec3;
    /// π.
    pub const PI: Real = core::f64::consts::PI;
    /// The largest value below 1.
    pub const ONE_MINUS_EPSILON: Real = 1.0 - f64::EPSILON / 2.0;
    /// The components of `v` widened to f64 (for messages and references).
    #[inline]
    pub fn wide3(v: V3) -> glam::DVec3 {
        v
    }
    /// `v` rounded to this precision.
    #[inline]
    pub fn narrow3(v: glam::DVec3) -> V3 {
        v
    }
    /// `u` rounded to this precision.
    #[inline]
    pub fn narrow2(u: glam::DVec2) -> V2 {
        u
    }
    /// `u` widened to f64 (exact).
    #[inline]
    pub fn wide2(u: V2) -> glam::DVec2 {
        u
    }
}

/// Names used by the f32 instantiation.
#[doc(hidden)]
pub mod f32 {
    /// The scalar.
    pub type Real = f32;
    /// A 2-vector of the scalar (the canonical sample `u`, surface parameters).
    pub type V2 = glam::Vec2;
    /// A 3-vector of the scalar (points and directions).
    pub type V3 = glam::Vec3;
    /// π.
    pub const PI: Real = core::f32::consts::PI;
    /// The largest value below 1.
    pub const ONE_MINUS_EPSILON: Real = 1.0 - f32::EPSILON / 2.0;
    /// The components of `v` widened to f64 (exact).
    #[inline]
    pub fn wide3(v: V3) -> glam::DVec3 {
        v.as_dvec3()
    }
    /// `v` rounded to this precision.
    #[inline]
    pub fn narrow3(v: glam::DVec3) -> V3 {
        v.as_vec3()
    }
    /// `u` rounded to this precision.
    #[inline]
    pub fn narrow2(u: glam::DVec2) -> V2 {
        u.as_vec2()
    }
    /// `u` widened to f64 (exact).
    #[inline]
    pub fn wide2(u: V2) -> glam::DVec2 {
        u.as_dvec2()
    }
}

/// Expands an implementation macro `$body!(precision, Vec2 type, Vec3 type)`
/// once as `pub mod f64` and once as `pub mod f32` of the calling module
/// (see the [module docs](crate::precision)).
#[doc(hidden)]
#[macro_export]
macro_rules! both_precisions {
    ($body:ident) => {
        /// The f64 (`DVec2`, `DVec3`) instantiation.
        #[allow(clippy::unnecessary_cast)] // `x as f64` is a no-op only in this instantiation
        pub mod f64 {
            $body!(f64, DVec2, DVec3);
        }
        /// The f32 (`Vec2`, `Vec3`) instantiation.
        pub mod f32 {
            $body!(f32, Vec2, Vec3);
        }
    };
}
