//! Wall time of a run, per-sample cost and Monte Carlo efficiency.

use super::estimate::Estimate;
use std::time::{Duration, Instant};

/// How long a run of `samples` samples on `threads` threads took.
///
/// Costs are reported as ns/sample, and the
/// efficiency ε = 1/(V·T) (V the variance of one sample's estimate, T its
/// time; Hammersley & Handscomb 1964, §5.1, "Monte Carlo Methods"), which is
/// independent of n and the figure to compare two strategies by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Timing {
    /// Wall-clock time of the whole run.
    pub wall: Duration,
    /// Samples taken.
    pub samples: u64,
    /// Threads the run used.
    pub threads: usize,
}

impl Timing {
    /// Runs `f`, timing it with [`Instant`], and returns its result with a
    /// timing for `samples` samples on `threads` threads.
    pub fn measure<T>(samples: u64, threads: usize, f: impl FnOnce() -> T) -> (T, Timing) {
        let start = Instant::now();
        let out = f();
        let wall = start.elapsed();
        (
            out,
            Timing {
                wall,
                samples,
                threads,
            },
        )
    }

    /// Wall-clock nanoseconds per sample, `wall / samples`. `None` for 0
    /// samples.
    pub fn ns_per_sample(&self) -> Option<f64> {
        (self.samples > 0).then(|| self.wall.as_secs_f64() * 1e9 / self.samples as f64)
    }

    /// Thread-nanoseconds per sample, `wall · threads / samples`: the cost on
    /// one core, if every thread was busy throughout. `None` for 0 samples.
    pub fn thread_ns_per_sample(&self) -> Option<f64> {
        self.ns_per_sample().map(|t| t * self.threads as f64)
    }

    /// The efficiency ε = 1/(V·T) in 1/(unit² · s), V the per-sample
    /// variance s² of `estimate` and T the thread-time per sample in
    /// seconds. `None` if either is unavailable or 0.
    pub fn efficiency(&self, estimate: &Estimate) -> Option<f64> {
        let v = estimate.variance()?;
        let t = self.thread_ns_per_sample()? * 1e-9;
        let eff = 1.0 / (v * t);
        (v > 0.0 && t > 0.0 && eff.is_finite()).then_some(eff)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statistics::run_chunked_timed;

    #[test]
    fn per_sample_cost_and_efficiency() {
        let t = Timing {
            wall: Duration::from_millis(10),
            samples: 1_000_000,
            threads: 2,
        };
        assert!((t.ns_per_sample().unwrap() - 10.0).abs() < 1e-9);
        assert!((t.thread_ns_per_sample().unwrap() - 20.0).abs() < 1e-9);
        let e: Estimate = [0.0, 2.0].into_iter().collect(); // s² = 2
        assert!((t.efficiency(&e).unwrap() - 1.0 / (2.0 * 20e-9)).abs() < 1e-3);
        // Undefined cases: None.
        let none = Timing { samples: 0, ..t };
        assert_eq!(none.ns_per_sample(), None);
        assert_eq!(none.efficiency(&e), None);
        let constant: Estimate = [1.0, 1.0].into_iter().collect();
        assert_eq!(t.efficiency(&constant), None);
        assert_eq!(t.efficiency(&Estimate::new()), None);
    }

    #[test]
    fn timed_run_reports_its_samples_and_threads() {
        let r = run_chunked_timed(10_000, 1000, 2, |_, r| r.map(|i| i as f64).collect()).unwrap();
        assert_eq!(r.timing.samples, 10_000);
        assert_eq!(r.timing.threads, 2);
        assert_eq!(r.estimate.mean(), Some(4999.5));
        assert!(r.timing.ns_per_sample().unwrap() >= 0.0);
    }
}
