//! The chi-square test itself: histogram, expected counts, pooling,
//! statistic, p-value, and a report that says why a test failed.
//!
//! # Procedure
//! 1. Draw n directions `sample(i)`, i = 0 … n−1, and count them per cell of
//!    the [`Grid`]. A non-finite direction, or one whose length differs from
//!    1 by more than [`UNIT_TOLERANCE`], is an immediate failure.
//! 2. Expected counts Eᵢ = n ∫_cellᵢ p(ω) dω, integrated in the cell's
//!    (t = 1 − cos θ, φ) coordinates, where dω = dt dφ exactly, by the
//!    adaptive quadrature of [`super::quadrature`] with an absolute error
//!    target of [`QUADRATURE_RELATIVE_TOLERANCE`]·√max(Eᵢ, 1) = 1e-3·√max(Eᵢ, 1)
//!    counts per cell, at most [`QUADRATURE_MAX_SPLITS`] = 2¹⁴ splits per
//!    cell (why these values: [`QUADRATURE_RELATIVE_TOLERANCE`]). The
//!    outside cell of a cap is integrated over bands 1 − cos θ ∈ [2ᵏh, 2ᵏ⁺¹h]
//!    (so densities concentrated just outside a tiny cap are resolved), with
//!    the same total error target ([`crate::cell_integrals`]). A negative or
//!    NaN pdf value is an immediate failure.
//! 3. A cell with Eᵢ = 0 and Oᵢ = 0 is ignored; Eᵢ = 0 and Oᵢ > 0 is an
//!    immediate failure (a sample where the density says none can be).
//! 4. Cells with 0 < Eᵢ < [`POOL_THRESHOLD`] (= 5, the usual rule for the χ²
//!    approximation) are pooled into one cell (observed and expected counts
//!    added). If that pooled cell still has E < 5 it is merged into the
//!    regular cell of smallest E. Mitsuba 3 (`mi.math.chi2`) instead sorts
//!    the low cells by E and pools them into consecutive groups that each
//!    reach the threshold; one pooled cell is simpler and costs at most a
//!    few degrees of freedom.
//! 5. X² = Σ (Oᵢ − Eᵢ)²/Eᵢ over the k cells left, dof = k − 1 (dof < 1 is an
//!    immediate failure), p = 1 − F_{χ²(dof)}(X²), computed as statrs'
//!    survival function `sf` (the same quantity without the cancellation of
//!    1 − F near p = 0). The test passes when there is no immediate failure
//!    and p ≥ α.

use crate::binning::{Binning, Cell, Grid};
use crate::cell_integrals::{integrand, integrate_cell, Smoothness};
use crate::quadrature::{neumaier_sum, INITIAL_SPLIT};
use crate::ChiSquareError;
use glam::DVec3;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::fmt::{self, Write as _};

/// Cells whose expected count is below this are pooled (the common rule of
/// thumb for the χ² approximation; Mitsuba 3 uses the same 5).
pub const POOL_THRESHOLD: f64 = 5.0;

/// A sample whose length differs from 1 by more than this is rejected as
/// not a unit direction. Loose enough for f32 samplers widened to f64
/// (their unit vectors are off by a few 1e-7).
pub const UNIT_TOLERANCE: f64 = 1e-5;

/// The quadrature's target c: expected-count error δᵢ ≤ c·√max(Eᵢ, 1) in
/// every cell; c = 1e-3.
///
/// Why this value. Errors δᵢ in the expected counts make X² noncentral,
/// with noncentrality λ = Σ δᵢ²/Eᵢ ≤ c²k over k cells, and raise the
/// probability of rejecting a correct sampler at the critical value x_α from
/// α to P(χ²′(k − 1, λ) > x_α) — to first order by λ·f_{χ²(k+1)}(x_α)
/// (f the χ² density), relative to α about c²·z_α·√(k/2), z_α the normal
/// quantile of α. The test's stated level is only its level if that is
/// small. With c = 1e-3 the exact noncentral tail exceeds α by at most
/// 9.8e-4·α for every grid up to 2¹⁶ cells and every α ≥ 1e-7 (5e-5·α on
/// the suites' 257-cell caps at their Šidák level); with c = 0.02, as this
/// constant once was, by 3 % on a 20 × 40 sphere grid, 6.5 % on 40 × 80 and
/// 32 % on 2¹⁶ cells at α = 1.7e-4 (`tests/chi_square.rs`,
/// `the_quadrature_target_keeps_the_stated_level`). The price is paid only
/// by densities with a jump inside a cell (smooth densities, and jumps on
/// cell edges, converge on the first level; see [`crate::quadrature`]),
/// whose cost grows like 1/c.
pub const QUADRATURE_RELATIVE_TOLERANCE: f64 = 1e-3;

