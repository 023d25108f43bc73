//! A streaming estimate of a mean: count, compensated sum, Welford variance,
//! and an exact-as-possible merge of two estimates.
//!
//! **Mean.** The samples are summed with a Neumaier-compensated sum
//! ([`NeumaierSum`], Neumaier 1974); the mean is that sum divided by n and
//! kept as an unevaluated pair `m = m_hi + m_lo` with
//!
//! ```text
//! m_hi = fl(s / n),   m_lo = (fma(−m_hi, n, s) + c) / n      (s + c the compensated sum)
//! ```
//!
//! (`s − m_hi·n` is exact, being the remainder of a rounded division), so the
//! mean carries ~2·53 bits and [`Estimate::mean`] returns it rounded once.
//! For a constant integrand x, `mean() == x` to within one rounding for any
//! n up to 2⁵³; a plain running sum drifts by up to n·ε relative.
//!
//! **Variance.** Welford's recurrence (B. P. Welford, "Note on a method for
//! calculating corrected sums of squares and products", Technometrics 4
//! (1962) 419–420):
//!
//! ```text
//! M₂ ← M₂ + (x − m_{k−1})·(x − m_k),     s² = M₂ / (n − 1)
//! ```
//!
//! with the means `m_k` the double-length compensated means above (instead of
//! Welford's own `m_k = m_{k−1} + (x − m_{k−1})/k`, whose rounding errors
//! accumulate) and M₂ itself summed with a Neumaier sum. Every term is
//! mathematically ≥ 0, so M₂ has no cancellation; the error of each term is
//! a few ε relative, so the variance is accurate to O(ε)·(a small multiple)
//! whatever the offset of the data (1e9 + noise of 1e-3 is no harder than
//! noise alone), unlike the textbook `Σx² − n·m²`, which loses everything.
//! [`Estimate::from_values`] sums its M₂ in windows of plain adds, within
//! about 260u relative, u = 2⁻⁵³ (`non_negative_lane_sums` gives the bound).
//!
//! **Merge.** Two estimates combine by the pairwise formula of Chan, Golub &
//! LeVeque (T. F. Chan, G. H. Golub, R. J. LeVeque, "Updating formulae and a
//! pairwise algorithm for computing sample variances", Stanford report
//! STAN-CS-79-773, 1979; "Algorithms for computing the sample variance:
//! analysis and recommendations", The American Statistician 37 (1983)
//! 242–247):
//!
//! ```text
//! n = n_a + n_b,   δ = m_b − m_a,
//! Σ = Σ_a ⊕ Σ_b,   M₂ = M₂_a ⊕ M₂_b ⊕ δ²·n_a·n_b / n
//! ```
//!
//! with `⊕` the compensated merge and the mean recomputed from Σ. The merge is
//! a pure function of the two states, so merging the same chunks in the same
//! order gives the same bits on any machine and any thread count (this is
//! what [`run_chunked`](super::run_chunked) relies on). The mean of a merge
//! equals the one-pass mean to the bit whenever the compensated sum is exact
//! in both (e.g. integers, or any data whose partial sums are representable),
//! and to within one rounding otherwise; the variance agrees to a few ε
//! relative (different but equally accurate roundings).
//!
//! **Non-finite samples.** A NaN or ±∞ pushed is not added to the sums but
//! counted ([`Estimate::non_finite`]); from then on every statistic returns
//! `None` (or [`StatisticsError::NonFinite`]), because the mean of a
//! population containing an infinite value is not finite. Nothing returns NaN.

use super::confidence::ConfidenceInterval;
use super::error::StatisticsError;
use super::neumaier::NeumaierSum;

/// A streaming estimate of a mean and its variance (module docs: Welford
/// 1962, Neumaier 1974, Chan, Golub & LeVeque 1983).
///
/// ```
/// use lambert_estimator::statistics::Estimate;
/// let mut e = Estimate::new();
/// for x in [1.0, 2.0, 3.0, 4.0] {
///     e.push(x);
/// }
/// assert_eq!(e.n(), 4);
/// assert_eq!(e.mean(), Some(2.5));
/// assert_eq!(e.variance(), Some(5.0 / 3.0));
/// let ci = e.confidence_interval(0.95).unwrap();
/// assert!(ci.contains(2.5));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Estimate {
    /// Finite samples pushed.
    n: u64,
    /// Non-finite samples pushed (not in the sums).
    non_finite: u64,
    /// Finite samples pushed that were not 0 (the hits).
    nonzero: u64,
    /// Σx, compensated.
    sum: NeumaierSum,
    /// The mean Σx / n as an unevaluated pair `mean_hi + mean_lo`.
    mean_hi: f64,
    mean_lo: f64,
    /// M₂ = Σ(x − m)², compensated.
    m2: NeumaierSum,
}

