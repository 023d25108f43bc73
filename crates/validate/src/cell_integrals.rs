//! A density integrated over every cell of a [`Grid`]: the expected-count
//! side of the chi-square test, and on its own the tool that compares two
//! densities cell by cell (a warp's `pdf` against a density written
//! independently).
//!
//! Each grid cell is integrated in its (t = 1 − cos θ, φ) coordinates, where
//! dω = dt dφ exactly, by the adaptive quadrature of [`crate::quadrature`].
//! The outside cell of a cap, t ∈ [h, 2], is integrated as bands
//! t ∈ [2ᵏh, 2ᵏ⁺¹h] (the last one ending at 2) times 8 sectors of φ, so that
//! a density concentrated just outside a tiny cap is resolved; the errors of
//! its k regions add about like √k, so each gets the cell's target over √k.

use crate::binning::{Binning, Cell, Grid};
use crate::quadrature::{integrate_regions, neumaier_sum, INITIAL_SPLIT};
use crate::ChiSquareError;
use glam::DVec3;
use std::f64::consts::PI;

/// ∫ p dω over each cell of a grid, with the quadrature's bookkeeping.
#[derive(Clone, Debug, PartialEq)]
pub struct CellIntegrals {
    /// ∫_cell p dω per cell (flat index of the [`Grid`]).
    pub probabilities: Vec<f64>,
    /// The quadrature's estimated absolute error per cell.
    pub errors: Vec<f64>,
    /// Σ probabilities (compensated): ∫ p dω over the sphere.
    pub total: f64,
    /// Σ errors.
    pub error: f64,
    /// Cells whose quadrature hit its split budget before its target.
    pub unconverged_cells: usize,
    /// Number of density evaluations.
    pub evaluations: u64,
    /// The first negative or non-finite density value met (direction and
    /// value); such values are integrated as 0.
    pub invalid_pdf: Option<(DVec3, f64)>,
}

/// The regions, in (t, φ), that make up cell `index` of `grid`.
fn regions(grid: &Grid, index: usize) -> Vec<((f64, f64), (f64, f64))> {
    match grid.cell(index) {
        Cell::Grid {
            one_minus_cos, phi, ..
        } => vec![(one_minus_cos, phi)],
        Cell::Outside {
            one_minus_cos_max: h,
        } => outside_regions(h),
        Cell::Part { .. } => unreachable!("a grid has no partition cells"),
    }
}

/// The outside of a cap, t = 1 − cos θ ∈ [h, 2], as bands [2ᵏh, 2ᵏ⁺¹h]
/// (the last one ending at 2) times 8 sectors of φ.
fn outside_regions(h: f64) -> Vec<((f64, f64), (f64, f64))> {
    let mut bands = Vec::new();
    let mut t0 = h;
    while t0 < 2.0 {
        let t1 = if 2.0 * t0 >= 1.5 { 2.0 } else { 2.0 * t0 };
        bands.push((t0, t1));
        t0 = t1;
    }
    let sectors = 8;
    let mut regions = Vec::with_capacity(bands.len() * sectors);
    for band in bands {
        for s in 0..sectors {
            let phi = (
                2.0 * PI * s as f64 / sectors as f64,
                2.0 * PI * (s + 1) as f64 / sectors as f64,
            );
            regions.push((band, phi));
        }
    }
    regions
}

/// One cell's integral: (value, error, converged, evaluations).
pub(crate) struct CellIntegral {
    pub value: f64,
    pub error: f64,
    pub converged: bool,
    pub evaluations: u64,
}

/// What a density is like inside the cells it is integrated over, which
/// decides the quadrature's error check ([`crate::quadrature`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Smoothness {
    /// It may jump anywhere, also close to a cell's edge: every region is
    /// checked against a Simpson rule with nodes on its boundary, so a jump
    /// hiding between the Gauss nodes is refined (the chi-square test's
    /// choice: the claimed pdf is the unknown).
    MayJump,
    /// It is smooth inside every cell (its jumps lie on cell edges, to
    /// rounding): the Gauss rule's own two levels estimate the error, and
    /// values within rounding of an edge are never evaluated.
    Smooth,
}