/// Split budget of the quadrature per cell (each split is 292 pdf calls).
/// A cell whose error estimate has not reached the target within it is
/// reported ([`ChiSquareOutcome::unconverged_cells`]). The estimate is
/// conservative: where a uniform cone's rim crosses the cells of a sphere
/// grid, cells still "unconverged" after 2¹⁴ splits are measured within
/// 1/40 of the target against exact cell probabilities
/// (`quadrature_meets_its_documented_target_across_a_jump`).
pub const QUADRATURE_MAX_SPLITS: usize = 1 << 14;

/// A cell whose quadrature found no density although samples landed in it
/// is integrated again from this finer start (a 64 × 64 split), which finds
/// features down to 1/4096 of the cell (a light's corner clipped by a cell)
/// before the samples are declared to be in a zero-density cell. The
/// outside cell of a cap, already made of r regions (bands × sectors),
/// shares those 4096 starting regions among them (a ⌈64/√r⌉ split each):
/// it is as finely searched for its size, without the ~10⁸ evaluations a
/// 64 × 64 start in each of its ~300 regions would cost a tiny cap whose
/// sampler strays outside it.
pub const QUADRATURE_RESCUE_SPLIT: usize = 64;

/// Environment variable: when set (to anything but `0`),
/// [`ChiSquareOutcome::assert_passed`] includes the full [`ChiSquareOutcome::table`]
/// in its panic message.
pub const TABLE_ENV_VAR: &str = "LAMBERT_CHI2_TABLE";

/// The per-test significance level that gives a family of `m` independent
/// tests the family-wise level `family_alpha` (Šidák 1967):
///
/// α₁ = 1 − (1 − α)^(1/m),
///
/// computed as −expm1(ln(1 − α)/m) to keep precision for small α. Mitsuba 3's
/// `ChiSquareTest.run(significance_level, test_count)` applies the same
/// correction. `m = 0` is treated as 1; α outside [0, 1] gives NaN.
pub fn sidak_level(family_alpha: f64, m: usize) -> f64 {
    if !(0.0..=1.0).contains(&family_alpha) {
        return f64::NAN;
    }
    -((-family_alpha).ln_1p() / m.max(1) as f64).exp_m1()
}

/// A chi-square goodness-of-fit test of a direction sampler against its
/// claimed density per steradian (see the [module docs](self) for the
/// procedure and [`super`] for the sources).
///
/// ```
/// use glam::DVec3;
/// use lambert_validate::{Binning, ChiSquareTest};
/// let test = ChiSquareTest::new(Binning::Sphere { theta_bins: 8, phi_bins: 16 })
///     .samples(10_000)
///     .significance(0.01);
/// // A sampler that always returns +z, judged against the uniform sphere.
/// let outcome = test.run(|_| DVec3::Z, |_| 0.25 / std::f64::consts::PI).unwrap();
/// assert!(!outcome.passed());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChiSquareTest {
    binning: Binning,
    samples: u64,
    significance: f64,
}

impl ChiSquareTest {
    /// A test on `binning` with the defaults n = 1 000 000 samples and
    /// α = 0.01. Parameters are validated by [`ChiSquareTest::run`].
    pub fn new(binning: Binning) -> Self {
        ChiSquareTest {
            binning,
            samples: 1_000_000,
            significance: 0.01,
        }
    }

    /// Sets the number of samples n (≥ 1, ≤ 2⁵³).
    pub fn samples(mut self, n: u64) -> Self {
        self.samples = n;
        self
    }

