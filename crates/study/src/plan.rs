//! The fixed list of a study's rows, shards of it, and replicate seeds.

use std::fmt;
use std::str::FromStr;

use lambert_estimator::estimation::{SequenceKind, RQMC_REPLICATES};
use lambert_estimator::precision::Precision;
use lambert_estimator::strategy::Strategy;

use crate::config::StudyConfig;

/// One row of a study: a (scene, strategy, sequence, N) cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RowKey {
    /// The row's index in the canonical order.
    pub index: usize,
    /// Index of the scene in the study's list.
    pub scene: usize,
    /// The strategy.
    pub strategy: Strategy,
    /// The sequence.
    pub sequence: SequenceKind,
    /// The precision of the per-sample arithmetic.
    pub precision: Precision,
    /// N = 2^log2_n.
    pub log2_n: u32,
}

impl RowKey {
    /// N.
    pub fn n(&self) -> u64 {
        1u64 << self.log2_n
    }
}

/// The smallest N an estimate with this sequence accepts.
pub fn minimum_samples(sequence: SequenceKind) -> u64 {
    match sequence {
        SequenceKind::Independent => 2,
        _ => 2 * RQMC_REPLICATES,
    }
}

/// Every row of the study in canonical order: scenes (outermost), then
/// strategies, then sequences, then N ascending. Rows whose N is below the
/// sequence's minimum ([`minimum_samples`]) are left out.
pub fn plan(config: &StudyConfig) -> Vec<RowKey> {
    let mut rows = Vec::new();
    for scene in 0..config.scenes.len() {
        for &strategy in &config.strategies {
            for &sequence in &config.sequences {
                for &precision in &config.precisions {
                    for log2_n in config.n_min_log2..=config.n_max_log2 {
                        if (1u64 << log2_n) < minimum_samples(sequence) {
                            continue;
                        }
                        rows.push(RowKey {
                            index: rows.len(),
                            scene,
                            strategy,
                            sequence,
                            precision,
                            log2_n,
                        });
                    }
                }
            }
        }
    }
    rows
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn fnv(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01B3)
    })
}

/// The seed of replicate `replicate` of a row: a SplitMix64 hash chain of
/// the study seed, the scene's name, the strategy's and sequence's names,
/// log₂ N and the replicate index. It depends on the row's content, not on
/// its index, so every replicate of every row is independent of every other
/// and a row gives the same numbers whichever study, shard or resume runs it.
pub fn replicate_seed(
    base: u64,
    scene_name: &str,
    strategy: Strategy,
    sequence: SequenceKind,
    log2_n: u32,
    replicate: usize,
) -> u64 {
    let mut h = splitmix(base);
    for part in [
        fnv(scene_name),
        fnv(strategy.name()),
        fnv(sequence.name()),
        u64::from(log2_n),
        replicate as u64,
    ] {
        h = splitmix(h ^ part);
    }
    h
}

/// A deterministic slice of the rows: the rows with `index % count == k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which slice, 0 ≤ k < count.
    pub k: usize,
    /// How many slices.
    pub count: usize,
}

impl Shard {
    /// The whole study.
    pub const ALL: Shard = Shard { k: 0, count: 1 };

    /// Whether row `index` belongs to this shard.
    pub fn contains(&self, index: usize) -> bool {
        index % self.count == self.k
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.count)
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("expected K/N with 0 ≤ K < N, e.g. 0/4, got {s:?}");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let k: usize = k.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || k >= count {
            return Err(bad());
        }
        Ok(Shard { k, count })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plan_is_canonical_and_shards_partition_it() {
        let c = StudyConfig::quick();
        let rows = plan(&c);
        // scenes × 8 strategies × 3 sequences × 10 N (2^5..2^14).
        assert_eq!(rows.len(), c.scenes.len() * 8 * 3 * 10);
        assert!(rows.iter().enumerate().all(|(i, r)| r.index == i));
        let shards: Vec<Shard> = (0..4).map(|k| Shard { k, count: 4 }).collect();
        for r in &rows {
            assert_eq!(shards.iter().filter(|s| s.contains(r.index)).count(), 1);
        }
        assert_eq!("1/4".parse::<Shard>().unwrap(), shards[1]);
        assert!("4/4".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }

    #[test]
    fn seeds_differ() {
        let a = replicate_seed(1, "s", Strategy::Light, SequenceKind::Sobol, 5, 0);
        let b = replicate_seed(1, "s", Strategy::Light, SequenceKind::Sobol, 5, 1);
        let c = replicate_seed(1, "s", Strategy::Light, SequenceKind::Sobol, 6, 0);
        let d = replicate_seed(2, "s", Strategy::Light, SequenceKind::Sobol, 5, 0);
        assert!(a != b && a != c && a != d && b != c);
    }
}
