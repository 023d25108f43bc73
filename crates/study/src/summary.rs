//! `summary.md`: per scene, strategy × sequence ranked by the time to reach
//! 0.1 % relative RMSE and by efficiency, with the fitted convergence slope
//! next to the theoretical one, and notes on the rows whose intervals are
//! not the CLT ones (few or no hits) and on the rows whose replicate spread
//! disagrees with their reported standard error ([`spread_band`]).
//! Computed from the finished rows (so it works after a merge of shards).

use std::collections::BTreeMap;
use std::fmt::Write;

use lambert_estimator::estimation::{SequenceKind, RQMC_REPLICATES};
use lambert_estimator::precision::Precision;
use lambert_estimator::statistics::rounding::mean_rounding_floor;
use lambert_estimator::strategy::Strategy;
use statrs::distribution::{ChiSquared, ContinuousCDF, FisherSnedecor};

use crate::fit::{fit_loglog, LogLogFit};
use crate::results::{sequence_label, ResultRow};

/// The target of the time-to-error column: 0.1 % relative RMSE.
pub const TARGET_REL_RMSE: f64 = 1e-3;

/// The statistics of one (scene, strategy, sequence) group.
#[derive(Clone, Debug, PartialEq)]
pub struct GroupSummary {
    /// Scene name.
    pub scene: String,
    /// Strategy.
    pub strategy: Strategy,
    /// Sequence.
    pub sequence: SequenceKind,
    /// The precision of the per-sample arithmetic.
    pub precision: Precision,
    /// The scene's closed form.
    pub reference: Option<f64>,
    /// The fit of RMSE against N (`None` without a reference).
    pub fit: Option<LogLogFit>,
    /// ns/sample at the largest N (the least overhead-dominated).
    pub ns_per_sample: f64,
    /// Efficiency at the largest N (`None` for a zero-variance estimate).
    pub efficiency: Option<f64>,
    /// Relative RMSE at the largest N.
    pub final_rel_rmse: Option<f64>,
    /// Largest N.
    pub n_max: u64,
    /// Predicted seconds (one thread) to reach [`TARGET_REL_RMSE`]: N* from
    /// the fit, times ns/sample; 0 for an exact estimator; the time of the
    /// smallest N when every N is already within the target (exact up to
    /// rounding: no decreasing fit); `None` without a reference, with a
    /// zero reference, or without a decreasing fit otherwise.
    pub time_to_target: Option<f64>,
    /// (log₂ N, replicates) of the rows where some replicates' intervals
    /// were not the CLT ones (few or no hits, few misses, a heavy tail).
    pub warning_rows: Vec<(u32, usize)>,
    /// (log₂ N, replicate spread / reported standard error) of the rows
    /// where the ratio falls outside its [`spread_band`].
    pub spread_flags: Vec<(u32, f64)>,
}

/// The family-wise level of the spread check over all the rows of a
/// summary (Šidák-corrected per row).
pub const SPREAD_FAMILY_ALPHA: f64 = 0.01;

/// The two-sided band, at level 1 − `alpha`, of the ratio s/σ of a row's
/// replicate spread s (the sample standard deviation of its M estimates)
/// to its reported standard error σ (the median of the M replicates' σᵣ),
/// when the σᵣ are honest and the estimates normal: s²/σ² ~ F(M − 1, ν),
/// with ν the degrees of freedom of one σᵣ — N − 1 for independent samples
/// (σᵣ from N samples), R − 1 = 15 for randomized QMC (from R = 16
/// replicates). Taking the median of M such σᵣ as if it had the precision
/// of one makes the band conservative. A ratio above the band means the
/// typical reported σ is too small: the signature of a heavy tail (area
/// sampling near an emitter, whose infinite-variance limit the sample
/// variance cannot show) or of rare events that some replicates saw and
/// others did not. Below it, σ overstates the error. `None` for M < 2.
pub fn spread_band(
    replicates: usize,
    sequence: SequenceKind,
    n: u64,
    alpha: f64,
) -> Option<(f64, f64)> {
    if replicates < 2 {
        return None;
    }
    let d1 = (replicates - 1) as f64;
    let d2 = match sequence {
        SequenceKind::Independent => n.saturating_sub(1).max(1) as f64,
        _ => (RQMC_REPLICATES - 1) as f64,
    };
    let (lo, hi) = if d2 > 1e6 {
        // F(d1, ∞) = χ²(d1)/d1 (statrs' F quantile loses precision there).
        let chi = ChiSquared::new(d1).ok()?;
        (
            chi.inverse_cdf(alpha / 2.0) / d1,
            chi.inverse_cdf(1.0 - alpha / 2.0) / d1,
        )
    } else {
        let f = FisherSnedecor::new(d1, d2).ok()?;
        (f.inverse_cdf(alpha / 2.0), f.inverse_cdf(1.0 - alpha / 2.0))
    };
    Some((lo.sqrt(), hi.sqrt()))
}