    /// Sets the significance level α ∈ (0, 1) of this one test (use
    /// [`sidak_level`] for a test that is one of a family).
    pub fn significance(mut self, alpha: f64) -> Self {
        self.significance = alpha;
        self
    }

    /// The binning.
    pub fn binning(&self) -> Binning {
        self.binning
    }

    /// Runs the test: draws `sample(i)` for i = 0 … n−1 (unit directions;
    /// deterministic if the caller seeds its generator), and judges them
    /// against `pdf(ω)`, the claimed density per steradian (finite, ≥ 0).
    ///
    /// Errors only on an invalid configuration, before sampling; a sampler
    /// or pdf that misbehaves gives an outcome that does not pass, with the
    /// reason in [`ChiSquareOutcome::failure`].
    pub fn run<S, P>(&self, mut sample: S, mut pdf: P) -> Result<ChiSquareOutcome, ChiSquareError>
    where
        S: FnMut(u64) -> DVec3,
        P: FnMut(DVec3) -> f64,
    {
        let grid = Grid::new(&self.binning)?;
        self.check_parameters()?;
        let n = self.samples;

        // 1. Histogram.
        let mut observed = vec![0u64; grid.cell_count()];
        let mut invalid: Option<(u64, DVec3)> = None;
        let mut invalid_count = 0u64;
        for i in 0..n {
            let w = sample(i);
            if w.is_finite() && (w.length() - 1.0).abs() <= UNIT_TOLERANCE {
                observed[grid.locate(w)] += 1;
            } else {
                invalid_count += 1;
                invalid.get_or_insert((i, w));
            }
        }

        // 2. Expected counts.
        let nf = n as f64;
        let mut bad_pdf: Option<(DVec3, f64)> = None;
        let mut integrand = integrand(&grid, &mut pdf, &mut bad_pdf);
        let mut expected = vec![0.0f64; grid.cell_count()];
        let mut probabilities = Vec::with_capacity(grid.cell_count());
        let mut quadrature_error = 0.0;
        let mut unconverged_cells = 0usize;
        let mut evaluations = 0u64;
        let tolerance = |p: f64| QUADRATURE_RELATIVE_TOLERANCE * (nf * p).max(1.0).sqrt() / nf;
        for (index, e) in expected.iter_mut().enumerate() {
            let mut integrate = |start: usize| {
                integrate_cell(
                    &grid,
                    index,
                    &mut integrand,
                    &tolerance,
                    QUADRATURE_MAX_SPLITS,
                    start,
                    Smoothness::MayJump,
                )
            };
            let mut result = integrate(INITIAL_SPLIT);
            if result.value == 0.0 && observed[index] > 0 {
                let first = result.evaluations;
                result = integrate(QUADRATURE_RESCUE_SPLIT);
                result.evaluations += first;
            }
            quadrature_error += result.error;
            evaluations += result.evaluations;
            unconverged_cells += usize::from(!result.converged);
            probabilities.push(result.value);
            *e = nf * result.value;
        }
        drop(integrand);
        let pdf_integral = neumaier_sum(probabilities);
        let invalid = invalid.map(|(index, direction)| ImmediateFailure::InvalidDirection {
            index,
            direction,
            count: invalid_count,
        });
        let bad_pdf =
            bad_pdf.map(|(direction, value)| ImmediateFailure::InvalidPdf { direction, value });
        Ok(self.finish(
            Some(grid),
            observed,
            expected,
            invalid.or(bad_pdf),
            Quadrature {
                pdf_integral,
                error: quadrature_error,
                unconverged_cells,
                evaluations,
            },
        ))
    }

