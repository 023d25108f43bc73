//! `results.csv`: one row per (scene, strategy, sequence, precision, N), written and
//! flushed as each row finishes, read back keeping only whole rows.
//!
//! The schema is documented in `notebooks-data/README.md`. Numbers are
//! written in Rust's shortest round-trip scientific form (`{:e}`), so a
//! value read back and written again gives the same bytes; an empty field
//! is "not available" (no closed form, or an exact estimate's efficiency).
//! Every column except `ns_per_sample` and `efficiency` (which hold measured
//! times) is a deterministic function of the study's configuration.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::Path;
use std::str::FromStr;

use lambert_estimator::estimation::SequenceKind;
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::Strategy;

use crate::aggregate::RowStats;

/// The header line (without the newline).
pub const CSV_HEADER: &str = "row,scene,strategy,sequence,precision,log2_n,n,replicates,reference,mean_estimate,mean_rel_error,rmse,rel_rmse,coverage,hits,warnings,std_error,replicate_sd,sample_variance,ns_per_sample,efficiency";

/// The number of columns.
const COLUMNS: usize = 21;

/// The columns that hold measured times (they differ from run to run); every
/// other column is deterministic.
pub const TIMING_COLUMNS: [&str; 2] = ["ns_per_sample", "efficiency"];

/// One row of `results.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct ResultRow {
    /// Index in the study's canonical order.
    pub row: usize,
    /// Scene name.
    pub scene: String,
    /// Strategy.
    pub strategy: Strategy,
    /// Sequence.
    pub sequence: SequenceKind,
    /// The precision of the per-sample arithmetic.
    pub precision: Precision,
    /// log₂ N.
    pub log2_n: u32,
    /// The closed form, if any.
    pub reference: Option<f64>,
    /// The row's statistics.
    pub stats: RowStats,
}

impl ResultRow {
    /// N.
    pub fn n(&self) -> u64 {
        1u64 << self.log2_n
    }

    /// The CSV line (without the newline).
    pub fn to_csv(&self) -> String {
        let s = &self.stats;
        format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            self.row,
            self.scene,
            self.strategy.name(),
            self.sequence.name(),
            self.precision.name(),
            self.log2_n,
            self.n(),
            s.replicates,
            opt(self.reference),
            num(s.mean_estimate),
            opt(s.mean_rel_error),
            opt(s.rmse),
            opt(s.rel_rmse),
            opt(s.coverage),
            s.hits,
            s.warnings,
            num(s.std_error),
            opt(s.replicate_sd),
            num(s.sample_variance),
            num(s.ns_per_sample),
            opt(s.efficiency),
        )
    }

    /// The line without the timing columns (for comparing runs).
    pub fn deterministic_part(&self) -> String {
        let line = self.to_csv();
        let fields: Vec<&str> = line.split(',').collect();
        fields[..fields.len() - TIMING_COLUMNS.len()].join(",")
    }

    /// Parses a CSV line (without the newline).
    pub fn from_csv(line: &str) -> Result<Self, String> {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != COLUMNS {
            return Err(format!(
                "expected {COLUMNS} fields, got {} (a results.csv from before the hits, \
                 warnings, std_error and replicate_sd columns, or from before the precision \
                 column, cannot be resumed or merged: run the study again)",
                f.len()
            ));
        }
        let row: usize = parse(f[0], "row")?;
        let log2_n: u32 = parse(f[5], "log2_n")?;
        let n: u64 = parse(f[6], "n")?;
        if log2_n > 62 || n != 1u64 << log2_n {
            return Err(format!("n {n} is not 2^log2_n = 2^{log2_n}"));
        }
        let stats = RowStats {
            replicates: parse(f[7], "replicates")?,
            mean_estimate: parse(f[9], "mean_estimate")?,
            mean_rel_error: parse_opt(f[10], "mean_rel_error")?,
            rmse: parse_opt(f[11], "rmse")?,
            rel_rmse: parse_opt(f[12], "rel_rmse")?,
            coverage: parse_opt(f[13], "coverage")?,
            hits: parse(f[14], "hits")?,
            warnings: parse(f[15], "warnings")?,
            std_error: parse(f[16], "std_error")?,
            replicate_sd: parse_opt(f[17], "replicate_sd")?,
            sample_variance: parse(f[18], "sample_variance")?,
            ns_per_sample: parse(f[19], "ns_per_sample")?,
            efficiency: parse_opt(f[20], "efficiency")?,
        };
        Ok(ResultRow {
            row,
            scene: f[1].to_string(),
            strategy: f[2].parse().map_err(|e| format!("strategy: {e}"))?,
            sequence: f[3].parse().map_err(|e| format!("sequence: {e}"))?,
            precision: f[4].parse().map_err(|e| format!("precision: {e}"))?,
            log2_n,
            reference: parse_opt(f[8], "reference")?,
            stats,
        })
    }
}

/// How summaries and plots name a row's sequence: the sequence's name,
/// followed by ` f32` for a row run in f32 (f64, the default, is not
/// named, so the built-in study's tables read as before).
pub fn sequence_label(sequence: SequenceKind, precision: Precision) -> String {
    match precision {
        Precision::F64 => sequence.name().to_string(),
        Precision::F32 => format!("{} f32", sequence.name()),
    }
}

fn num(x: f64) -> String {
    format!("{x:e}")
}

fn opt(x: Option<f64>) -> String {
    x.map(num).unwrap_or_default()
}

fn parse<T: FromStr>(s: &str, field: &str) -> Result<T, String> {
    s.parse()
        .map_err(|_| format!("{field}: cannot parse {s:?}"))
}