/// The compensated sum `s + c` divided by `n`, as `hi + lo` (module docs).
#[inline]
fn split_mean(sum: &NeumaierSum, n: u64) -> (f64, f64) {
    let nf = n as f64;
    let (s, c) = sum.parts();
    let hi = s / nf;
    // s − hi·n: the remainder of a rounded division, exactly representable
    // (no underflow for any s this crate meets), computed exactly by the fma.
    let r = (-hi).mul_add(nf, s);
    (hi, (r + c) / nf)
}

/// Lanes of [`lane_sums`]: 16, two AVX-512 vectors of f64. Each lane's
/// running sum is one dependency chain of floating-point adds (about four
/// cycles each), so k lanes add at most k values per four cycles: with 4
/// lanes (the earlier choice) the two passes of [`Estimate::from_values`]
/// cost about 30 % of a light-sampled estimate's time per sample; 16 lanes
/// keep two vector units busy. The lane count fixes which values are summed
/// together, so it is part of every estimate's bits.
const SUM_LANES: usize = 16;

/// The compensated sum of `f(x)` over the finite values of `values`, and
/// optionally the count of non-zero values, in
/// [`SUM_LANES`] lanes (value i in lane i mod 16) merged in lane order, as
/// [`Estimate::from_values`] documents.
///
/// Branch-free, so it vectorises (the lanes are two vectors): a
/// non-finite value adds 0 to its lane instead of being skipped, which
/// leaves the lane's bits as they were (its running sum starts at +0 and
/// can never become −0 by round-to-nearest additions, so s + 0 = s and the
/// rounding error (s − s) + 0 = +0 adds nothing to the compensation).
/// `ALL_FINITE` drops that test and select (6 % of
/// [`Estimate::from_values`]'s time): the bits are the same when every
/// value is finite, and a non-finite value then makes the sum non-finite
/// (see `from_values`). `COUNT` also counts the values x ≠ 0 (of `values`,
/// not of f(x)), returned with the sum (0 without it): counting there, and
/// not in a pass of its own, took `from_values` from 0.33 to 0.25 ns per
/// value (AVX-512, 4096 values).
#[inline(always)]
fn lane_sums<const ALL_FINITE: bool, const COUNT: bool>(
    values: &[f64],
    f: impl Fn(f64) -> f64,
) -> (NeumaierSum, u64) {
    const LANES: usize = SUM_LANES;
    let mut s = [0.0f64; LANES];
    let mut c = [0.0f64; LANES];
    let mut nonzero = [0u64; LANES];
    let add = |s: &mut f64, c: &mut f64, nz: &mut u64, x: f64| {
        if COUNT {
            *nz += u64::from(x != 0.0);
        }
        let y = if ALL_FINITE || x.is_finite() {
            f(x)
        } else {
            0.0
        };
        // Neumaier's step (NeumaierSum::add), written with a select.
        let t = *s + y;
        let err = if s.abs() >= y.abs() {
            (*s - t) + y
        } else {
            (y - t) + *s
        };
        *c += err;
        *s = t;
    };
    let mut blocks = values.chunks_exact(LANES);
    for block in blocks.by_ref() {
        for j in 0..LANES {
            add(&mut s[j], &mut c[j], &mut nonzero[j], block[j]);
        }
    }
    for (j, &x) in blocks.remainder().iter().enumerate() {
        add(&mut s[j], &mut c[j], &mut nonzero[j], x);
    }
    let mut sum = NeumaierSum::from_parts(s[0], c[0]);
    for j in 1..LANES {
        sum.merge(&NeumaierSum::from_parts(s[j], c[j]));
    }
    (sum, nonzero.iter().sum())
}

/// Values per window of [`non_negative_lane_sums`]: each of its
/// [`SUM_LANES`] lanes adds at most `WINDOW / SUM_LANES` = 256 terms
/// without compensation before the window's lane sums join compensated
/// totals. A chunk of the estimators (4096 samples) is one window.
const WINDOW: usize = 4096;