/// The ratio s/σ of a row, if it falls outside its band at level
/// 1 − `alpha`. Rows with σ = 0 (every replicate exact, or no hit) are not
/// judged, nor, on the low side, rows whose σ is the rounding floor (a bound
/// on the arithmetic, not a standard deviation).
fn spread_flag(row: &ResultRow, alpha: f64) -> Option<f64> {
    let s = &row.stats;
    let sd = s.replicate_sd?;
    if !(s.std_error > 0.0) {
        return None;
    }
    let ratio = sd / s.std_error;
    let (lo, hi) = spread_band(s.replicates, row.sequence, row.n(), alpha)?;
    let at_floor = s.std_error <= mean_rounding_floor(s.mean_estimate, row.n()) * 1.000_001;
    (ratio > hi || (ratio < lo && !at_floor)).then_some(ratio)
}

/// The theoretical RMSE slope of a sequence ("exact" handled by the
/// caller): −½ for independent samples; for jittered stratification in 2-D
/// −1 on smooth integrands (−¾ with discontinuities); for Owen-scrambled
/// Sobol −3/2 on smooth integrands (−¾ with discontinuities; Owen 1997).
pub fn theoretical_slope(sequence: SequenceKind) -> &'static str {
    match sequence {
        SequenceKind::Independent => "−0.5",
        SequenceKind::Stratified => "−1 smooth / −0.75 edges",
        SequenceKind::Sobol => "−1.5 smooth / −0.75 edges",
    }
}

/// Groups rows by (scene, strategy, sequence), in the rows' order of first
/// appearance, and summarises each group.
pub fn group_summaries(rows: &[ResultRow]) -> Vec<GroupSummary> {
    let alpha = sidak(SPREAD_FAMILY_ALPHA, rows.len());
    let mut order: Vec<(String, Strategy, SequenceKind, Precision)> = Vec::new();
    let mut groups: BTreeMap<usize, Vec<&ResultRow>> = BTreeMap::new();
    let mut sorted: Vec<&ResultRow> = rows.iter().collect();
    sorted.sort_by_key(|r| r.row);
    for r in sorted {
        let key = (r.scene.clone(), r.strategy, r.sequence, r.precision);
        let i = match order.iter().position(|k| *k == key) {
            Some(i) => i,
            None => {
                order.push(key);
                order.len() - 1
            }
        };
        groups.entry(i).or_default().push(r);
    }
    groups
        .into_iter()
        .map(|(i, mut g)| {
            g.sort_by_key(|r| r.log2_n);
            let (scene, strategy, sequence, precision) = order[i].clone();
            let last = g[g.len() - 1];
            let reference = last.reference;
            let fit = reference.map(|_| {
                let pts: Vec<(f64, f64)> = g
                    .iter()
                    .filter_map(|r| r.stats.rmse.map(|e| (r.n() as f64, e)))
                    .collect();
                fit_loglog(&pts)
            });
            // Every N already within the target (an estimator exact up to
            // rounding, whose error does not fall with N and so has no
            // slope): the time of the smallest N bounds it.
            let within = |t: f64| {
                g.iter()
                    .all(|r| r.stats.rmse.is_some_and(|e| e <= TARGET_REL_RMSE * t.abs()))
            };
            let time_to_target = match (reference, fit) {
                (Some(t), Some(LogLogFit::Exact)) if t != 0.0 => Some(0.0),
                (Some(t), Some(_)) if t != 0.0 && within(t) => {
                    Some(g[0].n() as f64 * g[0].stats.ns_per_sample * 1e-9)
                }
                (Some(t), Some(f)) if t != 0.0 => f
                    .n_for(TARGET_REL_RMSE * t.abs())
                    .map(|n| n.max(1.0) * last.stats.ns_per_sample * 1e-9),
                _ => None,
            };
            GroupSummary {
                scene,
                strategy,
                sequence,
                precision,
                reference,
                fit,
                ns_per_sample: last.stats.ns_per_sample,
                efficiency: last.stats.efficiency,
                final_rel_rmse: last.stats.rel_rmse,
                n_max: last.n(),
                time_to_target,
                warning_rows: g
                    .iter()
                    .filter(|r| r.stats.warnings > 0)
                    .map(|r| (r.log2_n, r.stats.warnings))
                    .collect(),
                spread_flags: g
                    .iter()
                    .filter_map(|r| spread_flag(r, alpha).map(|x| (r.log2_n, x)))
                    .collect(),
            }
        })
        .collect()
}

