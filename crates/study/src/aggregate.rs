//! Reducing one row's M replicate estimates to its statistics.

use lambert_estimator::interval::IntervalKind;

/// What one replicate estimate contributes to its row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReplicateResult {
    /// The estimate, W/m².
    pub mean: f64,
    /// Its reported standard error.
    pub std_error: f64,
    /// Its 99 % confidence interval.
    pub ci99: (f64, f64),
    /// How the interval was formed (anything but the CLT one comes with a
    /// warning: few or no hits, few misses, a heavy tail).
    pub interval: IntervalKind,
    /// Samples whose value was not 0.
    pub hits: u64,
    /// Wall time per sample, ns.
    pub ns_per_sample: f64,
    /// Variance of one sample's estimate.
    pub sample_variance: f64,
}

/// The statistics of one row (one scene, strategy, sequence and N) over its
/// replicates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RowStats {
    /// Replicates M.
    pub replicates: usize,
    /// Mean of the M estimates.
    pub mean_estimate: f64,
    /// Mean relative error, mean over replicates of (estimate − truth)/truth
    /// (signed: a bias shows here); `None` without a reference or when the
    /// truth is 0.
    pub mean_rel_error: Option<f64>,
    /// Root mean square error √(mean (estimate − truth)²); `None` without a
    /// reference.
    pub rmse: Option<f64>,
    /// RMSE / |truth|; `None` without a reference or when the truth is 0.
    pub rel_rmse: Option<f64>,
    /// Fraction of replicates whose 99 % interval contains the truth
    /// (closed interval); `None` without a reference.
    pub coverage: Option<f64>,
    /// Samples whose value was not 0, summed over the replicates.
    pub hits: u64,
    /// Replicates whose interval was not the CLT one (it came with a
    /// warning: few or no hits, few misses, a heavy tail).
    pub warnings: usize,
    /// The median of the replicates' reported standard errors: the typical
    /// replicate's claim (robust to the one replicate of a heavy-tailed
    /// estimator that reached the tail and reports a huge σ while the
    /// others report small ones).
    pub std_error: f64,
    /// The sample standard deviation of the M estimates (`None` for
    /// M = 1): what the standard error should match.
    pub replicate_sd: Option<f64>,
    /// Mean over replicates of the variance of one sample's estimate, V.
    pub sample_variance: f64,
    /// Median over replicates of the wall time per sample, ns (T = this
    /// × 1e-9 s).
    pub ns_per_sample: f64,
    /// Efficiency ε = 1/(V·T), T in seconds per sample; `None` when V = 0
    /// (an exact estimate: infinitely efficient).
    pub efficiency: Option<f64>,
}