/// Σ f(x) over the finite values of `values` for an f(x) ≥ 0 (the squared
/// deviations of M₂), as [`Estimate::from_values`] documents: value i in
/// lane i mod [`SUM_LANES`], plain sums within each [`WINDOW`], each
/// window's lane sums added to that lane's Neumaier sum, the lanes merged
/// in order. `ALL_FINITE` as in [`lane_sums`].
///
/// **Why not compensated throughout.** The terms are all ≥ 0, so their
/// sum has no cancellation: a plain sum of k non-negative terms is within
/// (k − 1)·u of the exact sum, relative (u = 2⁻⁵³; Higham, "Accuracy and
/// Stability of Numerical Algorithms", 2nd ed., §4.2). With k ≤ 256 per
/// lane and window, and each term (x − m)² within about 3u of its exact
/// value, M₂ is within (255 + 3 + a few)·u ≈ 3e-14 relative of the exact
/// M₂ of the rounded samples, whatever n is (the windows' sums are
/// compensated). That is ten orders of magnitude below the statistical
/// error of any variance estimate, and the plain adds made the whole
/// estimate of a light-sampled sphere 6 % (f64) and 10 % (f32) faster than
/// Neumaier steps per term (measured in one run against the compensated
/// pass, medians of 5 seeds, 2²⁴ samples, AVX-512). The mean keeps its compensated sum: its
/// bits are the estimate itself.
#[inline(always)]
fn non_negative_lane_sums<const ALL_FINITE: bool>(
    values: &[f64],
    f: impl Fn(f64) -> f64,
) -> NeumaierSum {
    const LANES: usize = SUM_LANES;
    const { assert!(WINDOW.is_multiple_of(LANES)) };
    let term = |x: f64| {
        if ALL_FINITE || x.is_finite() {
            f(x)
        } else {
            0.0
        }
    };
    // The lanes' compensated totals as two arrays, added to lane by lane
    // like the window sums (an array of `NeumaierSum`s led the compiler to
    // split the window loop into 4-, 2-, 8- and 1-wide pieces, which
    // took back most of the gain).
    let (mut totals, mut compensations) = ([0.0f64; LANES], [0.0f64; LANES]);
    for window in values.chunks(WINDOW) {
        let mut s = [0.0f64; LANES];
        let (blocks, rest) = window.as_chunks::<LANES>();
        for block in blocks {
            for j in 0..LANES {
                s[j] += term(block[j]);
            }
        }
        for (j, &x) in rest.iter().enumerate() {
            s[j] += term(x);
        }
        for j in 0..LANES {
            let mut total = NeumaierSum::from_parts(totals[j], compensations[j]);
            total.add(s[j]);
            (totals[j], compensations[j]) = total.parts();
        }
    }
    let mut sum = NeumaierSum::from_parts(totals[0], compensations[0]);
    for j in 1..LANES {
        sum.merge(&NeumaierSum::from_parts(totals[j], compensations[j]));
    }
    sum
}

impl Estimate {
    /// The empty estimate (n = 0).
    pub const fn new() -> Self {
        Self {
            n: 0,
            non_finite: 0,
            nonzero: 0,
            sum: NeumaierSum::new(),
            mean_hi: 0.0,
            mean_lo: 0.0,
            m2: NeumaierSum::new(),
        }
    }

    /// Adds one sample `x` (Welford's update with compensated means, module
    /// docs). A NaN or ±∞ is counted in [`non_finite`](Estimate::non_finite)
    /// instead.
    #[inline]
    pub fn push(&mut self, x: f64) {
        if !x.is_finite() {
            self.non_finite += 1;
            return;
        }
        let before = (x - self.mean_hi) - self.mean_lo;
        self.n += 1;
        self.nonzero += u64::from(x != 0.0);
        self.sum.add(x);
        let (hi, lo) = split_mean(&self.sum, self.n);
        self.mean_hi = hi;
        self.mean_lo = lo;
        let after = (x - hi) - lo;
        self.m2.add(before * after);
    }