fn parse_opt(s: &str, field: &str) -> Result<Option<f64>, String> {
    if s.is_empty() {
        Ok(None)
    } else {
        parse(s, field).map(Some)
    }
}

/// The whole rows of a results file and the byte length of the prefix that
/// holds them (header included): a last line without its newline, or a last
/// line that does not parse, is an interrupted write and is left out; a bad
/// line before the last is an error. A missing or empty file has no rows.
pub fn read_results(path: &Path) -> Result<(Vec<ResultRow>, u64), String> {
    let text = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((Vec::new(), 0)),
        Err(e) => return Err(format!("cannot read {}: {e}", path.display())),
    };
    let mut rows = Vec::new();
    let mut offset = 0usize;
    let mut valid = 0u64;
    let mut first = true;
    while let Some(end) = text[offset..].iter().position(|&b| b == b'\n') {
        let line_end = offset + end;
        let line = std::str::from_utf8(&text[offset..line_end]);
        let next = line_end + 1;
        let is_last = text[next..].iter().all(|&b| b != b'\n');
        if first {
            if line != Ok(CSV_HEADER) {
                return Err(format!(
                    "{}: the first line is not the results header{}",
                    path.display(),
                    if line.is_ok_and(|l| l.starts_with("row,scene,strategy,sequence,log2_n")) {
                        " (a results.csv from before the precision column: run the study again)"
                    } else {
                        ""
                    }
                ));
            }
            first = false;
        } else {
            match line
                .map_err(|e| e.to_string())
                .and_then(ResultRow::from_csv)
            {
                Ok(row) => rows.push(row),
                Err(_) if is_last => break,
                Err(e) => return Err(format!("{}: line {}: {e}", path.display(), rows.len() + 2)),
            }
        }
        offset = next;
        valid = next as u64;
    }
    Ok((rows, valid))
}

/// Appends rows to a results file, flushing each one.
pub struct ResultsWriter {
    out: BufWriter<File>,
}

impl ResultsWriter {
    /// Opens `path` for appending after its first `keep` bytes (the whole
    /// rows [`read_results`] found; 0 to start afresh), writing the header
    /// if the kept part is empty.
    pub fn open(path: &Path, keep: u64) -> Result<Self, String> {
        let file = OpenOptions::new()
            .create(true)
            .write(true)
            .truncate(false)
            .open(path)
            .map_err(|e| format!("cannot open {}: {e}", path.display()))?;
        file.set_len(keep)
            .map_err(|e| format!("cannot truncate {}: {e}", path.display()))?;
        let mut file = file;
        use std::io::Seek;
        file.seek(std::io::SeekFrom::End(0))
            .map_err(|e| format!("cannot seek {}: {e}", path.display()))?;
        let mut w = ResultsWriter {
            out: BufWriter::new(file),
        };
        if keep == 0 {
            w.write_line(CSV_HEADER)?;
        }
        Ok(w)
    }

    fn write_line(&mut self, line: &str) -> Result<(), String> {
        self.out
            .write_all(line.as_bytes())
            .and_then(|()| self.out.write_all(b"\n"))
            .and_then(|()| self.out.flush())
            .map_err(|e| format!("cannot write results: {e}"))
    }

    /// Writes one row and flushes it.
    pub fn write_row(&mut self, row: &ResultRow) -> Result<(), String> {
        self.write_line(&row.to_csv())
    }
}

/// Writes a complete results file (header and rows, in the given order).
pub fn write_results(path: &Path, rows: &[ResultRow]) -> Result<(), String> {
    let mut w = ResultsWriter::open(path, 0)?;
    for r in rows {
        w.write_row(r)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(i: usize) -> ResultRow {
        ResultRow {
            row: i,
            scene: "uniform-sky".into(),
            strategy: Strategy::Light,
            sequence: SequenceKind::Sobol,
            precision: Precision::F64,
            log2_n: 7,
            reference: Some(std::f64::consts::PI),
            stats: RowStats {
                replicates: 8,
                mean_estimate: 3.127_592_7,
                mean_rel_error: Some(-1.234_567_890_123e-9),
                rmse: Some(1e-300),
                rel_rmse: None,
                coverage: Some(0.875),
                hits: 1000,
                warnings: 1,
                std_error: 1.0 / 3.0,
                replicate_sd: Some(0.25),
                sample_variance: 0.1 + 0.2,
                ns_per_sample: 12.5,
                efficiency: None,
            },
        }
    }

    #[test]
    fn round_trips_to_the_byte() {
        let r = row(3);
        let line = r.to_csv();
        let back = ResultRow::from_csv(&line).unwrap();
        assert_eq!(back, r);
        assert_eq!(back.to_csv(), line);
        assert_eq!(CSV_HEADER.split(',').count(), line.split(',').count());
    }

    #[test]
    fn keeps_only_whole_rows() {
        let dir = std::env::temp_dir().join(format!("lambert-results-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("results.csv");
        write_results(&path, &[row(0), row(1)]).unwrap();
        let full = std::fs::read(&path).unwrap();
        // Cut the last row in half.
        let cut = full.len() - 20;
        std::fs::write(&path, &full[..cut]).unwrap();
        let (rows, valid) = read_results(&path).unwrap();
        assert_eq!(rows.len(), 1);
        let mut w = ResultsWriter::open(&path, valid).unwrap();
        w.write_row(&row(1)).unwrap();
        drop(w);
        assert_eq!(std::fs::read(&path).unwrap(), full);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