    /// The chi-square test over a partition the caller supplies: cell k has
    /// probability `probabilities[k]` under the null hypothesis, and
    /// `sample_cell(i)` draws sample i and says which cell it fell in
    /// (`None`: in no cell, an immediate failure).
    ///
    /// This is the mode for densities with sharp supports, such as uniform
    /// densities on spherical polygons: a partition of the support itself
    /// (sub-triangles of a triangle, sub-rectangles of a rectangle, rings
    /// and sectors of a disk) has exact cell probabilities from closed-form
    /// solid angles or areas, where equal-solid-angle cells would cut the
    /// support's edges and leave the quadrature an indicator function to
    /// integrate. Pooling, the statistic and the verdict are as in
    /// [`ChiSquareTest::run`]; the binning set on the test is not used.
    ///
    /// Errors when a probability is negative or not finite, or when they
    /// do not sum to 1 within 1e-9 (nothing is sampled then).
    pub fn run_partition<S>(
        &self,
        probabilities: &[f64],
        mut sample_cell: S,
    ) -> Result<ChiSquareOutcome, ChiSquareError>
    where
        S: FnMut(u64) -> Option<usize>,
    {
        self.check_parameters()?;
        for &p in probabilities {
            if !(p.is_finite() && p >= 0.0) {
                return Err(ChiSquareError::OutOfRange {
                    field: "probabilities",
                    value: p,
                    range: "[0, ∞) and finite",
                });
            }
        }
        let total = neumaier_sum(probabilities.iter().copied());
        if !((total - 1.0).abs() <= 1e-9) {
            return Err(ChiSquareError::OutOfRange {
                field: "sum of probabilities",
                value: total,
                range: "1 ± 1e-9",
            });
        }
        let n = self.samples;
        let mut observed = vec![0u64; probabilities.len()];
        let (mut outside, mut outside_count) = (None, 0u64);
        for i in 0..n {
            match sample_cell(i) {
                Some(k) if k < observed.len() => observed[k] += 1,
                _ => {
                    outside_count += 1;
                    outside.get_or_insert(i);
                }
            }
        }
        let expected = probabilities.iter().map(|p| p * n as f64).collect();
        let failure = outside.map(|index| ImmediateFailure::OutsidePartition {
            index,
            count: outside_count,
        });
        Ok(self.finish(
            None,
            observed,
            expected,
            failure,
            Quadrature {
                pdf_integral: total,
                error: 0.0,
                unconverged_cells: 0,
                evaluations: 0,
            },
        ))
    }

    /// Validates the sample count and the significance level.
    fn check_parameters(&self) -> Result<(), ChiSquareError> {
        if !(1..=1u64 << 53).contains(&self.samples) {
            return Err(ChiSquareError::OutOfRange {
                field: "samples",
                value: self.samples as f64,
                range: "[1, 2^53]",
            });
        }
        if !(self.significance > 0.0 && self.significance < 1.0) {
            return Err(ChiSquareError::OutOfRange {
                field: "significance",
                value: self.significance,
                range: "(0, 1)",
            });
        }
        Ok(())
    }