    /// The estimate of a block of samples held in memory, by two passes:
    /// the compensated sum gives the mean, then M₂ = Σ(x − m)² is summed
    /// about it (non-negative terms, plain adds in windows of 4096 values
    /// whose sums are compensated: within about 260u relative (u = 2⁻⁵³), see
    /// `non_negative_lane_sums`). Two passes cost a fraction of a push per
    /// sample (whose Welford update is accurate to a few u), so the
    /// estimators fill a chunk's values in a buffer and summarise it here;
    /// the result merges like any other estimate. Non-finite values are
    /// counted in [`non_finite`](Estimate::non_finite), non-zero ones in
    /// [`nonzero`](Estimate::nonzero) (in the first pass, with the sums).
    #[inline(always)]
    pub fn from_values(values: &[f64]) -> Estimate {
        // SUM_LANES interleaved compensated sums (value i goes to lane i mod 16),
        // merged in a fixed order: the same accuracy as one, without one
        // long dependency chain.
        //
        // The usual case, every value finite, takes one pass for the sum
        // and the non-zero count. A NaN or ±∞ makes its lane's compensation
        // NaN for good ((±∞ − ±∞) or NaN enters it, and NaN + c = NaN), and
        // so the merged sum's: a finite sum proves every value finite, and
        // is then what the careful pass below would give, to the bit.
        let (sum, nonzero) = lane_sums::<true, true>(values, |x| x);
        let (hi, lo) = sum.parts();
        let (n, nonzero, non_finite, sum) = if hi.is_finite() && lo.is_finite() {
            (values.len() as u64, nonzero, 0, sum)
        } else {
            let mut n = 0u64;
            let mut nonzero = 0u64;
            for &x in values {
                n += u64::from(x.is_finite());
                nonzero += u64::from(x.is_finite() && x != 0.0);
            }
            let non_finite = values.len() as u64 - n;
            let sum = if non_finite == 0 {
                sum
            } else {
                lane_sums::<false, false>(values, |x| x).0
            };
            (n, nonzero, non_finite, sum)
        };
        let all_finite = non_finite == 0;
        if n == 0 {
            return Estimate {
                non_finite,
                ..Estimate::new()
            };
        }
        let (mean_hi, mean_lo) = split_mean(&sum, n);
        let deviation2 = |x: f64| {
            let d = (x - mean_hi) - mean_lo;
            d * d
        };
        let m2 = if all_finite {
            non_negative_lane_sums::<true>(values, deviation2)
        } else {
            non_negative_lane_sums::<false>(values, deviation2)
        };
        Estimate {
            n,
            non_finite,
            nonzero,
            sum,
            mean_hi,
            mean_lo,
            m2,
        }
    }

    /// Adds `count` copies of `x` at once, in O(1) (O(count / 2⁵³)).
    ///
    /// The copies form a block with n = count, Σ = x·count exactly (a
    /// two-product, `hi = fl(x·count)`, `lo = fma(x, count, −hi)`), mean x
    /// and M₂ = 0, merged by [`merge`](Estimate::merge). Pushing the copies
    /// one by one gives the same statistics to within the roundings of the
    /// one-by-one path. Blocks larger than 2⁵³ (where `count as f64` stops
    /// being exact) are split.
    pub fn push_n(&mut self, x: f64, count: u64) {
        if count == 0 {
            return;
        }
        if !x.is_finite() {
            self.non_finite += count;
            return;
        }
        const MAX_BLOCK: u64 = 1 << 53;
        let mut remaining = count;
        while remaining > 0 {
            let k = remaining.min(MAX_BLOCK);
            let kf = k as f64;
            let hi = x * kf;
            let lo = x.mul_add(kf, -hi);
            let block = Estimate {
                n: k,
                non_finite: 0,
                nonzero: if x != 0.0 { k } else { 0 },
                sum: NeumaierSum::from_parts(hi, lo),
                mean_hi: x,
                mean_lo: 0.0,
                m2: NeumaierSum::new(),
            };
            self.merge(&block);
            remaining -= k;
        }
    }

    /// Merges `other` into `self` (Chan, Golub & LeVeque's pairwise formula,
    /// module docs): afterwards `self` is the estimate of both sets of
    /// samples. Deterministic: the same states merged in the same order give
    /// the same bits. Merging with an empty estimate changes nothing.
    pub fn merge(&mut self, other: &Estimate) {
        if other.n == 0 {
            self.non_finite += other.non_finite;
            return;
        }
        if self.n == 0 {
            let non_finite = self.non_finite + other.non_finite;
            *self = *other;
            self.non_finite = non_finite;
            return;
        }
        let na = self.n as f64;
        let nb = other.n as f64;
        let n = self.n + other.n;
        let delta = (other.mean_hi - self.mean_hi) + (other.mean_lo - self.mean_lo);
        self.sum.merge(&other.sum);
        self.m2.merge(&other.m2);
        self.m2.add(delta * delta * (na * (nb / n as f64)));
        self.n = n;
        self.non_finite += other.non_finite;
        self.nonzero += other.nonzero;
        let (hi, lo) = split_mean(&self.sum, n);
        self.mean_hi = hi;
        self.mean_lo = lo;
    }

    /// `self` merged with `other` (by value; see [`merge`](Estimate::merge)).
    #[must_use]
    pub fn merged(mut self, other: &Estimate) -> Estimate {
        self.merge(other);
        self
    }

    /// The number n of finite samples pushed.
    pub fn n(&self) -> u64 {
        self.n
    }

    /// The number of non-finite samples pushed (NaN, ±∞). When it is not 0,
    /// every statistic is `None`.
    pub fn non_finite(&self) -> u64 {
        self.non_finite
    }

    /// The number of finite samples pushed that were not 0: the *hits* of a
    /// Monte Carlo estimate whose samples are 0 wherever the integrand is
    /// not seen. With few hits the sample variance says little about the
    /// error (see [`bounded`](super::bounded)).
    pub fn nonzero(&self) -> u64 {
        self.nonzero
    }

