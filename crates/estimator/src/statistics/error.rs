//! What can go wrong when asking for a statistic or running estimates.

use std::fmt;

/// Why a statistic could not be computed or a run could not start.
#[derive(Clone, Debug, PartialEq)]
pub enum StatisticsError {
    /// A confidence level outside the open interval (0, 1), or NaN.
    InvalidLevel(f64),
    /// The statistic needs more samples than the estimate holds.
    TooFewSamples {
        /// Samples held.
        n: u64,
        /// Samples needed.
        needed: u64,
    },
    /// A non-finite sample was pushed, or a sum overflowed: the estimate has
    /// no finite mean or variance.
    NonFinite {
        /// How many non-finite samples were pushed (0 if a sum overflowed).
        count: u64,
    },
    /// A parallel run was asked for chunks of 0 samples.
    ZeroChunkSize,
    /// A parallel run was asked for 0 threads.
    ZeroThreads,
    /// The rayon thread pool could not be built (the message of rayon's
    /// `ThreadPoolBuildError`).
    ThreadPool(String),
}

impl fmt::Display for StatisticsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StatisticsError::InvalidLevel(level) => write!(
                f,
                "confidence level {level} is not in the open interval (0, 1)"
            ),
            StatisticsError::TooFewSamples { n, needed } => {
                write!(f, "{n} sample(s) held, at least {needed} needed")
            }
            StatisticsError::NonFinite { count } => write!(
                f,
                "the estimate is not finite ({count} non-finite sample(s) pushed, or a sum overflowed)"
            ),
            StatisticsError::ZeroChunkSize => write!(f, "chunk size must be at least 1 sample"),
            StatisticsError::ZeroThreads => write!(f, "thread count must be at least 1"),
            StatisticsError::ThreadPool(msg) => write!(f, "could not build the thread pool: {msg}"),
        }
    }
}

impl std::error::Error for StatisticsError {}