    /// Pools, computes the statistic and the verdict (steps 3–5).
    fn finish(
        &self,
        grid: Option<Grid>,
        observed: Vec<u64>,
        expected: Vec<f64>,
        earlier_failure: Option<ImmediateFailure>,
        quadrature: Quadrature,
    ) -> ChiSquareOutcome {
        let n = self.samples;
        let cell_of = |index: usize| match &grid {
            Some(g) => g.cell(index),
            None => Cell::Part { index },
        };

        // 3.–5. Zero cells, pooling, statistic.
        let mut zero_pdf: Option<(usize, u64)> = None;
        let (mut zero_pdf_cells, mut zero_pdf_samples) = (0usize, 0u64);
        let mut regular: Vec<(f64, f64)> = Vec::new();
        let (mut pooled_o, mut pooled_e, mut pooled_cells) = (0.0f64, 0.0f64, 0usize);
        for (index, (&o, &e)) in observed.iter().zip(&expected).enumerate() {
            if e == 0.0 {
                if o > 0 {
                    zero_pdf.get_or_insert((index, o));
                    zero_pdf_cells += 1;
                    zero_pdf_samples += o;
                }
            } else if e < POOL_THRESHOLD {
                pooled_o += o as f64;
                pooled_e += e;
                pooled_cells += 1;
            } else {
                regular.push((o as f64, e));
            }
        }
        let mut pooled_merged = false;
        if pooled_cells > 0 {
            if pooled_e >= POOL_THRESHOLD || regular.is_empty() {
                regular.push((pooled_o, pooled_e));
            } else {
                let smallest = (0..regular.len())
                    .min_by(|&a, &b| regular[a].1.total_cmp(&regular[b].1))
                    .unwrap_or(0);
                regular[smallest].0 += pooled_o;
                regular[smallest].1 += pooled_e;
                pooled_merged = true;
            }
        }
        let statistic = neumaier_sum(regular.iter().map(|&(o, e)| (o - e) * (o - e) / e));
        let degrees_of_freedom = regular.len().saturating_sub(1);
        let p_value = match ChiSquared::new(degrees_of_freedom as f64) {
            Ok(d) if degrees_of_freedom >= 1 && statistic.is_finite() => d.sf(statistic),
            _ => 0.0,
        };

        let failure = if earlier_failure.is_some() {
            earlier_failure
        } else if let Some((index, observed)) = zero_pdf {
            Some(ImmediateFailure::SamplesInZeroPdfCell {
                index,
                cell: cell_of(index),
                observed,
                cells: zero_pdf_cells,
                samples: zero_pdf_samples,
            })
        } else if degrees_of_freedom < 1 {
            Some(ImmediateFailure::TooFewDegreesOfFreedom {
                cells: regular.len(),
            })
        } else {
            None
        };

        ChiSquareOutcome {
            statistic,
            degrees_of_freedom,
            p_value,
            significance: self.significance,
            samples: n,
            pdf_integral: quadrature.pdf_integral,
            quadrature_error: quadrature.error,
            unconverged_cells: quadrature.unconverged_cells,
            pdf_evaluations: quadrature.evaluations,
            pooled_cells,
            pooled_expected: pooled_e,
            pooled_observed: pooled_o as u64,
            pooled_merged,
            failure,
            grid,
            observed,
            expected,
        }
    }
}

/// Why a test failed regardless of its statistic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ImmediateFailure {
    /// The sampler returned a non-finite direction or one not of unit length
    /// (to [`UNIT_TOLERANCE`]); such samples are not binned.
    InvalidDirection {
        /// Index of the first such sample.
        index: u64,
        /// The first such direction.
        direction: DVec3,
        /// How many samples were invalid.
        count: u64,
    },
    /// The pdf returned a negative or non-finite value (treated as 0).
    InvalidPdf {
        /// The first direction where it did.
        direction: DVec3,
        /// The value it returned.
        value: f64,
    },
    /// Samples fell in a cell where the integrated pdf is exactly 0.
    SamplesInZeroPdfCell {
        /// Flat index of the first such cell.
        index: usize,
        /// The first such cell.
        cell: Cell,
        /// Samples in that cell.
        observed: u64,
        /// Number of such cells.
        cells: usize,
        /// Samples in all such cells.
        samples: u64,
    },
    /// Samples fell in no cell of a caller-supplied partition.
    OutsidePartition {
        /// Index of the first such sample.
        index: u64,
        /// How many samples did.
        count: u64,
    },
    /// Fewer than 2 cells were left after pooling (dof < 1).
    TooFewDegreesOfFreedom {
        /// Cells left after pooling.
        cells: usize,
    },
}

impl fmt::Display for ImmediateFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ImmediateFailure::InvalidDirection { index, direction, count } => write!(
                f,
                "{count} sample(s) not finite unit directions; first: sample {index} = {direction} (|w| = {})",
                direction.length()
            ),
            ImmediateFailure::InvalidPdf { direction, value } => {
                write!(f, "pdf({direction}) = {value}: a pdf must be finite and ≥ 0")
            }
            ImmediateFailure::SamplesInZeroPdfCell { index, cell, observed, cells, samples } => write!(
                f,
                "{samples} sample(s) in {cells} cell(s) where the integrated pdf is 0; first: cell {index}, {cell}, with {observed} sample(s)"
            ),
            ImmediateFailure::OutsidePartition { index, count } => write!(
                f,
                "{count} sample(s) outside every cell of the partition; first: sample {index}"
            ),
            ImmediateFailure::TooFewDegreesOfFreedom { cells } => write!(
                f,
                "only {cells} cell(s) after pooling: no degrees of freedom (use more samples or fewer cells)"
            ),
        }
    }
}