    /// True if no sample, finite or not, was pushed.
    pub fn is_empty(&self) -> bool {
        self.n == 0 && self.non_finite == 0
    }

    /// Whether the statistics are defined: no non-finite sample was pushed
    /// and the sums are finite.
    fn is_finite(&self) -> bool {
        self.non_finite == 0 && self.sum.sum().is_finite() && self.m2.sum().is_finite()
    }

    /// The compensated sum Σx (0 for n = 0); `None` after a non-finite
    /// sample or if the sum overflowed.
    pub fn sum(&self) -> Option<f64> {
        let s = self.sum.sum();
        (self.non_finite == 0 && s.is_finite()).then_some(s)
    }

    /// The sample mean m = Σx / n, from the compensated sum (module docs).
    /// `None` if n = 0, after a non-finite sample, or if the sum
    /// overflowed. (An overflow of M₂ alone, from samples above ~1e154,
    /// leaves the mean defined and only the variance `None`.)
    pub fn mean(&self) -> Option<f64> {
        let m = self.mean_hi + self.mean_lo;
        (self.n > 0 && self.sum().is_some() && m.is_finite()).then_some(m)
    }

    /// The sample (unbiased) variance s² = M₂ / (n − 1), M₂ = Σ(x − m)²
    /// by Welford's recurrence. `None` if n < 2, after a non-finite sample,
    /// or on overflow. Never negative.
    pub fn variance(&self) -> Option<f64> {
        if self.n < 2 || !self.is_finite() {
            return None;
        }
        let v = self.m2.sum().max(0.0) / (self.n - 1) as f64;
        v.is_finite().then_some(v)
    }

    /// The sample standard deviation s = √s² (`None` as for
    /// [`variance`](Estimate::variance)).
    pub fn std_dev(&self) -> Option<f64> {
        self.variance().map(f64::sqrt)
    }

    /// The standard error of the mean, s / √n = √(s² / n) (`None` as for
    /// [`variance`](Estimate::variance), so n ≥ 2).
    pub fn std_error(&self) -> Option<f64> {
        self.variance().map(|v| (v / self.n as f64).sqrt())
    }

    /// A two-sided confidence interval for the true mean at `level`
    /// (e.g. 0.99): `m ± q·s/√n`, q Student's t quantile with n − 1 degrees
    /// of freedom for n < [`STUDENT_T_BELOW`](super::STUDENT_T_BELOW), the normal quantile from it on
    /// (see [`ConfidenceInterval`]).
    ///
    /// # Errors
    /// [`StatisticsError::InvalidLevel`] unless 0 < level < 1;
    /// [`StatisticsError::TooFewSamples`] for n < 2 (no variance);
    /// [`StatisticsError::NonFinite`] after a non-finite sample or overflow.
    pub fn confidence_interval(&self, level: f64) -> Result<ConfidenceInterval, StatisticsError> {
        if !(level > 0.0 && level < 1.0) {
            return Err(StatisticsError::InvalidLevel(level));
        }
        if !self.is_finite() {
            return Err(StatisticsError::NonFinite {
                count: self.non_finite,
            });
        }
        if self.n < 2 {
            return Err(StatisticsError::TooFewSamples {
                n: self.n,
                needed: 2,
            });
        }
        let (Some(mean), Some(se)) = (self.mean(), self.std_error()) else {
            return Err(StatisticsError::NonFinite { count: 0 });
        };
        Ok(ConfidenceInterval::new(mean, se, self.n, level))
    }

    /// The relative error |m − r| / |r| against a reference value r.
    /// `None` if there is no mean, or r is 0 or not finite.
    pub fn relative_error(&self, reference: f64) -> Option<f64> {
        if reference == 0.0 || !reference.is_finite() {
            return None;
        }
        self.mean().map(|m| (m - reference).abs() / reference.abs())
    }

    /// The z-score (m − r) / (s/√n) against a reference value r: ~N(0, 1)
    /// for large n when r is the true mean and the standard error is honest.
    /// `None` if there is no standard error (n < 2, non-finite), it is 0 (a
    /// constant integrand: use [`relative_error`](Estimate::relative_error)),
    /// or r is not finite.
    pub fn z(&self, reference: f64) -> Option<f64> {
        if !reference.is_finite() {
            return None;
        }
        let se = self.std_error()?;
        let m = self.mean()?;
        let z = (m - reference) / se;
        (se > 0.0 && z.is_finite()).then_some(z)
    }
}

impl FromIterator<f64> for Estimate {
    fn from_iter<I: IntoIterator<Item = f64>>(iter: I) -> Self {
        let mut e = Estimate::new();
        e.extend(iter);
        e
    }
}

