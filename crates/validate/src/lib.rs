//! # lambert-validate
//!
//! Pearson's chi-square goodness-of-fit test for direction samplers, the
//! catalogue of lambert's warps behind one trait ([`catalog`]) and the warp
//! suite that runs the test on every one of them ([`warp_suite`]). Another
//! renderer's test suite can depend on this crate to check its own samplers.
//!
//! A sampler draws n unit directions; the sphere (or a cap of it) is cut into
//! cells of equal solid angle; the observed count Oᵢ of each cell is compared
//! with its expected count Eᵢ = n ∫_cellᵢ p(ω) dω, the density integrated
//! numerically over the cell. Pearson's statistic
//!
//! X² = Σᵢ (Oᵢ − Eᵢ)² / Eᵢ
//!
//! is, under the null hypothesis "the samples are distributed with density
//! p", asymptotically χ² with k − 1 degrees of freedom (k the number of cells
//! after pooling), and the p-value is 1 − F_{χ²(k−1)}(X²) (K. Pearson, "On the
//! criterion that a given system of deviations from the probable …", Phil.
//! Mag. 50, 1900).
//!
//! The approach follows Wenzel Jakob's chi-square test in Mitsuba 0.5 and
//! Mitsuba 3 (`mitsuba.chi2.ChiSquareTest`, with `mi.math.chi2` for the
//! pooling): a histogram over a (cos θ, φ) grid, the pdf integrated per
//! cell, low-count cells pooled, samples in zero-density cells an immediate
//! failure, and a Šidák-corrected significance level for families of tests
//! ([`sidak_level`]). pbrt-v4 has no such test (its sampling tests compare
//! pdfs to histograms by eye-tolerances). Differences from Mitsuba 3 are
//! stated where they occur: cells of equal solid angle are measured by the
//! cancellation-free 1 − cos θ (so caps of 1e-6 rad get many rows), a
//! dedicated cap mode, an adaptive quadrature with an error target tied to
//! the sample count instead of a fixed trapezoid rule, and all low-count
//! cells pooled into one cell.
//!
//! The pieces, one per file: [`binning`] (the sphere and cap grids),
//! [`quadrature`] (adaptive integration over a rectangle),
//! [`cell_integrals`] (a density integrated over every cell of a grid),
//! [`chi_square`] (the test and its outcome) and [`power`] (the probability
//! that the test rejects a given departure, for stating a negative
//! control's power).
//!
//! ```
//! use glam::DVec3;
//! use lambert_validate::{Binning, ChiSquareTest};
//! // A uniform sphere sampler (a tiny low-discrepancy one, for the example).
//! let n = 20_000u64;
//! let sample = |i: u64| {
//!     let u0 = (i as f64 + 0.5) / n as f64;
//!     let u1 = (i as f64 * 0.618_033_988_749_894_9).fract();
//!     let z = 1.0 - 2.0 * u0;
//!     let r = (1.0 - z * z).max(0.0).sqrt();
//!     let phi = 2.0 * std::f64::consts::PI * u1;
//!     DVec3::new(r * phi.cos(), r * phi.sin(), z)
//! };
//! let pdf = |_w: DVec3| 1.0 / (4.0 * std::f64::consts::PI);
//! let outcome = ChiSquareTest::new(Binning::Sphere { theta_bins: 10, phi_bins: 20 })
//!     .samples(n)
//!     .significance(0.01)
//!     .run(sample, pdf)
//!     .unwrap();
//! assert!((outcome.pdf_integral - 1.0).abs() < 1e-12);
//! assert!(outcome.passed(), "{outcome}");
//! ```

pub mod binning;
pub mod catalog;
pub mod cell_integrals;
pub mod chi_square;
pub mod power;
pub mod quadrature;
pub mod warp_suite;

pub use binning::{Binning, Cell, Grid};
pub use cell_integrals::{integrate_cells, CellIntegrals, Smoothness};
pub use chi_square::{sidak_level, ChiSquareOutcome, ChiSquareTest, ImmediateFailure};
pub use power::{chi_square_power, critical_value, noncentral_chi_square_sf, noncentrality};
pub use quadrature::{integrate_rectangle, Integral};

use std::fmt;

/// A chi-square test configured with values it cannot run with; nothing was
/// sampled. Each variant names the offending field and value.
#[derive(Clone, Debug, PartialEq)]
pub enum ChiSquareError {
    /// A binning or test parameter outside its valid range.
    OutOfRange {
        /// The parameter's name.
        field: &'static str,
        /// Its value (counts are converted to f64).
        value: f64,
        /// The valid range, in words.
        range: &'static str,
    },
    /// The cap axis is not a finite unit vector (to 1e-6).
    AxisNotUnit {
        /// The axis given.
        axis: glam::DVec3,
    },
}

impl fmt::Display for ChiSquareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ChiSquareError::OutOfRange {
                field,
                value,
                range,
            } => {
                write!(f, "chi-square test: `{field}` = {value} is outside {range}")
            }
            ChiSquareError::AxisNotUnit { axis } => write!(
                f,
                "chi-square test: cap axis {axis} is not a finite unit vector (|axis| = {})",
                axis.length()
            ),
        }
    }
}

impl std::error::Error for ChiSquareError {}
