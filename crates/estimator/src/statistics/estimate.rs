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
//! [`Estimate::from_values`], which summarises a chunk held in memory, sums
//! non-negative samples with plain adds in windows of 256 values whose
//! sums are compensated (within about 17u relative, u = 2⁻⁵³, whatever n
//! is: `window_sums` gives the bound), samples of which one is negative
//! with a Neumaier step per value, and equal samples exactly.
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
//! about 260u relative, u = 2⁻⁵³ (`window_sums` gives the bound).
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

/// The compensated sum of `f(x)` over the finite values of `values`, in
/// [`SUM_LANES`] lanes (value i in lane i mod 16) merged in lane order:
/// how [`Estimate::from_values`] sums samples of which one is negative.
///
/// Branch-free, so it vectorises (the lanes are two vectors): a
/// non-finite value adds 0 to its lane instead of being skipped, which
/// leaves the lane's bits as they were (its running sum starts at +0 and
/// can never become −0 by round-to-nearest additions, so s + 0 = s and the
/// rounding error (s − s) + 0 = +0 adds nothing to the compensation).
/// `ALL_FINITE` drops that test and select (6 % of
/// [`Estimate::from_values`]'s time): the bits are the same when every
/// value is finite.
#[inline(always)]
fn lane_sums<const ALL_FINITE: bool>(values: &[f64], f: impl Fn(f64) -> f64) -> NeumaierSum {
    const LANES: usize = SUM_LANES;
    let mut s = [0.0f64; LANES];
    let mut c = [0.0f64; LANES];
    let add = |s: &mut f64, c: &mut f64, x: f64| {
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
            add(&mut s[j], &mut c[j], block[j]);
        }
    }
    for (j, &x) in blocks.remainder().iter().enumerate() {
        add(&mut s[j], &mut c[j], x);
    }
    let mut sum = NeumaierSum::from_parts(s[0], c[0]);
    for j in 1..LANES {
        sum.merge(&NeumaierSum::from_parts(s[j], c[j]));
    }
    sum
}

/// Values per window of [`window_sums`] when it sums M₂: each of its
/// [`SUM_LANES`] lanes adds at most `M2_WINDOW / SUM_LANES` = 256 terms
/// without compensation before the window's lane sums join compensated
/// totals. A chunk of the estimators (4096 samples) is one window.
const M2_WINDOW: usize = 4096;

/// Values per window of [`window_sums`] when it sums the samples
/// themselves: 16 terms per lane, so that the mean is within about 20u of
/// exact (the rounding floor, `super::rounding`, is derived from it),
/// where 256 terms would allow 260u; the 16 compensated steps per window
/// cost less than one Neumaier step per 16 values.
const MEAN_WINDOW: usize = 256;

/// What the first pass of [`Estimate::from_values`] learns besides the
/// sum, over the finite values: how many are non-zero, the smallest and the
/// largest (a chunk with no finite value has min = +∞, max = −∞).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Scan {
    nonzero: u64,
    min: f64,
    max: f64,
}