impl Extend<f64> for Estimate {
    fn extend<I: IntoIterator<Item = f64>>(&mut self, iter: I) {
        iter.into_iter().for_each(|x| self.push(x));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statistics::QuantileSource;

    /// The sums without the finiteness test give the bits of the sums with
    /// it, on finite values (a remainder lane included); the checked sums
    /// treat a non-finite value as 0, which the unchecked ones would not
    /// (negative control: they differ when one is present).
    #[test]
    fn unchecked_lane_sums_keep_the_bits_on_finite_values() {
        let values: Vec<f64> = (0..4099)
            .map(|i| ((i as f64) * 0.618_034).fract() * 3e-2)
            .collect();
        let square = |x: f64| x * x;
        assert_eq!(
            lane_sums::<true, true>(&values, |x| x),
            lane_sums::<false, true>(&values, |x| x)
        );
        assert_eq!(
            lane_sums::<true, false>(&values, square),
            lane_sums::<false, false>(&values, square)
        );
        let mut with_inf = values.clone();
        with_inf[17] = f64::INFINITY;
        assert_ne!(
            lane_sums::<true, false>(&with_inf, |x| x),
            lane_sums::<false, false>(&with_inf, |x| x)
        );
    }

    /// The windowed plain sums of non-negative terms are within their
    /// derived bound of a compensated sum over every term: each lane adds
    /// at most k = WINDOW / SUM_LANES terms plainly, within (k − 1)·u of
    /// their exact sum (Higham §4.2, u = 2⁻⁵³), and the compensated window
    /// totals and lane merges add about 2u; the reference (one Neumaier
    /// sum) is within 2u + n·u² of exact. So |plain − reference| ≤
    /// (k + 2)·u·Σterms. The data spans three whole windows and a
    /// remainder, with terms over twelve orders of magnitude and zeros.
    /// Skipping a non-finite value gives the bits of a 0 there, and the
    /// unchecked form has the checked form's bits on finite values.
    /// Negative control: the same bound rejects the sum without its
    /// largest term.
    #[test]
    fn non_negative_sums_are_within_their_bound() {
        let values: Vec<f64> = (0..3 * WINDOW + 37)
            .map(|i| {
                let x = ((i as f64) * 0.618_034).fract();
                if i % 7 == 0 {
                    0.0
                } else {
                    x * 10f64.powi(i as i32 % 13 - 6)
                }
            })
            .collect();
        let square = |x: f64| x * x;
        let reference: NeumaierSum = values.iter().map(|&x| square(x)).sum();
        let reference = reference.sum();
        let u = f64::EPSILON / 2.0;
        let bound = ((WINDOW / SUM_LANES) as f64 + 2.0) * u * reference;
        let got = non_negative_lane_sums::<true>(&values, square).sum();
        assert!((got - reference).abs() <= bound, "{got} vs {reference}");
        let largest = values.iter().map(|&x| square(x)).fold(0.0, f64::max);
        assert!((got - largest - reference).abs() > bound);
        let bits = |s: NeumaierSum| {
            let (s, c) = s.parts();
            (s.to_bits(), c.to_bits())
        };
        assert_eq!(
            bits(non_negative_lane_sums::<false>(&values, square)),
            bits(non_negative_lane_sums::<true>(&values, square))
        );
        let (mut odd, mut zeroed) = (values.clone(), values.clone());
        for (at, bad) in [(5, f64::NAN), (900, f64::INFINITY), (WINDOW, f64::NAN)] {
            odd[at] = bad;
            zeroed[at] = 0.0;
        }
        assert_eq!(
            bits(non_negative_lane_sums::<false>(&odd, square)),
            bits(non_negative_lane_sums::<true>(&zeroed, square))
        );
    }

    /// The statistics as `from_values` computed them before its one-pass
    /// fast path: the counts first, then sums that skip non-finite values.
    fn careful(values: &[f64]) -> Estimate {
        let n = values.iter().filter(|x| x.is_finite()).count() as u64;
        let nonzero = values
            .iter()
            .filter(|x| x.is_finite() && **x != 0.0)
            .count() as u64;
        let sum = lane_sums::<false, false>(values, |x| x).0;
        if n == 0 {
            return Estimate {
                non_finite: values.len() as u64,
                ..Estimate::new()
            };
        }
        let (mean_hi, mean_lo) = split_mean(&sum, n);
        let deviation2 = |x: f64| {
            let d = (x - mean_hi) - mean_lo;
            d * d
        };
        Estimate {
            n,
            non_finite: values.len() as u64 - n,
            nonzero,
            sum,
            mean_hi,
            mean_lo,
            m2: non_negative_lane_sums::<false>(values, deviation2),
        }
    }

    /// Every field's bits (an overflowed estimate holds NaNs, which `==`
    /// would call unequal to themselves).
    fn bits(e: &Estimate) -> [u64; 9] {
        let (s, c) = e.sum.parts();
        let (m, mc) = e.m2.parts();
        [e.n, e.non_finite, e.nonzero, s.to_bits(), c.to_bits()]
            .into_iter()
            .chain([e.mean_hi, e.mean_lo, m, mc].map(f64::to_bits))
            .collect::<Vec<_>>()
            .try_into()
            .unwrap()
    }

    /// The one-pass fast path gives the careful path's bits: on finite
    /// values with zeros, and with a NaN, ±∞ or a sum that overflows in any
    /// lane and at the remainder, where it must fall back. Negative
    /// control: the fast pass alone, without its finiteness check, would
    /// count every value as a sample.
    #[test]
    fn one_pass_fast_path_gives_the_careful_bits() {
        let values: Vec<f64> = (0..4099)
            .map(|i| {
                let x = ((i as f64) * 0.618_034).fract();
                if x < 0.3 {
                    0.0
                } else {
                    x * 3e-2
                }
            })
            .collect();
        assert_eq!(
            bits(&Estimate::from_values(&values)),
            bits(&careful(&values))
        );
        assert!(careful(&values).nonzero() < 4099 && careful(&values).nonzero() > 0);
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX] {
            for at in [0usize, 5, 15, 16, 2000, 4097, 4098] {
                let mut v = values.clone();
                v[at] = bad;
                if bad == f64::MAX {
                    // A second f64::MAX in the same lane overflows its sum.
                    v[(at + 16) % 4096] = f64::MAX;
                }
                let got = Estimate::from_values(&v);
                assert_eq!(bits(&got), bits(&careful(&v)), "{bad} at {at}");
                let (fast, _) = lane_sums::<true, true>(&v, |x| x);
                assert!(!fast.sum().is_finite(), "{bad} at {at}: fast sum finite");
            }
        }
        let mut nan = values.clone();
        nan[3] = f64::NAN;
        assert_eq!(Estimate::from_values(&nan).n(), 4098);
        assert_ne!(Estimate::from_values(&nan).n(), nan.len() as u64);
        let all_nan = [f64::NAN; 20];
        assert_eq!(
            bits(&Estimate::from_values(&all_nan)),
            bits(&careful(&all_nan))
        );
    }