/// The median of a non-empty list (mean of the two middle values for an
/// even count).
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Reduces the replicates of one row against `truth` (the closed form, if
/// any). Sums are taken in replicate order, so the result is deterministic.
///
/// # Panics
/// If `replicates` is empty.
pub fn aggregate(truth: Option<f64>, replicates: &[ReplicateResult]) -> RowStats {
    assert!(!replicates.is_empty(), "a row needs at least one replicate");
    let m = replicates.len() as f64;
    let mean_estimate = replicates.iter().map(|r| r.mean).sum::<f64>() / m;
    let hits = replicates.iter().map(|r| r.hits).sum();
    let warnings = replicates
        .iter()
        .filter(|r| r.interval != IntervalKind::CentralLimit)
        .count();
    let std_error = median(&replicates.iter().map(|r| r.std_error).collect::<Vec<_>>());
    let replicate_sd = (replicates.len() > 1).then(|| {
        let ss: f64 = replicates
            .iter()
            .map(|r| (r.mean - mean_estimate) * (r.mean - mean_estimate))
            .sum();
        (ss / (m - 1.0)).sqrt()
    });
    let sample_variance = replicates.iter().map(|r| r.sample_variance).sum::<f64>() / m;
    let ns: Vec<f64> = replicates.iter().map(|r| r.ns_per_sample).collect();
    let ns_per_sample = median(&ns);
    let t = ns_per_sample * 1e-9;
    let efficiency = if sample_variance > 0.0 && t > 0.0 {
        Some(1.0 / (sample_variance * t))
    } else {
        None
    };
    let (mean_rel_error, rmse, rel_rmse, coverage) = match truth {
        None => (None, None, None, None),
        Some(truth) => {
            let mse = replicates
                .iter()
                .map(|r| (r.mean - truth) * (r.mean - truth))
                .sum::<f64>()
                / m;
            let rmse = mse.sqrt();
            let covered = replicates
                .iter()
                .filter(|r| r.ci99.0 <= truth && truth <= r.ci99.1)
                .count() as f64;
            let (rel_err, rel_rmse) = if truth != 0.0 {
                let e = replicates
                    .iter()
                    .map(|r| (r.mean - truth) / truth)
                    .sum::<f64>()
                    / m;
                (Some(e), Some(rmse / truth.abs()))
            } else {
                (None, None)
            };
            (rel_err, Some(rmse), rel_rmse, Some(covered / m))
        }
    };
    RowStats {
        replicates: replicates.len(),
        mean_estimate,
        mean_rel_error,
        rmse,
        rel_rmse,
        coverage,
        hits,
        warnings,
        std_error,
        replicate_sd,
        sample_variance,
        ns_per_sample,
        efficiency,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(mean: f64, lo: f64, hi: f64, ns: f64, v: f64) -> ReplicateResult {
        ReplicateResult {
            mean,
            std_error: 0.5,
            ci99: (lo, hi),
            interval: IntervalKind::CentralLimit,
            hits: 10,
            ns_per_sample: ns,
            sample_variance: v,
        }
    }

    #[test]
    fn hand_computed_row() {
        // Truth 2; estimates 1, 2, 3, 4 → errors −1, 0, 1, 2.
        let reps = [
            r(1.0, 0.5, 1.5, 10.0, 1.0),
            r(2.0, 1.0, 3.0, 30.0, 2.0),
            r(3.0, 1.9, 4.0, 20.0, 3.0),
            r(4.0, 3.0, 5.0, 40.0, 6.0),
        ];
        let s = aggregate(Some(2.0), &reps);
        assert_eq!(s.replicates, 4);
        assert_eq!(s.mean_estimate, 2.5);
        // mean relative error: (−0.5 + 0 + 0.5 + 1)/4 = 0.25
        assert_eq!(s.mean_rel_error, Some(0.25));
        // mse = (1 + 0 + 1 + 4)/4 = 1.5
        assert_eq!(s.rmse, Some(1.5f64.sqrt()));
        assert_eq!(s.rel_rmse, Some(1.5f64.sqrt() / 2.0));
        // the 2nd and 3rd intervals contain 2
        assert_eq!(s.coverage, Some(0.5));
        assert_eq!(s.sample_variance, 3.0);
        // median of 10, 30, 20, 40 = 25
        assert_eq!(s.ns_per_sample, 25.0);
        assert_eq!((s.hits, s.warnings, s.std_error), (40, 0, 0.5));
        // Spread of 1, 2, 3, 4 about 2.5: √(5/3).
        assert_eq!(s.replicate_sd, Some((5.0f64 / 3.0).sqrt()));
        assert!((s.efficiency.unwrap() - 1.0 / (3.0 * 25e-9)).abs() < 1e-3);
    }

    #[test]
    fn without_reference_and_exact() {
        let reps = [r(3.0, 3.0, 3.0, 5.0, 0.0), r(3.0, 3.0, 3.0, 7.0, 0.0)];
        let s = aggregate(None, &reps);
        assert_eq!(s.rmse, None);
        assert_eq!(s.coverage, None);
        assert_eq!(s.efficiency, None);
        assert_eq!(s.ns_per_sample, 6.0);
        let s = aggregate(Some(3.0), &reps);
        assert_eq!(s.rmse, Some(0.0));
        assert_eq!(s.coverage, Some(1.0));
        assert_eq!(s.mean_rel_error, Some(0.0));
    }
}
