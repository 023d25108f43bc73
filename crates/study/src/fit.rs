//! The convergence slope: least squares of ln RMSE against ln N.

/// A fitted line ln y = intercept + slope · ln N.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LogLogFit {
    /// Every error is 0: the estimator is exact.
    Exact,
    /// Fewer than two points with a positive error: nothing to fit.
    TooFewPoints,
    /// The least-squares line.
    Line {
        /// Slope d ln y / d ln N.
        slope: f64,
        /// Standard error of the slope, √(s²/Sxx) with s² the residual
        /// variance on n − 2 degrees of freedom (0 for two points).
        slope_se: f64,
        /// Intercept at ln N = 0.
        intercept: f64,
        /// Points used.
        points: usize,
    },
}

impl LogLogFit {
    /// The fitted y at `n` (None unless a line).
    pub fn predict(&self, n: f64) -> Option<f64> {
        match *self {
            LogLogFit::Line {
                slope, intercept, ..
            } => Some((intercept + slope * n.ln()).exp()),
            _ => None,
        }
    }

    /// The N at which the fitted y reaches `target` (None unless a line
    /// with a negative slope).
    pub fn n_for(&self, target: f64) -> Option<f64> {
        match *self {
            LogLogFit::Line {
                slope, intercept, ..
            } if slope < 0.0 => Some(((target.ln() - intercept) / slope).exp()),
            _ => None,
        }
    }
}

/// Fits ln y = a + b ln n by ordinary least squares over the points with
/// y > 0 (points with y = 0, exact at that N, carry no slope information);
/// [`LogLogFit::Exact`] when every y is 0.
pub fn fit_loglog(points: &[(f64, f64)]) -> LogLogFit {
    if !points.is_empty() && points.iter().all(|&(_, y)| y == 0.0) {
        return LogLogFit::Exact;
    }
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|&&(n, y)| y > 0.0 && y.is_finite() && n > 0.0)
        .map(|&(n, y)| (n.ln(), y.ln()))
        .collect();
    let k = xy.len();
    if k < 2 {
        return LogLogFit::TooFewPoints;
    }
    let kf = k as f64;
    let mx = xy.iter().map(|p| p.0).sum::<f64>() / kf;
    let my = xy.iter().map(|p| p.1).sum::<f64>() / kf;
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx <= 0.0 {
        return LogLogFit::TooFewPoints;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let slope_se = if k > 2 {
        let ssr: f64 = xy
            .iter()
            .map(|p| {
                let r = p.1 - (intercept + slope * p.0);
                r * r
            })
            .sum();
        (ssr / (kf - 2.0) / sxx).sqrt()
    } else {
        0.0
    };
    LogLogFit::Line {
        slope,
        slope_se,
        intercept,
        points: k,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_half_power_line() {
        let pts: Vec<(f64, f64)> = (0..12)
            .map(|k| {
                let n = f64::from(1u32 << k);
                (n, 3.0 / n.sqrt())
            })
            .collect();
        match fit_loglog(&pts) {
            LogLogFit::Line {
                slope,
                slope_se,
                intercept,
                points,
            } => {
                assert!((slope + 0.5).abs() < 1e-12, "{slope}");
                assert!(slope_se < 1e-12, "{slope_se}");
                assert!((intercept - 3f64.ln()).abs() < 1e-12);
                assert_eq!(points, 12);
            }
            other => panic!("{other:?}"),
        }
        let fit = fit_loglog(&pts);
        // 3/√N = 0.003 at N = 1e6.
        assert!((fit.n_for(0.003).unwrap() / 1e6 - 1.0).abs() < 1e-9);
    }

    #[test]
    fn zeros_skipped_exact_and_noise() {
        assert_eq!(fit_loglog(&[(1.0, 0.0), (2.0, 0.0)]), LogLogFit::Exact);
        assert_eq!(
            fit_loglog(&[(1.0, 0.0), (2.0, 1.0)]),
            LogLogFit::TooFewPoints
        );
        let with_zero = fit_loglog(&[(1.0, 1.0), (2.0, 0.0), (4.0, 0.25), (16.0, 1.0 / 16.0)]);
        match with_zero {
            LogLogFit::Line { slope, points, .. } => {
                assert!((slope + 1.0).abs() < 1e-12);
                assert_eq!(points, 3);
            }
            other => panic!("{other:?}"),
        }
        // Hand-computed: x = ln(1, e, e²) = 0, 1, 2 after scaling; y = 0, 1, 1
        // → slope 0.5, residuals −1/6, 1/3, −1/6, s² = (1/36+1/9+1/36)/1 = 1/6,
        // Sxx = 2, se = √(1/12).
        let e = std::f64::consts::E;
        match fit_loglog(&[(1.0, 1.0), (e, e), (e * e, e)]) {
            LogLogFit::Line {
                slope, slope_se, ..
            } => {
                assert!((slope - 0.5).abs() < 1e-12);
                assert!((slope_se - (1.0f64 / 12.0).sqrt()).abs() < 1e-12);
            }
            other => panic!("{other:?}"),
        }
    }
}
