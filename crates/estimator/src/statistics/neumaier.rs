//! Neumaier-compensated summation (the Kahan–Babuška–Neumaier sum).
//!
//! A running sum `s` is kept together with a compensation `c` that collects
//! the rounding error of every addition. Adding `x`:
//!
//! ```text
//! t = s + x
//! c += (s − t) + x   if |s| ≥ |x|      (the low part of x that t lost)
//! c += (x − t) + s   otherwise         (the low part of s that t lost)
//! s = t
//! ```
//!
//! Each bracket is the exact rounding error of `s + x` (Fast2Sum, Dekker
//! 1971, valid when the larger operand comes first), so `s + c` carries the
//! sum to an error of
//!
//! ```text
//! |(s + c) − Σxᵢ| ≤ ε·|Σxᵢ| + O(n·ε²)·Σ|xᵢ|,     ε = 2⁻⁵³,
//! ```
//!
//! against `(n − 1)·ε·Σ|xᵢ|` for the plain loop: while n·ε·Σ|xᵢ| ≪ |Σxᵢ|
//! (no severe cancellation, n ≪ 1/ε ≈ 4.5·10¹⁵) the result is the exact sum
//! to about one rounding. Unlike Kahan's original (1965), the branch keeps this bound
//! when an addend is larger than the running sum.
//!
//! Source: A. Neumaier, "Rundungsfehleranalyse einiger Verfahren zur
//! Summation endlicher Summen", ZAMM 54 (1974) 39–51. The same two-branch
//! form is Julia's `sum_kbn` (KahanSummation.jl).

/// A compensated running sum, `sum() = s + c` (Neumaier 1974).
///
/// ```
/// use lambert_estimator::statistics::NeumaierSum;
/// let mut s = NeumaierSum::new();
/// for x in [1.0, 1e100, 1.0, -1e100] {
///     s.add(x);
/// }
/// assert_eq!(s.sum(), 2.0); // the plain loop gives 0
/// ```
///
/// Non-finite input: once a NaN or an infinity is added, or the sum
/// overflows, [`sum`](NeumaierSum::sum) returns that non-finite value (NaN,
/// or ±∞), as the plain sum would; the compensation is then meaningless and
/// ignored.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NeumaierSum {
    /// The running (rounded) sum `s`.
    sum: f64,
    /// The accumulated rounding errors `c`.
    compensation: f64,
}

impl NeumaierSum {
    /// The empty sum, 0.
    pub const fn new() -> Self {
        Self {
            sum: 0.0,
            compensation: 0.0,
        }
    }

    /// A sum whose value is the unevaluated pair `hi + lo` (e.g. the exact
    /// result of a two-product, `hi = fl(a·b)`, `lo = fma(a, b, −hi)`).
    pub const fn from_parts(hi: f64, lo: f64) -> Self {
        Self {
            sum: hi,
            compensation: lo,
        }
    }

    /// Adds `x`: `t = s + x`, `c += ` the exact rounding error of `s + x`,
    /// `s = t`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.sum + x;
        let err = if self.sum.abs() >= x.abs() {
            (self.sum - t) + x
        } else {
            (x - t) + self.sum
        };
        self.compensation += err;
        self.sum = t;
    }

    /// The compensated sum `s + c` (rounded once). If the running sum is
    /// not finite (a NaN or ±∞ was added, or it overflowed), that value.
    #[inline]
    pub fn sum(&self) -> f64 {
        if self.sum.is_finite() {
            self.sum + self.compensation
        } else {
            self.sum
        }
    }

    /// The running sum `s` and its compensation `c`, unevaluated: their
    /// exact sum `s + c` is the sum to the error bound of the module docs.
    #[inline]
    pub fn parts(&self) -> (f64, f64) {
        (self.sum, self.compensation)
    }

    /// Adds another sum: its running sum `s'` is added with its exact
    /// rounding error (as [`add`](NeumaierSum::add)), and its compensation
    /// joins ours, `c += c'`.
    ///
    /// The only roundings are that of `s + s'` (recovered exactly into `c`)
    /// and those of the two compensation additions, both of size
    /// ε·|c| ≈ ε²·|sum|: merging loses no more than adding the other sum's
    /// terms one by one would. The operation is deterministic, so merging
    /// the same sums in the same order gives the same bits.
    #[inline]
    pub fn merge(&mut self, other: &NeumaierSum) {
        self.add(other.sum);
        self.compensation += other.compensation;
    }
}

impl std::iter::Sum<f64> for NeumaierSum {
    fn sum<I: Iterator<Item = f64>>(iter: I) -> Self {
        let mut s = NeumaierSum::new();
        iter.for_each(|x| s.add(x));
        s
    }
}

impl Extend<f64> for NeumaierSum {
    fn extend<I: IntoIterator<Item = f64>>(&mut self, iter: I) {
        iter.into_iter().for_each(|x| self.add(x));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_what_the_plain_loop_loses() {
        let xs = [1.0, 1e100, 1.0, -1e100];
        let plain: f64 = xs.iter().sum();
        assert_eq!(plain, 0.0);
        assert_eq!(xs.iter().copied().sum::<NeumaierSum>().sum(), 2.0);
    }

    #[test]
    fn ten_million_tenths_are_exact_to_one_rounding() {
        // 0.1 is not representable; the exact sum of n copies of the f64
        // 0.1 is n·0.1f64, which the two-product gives exactly.
        let x = 0.1_f64;
        let n = 10_000_000u64;
        let mut s = NeumaierSum::new();
        let mut plain = 0.0;
        for _ in 0..n {
            s.add(x);
            plain += x;
        }
        let hi = x * n as f64;
        let lo = x.mul_add(n as f64, -hi);
        let exact = hi + lo;
        assert_eq!(s.sum(), exact);
        // The plain loop is off by far more than one rounding.
        assert!((plain - exact).abs() > 1e3 * f64::EPSILON * exact);
    }

    #[test]
    fn merge_of_two_halves_equals_one_pass_on_integers() {
        // Integers below 2^53: every partial sum is exact, so any order and
        // any split give the same bits.
        let xs: Vec<f64> = (0..1000).map(|i| ((i * 7919) % 1013) as f64).collect();
        let whole: NeumaierSum = xs.iter().copied().sum();
        let mut a: NeumaierSum = xs[..377].iter().copied().sum();
        let b: NeumaierSum = xs[377..].iter().copied().sum();
        a.merge(&b);
        assert_eq!(a.sum().to_bits(), whole.sum().to_bits());
    }

    #[test]
    fn merge_keeps_the_compensations_of_both_sides() {
        let mut a = NeumaierSum::new();
        let mut b = NeumaierSum::new();
        for x in [1e16, 1.0, 1.0] {
            a.add(x);
        }
        for x in [-1e16, 1.0] {
            b.add(x);
        }
        a.merge(&b);
        assert_eq!(a.sum(), 3.0);
    }

    #[test]
    fn non_finite_input_propagates() {
        let mut s = NeumaierSum::new();
        s.add(1.0);
        s.add(f64::INFINITY);
        assert_eq!(s.sum(), f64::INFINITY);
        s.add(f64::NEG_INFINITY);
        assert!(s.sum().is_nan());
        let mut o = NeumaierSum::new();
        o.add(f64::MAX);
        o.add(f64::MAX);
        assert_eq!(o.sum(), f64::INFINITY);
    }
}