/// The per-test level of a family of `k` tests at family-wise level
/// `alpha` (Šidák 1967): 1 − (1 − α)^{1/k}.
fn sidak(alpha: f64, k: usize) -> f64 {
    -((1.0 - alpha).ln() / k.max(1) as f64).exp_m1()
}

/// The rows of `items` as "2^5…2^9 (8 of 8), 2^11 (3 of 8)": runs of
/// consecutive log₂ N with the same detail are joined.
fn exponents<T>(items: &[(u32, T)], detail: impl Fn(&T) -> String) -> String {
    let mut runs: Vec<(u32, u32, String)> = Vec::new();
    for (k, x) in items {
        let d = detail(x);
        match runs.last_mut() {
            Some((_, last, prev)) if *last + 1 == *k && *prev == d => *last = *k,
            _ => runs.push((*k, *k, d)),
        }
    }
    runs.iter()
        .map(|(a, b, d)| {
            if a == b {
                format!("2^{a}{d}")
            } else {
                format!("2^{a}…2^{b}{d}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn seconds(t: Option<f64>) -> String {
    match t {
        None => "—".into(),
        Some(0.0) => "0 (exact)".into(),
        Some(t) if t < 1e-3 => format!("{:.1} µs", t * 1e6),
        Some(t) if t < 1.0 => format!("{:.1} ms", t * 1e3),
        Some(t) if t < 3600.0 => format!("{t:.2} s"),
        Some(t) if t < 86400.0 * 365.0 => format!("{:.1} h", t / 3600.0),
        Some(t) => format!("{:.1e} years", t / (86400.0 * 365.0)),
    }
}

fn slope_text(fit: Option<LogLogFit>) -> String {
    match fit {
        None => "— (no closed form)".into(),
        Some(LogLogFit::Exact) => "exact".into(),
        Some(LogLogFit::TooFewPoints) => "—".into(),
        Some(LogLogFit::Line {
            slope, slope_se, ..
        }) => format!("{slope:.3} ± {slope_se:.3}"),
    }
}

/// The Markdown summary of a study's rows.
pub fn summary_markdown(title: &str, rows: &[ResultRow]) -> String {
    let groups = group_summaries(rows);
    let mut s = String::new();
    let _ = writeln!(s, "# Study `{title}`\n");
    let _ = writeln!(
        s,
        "Per scene, every strategy × sequence ranked by the predicted one-thread time to reach \
         0.1 % relative RMSE (from the log-log fit of RMSE against N, times ns/sample at the \
         largest N), then by efficiency ε = 1/(V·T) (V: variance of one sample's estimate, T: \
         seconds per sample). Measured slope: least squares of ln RMSE on ln N ± its standard \
         error; theoretical slopes: −½ for independent Monte Carlo, −1 (jittered) and −3/2 \
         (Owen-scrambled Sobol) on smooth integrands, −¾ for both with discontinuities; \
         \"exact\" when every replicate has zero error. Scenes without a closed form have no \
         error columns.\n"
    );
    let _ = writeln!(
        s,
        "Notes under a scene's table: **few hits** lists the N at which some replicates' 99 % \
         intervals are not the central-limit ones, because a part of the estimate had fewer \
         than 30 hits (or misses), or area sampling's heavy-tailed core was out of reach; \
         their intervals come from rare-event bounds and say so. **σ vs spread** lists the N \
         at which the spread of the replicates disagrees with their median reported standard \
         error (outside its F band at a {SPREAD_FAMILY_ALPHA} family-wise level, Šidák over \
         the rows), with the ratio spread/σ: a ratio far above 1 is the mark of a heavy tail \
         or of rare events, where the sample variance cannot be trusted.\n"
    );
    s.push_str(&crate::peers::peers_markdown(&groups));
    let mut scenes: Vec<&str> = Vec::new();
    for g in &groups {
        if !scenes.contains(&g.scene.as_str()) {
            scenes.push(&g.scene);
        }
    }
    for scene in scenes {
        let mut gs: Vec<&GroupSummary> = groups.iter().filter(|g| g.scene == scene).collect();
        let reference = gs[0].reference;
        gs.sort_by(|a, b| {
            let ta = a.time_to_target.unwrap_or(f64::INFINITY);
            let tb = b.time_to_target.unwrap_or(f64::INFINITY);
            ta.total_cmp(&tb).then_with(|| {
                let ea = a.efficiency.unwrap_or(f64::INFINITY);
                let eb = b.efficiency.unwrap_or(f64::INFINITY);
                eb.total_cmp(&ea)
            })
        });
        let _ = writeln!(s, "## {scene}\n");
        match reference {
            Some(r) => {
                let _ = writeln!(s, "Closed form E = {r:.9e} W/m².\n");
            }
            None => {
                let _ = writeln!(s, "No closed form: ranked by efficiency only.\n");
            }
        }
        let _ = writeln!(
            s,
            "| rank | strategy | sequence | time to 0.1 % | efficiency 1/(V·T) | ns/sample | rel. RMSE at N = {} | slope | theory |",
            gs[0].n_max
        );
        let _ = writeln!(s, "|---:|---|---|---:|---:|---:|---:|---:|---|");
        for (i, g) in gs.iter().enumerate() {
            let theory = if g.fit == Some(LogLogFit::Exact) {
                "exact"
            } else {
                theoretical_slope(g.sequence)
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {:.1} | {} | {} | {} |",
                i + 1,
                g.strategy,
                sequence_label(g.sequence, g.precision),
                seconds(g.time_to_target),
                g.efficiency
                    .map(|e| format!("{e:.3e}"))
                    .unwrap_or_else(|| "∞ (V = 0)".into()),
                g.ns_per_sample,
                g.final_rel_rmse
                    .map(|e| format!("{e:.2e}"))
                    .unwrap_or_else(|| "—".into()),
                slope_text(g.fit),
                theory,
            );
        }
        let _ = writeln!(s);
        let mut notes = String::new();
        for g in &gs {
            if !g.warning_rows.is_empty() {
                let m = rows
                    .iter()
                    .find(|r| r.scene == g.scene)
                    .map_or(0, |r| r.stats.replicates);
                let _ = writeln!(
                    notes,
                    "- **few hits**: {} × {} at N = {} (replicates with rare-event intervals).",
                    g.strategy,
                    sequence_label(g.sequence, g.precision),
                    exponents(&g.warning_rows, |w| format!(" ({w} of {m})")),
                );
            }
            if !g.spread_flags.is_empty() {
                let _ = writeln!(
                    notes,
                    "- **σ vs spread**: {} × {} at N = {} (spread/σ).",
                    g.strategy,
                    sequence_label(g.sequence, g.precision),
                    exponents(&g.spread_flags, |x| format!(" ({x:.2})"))
                );
            }
        }
        if !notes.is_empty() {
            let _ = writeln!(s, "Notes:\n\n{notes}");
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aggregate::RowStats;

    fn row(i: usize, strategy: Strategy, log2_n: u32, rmse: f64) -> ResultRow {
        ResultRow {
            row: i,
            scene: "s".into(),
            strategy,
            sequence: SequenceKind::Independent,
            precision: Precision::F64,
            log2_n,
            reference: Some(2.0),
            stats: RowStats {
                replicates: 4,
                mean_estimate: 2.0,
                mean_rel_error: Some(0.0),
                rmse: Some(rmse),
                rel_rmse: Some(rmse / 2.0),
                coverage: Some(1.0),
                hits: 100,
                warnings: 0,
                std_error: rmse,
                replicate_sd: Some(rmse),
                sample_variance: rmse,
                ns_per_sample: 10.0,
                efficiency: if rmse > 0.0 { Some(1.0) } else { None },
            },
        }
    }

    #[test]
    fn groups_fit_and_rank() {
        // Light: RMSE = 2/√N exactly; cosine: exact.
        let mut rows = Vec::new();
        for k in 0..6 {
            rows.push(row(
                k as usize,
                Strategy::Light,
                k,
                2.0 / f64::from(1u32 << k).sqrt(),
            ));
        }
        for k in 0..6 {
            rows.push(row(6 + k as usize, Strategy::CosineHemisphere, k, 0.0));
        }
        let g = group_summaries(&rows);
        assert_eq!(g.len(), 2);
        match g[0].fit {
            Some(LogLogFit::Line {
                slope, slope_se, ..
            }) => {
                assert!((slope + 0.5).abs() < 1e-12 && slope_se < 1e-12);
            }
            ref other => panic!("{other:?}"),
        }
        // 0.1 % of E = 2 is 0.002 = 2/√N → N = 1e6; × 10 ns = 10 ms.
        assert!((g[0].time_to_target.unwrap() - 1e-2).abs() < 1e-9);
        assert_eq!(g[1].fit, Some(LogLogFit::Exact));
        assert_eq!(g[1].time_to_target, Some(0.0));
        let md = summary_markdown("t", &rows);
        let cos = md.find("| 1 | cosine-hemisphere").unwrap();
        let light = md.find("| 2 | light").unwrap();
        assert!(cos < light, "{md}");
        assert!(md.contains("-0.500 ± 0.000"), "{md}");
        assert!(md.contains("| exact | exact |"), "{md}");
        assert!(
            !md.contains("- **few hits**") && !md.contains("- **σ vs spread**"),
            "{md}"
        );
    }

    /// A row with warnings is noted; a row whose spread is 10× its σ is
    /// flagged, and one whose spread matches it is not.
    #[test]
    fn notes_few_hits_and_spread_disagreement() {
        let mut rows: Vec<ResultRow> = (0..4)
            .map(|k| row(k as usize, Strategy::Area, 10 + k, 1e-3))
            .collect();
        rows[1].stats.warnings = 3;
        rows[2].stats.replicate_sd = Some(1e-2);
        let g = group_summaries(&rows);
        assert_eq!(g[0].warning_rows, vec![(11, 3)]);
        assert_eq!(g[0].spread_flags.len(), 1);
        assert_eq!(g[0].spread_flags[0].0, 12);
        let md = summary_markdown("t", &rows);
        assert!(
            md.contains("- **few hits**: area × independent at N = 2^11 (3 of 4)"),
            "{md}"
        );
        assert!(
            md.contains("- **σ vs spread**: area × independent at N = 2^12 (10.00)"),
            "{md}"
        );
    }

    #[test]
    fn runs_of_exponents_are_joined() {
        let items = [(5, 8), (6, 8), (7, 8), (9, 8), (10, 3), (11, 3)];
        assert_eq!(
            exponents(&items, |x| format!(" ({x})")),
            "2^5…2^7 (8), 2^9 (8), 2^10…2^11 (3)"
        );
    }

    /// The band of s/σ for M = 8 independent replicates of 2²⁰ samples at
    /// α = 0.01: √(χ²₀.₀₀₅(7)/7) = √(0.9893/7) and √(χ²₀.₉₉₅(7)/7) =
    /// √(20.278/7) (tables, to 1e-3; F(7, 2²⁰ − 1) is χ²(7)/7 to ~1e-5).
    /// The randomized-QMC band, F(7, 15), is wider: F₀.₉₉₅(7, 15) = 4.85.
    #[test]
    fn spread_band_matches_the_tables() {
        let (lo, hi) = spread_band(8, SequenceKind::Independent, 1 << 20, 0.01).unwrap();
        assert!((lo - (0.9893f64 / 7.0).sqrt()).abs() < 1e-3, "{lo}");
        assert!((hi - (20.278f64 / 7.0).sqrt()).abs() < 1e-3, "{hi}");
        let (lo_q, hi_q) = spread_band(8, SequenceKind::Sobol, 1 << 20, 0.01).unwrap();
        assert!((hi_q - 4.85f64.sqrt()).abs() < 1e-2, "{hi_q}");
        assert!(lo_q < lo && hi_q > hi, "{lo_q} {hi_q}");
        assert_eq!(spread_band(1, SequenceKind::Sobol, 1 << 20, 0.01), None);
    }
}