/// Σ f(x) over the finite values of `values` for an f(x) ≥ 0, as
/// [`Estimate::from_values`] documents: value i in lane i mod
/// [`SUM_LANES`], plain sums within each window of `WINDOW` values
/// ([`MEAN_WINDOW`] for the samples, [`M2_WINDOW`] for M₂), each window's
/// lane sums added to that lane's Neumaier sum, the lanes merged in order.
/// `ALL_FINITE` as in [`lane_sums`]. With `SCAN` it also returns the
/// [`Scan`] of `values` (of x, not f(x); without it, a [`Scan`] of
/// nothing): counting there, and not in a pass of its own, took
/// `from_values` from 0.33 to 0.25 ns per value (AVX-512, 4096 values).
///
/// **Why not compensated throughout.** When the terms are all ≥ 0 their
/// sum has no cancellation: a plain sum of k non-negative terms is within
/// (k − 1)·u of the exact sum, relative (u = 2⁻⁵³; Higham, "Accuracy and
/// Stability of Numerical Algorithms", 2nd ed., §4.2), and the windows'
/// sums are compensated, so the bound holds whatever n is. With k = 16
/// per lane and window (the samples) the sum is within about 17u; with
/// k = 256 (M₂, whose terms (x − m)² are each within about 3u of exact)
/// within about 260u ≈ 3e-14 relative, ten orders of magnitude below the
/// statistical error of any variance estimate. Measured in one run
/// against a Neumaier step per term (light-sampled sphere, whole
/// estimate, medians of 5–7 seeds, 2²⁴ samples, AVX-512): the plain M₂
/// made it 6 % (f64) and 10 % (f32) faster, and the plain sum of the
/// samples a further 4 % (f64) and 6.5 % (f32), once whole windows ran
/// with a fixed trip count (with the partial-window loop for every window
/// the f32 gain was 2–4 %). The result is only claimed for f(x) ≥ 0:
/// [`Estimate::from_values`] sums samples with a negative one compensated
/// ([`lane_sums`]).
#[inline(always)]
fn window_sums<const ALL_FINITE: bool, const SCAN: bool, const WINDOW: usize>(
    values: &[f64],
    f: impl Fn(f64) -> f64,
) -> (NeumaierSum, Scan) {
    const LANES: usize = SUM_LANES;
    const { assert!(WINDOW.is_multiple_of(LANES)) };
    let finite = |x: f64| ALL_FINITE || x.is_finite();
    let term = |x: f64| if finite(x) { f(x) } else { 0.0 };
    // The lanes' compensated totals as two arrays, added to lane by lane
    // like the window sums (an array of `NeumaierSum`s led the compiler to
    // split the window loop into 4-, 2-, 8- and 1-wide pieces, which
    // took back most of the gain).
    let (mut totals, mut compensations) = ([0.0f64; LANES], [0.0f64; LANES]);
    let mut nonzero = [0u64; LANES];
    let (mut min, mut max) = ([f64::INFINITY; LANES], [f64::NEG_INFINITY; LANES]);
    let mut step = |s: &mut [f64; LANES], j: usize, x: f64| {
        s[j] += term(x);
        if SCAN {
            nonzero[j] += u64::from(finite(x) && x != 0.0);
            if ALL_FINITE {
                // f64::min and max, not selects that keep the old value:
                // the compiler turned those into conditional stores, and
                // on AVX2, whose sixteen registers do not hold these
                // lanes, into masked stores (`vmaskmovpd`, microcoded on
                // AMD: a fifth of an estimate's time on a Zen 2 host).
                // With no NaN the two agree but for the sign of a zero,
                // which the scan's readers ignore (`from_values`: an
                // equality, a comparison with 0, a constant plus 0).
                min[j] = min[j].min(x);
                max[j] = max[j].max(x);
            } else {
                // A non-finite x is never taken.
                min[j] = if finite(x) && x < min[j] { x } else { min[j] };
                max[j] = if finite(x) && x > max[j] { x } else { max[j] };
            }
        }
    };
    let mut close = |s: &[f64; LANES]| {
        for j in 0..LANES {
            let mut total = NeumaierSum::from_parts(totals[j], compensations[j]);
            total.add(s[j]);
            (totals[j], compensations[j]) = total.parts();
        }
    };
    // Whole windows apart from the last, partial one: a fixed trip count
    // the compiler unrolls, with the scan's lanes kept in registers.
    let (windows, last) = values.as_chunks::<WINDOW>();
    for window in windows {
        let mut s = [0.0f64; LANES];
        for block in window.as_chunks::<LANES>().0 {
            for (j, &x) in block.iter().enumerate() {
                step(&mut s, j, x);
            }
        }
        close(&s);
    }
    if !last.is_empty() {
        let mut s = [0.0f64; LANES];
        let (blocks, rest) = last.as_chunks::<LANES>();
        for block in blocks {
            for (j, &x) in block.iter().enumerate() {
                step(&mut s, j, x);
            }
        }
        for (j, &x) in rest.iter().enumerate() {
            step(&mut s, j, x);
        }
        close(&s);
    }
    let mut sum = NeumaierSum::from_parts(totals[0], compensations[0]);
    for j in 1..LANES {
        sum.merge(&NeumaierSum::from_parts(totals[j], compensations[j]));
    }
    let scan = Scan {
        nonzero: nonzero.iter().sum(),
        min: min.iter().copied().fold(f64::INFINITY, f64::min),
        max: max.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    };
    (sum, scan)
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

    /// The estimate of a block of samples held in memory, by two passes.
    /// The first sums the samples and finds their count of non-zero
    /// values, their minimum and their maximum; the second sums
    /// M₂ = Σ(x − m)² about the mean. Both sum in 16 lanes
    /// (value i in lane i mod 16) with plain adds in windows whose lane
    /// sums are compensated: windows of 256 values for the samples, which
    /// keeps non-negative ones within about 17u relative (u = 2⁻⁵³), and
    /// of 4096 for M₂, within about 260u (`window_sums` derives the
    /// bounds). Samples of which one is negative are summed with a
    /// compensated (Neumaier) step per value instead, since their sum may
    /// cancel; samples that are all equal give the exact block of
    /// [`push_n`](Estimate::push_n) (mean x, M₂ = 0), so a zero-variance
    /// integrand keeps its exact mean. Two passes cost a fraction of a
    /// push per sample (whose Welford update is accurate to a few u), so
    /// the estimators fill a chunk's values in a buffer and summarise it
    /// here; the result merges like any other estimate. Non-finite values
    /// are counted in [`non_finite`](Estimate::non_finite), non-zero ones
    /// in [`nonzero`](Estimate::nonzero).
    ///
    /// ```
    /// use lambert_estimator::statistics::Estimate;
    /// let e = Estimate::from_values(&[0.1; 5000]);
    /// assert_eq!((e.mean(), e.variance()), (Some(0.1), Some(0.0)));
    /// let e = Estimate::from_values(&[1.0, 2.0, f64::NAN, 4.0]);
    /// assert_eq!((e.n(), e.non_finite(), e.mean()), (3, 1, None));
    /// ```
    #[inline(always)]
    pub fn from_values(values: &[f64]) -> Estimate {
        // The usual case, every value finite, takes one pass for the sum
        // and the scan. A NaN or ±∞ makes its lane's sum non-finite for
        // good (NaN + x = NaN, ∞ + x is ∞ or NaN), and so the merged
        // sum: a finite sum proves every value finite, and is then what
        // the checked pass below would give, to the bit.
        let (mut sum, mut scan) = window_sums::<true, true, MEAN_WINDOW>(values, |x| x);
        let (hi, lo) = sum.parts();
        let mut n = values.len() as u64;
        if !(hi.is_finite() && lo.is_finite()) {
            n = values.iter().map(|x| u64::from(x.is_finite())).sum();
            (sum, scan) = window_sums::<false, true, MEAN_WINDOW>(values, |x| x);
        }
        let non_finite = values.len() as u64 - n;
        let all_finite = non_finite == 0;
        if n == 0 {
            return Estimate {
                non_finite,
                ..Estimate::new()
            };
        }
        if scan.min == scan.max {
            let mut constant = Estimate::new();
            // + 0: a chunk of zeros, some of them −0, has the mean +0
            // whichever zero the scan kept.
            constant.push_n(scan.min + 0.0, n);
            constant.non_finite = non_finite;
            return constant;
        }
        if scan.min < 0.0 {
            sum = if all_finite {
                lane_sums::<true>(values, |x| x)
            } else {
                lane_sums::<false>(values, |x| x)
            };
        }
        let (mean_hi, mean_lo) = split_mean(&sum, n);
        let deviation2 = |x: f64| {
            let d = (x - mean_hi) - mean_lo;
            d * d
        };
        let m2 = if all_finite {
            window_sums::<true, false, M2_WINDOW>(values, deviation2).0
        } else {
            window_sums::<false, false, M2_WINDOW>(values, deviation2).0
        };
        Estimate {
            n,
            non_finite,
            nonzero: scan.nonzero,
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
            lane_sums::<true>(&values, |x| x),
            lane_sums::<false>(&values, |x| x)
        );
        assert_eq!(
            lane_sums::<true>(&values, square),
            lane_sums::<false>(&values, square)
        );
        let mut with_inf = values.clone();
        with_inf[17] = f64::INFINITY;
        assert_ne!(
            lane_sums::<true>(&with_inf, |x| x),
            lane_sums::<false>(&with_inf, |x| x)
        );
    }

    /// The windowed plain sums of non-negative terms are within their
    /// derived bound of a compensated sum over every term, for both
    /// windows: each lane adds at most k = W / SUM_LANES terms plainly,
    /// within (k − 1)·u of their exact sum (Higham §4.2, u = 2⁻⁵³), and
    /// the compensated window totals and lane merges add about 2u; the
    /// reference (one Neumaier sum) is within 2u + n·u² of exact. So
    /// |plain − reference| ≤ (k + 2)·u·Σterms. The data spans three whole
    /// M₂ windows and a remainder, with terms over twelve orders of
    /// magnitude and zeros. Skipping a non-finite value gives the bits of
    /// a 0 there, and the unchecked form has the checked form's bits on
    /// finite values. Negative control: the same bound rejects the sum
    /// without its largest term.
    #[test]
    fn non_negative_sums_are_within_their_bound() {
        fn check<const W: usize>(values: &[f64]) {
            let square = |x: f64| x * x;
            let reference: NeumaierSum = values.iter().map(|&x| square(x)).sum();
            let reference = reference.sum();
            let u = f64::EPSILON / 2.0;
            let bound = ((W / SUM_LANES) as f64 + 2.0) * u * reference;
            let got = window_sums::<true, false, W>(values, square).0.sum();
            assert!(
                (got - reference).abs() <= bound,
                "{W}: {got} vs {reference}"
            );
            let largest = values.iter().map(|&x| square(x)).fold(0.0, f64::max);
            assert!((got - largest - reference).abs() > bound);
            let bits = |s: NeumaierSum| {
                let (s, c) = s.parts();
                (s.to_bits(), c.to_bits())
            };
            assert_eq!(
                bits(window_sums::<false, false, W>(values, square).0),
                bits(window_sums::<true, false, W>(values, square).0)
            );
            let (mut odd, mut zeroed) = (values.to_vec(), values.to_vec());
            for (at, bad) in [(5, f64::NAN), (900, f64::INFINITY), (W, f64::NAN)] {
                odd[at] = bad;
                zeroed[at] = 0.0;
            }
            assert_eq!(
                bits(window_sums::<false, false, W>(&odd, square).0),
                bits(window_sums::<true, false, W>(&zeroed, square).0)
            );
        }
        let values: Vec<f64> = (0..3 * M2_WINDOW + 37)
            .map(|i| {
                let x = ((i as f64) * 0.618_034).fract();
                if i % 7 == 0 {
                    0.0
                } else {
                    x * 10f64.powi(i as i32 % 13 - 6)
                }
            })
            .collect();
        check::<M2_WINDOW>(&values);
        check::<MEAN_WINDOW>(&values);
    }

    /// The first pass's scan (non-zero count, minimum, maximum) is the
    /// plain one over the finite values, checked or not, over several
    /// windows and a remainder; the sum it returns with is the scan-free
    /// sum's. Negative control: a scan that took the non-finite values
    /// would report −∞ and ∞.
    #[test]
    fn the_scan_counts_and_bounds_the_finite_values() {
        let values: Vec<f64> = (0..2 * M2_WINDOW + 21)
            .map(|i| match i % 5 {
                0 => 0.0,
                _ => ((i as f64) * 0.618_034).fract() - 0.25,
            })
            .collect();
        let naive = |v: &[f64]| {
            let finite = || v.iter().copied().filter(|x| x.is_finite());
            Scan {
                nonzero: finite().filter(|&x| x != 0.0).count() as u64,
                min: finite().fold(f64::INFINITY, f64::min),
                max: finite().fold(f64::NEG_INFINITY, f64::max),
            }
        };
        let want = naive(&values);
        assert!(want.min < 0.0 && want.max > 0.0 && want.nonzero < values.len() as u64);
        assert_eq!(
            window_sums::<true, true, MEAN_WINDOW>(&values, |x| x).1,
            want
        );
        assert_eq!(
            window_sums::<false, true, MEAN_WINDOW>(&values, |x| x).1,
            want
        );
        assert_eq!(
            window_sums::<true, true, MEAN_WINDOW>(&values, |x| x).0,
            window_sums::<true, false, MEAN_WINDOW>(&values, |x| x).0
        );
        let mut odd = values.clone();
        odd[3] = f64::NEG_INFINITY;
        odd[M2_WINDOW + 1] = f64::INFINITY;
        odd[2 * M2_WINDOW + 20] = f64::NAN;
        let got = window_sums::<false, true, MEAN_WINDOW>(&odd, |x| x).1;
        assert_eq!(got, naive(&odd));
        assert!(got.min > f64::NEG_INFINITY && got.max < f64::INFINITY);
    }

    /// Samples with a negative one are summed compensated, so a sum that
    /// cancels keeps its small exact part: 10¹⁶ and −10¹⁶ around ones sum
    /// exactly to the count of ones. Negative control: the plain window
    /// sum of the same samples loses the ones (1 is below half an ulp of
    /// 10¹⁶), so the rule is what keeps them.
    #[test]
    fn samples_with_a_negative_one_are_summed_compensated() {
        let values: Vec<f64> = (0..48 * 90)
            .map(|i| match i % 48 {
                0 => 1e16,
                16 => -1e16,
                _ => 1.0,
            })
            .collect();
        let ones = values.iter().filter(|&&x| x == 1.0).count() as f64;
        let e = Estimate::from_values(&values);
        assert_eq!(e.sum(), Some(ones));
        assert_eq!(e.sum, lane_sums::<true>(&values, |x| x));
        assert_ne!(
            window_sums::<true, false, MEAN_WINDOW>(&values, |x| x)
                .0
                .sum(),
            ones
        );
    }

    /// Equal samples give push_n's exact block: the mean is the value and
    /// the variance 0, with or without a non-finite sample among them.
    /// Negative control: the plain window sum of 4096 copies of 0.1 is
    /// not 409.6's nearest double, so without the rule the mean would be
    /// off and the variance not 0.
    #[test]
    fn equal_samples_give_their_value_and_no_variance() {
        for x in [0.1, 1.0 / 3.0, 7.0, 0.0, -2.5] {
            let mut values = vec![x; M2_WINDOW + 5];
            let e = Estimate::from_values(&values);
            assert_eq!(
                (e.mean(), e.variance(), e.n()),
                (Some(x), Some(0.0), values.len() as u64)
            );
            assert_eq!(e.nonzero(), if x == 0.0 { 0 } else { values.len() as u64 });
            values[9] = f64::NAN;
            let e = Estimate::from_values(&values);
            assert_eq!((e.non_finite(), e.n()), (1, M2_WINDOW as u64 + 4));
            assert_eq!(bits(&e), bits(&careful(&values)));
        }
        let tenths = vec![0.1; M2_WINDOW];
        let plain = window_sums::<true, false, MEAN_WINDOW>(&tenths, |x| x)
            .0
            .sum();
        assert_ne!(plain, 0.1 * M2_WINDOW as f64);
    }

    /// The statistics as `from_values` defines them, by the checked passes
    /// only: the counts first, then sums that skip non-finite values.
    fn careful(values: &[f64]) -> Estimate {
        let n = values.iter().filter(|x| x.is_finite()).count() as u64;
        let (plain, scan) = window_sums::<false, true, MEAN_WINDOW>(values, |x| x);
        if n == 0 {
            return Estimate {
                non_finite: values.len() as u64,
                ..Estimate::new()
            };
        }
        if scan.min == scan.max {
            let mut e = Estimate::new();
            e.push_n(scan.min, n);
            e.non_finite = values.len() as u64 - n;
            return e;
        }
        let sum = if scan.min < 0.0 {
            lane_sums::<false>(values, |x| x)
        } else {
            plain
        };
        let (mean_hi, mean_lo) = split_mean(&sum, n);
        let deviation2 = |x: f64| {
            let d = (x - mean_hi) - mean_lo;
            d * d
        };
        Estimate {
            n,
            non_finite: values.len() as u64 - n,
            nonzero: scan.nonzero,
            sum,
            mean_hi,
            mean_lo,
            m2: window_sums::<false, false, M2_WINDOW>(values, deviation2).0,
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
                let (fast, _) = window_sums::<true, true, MEAN_WINDOW>(&v, |x| x);
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
