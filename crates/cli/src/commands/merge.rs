//! `lambert merge`: combines the results of a study's shards into the
//! results of one run (the same rows, the same bytes, in canonical order),
//! then writes its summary and plots.

use std::collections::BTreeMap;
use std::path::PathBuf;

use clap::Args;
use lambert_study::results::write_results;
use lambert_study::{read_results, summary_markdown, ResultRow};

/// Options of `lambert merge`.
#[derive(Args, Debug, Clone)]
pub struct MergeOptions {
    /// Shard output folders (each holding a results.csv).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Output folder.
    #[arg(long)]
    pub out: PathBuf,
    /// No report on stdout.
    #[arg(long)]
    pub quiet: bool,
}

/// Merges rows: sorted by row index; a row present twice must be identical
/// apart from its timing columns (the first copy is kept).
pub fn merge_rows(sets: Vec<(String, Vec<ResultRow>)>) -> Result<Vec<ResultRow>, String> {
    let mut by_index: BTreeMap<usize, (String, ResultRow)> = BTreeMap::new();
    for (source, rows) in sets {
        for r in rows {
            if let Some((first, old)) = by_index.get(&r.row) {
                if old.deterministic_part() != r.deterministic_part() {
                    return Err(format!(
                        "row {} differs between {first} and {source}: are they shards of the same study?",
                        r.row
                    ));
                }
                continue;
            }
            by_index.insert(r.row, (source.clone(), r));
        }
    }
    Ok(by_index.into_values().map(|(_, r)| r).collect())
}

/// Runs the merge.
pub fn run(options: &MergeOptions) -> Result<(), String> {
    let mut sets = Vec::new();
    for d in &options.dirs {
        let path = d.join("results.csv");
        if !path.exists() {
            return Err(format!("{}: no such file", path.display()));
        }
        let (rows, _) = read_results(&path)?;
        sets.push((path.display().to_string(), rows));
    }
    let rows = merge_rows(sets)?;
    let missing: Vec<usize> = match rows.last() {
        None => Vec::new(),
        Some(last) => {
            let have: std::collections::HashSet<usize> = rows.iter().map(|r| r.row).collect();
            (0..=last.row).filter(|i| !have.contains(i)).collect()
        }
    };
    std::fs::create_dir_all(&options.out)
        .map_err(|e| format!("cannot create {}: {e}", options.out.display()))?;
    write_results(&options.out.join("results.csv"), &rows)?;
    let title = options
        .out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "merged".into());
    let summary = summary_markdown(&title, &rows);
    super::study::write_outputs(&options.out, &summary, &rows)?;
    if !options.quiet {
        println!(
            "merged {} rows from {} folders → {}",
            rows.len(),
            options.dirs.len(),
            options.out.display()
        );
        if !missing.is_empty() {
            println!(
                "warning: {} rows missing (first: {}); is a shard unfinished?",
                missing.len(),
                missing[0]
            );
        }
    }
    Ok(())
}
