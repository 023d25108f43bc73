//! # lambert-study
//!
//! Convergence studies: scenes × strategies × sequences × sample counts
//! N = 2^lo … 2^hi × M replicates, each estimate compared with the scene's
//! closed form.
//!
//! A study is planned as a fixed list of rows ([`plan()`]), one per (scene,
//! strategy, sequence, N), in a canonical order; each row runs M estimates
//! with [`lambert_estimator::estimation::estimate`] and is reduced to one CSV row
//! ([`aggregate()`]). Rows are independent of each other (every replicate's
//! seed is a hash of the study seed, the row's key and the replicate
//! index), so a study splits into deterministic shards (`index % N == K`)
//! and any subset of rows can be run, resumed or merged to the bit.
//! Per-group statistics (the log-log slope of RMSE against N and the time to
//! reach 0.1 % relative RMSE, [`fit`]) are computed from the finished CSV
//! ([`summary`](mod@summary)).

pub mod aggregate;
pub mod config;
pub mod fit;
pub mod peers;
pub mod plan;
pub mod plot;
pub mod results;
pub mod run;
pub mod summary;

pub use aggregate::{aggregate, ReplicateResult, RowStats};
pub use config::{StudyConfig, StudyError, StudyScene, RUNS_DIR};
pub use fit::{fit_loglog, LogLogFit};
pub use plan::{plan, replicate_seed, RowKey, Shard};
pub use results::{read_results, sequence_label, ResultRow, ResultsWriter, CSV_HEADER};
pub use run::{run_replicates, run_row, run_study, RunOptions};
pub use summary::{group_summaries, summary_markdown, GroupSummary};