/// Integrates `integrand(t, φ)` over cell `index` of `grid`, starting each
/// region from a `start` × `start` split, to the absolute target
/// `tolerance(p)` for the cell (p the current estimate of its integral),
/// with at most `max_splits` splits per region.
pub(crate) fn integrate_cell<F, T>(
    grid: &Grid,
    index: usize,
    integrand: &mut F,
    tolerance: &T,
    max_splits: usize,
    start: usize,
    smoothness: Smoothness,
) -> CellIntegral
where
    F: FnMut(f64, f64) -> f64,
    T: Fn(f64) -> f64,
{
    let regions = regions(grid, index);
    let scale = 1.0 / (regions.len() as f64).sqrt();
    // A finer start is shared among the regions of a many-region cell
    // (see `QUADRATURE_RESCUE_SPLIT`).
    let start = if start > INITIAL_SPLIT {
        ((start as f64 * scale).ceil() as usize).max(INITIAL_SPLIT)
    } else {
        start
    };
    let mut out = CellIntegral {
        value: 0.0,
        error: 0.0,
        converged: true,
        evaluations: 0,
    };
    for &(t, phi) in &regions {
        let r = integrate_regions(
            &mut *integrand,
            t,
            phi,
            |p| tolerance(p) * scale,
            max_splits,
            start,
            smoothness == Smoothness::MayJump,
        );
        out.value += r.value;
        out.error += r.error;
        out.converged &= r.converged;
        out.evaluations += r.evaluations;
    }
    out
}

/// The integrand of a density per steradian `pdf` in a grid's (t, φ)
/// coordinates; negative and non-finite values count as 0 and the first
/// is kept in `bad`.
pub(crate) fn integrand<'a, P: FnMut(DVec3) -> f64>(
    grid: &'a Grid,
    pdf: &'a mut P,
    bad: &'a mut Option<(DVec3, f64)>,
) -> impl FnMut(f64, f64) -> f64 + 'a {
    move |t: f64, phi: f64| {
        let w = grid.direction(t, phi);
        let p = pdf(w);
        if p.is_finite() && p >= 0.0 {
            p
        } else {
            bad.get_or_insert((w, p));
            0.0
        }
    }
}

/// ∫ `pdf` dω over every cell of `binning`'s grid, each to the absolute
/// error `tolerance` (a probability) with at most `max_splits` splits per
/// region (a cell that runs out is counted in
/// [`CellIntegrals::unconverged_cells`]; its error estimate stays in
/// [`CellIntegrals::errors`]), with the error check `smoothness` calls for.
///
/// ```
/// use glam::DVec3;
/// use lambert_validate::{integrate_cells, Binning, Smoothness};
/// // The cosine density: ∫ cos θ/π dω = 1, and ¾ over the first row,
/// // 1 − cos θ ∈ [0, ½] (cos θ from ½ to 1: ∫ 2 cos θ d(cos θ) = ¾).
/// let cells = integrate_cells(
///     &Binning::Sphere { theta_bins: 4, phi_bins: 1 },
///     |w: DVec3| w.z.max(0.0) / std::f64::consts::PI,
///     1e-14,
///     1 << 10,
///     Smoothness::MayJump,
/// )
/// .unwrap();
/// assert!((cells.total - 1.0).abs() < 1e-14);
/// assert!((cells.probabilities[0] - 0.75).abs() < 1e-14);
/// ```
///
/// # Errors
/// An invalid binning, or a tolerance that is not positive and finite.
pub fn integrate_cells(
    binning: &Binning,
    mut pdf: impl FnMut(DVec3) -> f64,
    tolerance: f64,
    max_splits: usize,
    smoothness: Smoothness,
) -> Result<CellIntegrals, ChiSquareError> {
    let grid = Grid::new(binning)?;
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(ChiSquareError::OutOfRange {
            field: "tolerance",
            value: tolerance,
            range: "(0, ∞)",
        });
    }
    let mut bad = None;
    let mut f = integrand(&grid, &mut pdf, &mut bad);
    let mut probabilities = Vec::with_capacity(grid.cell_count());
    let mut errors = Vec::with_capacity(grid.cell_count());
    let (mut unconverged_cells, mut evaluations) = (0, 0);
    for index in 0..grid.cell_count() {
        let c = integrate_cell(
            &grid,
            index,
            &mut f,
            &|_| tolerance,
            max_splits,
            INITIAL_SPLIT,
            smoothness,
        );
        probabilities.push(c.value);
        errors.push(c.error);
        unconverged_cells += usize::from(!c.converged);
        evaluations += c.evaluations;
    }
    drop(f);
    Ok(CellIntegrals {
        total: neumaier_sum(probabilities.iter().copied()),
        error: neumaier_sum(errors.iter().copied()),
        probabilities,
        errors,
        unconverged_cells,
        evaluations,
        invalid_pdf: bad,
    })
}