/// The result of [`ChiSquareTest::run`].
#[derive(Clone, Debug)]
pub struct ChiSquareOutcome {
    /// Pearson's X² = Σ (O − E)²/E over the cells after pooling.
    pub statistic: f64,
    /// k − 1, k the number of cells after pooling.
    pub degrees_of_freedom: usize,
    /// 1 − F_{χ²(dof)}(X²); 0 if dof < 1.
    pub p_value: f64,
    /// The significance level α the p-value is compared with.
    pub significance: f64,
    /// n, the number of samples drawn.
    pub samples: u64,
    /// ∫ pdf dω over the whole sphere (cells plus outside), by quadrature:
    /// 1 for a normalised density, to about `quadrature_error`.
    pub pdf_integral: f64,
    /// The quadrature's estimated absolute error on `pdf_integral`.
    pub quadrature_error: f64,
    /// Cells whose quadrature hit its split budget before its tolerance.
    pub unconverged_cells: usize,
    /// Number of pdf evaluations the quadrature made.
    pub pdf_evaluations: u64,
    /// Number of cells with 0 < E < 5 that were pooled.
    pub pooled_cells: usize,
    /// Expected count of the pooled cell.
    pub pooled_expected: f64,
    /// Observed count of the pooled cell.
    pub pooled_observed: u64,
    /// Whether the pooled cell (E < 5) was merged into the smallest regular cell.
    pub pooled_merged: bool,
    /// Set when the test failed regardless of the statistic.
    pub failure: Option<ImmediateFailure>,
    grid: Option<Grid>,
    observed: Vec<u64>,
    expected: Vec<f64>,
}

/// What the per-cell quadrature reports, carried into the outcome.
struct Quadrature {
    pdf_integral: f64,
    error: f64,
    unconverged_cells: usize,
    evaluations: u64,
}

impl ChiSquareOutcome {
    /// No immediate failure and p ≥ α (a NaN p-value does not pass).
    pub fn passed(&self) -> bool {
        self.failure.is_none() && self.p_value >= self.significance
    }

    /// The grid the samples were binned on (`None` for a caller-supplied
    /// partition).
    pub fn grid(&self) -> Option<&Grid> {
        self.grid.as_ref()
    }

    /// Observed counts per cell (flat index, see [`Grid`]).
    pub fn observed(&self) -> &[u64] {
        &self.observed
    }

    /// Expected counts per cell, n ∫_cell pdf dω.
    pub fn expected(&self) -> &[f64] {
        &self.expected
    }

    /// Observed against expected counts, one line per cell with either
    /// nonzero, as text (for dumping when a test fails): index, cell,
    /// O, E, (O − E)²/E and a note (`pooled` for E < 5, `ZERO PDF` for
    /// samples where E = 0).
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{self}");
        let _ = writeln!(
            s,
            "{:>8}  {:<70} {:>12} {:>14} {:>12}  note",
            "index", "cell", "observed", "expected", "(O-E)^2/E"
        );
        for (i, (&o, &e)) in self.observed.iter().zip(&self.expected).enumerate() {
            if o == 0 && e == 0.0 {
                continue;
            }
            let of = o as f64;
            let (contribution, note) = if e == 0.0 {
                (f64::INFINITY, "ZERO PDF")
            } else if e < POOL_THRESHOLD {
                ((of - e) * (of - e) / e, "pooled")
            } else {
                ((of - e) * (of - e) / e, "")
            };
            let cell = match &self.grid {
                Some(g) => g.cell(i).to_string(),
                None => Cell::Part { index: i }.to_string(),
            };
            let _ = writeln!(
                s,
                "{i:>8}  {cell:<70} {o:>12} {e:>14.3} {contribution:>12.3}  {note}"
            );
        }
        if self.pooled_cells > 0 {
            let _ = writeln!(
                s,
                "pooled cell: {} cells, observed {}, expected {:.3}{}",
                self.pooled_cells,
                self.pooled_observed,
                self.pooled_expected,
                if self.pooled_merged {
                    " (merged into the smallest regular cell)"
                } else {
                    ""
                }
            );
        }
        s
    }

    /// Panics with the summary, and with the full [`table`](Self::table) if
    /// the environment variable [`TABLE_ENV_VAR`] (`LAMBERT_CHI2_TABLE`) is
    /// set, unless the test passed.
    pub fn assert_passed(&self) {
        if self.passed() {
            return;
        }
        let want_table = std::env::var(TABLE_ENV_VAR).is_ok_and(|v| v != "0");
        if want_table {
            panic!("chi-square test failed\n{}", self.table());
        }
        panic!("chi-square test failed: {self}\n(set {TABLE_ENV_VAR}=1 for the per-cell table)");
    }
}

