//! Grids of equal-solid-angle cells on the sphere or on a cap.
//!
//! A direction is described in a frame (+z the axis) by t = 1 − cos θ ∈ [0, 2]
//! and φ ∈ [0, 2π). Since dω = d(cos θ) dφ = dt dφ, a grid uniform in t and in
//! φ has cells of equal solid angle: the whole sphere (t ∈ [0, 2]) or a cap
//! t ∈ [0, h], h = 1 − cos θmax, each cell of solid angle (Δt)(Δφ).
//!
//! t is computed without cancellation, 1 − cos θ = (x² + y²)/(1 + z) for
//! z > 0 ([`lambert_sampling::f64::one_minus_cos_theta`]), so a cap of
//! θmax = 1e-6 rad (h = 5e-13) still gets as many rows as asked: a
//! whole-sphere grid would put it in a fraction of one row, where no
//! sampler error could show.

use crate::ChiSquareError;
use glam::DVec3;
use lambert_geometry::f64::Frame;
use lambert_sampling::f64::{azimuth_fraction, one_minus_cos_theta};
use std::f64::consts::PI;

/// Relative allowance at the rim of a cap: a direction with
/// h < 1 − cos θ ≤ h (1 + `RIM_TOLERANCE`) is binned in the last row, not
/// outside. It absorbs the rounding of rotating a sample into the cap's
/// frame (about 1e-10 relative for θmax = 1e-6 rad, 1e-8 for 1e-8 rad); a
/// band of relative width 1e-6 of the cap holds 1e-6 of its samples, far
/// below what any test here can resolve.
pub const RIM_TOLERANCE: f64 = 1e-6;

/// How directions are binned: the whole sphere, or a cap about an axis.
///
/// Both grids have `theta_bins` rows uniform in cos θ (equivalently in
/// t = 1 − cos θ) and `phi_bins` columns uniform in φ, so every cell has
/// the same solid angle: 4π/(rows·cols) for the sphere, 2πh/(rows·cols)
/// for the cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Binning {
    /// The whole sphere about +z: rows uniform in cos θ ∈ [−1, 1].
    Sphere {
        /// Number of rows (in cos θ), ≥ 1.
        theta_bins: usize,
        /// Number of columns (in φ), ≥ 1.
        phi_bins: usize,
    },
    /// The cap 1 − cos θ ≤ h about `axis` (a unit vector), measured in the
    /// frame `Frame::from_normal(axis)`: rows uniform in 1 − cos θ ∈ [0, h],
    /// plus one "outside" cell for the rest of the sphere, whose expected
    /// count is the pdf integrated outside the cap.
    Cap {
        /// The cap's axis, a unit vector (to 1e-6; it is renormalised).
        axis: DVec3,
        /// h = 1 − cos θmax ∈ (0, 2].
        one_minus_cos_max: f64,
        /// Number of rows (in 1 − cos θ), ≥ 1.
        theta_bins: usize,
        /// Number of columns (in φ), ≥ 1.
        phi_bins: usize,
    },
}

/// One cell of a [`Grid`], for reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cell {
    /// A grid cell: 1 − cos θ ∈ [t0, t1), φ ∈ [φ0, φ1) radians.
    Grid {
        /// Row, 0 at the axis.
        row: usize,
        /// Column, 0 at φ = 0 (the frame's +x).
        col: usize,
        /// The cell's range of 1 − cos θ.
        one_minus_cos: (f64, f64),
        /// The cell's range of φ, in radians.
        phi: (f64, f64),
    },
    /// The rest of the sphere outside a cap: 1 − cos θ > h.
    Outside {
        /// h, the cap's 1 − cos θmax.
        one_minus_cos_max: f64,
    },
    /// Cell `index` of a caller-supplied partition
    /// ([`ChiSquareTest::run_partition`](super::ChiSquareTest::run_partition)).
    Part {
        /// The cell's index in the partition.
        index: usize,
    },
}