    #[test]
    fn empty_and_single_sample_give_none_not_nan() {
        let e = Estimate::new();
        assert!(e.is_empty());
        assert_eq!(e.n(), 0);
        assert_eq!(e.sum(), Some(0.0));
        assert_eq!(e.mean(), None);
        assert_eq!(e.variance(), None);
        assert_eq!(e.std_error(), None);
        assert_eq!(e.z(1.0), None);
        assert_eq!(e.relative_error(1.0), None);
        assert_eq!(
            e.confidence_interval(0.9),
            Err(StatisticsError::TooFewSamples { n: 0, needed: 2 })
        );
        let mut one = Estimate::new();
        one.push(2.5);
        assert_eq!(one.mean(), Some(2.5));
        assert_eq!(one.relative_error(2.0), Some(0.25));
        assert_eq!(one.variance(), None);
        assert_eq!(one.std_dev(), None);
        assert_eq!(one.z(2.0), None);
        assert_eq!(
            one.confidence_interval(0.9),
            Err(StatisticsError::TooFewSamples { n: 1, needed: 2 })
        );
    }

    #[test]
    fn non_finite_samples_are_counted_and_disable_the_statistics() {
        let mut e: Estimate = [1.0, 2.0, f64::NAN, 3.0].into_iter().collect();
        assert_eq!((e.n(), e.non_finite()), (3, 1));
        assert_eq!(e.mean(), None);
        assert_eq!(e.variance(), None);
        assert_eq!(e.sum(), None);
        assert_eq!(
            e.confidence_interval(0.5),
            Err(StatisticsError::NonFinite { count: 1 })
        );
        e.push_n(f64::INFINITY, 5);
        assert_eq!(e.non_finite(), 6);
        // Merging carries the count, from either side.
        let clean: Estimate = [1.0, 2.0].into_iter().collect();
        assert_eq!(clean.merged(&e).non_finite(), 6);
        assert_eq!(e.merged(&clean).non_finite(), 6);
        assert_eq!(Estimate::new().merged(&e).non_finite(), 6);
        // Overflow of finite samples: None, not NaN or ∞.
        let big: Estimate = [f64::MAX, f64::MAX].into_iter().collect();
        assert_eq!(big.non_finite(), 0);
        assert_eq!(big.mean(), None);
        assert_eq!(big.variance(), None);
    }