impl fmt::Display for ChiSquareOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: X² = {:.3}, dof = {}, p = {:.4e}, α = {:.4e}, n = {}, ∫pdf dω = {:.12} (±{:.1e}), pooled {} cell(s) (E = {:.2}, O = {})",
            if self.passed() { "passed" } else { "FAILED" },
            self.statistic,
            self.degrees_of_freedom,
            self.p_value,
            self.significance,
            self.samples,
            self.pdf_integral,
            self.quadrature_error,
            self.pooled_cells,
            self.pooled_expected,
            self.pooled_observed,
        )?;
        if self.unconverged_cells > 0 {
            write!(
                f,
                ", quadrature unconverged in {} cell(s)",
                self.unconverged_cells
            )?;
        }
        if let Some(failure) = &self.failure {
            write!(f, "; immediate failure: {failure}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sidak_matches_the_formula() {
        let a = sidak_level(0.01, 6);
        assert!((a - (1.0 - 0.99f64.powf(1.0 / 6.0))).abs() < 1e-15);
        assert_eq!(sidak_level(0.01, 1), 0.01);
        assert!((1.0 - (1.0 - a).powi(6) - 0.01).abs() < 1e-14);
        assert!(sidak_level(1e-12, 1000) > 0.0);
        assert!(sidak_level(-0.1, 3).is_nan());
    }

    #[test]
    fn invalid_configuration_is_an_error() {
        let b = Binning::Sphere {
            theta_bins: 4,
            phi_bins: 4,
        };
        let run = |t: ChiSquareTest| t.run(|_| DVec3::Z, |_| 0.25 / PI);
        assert!(run(ChiSquareTest::new(b).samples(0)).is_err());
        assert!(run(ChiSquareTest::new(b).significance(1.0)).is_err());
        assert!(run(ChiSquareTest::new(b).significance(f64::NAN)).is_err());
        let bad = Binning::Sphere {
            theta_bins: 0,
            phi_bins: 4,
        };
        assert!(run(ChiSquareTest::new(bad)).is_err());
    }

    #[test]
    fn bad_samples_and_pdfs_fail_immediately() {
        let b = Binning::Sphere {
            theta_bins: 4,
            phi_bins: 4,
        };
        let t = ChiSquareTest::new(b).samples(1000);
        let o = t
            .run(
                |i| if i == 7 { DVec3::NAN } else { DVec3::Z },
                |_| 0.25 / PI,
            )
            .unwrap();
        assert!(matches!(
            o.failure,
            Some(ImmediateFailure::InvalidDirection {
                index: 7,
                count: 1,
                ..
            })
        ));
        let o = t.run(|_| DVec3::new(0.0, 0.0, 1.1), |_| 0.25 / PI).unwrap();
        assert!(matches!(
            o.failure,
            Some(ImmediateFailure::InvalidDirection { count: 1000, .. })
        ));
        let o = t
            .run(|_| DVec3::Z, |w| if w.z < 0.0 { -1.0 } else { 0.5 / PI })
            .unwrap();
        assert!(matches!(
            o.failure,
            Some(ImmediateFailure::InvalidPdf { .. })
        ));
        assert!(!o.passed());
        assert!(o.to_string().contains("immediate failure"));
    }
}
