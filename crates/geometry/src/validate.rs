//! Validation of user-given geometry, in one place: every constructor of
//! this crate (and of the crates above it) checks its parameters with these
//! functions, so "finite", "positive" and "unit vector" mean the same thing
//! everywhere.
//!
//! - Scalars and vectors must be finite (no NaN, no ±∞).
//! - Lengths (radii) must be positive; quantities such as radiance must not
//!   be negative.
//! - A direction (normal, axis) may be given with any finite, non-zero
//!   length: it is normalised, after scaling by its largest component so
//!   that neither a huge vector (whose squared length overflows) nor a tiny
//!   one (whose squared length underflows) is mistaken for zero or
//!   normalised inexactly.

use glam::DVec3;

use crate::GeometryError;

/// Errors unless `value` is finite.
pub fn finite(field: &'static str, value: f64) -> Result<(), GeometryError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NotFinite {
            field,
            value: value.to_string(),
        })
    }
}

/// Errors unless every component of `v` (widened to f64) is finite.
pub fn finite3(field: &'static str, v: DVec3) -> Result<(), GeometryError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::NotFinite {
            field,
            value: v.to_string(),
        })
    }
}

/// Errors unless `value` is finite and > 0.
pub fn positive(field: &'static str, value: f64) -> Result<(), GeometryError> {
    finite(field, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(GeometryError::NotPositive { field, value })
    }
}

/// Errors unless `value` is finite and ≥ 0.
pub fn non_negative(field: &'static str, value: f64) -> Result<(), GeometryError> {
    finite(field, value)?;
    if value >= 0.0 {
        Ok(())
    } else {
        Err(GeometryError::Negative { field, value })
    }
}

macro_rules! validate_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use crate::precision::$p::{wide3, Real, V3};
        use crate::GeometryError;

        /// The power of two 2ᵉ ≥ `x` nearest above it for finite x > 0
        /// (clamped to the normal range), 1 for x = 0: dividing points by it
        /// is exact, brings their largest coordinate into [½, 1], and lets
        /// products of coordinates (cross products, Newell's normal) neither
        /// overflow nor underflow whatever the shape's size.
        #[inline]
        pub fn power_of_two_above(x: Real) -> Real {
            if !(x > 0.0) || !x.is_finite() {
                return 1.0;
            }
            let e = x.log2().ceil() as i32;
            let (lo, hi) = (Real::MIN_EXP - 1, Real::MAX_EXP - 1);
            (2.0 as Real).powi(e.clamp(lo, hi))
        }

        /// `v` normalised (any finite, non-zero length); errors if it is
        /// zero or not finite. The result is a unit vector to a few ulps.
        pub fn unit_vector(field: &'static str, v: V3) -> Result<V3, GeometryError> {
            super::finite3(field, wide3(v))?;
            let largest = v.abs().max_element();
            if !(largest > 0.0) {
                return Err(GeometryError::ZeroVector { field });
            }
            let scaled = v / largest;
            Ok(scaled / scaled.length())
        }
    };
}

crate::both_precisions!(validate_impl);