    #[test]
    fn constant_samples_have_zero_variance_and_no_z() {
        let e: Estimate = std::iter::repeat_n(0.7, 1000).collect();
        assert_eq!(e.mean(), Some(0.7));
        assert_eq!(e.variance(), Some(0.0));
        assert_eq!(e.std_error(), Some(0.0));
        assert_eq!(e.z(0.7), None);
        assert_eq!(e.relative_error(0.0), None);
        let ci = e.confidence_interval(0.99).unwrap();
        assert_eq!((ci.lower, ci.upper), (0.7, 0.7));
    }

    #[test]
    fn small_sample_statistics_match_hand_computation() {
        let e: Estimate = [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]
            .into_iter()
            .collect();
        assert_eq!(e.mean(), Some(5.0));
        assert_eq!(e.variance(), Some(32.0 / 7.0));
        assert_eq!(e.std_error(), Some((32.0 / 7.0 / 8.0_f64).sqrt()));
        let z = e.z(4.0).unwrap();
        assert!((z - 1.0 / (4.0_f64 / 7.0).sqrt()).abs() < 1e-15);
    }

    /// Quantiles: t₀.₉₉₅ with 9 and 28 dof, z₀.₉₉₅ (tables; 1e-9 absolute,
    /// statrs' incomplete-beta inversion is good to ~1e-12).
    #[test]
    fn confidence_interval_uses_student_t_below_30_and_normal_from_30() {
        let mut e = Estimate::new();
        for i in 0..10 {
            e.push(i as f64);
        }
        let ci = e.confidence_interval(0.99).unwrap();
        assert_eq!(ci.source, QuantileSource::StudentT { dof: 9 });
        assert!(
            (ci.quantile - 3.249_835_541_592_14).abs() < 1e-9,
            "{}",
            ci.quantile
        );
        assert!((ci.half_width - ci.quantile * e.std_error().unwrap()).abs() < 1e-15);
        assert!(ci.contains(4.5) && !ci.contains(ci.upper + 1e-9));
        for i in 10..29 {
            e.push(i as f64);
        }
        let ci = e.confidence_interval(0.99).unwrap();
        assert_eq!(ci.source, QuantileSource::StudentT { dof: 28 });
        assert!(
            (ci.quantile - 2.763_262_455_461_22).abs() < 1e-9,
            "{}",
            ci.quantile
        );
        e.push(29.0);
        let ci = e.confidence_interval(0.99).unwrap();
        assert_eq!(ci.source, QuantileSource::Normal);
        assert!(
            (ci.quantile - 2.575_829_303_548_90).abs() < 1e-9,
            "{}",
            ci.quantile
        );
    }

    #[test]
    fn invalid_levels_are_rejected() {
        let e: Estimate = [1.0, 2.0, 3.0].into_iter().collect();
        for level in [0.0, 1.0, -0.5, 1.5, f64::NAN, f64::INFINITY] {
            match e.confidence_interval(level) {
                Err(StatisticsError::InvalidLevel(_)) => {}
                other => panic!("level {level}: {other:?}"),
            }
        }
    }

    #[test]
    fn merge_with_empty_is_the_identity_to_the_bit() {
        let e: Estimate = (0..100).map(|i| (i as f64).sqrt()).collect();
        assert_eq!(e.merged(&Estimate::new()), e);
        assert_eq!(Estimate::new().merged(&e), e);
    }

    /// `push_n(x, k)` against k pushes: the mean to one rounding
    /// (|Δ| ≤ ε|m|), the variance to 1e-13 relative (the one-by-one path
    /// rounds each of its k Welford terms; ~k·ε² absolute on s² ≈ 1).
    #[test]
    fn push_n_matches_pushing_one_by_one() {
        let mut bulk: Estimate = (0..1000).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut single = bulk;
        bulk.push_n(3.1, 100_000);
        for _ in 0..100_000 {
            single.push(3.1);
        }
        assert_eq!(bulk.n(), single.n());
        let (mb, ms) = (bulk.mean().unwrap(), single.mean().unwrap());
        assert!((mb - ms).abs() <= f64::EPSILON * ms.abs(), "{mb} {ms}");
        let (vb, vs) = (bulk.variance().unwrap(), single.variance().unwrap());
        assert!((vb - vs).abs() <= 1e-13 * vs, "{vb} {vs}");
        // Of a constant alone: mean exact, variance exactly 0.
        let mut c = Estimate::new();
        c.push_n(0.1, 1 << 40);
        assert_eq!(c.mean(), Some(0.1));
        assert_eq!(c.variance(), Some(0.0));
        c.push_n(0.1, 0);
        assert_eq!(c.n(), 1 << 40);
    }
}
