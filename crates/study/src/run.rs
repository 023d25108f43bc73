//! Running a study's rows and writing them as they finish.

use std::collections::HashMap;
use std::path::Path;

use rayon::prelude::*;

use lambert_estimator::estimation::{estimate, EstimateConfig};

use crate::aggregate::{aggregate, ReplicateResult};
use crate::config::StudyConfig;
use crate::plan::{plan, replicate_seed, RowKey, Shard};
use crate::results::{read_results, ResultRow, ResultsWriter};

/// How to run a study.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunOptions {
    /// Which slice of the rows to run.
    pub shard: Shard,
    /// Keep the whole rows of an existing `results.csv` and run only the
    /// missing ones (otherwise the file is started afresh).
    pub resume: bool,
}

/// Runs one row's M replicate estimates (one thread each; replicates run in
/// parallel, collected in replicate order).
pub fn run_replicates(config: &StudyConfig, key: &RowKey) -> Result<Vec<ReplicateResult>, String> {
    let scene = &config.scenes[key.scene];
    (0..config.replicates)
        .into_par_iter()
        .map(|r| {
            let seed = replicate_seed(
                config.seed,
                &scene.name,
                key.strategy,
                key.sequence,
                key.log2_n,
                r,
            );
            let report = estimate(
                &scene.scene,
                &EstimateConfig {
                    strategy: key.strategy,
                    sequence: key.sequence,
                    samples: key.n(),
                    seed,
                    threads: 1,
                    precision: key.precision,
                },
            )
            .map_err(|e| {
                format!(
                    "{} / {} / {} / N = {}: {e}",
                    scene.name,
                    key.strategy,
                    key.sequence,
                    key.n()
                )
            })?;
            Ok(ReplicateResult {
                mean: report.mean,
                std_error: report.std_error,
                ci99: report.ci99,
                interval: report.interval,
                hits: report.hits,
                ns_per_sample: report.ns_per_sample,
                sample_variance: report.sample_variance,
            })
        })
        .collect()
}

/// Runs one row: [`run_replicates`] reduced against the scene's closed form.
pub fn run_row(config: &StudyConfig, key: &RowKey) -> Result<ResultRow, String> {
    let scene = &config.scenes[key.scene];
    let replicates = run_replicates(config, key)?;
    Ok(ResultRow {
        row: key.index,
        scene: scene.name.clone(),
        strategy: key.strategy,
        sequence: key.sequence,
        precision: key.precision,
        log2_n: key.log2_n,
        reference: scene.reference,
        stats: aggregate(scene.reference, &replicates),
    })
}

fn same_key(row: &ResultRow, key: &RowKey, config: &StudyConfig) -> bool {
    row.row == key.index
        && row.scene == config.scenes[key.scene].name
        && row.strategy == key.strategy
        && row.sequence == key.sequence
        && row.precision == key.precision
        && row.log2_n == key.log2_n
        && row.stats.replicates == config.replicates
}

/// Runs the study's rows of `options.shard` into `out_dir/results.csv`,
/// writing and flushing each row as it finishes, in canonical order.
/// `progress(done, total)` is called before the first row and after each.
/// Returns the shard's rows (resumed and new), in canonical order.
pub fn run_study(
    config: &StudyConfig,
    out_dir: &Path,
    options: RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<ResultRow>, String> {
    config.validate().map_err(|e| e.to_string())?;
    std::fs::create_dir_all(out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
    let path = out_dir.join("results.csv");
    let keys: Vec<RowKey> = plan(config)
        .into_iter()
        .filter(|k| options.shard.contains(k.index))
        .collect();
    let mut existing: HashMap<usize, ResultRow> = HashMap::new();
    let mut keep = 0;
    if options.resume {
        let (rows, valid) = read_results(&path)?;
        let by_index: HashMap<usize, &RowKey> = keys.iter().map(|k| (k.index, k)).collect();
        for r in rows {
            match by_index.get(&r.row) {
                Some(k) if same_key(&r, k, config) => {
                    existing.insert(r.row, r);
                }
                _ => {
                    return Err(format!(
                        "{}: row {} ({} / {} / {} / 2^{}) does not belong to this study or shard; \
                         use another --out, or run without --resume to start afresh",
                        path.display(),
                        r.row,
                        r.scene,
                        r.strategy,
                        r.sequence,
                        r.log2_n
                    ))
                }
            }
        }
        keep = valid;
    }
    let mut writer = ResultsWriter::open(&path, keep)?;
    let total = keys.len();
    let mut done = existing.len();
    progress(done, total);
    let mut out = Vec::with_capacity(total);
    for key in &keys {
        if let Some(r) = existing.remove(&key.index) {
            out.push(r);
            continue;
        }
        let row = run_row(config, key)?;
        writer.write_row(&row)?;
        out.push(row);
        done += 1;
        progress(done, total);
    }
    Ok(out)
}
