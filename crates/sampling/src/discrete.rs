//! Choosing one piece of a light (a fan triangle) in proportion to its
//! weight (solid angle or area), reusing the sample.

macro_rules! discrete_impl {
    ($p:ident, $v2:ident, $v3:ident) => {
        use lambert_geometry::precision::$p::{Real, ONE_MINUS_EPSILON};

        /// Picks index k with probability wₖ/W from the cumulative weights
        /// `cumulative` (increasing, last = W) using u ∈ [0, 1), and returns k with
        /// u rescaled to [0, 1) within k's interval, so one uniform number both
        /// chooses the piece and samples inside it (pbrt-v4 §A.1, "sample reuse").
        /// `None` when there are no pieces.
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::pick_by_cumulative;")]
        /// // Pieces of weight 1, 2, 1: u = 0.5 lands in the middle of the second.
        /// assert_eq!(pick_by_cumulative(&[1.0, 3.0, 4.0], 0.5), Some((1, 0.5)));
        /// assert_eq!(pick_by_cumulative(&[], 0.5), None);
        /// ```
        #[inline]
        pub fn pick_by_cumulative(cumulative: &[Real], u: Real) -> Option<(usize, Real)> {
            let total = *cumulative.last()?;
            let target = u * total;
            let k = cumulative
                .partition_point(|&c| c <= target)
                .min(cumulative.len() - 1);
            let lo = if k == 0 { 0.0 } else { cumulative[k - 1] };
            Some((k, rescale_within(target, lo, cumulative[k])))
        }

        /// Where `target` lies in the interval [lo, hi) of a cumulative
        /// table, as a number in [0, 1): (target − lo)/(hi − lo), clamped
        /// below 1. The second use of a reused uniform number
        /// ([`pick_by_cumulative`] returns it with the chosen index).
        ///
        /// ```
        #[doc = concat!("use lambert_sampling::", stringify!($p), "::rescale_within;")]
        /// assert_eq!(rescale_within(1.5, 1.0, 3.0), 0.25);
        /// assert!(rescale_within(3.0, 1.0, 3.0) < 1.0);
        /// ```
        #[inline(always)]
        pub fn rescale_within(target: Real, lo: Real, hi: Real) -> Real {
            ((target - lo) / (hi - lo)).clamp(0.0, ONE_MINUS_EPSILON)
        }
    };
}

lambert_geometry::both_precisions!(discrete_impl);

#[cfg(test)]
mod tests {
    use super::f64::pick_by_cumulative;

    #[test]
    fn picks_in_proportion_and_rescales() {
        let c = [1.0, 3.0, 4.0];
        assert_eq!(pick_by_cumulative(&c, 0.0), Some((0, 0.0)));
        assert_eq!(pick_by_cumulative(&c, 0.125), Some((0, 0.5)));
        assert_eq!(pick_by_cumulative(&c, 0.5), Some((1, 0.5)));
        assert_eq!(pick_by_cumulative(&c, 0.875), Some((2, 0.5)));
        assert!(pick_by_cumulative(&[], 0.5).is_none());
    }
}