impl std::fmt::Display for Cell {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Cell::Grid {
                row,
                col,
                one_minus_cos,
                phi,
            } => write!(
                f,
                "row {row} col {col} (1-cos θ ∈ [{:.6e}, {:.6e}), φ ∈ [{:.4}, {:.4}))",
                one_minus_cos.0, one_minus_cos.1, phi.0, phi.1
            ),
            Cell::Outside { one_minus_cos_max } => {
                write!(f, "outside the cap (1-cos θ > {one_minus_cos_max:.6e})")
            }
            Cell::Part { index } => write!(f, "partition cell {index}"),
        }
    }
}

/// A validated [`Binning`]: maps directions to flat cell indices and cell
/// coordinates (t, φ) back to directions.
///
/// Cells are numbered row-major, `row * cols + col`; in cap mode the
/// outside cell is the last index, `rows * cols`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    frame: Frame,
    t_max: f64,
    rows: usize,
    cols: usize,
    outside: bool,
}

impl Grid {
    /// Validates `binning`: at least one row and one column (and at most
    /// 2²⁴ cells), h ∈ (0, 2] and finite, the axis a unit vector to 1e-6.
    pub fn new(binning: &Binning) -> Result<Self, ChiSquareError> {
        let (frame, t_max, rows, cols, outside) = match *binning {
            Binning::Sphere {
                theta_bins,
                phi_bins,
            } => {
                let frame = Frame {
                    x: DVec3::X,
                    y: DVec3::Y,
                    z: DVec3::Z,
                };
                (frame, 2.0, theta_bins, phi_bins, false)
            }
            Binning::Cap {
                axis,
                one_minus_cos_max: h,
                theta_bins,
                phi_bins,
            } => {
                if !(axis.is_finite() && (axis.length() - 1.0).abs() <= 1e-6) {
                    return Err(ChiSquareError::AxisNotUnit { axis });
                }
                if !(h > 0.0 && h <= 2.0) {
                    return Err(ChiSquareError::OutOfRange {
                        field: "one_minus_cos_max",
                        value: h,
                        range: "(0, 2]",
                    });
                }
                let frame = Frame::from_normal(axis.normalize());
                (frame, h, theta_bins, phi_bins, h < 2.0)
            }
        };
        for (field, v) in [("theta_bins", rows), ("phi_bins", cols)] {
            if v == 0 {
                return Err(ChiSquareError::OutOfRange {
                    field,
                    value: v as f64,
                    range: "[1, 2^24] (and rows·cols ≤ 2^24)",
                });
            }
        }
        if rows.saturating_mul(cols) > 1 << 24 {
            return Err(ChiSquareError::OutOfRange {
                field: "theta_bins * phi_bins",
                value: rows as f64 * cols as f64,
                range: "[1, 2^24]",
            });
        }
        Ok(Grid {
            frame,
            t_max,
            rows,
            cols,
            outside,
        })
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// The frame whose +z is the grid's axis (+z itself for the sphere).
    pub fn frame(&self) -> Frame {
        self.frame
    }

    /// h: 2 for the sphere, 1 − cos θmax for a cap.
    pub fn one_minus_cos_max(&self) -> f64 {
        self.t_max
    }

    /// Whether there is an outside cell (a cap with h < 2).
    pub fn has_outside(&self) -> bool {
        self.outside
    }

    /// Number of cells, the outside cell included.
    pub fn cell_count(&self) -> usize {
        self.rows * self.cols + usize::from(self.outside)
    }

    /// The flat index of the cell holding the unit direction `w`.
    ///
    /// Rows are half-open, [t0, t1); t = h exactly, and t up to
    /// h (1 + [`RIM_TOLERANCE`]), fall in the last row. Without an outside
    /// cell, t is clamped into the last row.
    pub fn locate(&self, w: DVec3) -> usize {
        let local = self.frame.to_local(w);
        let t = one_minus_cos_theta(local);
        if self.outside && t > self.t_max * (1.0 + RIM_TOLERANCE) {
            return self.rows * self.cols;
        }
        let row = ((t / self.t_max * self.rows as f64) as usize).min(self.rows - 1);
        let col = ((azimuth_fraction(local) * self.cols as f64) as usize).min(self.cols - 1);
        row * self.cols + col
    }

    /// The cell with flat index `index`.
    ///
    /// # Panics
    /// If `index >= self.cell_count()`.
    pub fn cell(&self, index: usize) -> Cell {
        assert!(index < self.cell_count(), "cell index {index} out of range");
        if index == self.rows * self.cols {
            return Cell::Outside {
                one_minus_cos_max: self.t_max,
            };
        }
        let (row, col) = (index / self.cols, index % self.cols);
        Cell::Grid {
            row,
            col,
            one_minus_cos: (self.row_edge(row), self.row_edge(row + 1)),
            phi: (self.col_edge(col), self.col_edge(col + 1)),
        }
    }

    /// 1 − cos θ at the start of row `row` (h at `row == rows`).
    pub fn row_edge(&self, row: usize) -> f64 {
        if row >= self.rows {
            self.t_max
        } else {
            self.t_max * row as f64 / self.rows as f64
        }
    }

    /// φ at the start of column `col` (2π at `col == cols`).
    pub fn col_edge(&self, col: usize) -> f64 {
        2.0 * PI * col as f64 / self.cols as f64
    }

    /// The unit direction (world coordinates) with 1 − cos θ = `t` ∈ [0, 2]
    /// and azimuth `phi` (radians) in the grid's frame.
    pub fn direction(&self, t: f64, phi: f64) -> DVec3 {
        let sin_theta = (t * (2.0 - t)).max(0.0).sqrt();
        let (s, c) = phi.sin_cos();
        self.frame
            .from_local(DVec3::new(sin_theta * c, sin_theta * s, 1.0 - t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_centres_locate_to_their_own_cell() {
        let grids = [
            Grid::new(&Binning::Sphere {
                theta_bins: 7,
                phi_bins: 5,
            })
            .unwrap(),
            Grid::new(&Binning::Cap {
                axis: DVec3::new(1.0, 2.0, -3.0).normalize(),
                one_minus_cos_max: 2.0 * (0.5e-6f64).sin().powi(2),
                theta_bins: 9,
                phi_bins: 4,
            })
            .unwrap(),
            Grid::new(&Binning::Cap {
                axis: -DVec3::Y,
                one_minus_cos_max: 1.5,
                theta_bins: 3,
                phi_bins: 6,
            })
            .unwrap(),
        ];
        for g in grids {
            for i in 0..g.rows() * g.cols() {
                let Cell::Grid {
                    one_minus_cos: (t0, t1),
                    phi: (p0, p1),
                    ..
                } = g.cell(i)
                else {
                    panic!("grid cell expected");
                };
                let w = g.direction(0.5 * (t0 + t1), 0.5 * (p0 + p1));
                assert_eq!(g.locate(w), i, "{}", g.cell(i));
            }
            if g.has_outside() {
                let h = g.one_minus_cos_max();
                let w = g.direction(h + 0.5 * (2.0 - h), 1.0);
                assert_eq!(g.locate(w), g.cell_count() - 1);
                // Just outside the rim, within the rounding allowance: last row.
                let w = g.direction(h * (1.0 + 1e-9), 1.0);
                assert_eq!(g.locate(w) / g.cols(), g.rows() - 1);
            }
        }
    }

    #[test]
    fn bad_binnings_are_errors() {
        assert!(Grid::new(&Binning::Sphere {
            theta_bins: 0,
            phi_bins: 4
        })
        .is_err());
        let cap = |axis, h| Binning::Cap {
            axis,
            one_minus_cos_max: h,
            theta_bins: 4,
            phi_bins: 4,
        };
        assert!(Grid::new(&cap(DVec3::Z, 0.0)).is_err());
        assert!(Grid::new(&cap(DVec3::Z, 2.5)).is_err());
        assert!(Grid::new(&cap(DVec3::Z, f64::NAN)).is_err());
        assert!(Grid::new(&cap(DVec3::new(0.0, 0.0, 2.0), 0.5)).is_err());
        assert!(!Grid::new(&cap(DVec3::Z, 2.0)).unwrap().has_outside());
    }
}
