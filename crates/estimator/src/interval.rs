//! Honest 99 % intervals: the central limit theorem where the samples
//! support it, rare-event bounds where they do not.
//!
//! `m ± q·s/√N` is a statement about the normal limit of the sample mean.
//! It is false when the samples have not seen what the mean depends on: a
//! light that no sample hit (m = 0, s = 0, interval [0, 0]), a light hit a
//! handful of times (the mean is a Poisson count of a few, far from
//! normal), a sliver that every sample but a few missed (all samples equal,
//! s = 0), or the core of a heavy-tailed estimator that no sample reached.
//! Each sample's value is the sum of the *parts* of the emitters'
//! estimates (one per technique, two for MIS), each with a known bound
//! ([`PartBound`]); the estimator counts, per part, the samples in which it
//! was non-zero (its *hits*). A part is
//!
//! - **well sampled** when it had at least [`CLT_MIN_EVENTS`] hits (and,
//!   for a two-valued part, as many misses), or is constant;
//! - **rare, above**, with fewer hits h: its contribution Z ∈ [0, c] is
//!   non-zero only on a hit, so E(Z) ≤ c·p with p ≤ p_U(h) the binomial
//!   upper bound ([`bounded::hit_probability_upper`]; with h = 0,
//!   p ≤ 1 − α^{1/N} ≤ −ln α/N), and also p ≤ the geometric bound
//!   [`PartBound::hit_probability`] (Ω/π for a cosine-sampled direction),
//!   whichever is smaller;
//! - **rare, below** (a two-valued part, cosine sampling of a uniform
//!   emitter, whose misses are rare): c − Z is non-zero only on a miss, so
//!   E(Z) ≥ c − c·p_U(misses);
//! - **unresolved**: a two-valued part with too few hits *and* misses, or a
//!   heavy-tailed part whose core a sample reaches with probability q and
//!   N·q < [`CLT_MIN_EVENTS`].
//!
//! The interval ([`IntervalKind`]) is then
//!
//! - [`CentralLimit`](IntervalKind::CentralLimit), every part well sampled:
//!   `m ± q·se` (normal, or Student-t over the randomized-QMC replicates);
//!   also when the only rare parts are *negligible*: the interval below
//!   moves the CLT one by less than [`NEGLIGIBLE`] of its half-width (the
//!   cosine half of MIS with the power heuristic under a small light, whose
//!   weights make its share ~(Ω/π)² of E) — the interval still includes
//!   their bounds, but carries no warning;
//! - [`RareEvent`](IntervalKind::RareEvent), some parts rare and at least
//!   one well sampled: writing the sample value X = Y + Z (Z the rare parts
//!   above) or X = Y + c − Z′ (rare parts below), the CLT interval of Y at
//!   level 1 − 0.9α, widened by what the rare parts can hide, at level
//!   0.1α shared between them:
//!
//!   ```text
//!   [ m − q·se′ − c·h/N − c′·p_U(m′),  m + q·se′ + c·p_U(h) + c′·m′/N ],
//!   se′ = se + (bound on the standard error of the rare parts' sample mean)
//!   ```
//!
//!   (c, h: the rare-above parts' summed bound and hits; c′, m′ the rare-below
//!   parts' bound and misses; 0 ≤ Z̄ ≤ c·h/N, and the spread of Y is at most
//!   that of X plus that of Z by the triangle inequality);
//! - [`Bounded`](IntervalKind::Bounded), some part unresolved or none well
//!   sampled: the interval for the mean of values in [0, B], B the sum of
//!   the parts' bounds, that holds for any N and any distribution
//!   ([`bounded::bounded_mean_interval`], Hoeffding 1963): with 0 hits the
//!   one-sided [0, B·(1 − α^{1/N})]; its upper end is capped by
//!   Σ c·hit_probability, which no mean can exceed. Honest, and as wide as
//!   the bound makes it: for area sampling close to an emitter, very wide.
//!
//! Every kind but the first carries an [`EstimateWarning`] naming the
//! emitter and part that decided it.
//!
//! **Randomized QMC.** The stratified and Sobol estimates take their CLT
//! part from the spread of their R = 16 independent replicates, as before;
//! the rare-event bounds use the pooled N points as if their hits were
//! independent. They are not: one point per stratum (or per elementary
//! interval of a scrambled net) spreads them more evenly than independent
//! points, which for jittered strata provably makes missing a region of
//! measure p entirely no likelier than (1 − p)^N given the layout; for
//! scrambled nets and general regions we know no proof and measure the
//! coverage instead (the tests run every sequence).
//!
//! **Counts that every replicate shares.** Stratification can fix how many
//! samples hit a light: a cap straight overhead is, for a hemisphere
//! sampler, a strip u₀ ∈ [1 − h, 1) of the unit square, and the stratified
//! and Sobol points put exactly one point in each interval of width 1/n of
//! u₀, so each replicate of n points hits it ⌊n·h⌋ or ⌈n·h⌉ times — almost
//! always the same number. The replicates' means then agree to far better
//! than their actual error, which comes from the fractional interval that
//! some rare replicate misses (measured: a sphere of 0.1 rad overhead,
//! uniform-hemisphere × stratified at N = 2^17, 41 hits in every replicate,
//! a reported σ 1300× below the spread of independent estimates, z = −1200).
//! When every replicate hit a part the same number of times (and neither 0
//! nor every time), the interval is widened by one hit's worth per part,
//! ±c/n with n the samples per replicate — the count's deviation from its
//! expectation under such stratification — and carries a warning.
//!
//! **The rounding floor.** The standard error used is never below the
//! bound on the floating-point error of the accumulated mean
//! ([`rounding::mean_rounding_floor`]).

use std::fmt;

#[cfg(doc)]
use crate::statistics::bounded;
use crate::statistics::bounded::{bounded_mean_interval, hit_probability_upper};
#[cfg(doc)]
use crate::statistics::rounding;
use crate::statistics::rounding::mean_rounding_floor;
use crate::statistics::ConfidenceInterval;
use crate::strategy::{PartBound, PartShape};

/// The fewest hits (or misses, for a two-valued part) a part needs before
/// its share of the interval comes from the central limit theorem. With
/// fewer, a Wald interval for a Poisson count of mean λ covers at 99 % only
/// 63 % (λ = 1), 96 % (λ = 5), 97–98 % (λ = 10 … 25); from λ = 30 on it
/// stays within 0.5 % of 99 % (98.6 % at 30, 98.9 % at 200: the skewness
/// 1/√λ fades slowly).
pub const CLT_MIN_EVENTS: u64 = 30;

/// The confidence level of the reported interval (`ci99`).
pub const LEVEL: f64 = 0.99;

/// A rare part whose bounds move the CLT interval by less than this
/// fraction of its half-width is folded in without a warning (module
/// docs).
pub const NEGLIGIBLE: f64 = 0.1;

/// The share of 1 − [`LEVEL`] given to the rare-event bounds when an
/// interval combines them with the CLT ([`IntervalKind::RareEvent`]).
pub const RARE_SHARE: f64 = 0.1;

/// How an estimate's interval was formed (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IntervalKind {
    /// `m ± q·se`: every part of the estimate was well sampled.
    CentralLimit,
    /// The CLT for the well-sampled parts, widened by the rare-event bounds
    /// of the others.
    RareEvent,
    /// From the bound on a sample's value alone (Hoeffding): valid for any
    /// number of hits, wide.
    Bounded,
}

impl IntervalKind {
    /// The name used in JSON and CSV: `clt`, `rare-event`, `bounded`.
    pub fn name(self) -> &'static str {
        match self {
            IntervalKind::CentralLimit => "clt",
            IntervalKind::RareEvent => "rare-event",
            IntervalKind::Bounded => "bounded",
        }
    }
}

impl fmt::Display for IntervalKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What made a part of an estimate rare (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RareCause {
    /// The part was never non-zero: its contribution is only bounded
    /// above.
    NoHits,
    /// The part was non-zero in 1 … [`CLT_MIN_EVENTS`] − 1 samples.
    FewHits {
        /// Its hits.
        hits: u64,
    },
    /// A two-valued part that all but a few samples hit: the few misses
    /// decide the mean, and with none the samples are all equal.
    FewMisses {
        /// Its misses (0 … [`CLT_MIN_EVENTS`] − 1).
        misses: u64,
    },
    /// Area sampling close to the emitter: the expected number of samples
    /// in the core that carries the estimate is below [`CLT_MIN_EVENTS`].
    HeavyTail {
        /// N·q.
        expected_core_samples: f64,
    },
    /// Randomized QMC: every replicate hit the part the same number of
    /// times, so their spread cannot show how that count varies (module
    /// docs).
    FixedCount {
        /// The hits of each replicate.
        per_replicate: u64,
    },
}

/// Why an estimate's interval is not the plain CLT one: the part that
/// decided it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EstimateWarning {
    /// The emitter's index in the scene.
    pub emitter: usize,
    /// The part of its estimate ([`PartBound::name`]).
    pub part: &'static str,
    /// What happened.
    pub cause: RareCause,
}

impl fmt::Display for EstimateWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (e, part) = (self.emitter, self.part);
        match self.cause {
            RareCause::NoHits => write!(
                f,
                "emitter {e}, {part}: no hit, so the central limit theorem does not apply; \
                 its share is bounded above by the rare-event bound (0 hits in N: \
                 p ≤ 1 − α^(1/N) ≤ −ln α / N), not estimated"
            ),
            RareCause::FewHits { hits } => write!(
                f,
                "emitter {e}, {part}: only {hits} hits (< {CLT_MIN_EVENTS}), too few for the \
                 central limit theorem; the interval uses rare-event bounds"
            ),
            RareCause::FewMisses { misses } => write!(
                f,
                "emitter {e}, {part}: all but {misses} samples hit it with the same value \
                 (< {CLT_MIN_EVENTS} misses), so the standard error cannot show what the \
                 misses hide; the interval uses rare-event bounds"
            ),
            RareCause::FixedCount { per_replicate } => write!(
                f,
                "emitter {e}, {part}: every randomized replicate hit it exactly \
                 {per_replicate} times (the stratification fixes the count), so their spread \
                 cannot show the count's discreteness; the interval adds one hit's worth, \
                 ±bound/n per replicate"
            ),
            RareCause::HeavyTail {
                expected_core_samples,
            } => write!(
                f,
                "emitter {e}, {part}: heavy tail, area sampling this close to the emitter \
                 reaches the core that carries the estimate in {expected_core_samples:.3e} \
                 samples expected (< {CLT_MIN_EVENTS}), so the sample variance cannot show \
                 the error; the interval comes from the bound on a sample's value and is wide"
            ),
        }
    }
}

/// One part of an estimate with its bound and its hits over all samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartTally {
    /// The index of the part's emitter in the scene.
    pub emitter: usize,
    /// The part's bound.
    pub bound: PartBound,
    /// Samples in which the part was non-zero.
    pub hits: u64,
    /// Randomized QMC: the part's hits in each replicate, when every
    /// replicate had the same number (module docs); `None` otherwise, and
    /// for independent samples.
    pub replicate_hits: Option<u64>,
}

/// Where an estimate's standard error comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorSource {
    /// The spread of N independent samples: s/√N, normal quantile (N ≥ 30).
    Samples,
    /// The spread of R independent randomized-QMC replicates: Student-t
    /// with R − 1 degrees of freedom.
    Replicates(u64),
}

/// What an estimate's interval is formed from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleSummary {
    /// Samples N.
    pub n: u64,
    /// The reported estimate, delta lights included.
    pub mean: f64,
    /// The mean of the sampled part alone (no delta lights), ≥ 0.
    pub sampled_mean: f64,
    /// The exact irradiance of the delta lights.
    pub delta: f64,
    /// The standard error from the samples or replicates (before the
    /// rounding floor).
    pub std_error: f64,
    /// A bound on the error every sample carries alike, which no number of
    /// samples averages away: the rounding error of a projected sampler's
    /// Ω⊥ ([`PreparedEmitter::systematic_error`](crate::strategy::PreparedEmitter::systematic_error)).
    /// Added to the rounding floor.
    pub systematic: f64,
    /// Where it comes from.
    pub source: ErrorSource,
}

/// An estimate's honest interval (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HonestInterval {
    /// The standard error, never below the rounding floor.
    pub std_error: f64,
    /// The interval's ends, finite, around the estimate (the upper is
    /// f64::MAX when the bound on a sample's value overflows).
    pub ci: (f64, f64),
    /// How it was formed.
    pub kind: IntervalKind,
    /// Why it is not the plain CLT interval.
    pub warning: Option<EstimateWarning>,
}

/// The rare parts of an estimate on one side, summed.
#[derive(Clone, Copy, Debug, Default)]
struct Rare {
    /// Σ of their bounds c.
    bound: f64,
    /// Σ of their events (hits above, misses below): at least the number of
    /// samples in which any of them deviated.
    events: u64,
    /// Σ c·(known bound on the event probability): a bound on their share
    /// of the mean that holds whatever the samples say.
    known_share: f64,
}

impl Rare {
    fn add(&mut self, bound: f64, events: u64, event_probability: f64) {
        self.bound += bound;
        self.events += events;
        self.known_share += bound * event_probability;
    }

    /// A bound on their share of the mean at level 1 − α: c·p_U(events),
    /// or the known share if smaller.
    fn share_upper(&self, n: u64, alpha: f64) -> f64 {
        (self.bound * hit_probability_upper(self.events, n, alpha)).min(self.known_share)
    }

    /// The most their events can have moved the sample mean: c·events/N,
    /// and 0 with no event whatever the bound (which overflows to ∞ for an
    /// emitter whose values pass f64's range, where c·0 would be NaN).
    fn observed_share(&self, n: u64) -> f64 {
        if self.events == 0 {
            return 0.0;
        }
        self.bound * self.events as f64 / n as f64
    }

    fn is_empty(&self) -> bool {
        self.bound == 0.0 && self.events == 0
    }

    /// A bound on the standard error of the rare parts' contribution to the
    /// mean: with `events` non-zero values in [0, c] among N, the sample
    /// standard deviation is at most c·√(events/(N − 1)) (independent), and
    /// the spread of R replicate means, each at most c·events_r/n, is at
    /// most c·events·√(R/(R − 1))/N (randomized QMC).
    ///
    /// No events: every value of these parts was 0, and so is their
    /// spread, whatever the bound (which overflows to ∞ for an emitter
    /// whose values pass f64's range, where c·0 would be NaN).
    fn std_error(&self, n: u64, source: ErrorSource) -> f64 {
        if self.events == 0 {
            return 0.0;
        }
        let (c, k, nf) = (self.bound, self.events as f64, n as f64);
        match source {
            ErrorSource::Samples => c * (k / (nf - 1.0)).sqrt() / nf.sqrt(),
            ErrorSource::Replicates(r) => {
                let r = r as f64;
                c * k * (r / (r - 1.0)).sqrt() / nf
            }
        }
    }
}

/// The honest interval at confidence `level` (e.g. [`LEVEL`]) of an
/// estimate from its summary and the tallies of its parts (module docs).
///
/// # Panics
/// In debug builds, unless 0 < level < 1 and n ≥ 2.
pub fn honest_interval(summary: &SampleSummary, parts: &[PartTally], level: f64) -> HonestInterval {
    debug_assert!(level > 0.0 && level < 1.0, "level {level}");
    let n = summary.n;
    let floor = mean_rounding_floor(summary.sampled_mean.abs() + summary.delta.abs(), n)
        + summary.systematic;
    let std_error = summary.std_error.max(floor);
    let alpha = 1.0 - level;
    let mut above = Rare::default();
    let mut below = Rare::default();
    let mut well_sampled = 0usize;
    let mut unresolved = false;
    // The warning shown: a heavy tail first, else the rare part with the
    // fewest events.
    let mut warning: Option<(EstimateWarning, u64)> = None;
    let mut note = |part: &PartTally, cause: RareCause, events: u64| {
        let heavy = |c: &RareCause| matches!(c, RareCause::HeavyTail { .. });
        let replace = match &warning {
            None => true,
            Some((w, fewest)) => !heavy(&w.cause) && (heavy(&cause) || events < *fewest),
        };
        if replace {
            let w = EstimateWarning {
                emitter: part.emitter,
                part: part.bound.name,
                cause,
            };
            warning = Some((w, events));
        }
    };
    for part in parts {
        let (c, hits) = (part.bound.max, part.hits);
        let misses = n - hits.min(n);
        let few = |k: u64| k < CLT_MIN_EVENTS;
        let hit_cause = if hits == 0 {
            RareCause::NoHits
        } else {
            RareCause::FewHits { hits }
        };
        match part.bound.shape {
            PartShape::Constant => well_sampled += 1,
            PartShape::TwoValued if few(hits) && few(misses) => {
                unresolved = true;
                note(part, hit_cause, hits.min(misses));
            }
            PartShape::TwoValued if few(misses) => {
                below.add(c, misses, 1.0);
                note(part, RareCause::FewMisses { misses }, misses);
            }
            PartShape::HeavyTailed { core_probability }
                if (n as f64) * core_probability < CLT_MIN_EVENTS as f64 =>
            {
                unresolved = true;
                let expected_core_samples = n as f64 * core_probability;
                note(
                    part,
                    RareCause::HeavyTail {
                        expected_core_samples,
                    },
                    0,
                );
            }
            _ if few(hits) => {
                above.add(c, hits, part.bound.hit_probability);
                note(part, hit_cause, hits);
            }
            _ => well_sampled += 1,
        }
    }
    // Randomized QMC: parts whose count every replicate shares.
    let mut count_slack = 0.0;
    if let ErrorSource::Replicates(r) = summary.source {
        let per_replicate = (n / r).max(1);
        for part in parts {
            match part.replicate_hits {
                Some(h) if h > 0 && h < per_replicate && part.bound.max > 0.0 => {
                    count_slack += part.bound.max / per_replicate as f64;
                    note(part, RareCause::FixedCount { per_replicate: h }, h);
                }
                _ => {}
            }
        }
    }
    let warning = warning.map(|(w, _)| w);
    let clt = |level: f64, se: f64| {
        // A standard error past f64's range (a rare part's bound that
        // overflowed) bounds nothing: the whole line, which `finite` clips
        // to [0, f64::MAX].
        if !se.is_finite() {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        let dof_n = match summary.source {
            ErrorSource::Samples => n,
            ErrorSource::Replicates(r) => r,
        };
        let ci = ConfidenceInterval::new(summary.mean, se, dof_n, level);
        (ci.lower, ci.upper)
    };
    if above.is_empty() && below.is_empty() && !unresolved && count_slack == 0.0 {
        return HonestInterval {
            std_error,
            ci: clt(level, std_error),
            kind: IntervalKind::CentralLimit,
            warning: None,
        };
    }
    let delta = summary.delta;
    if unresolved || well_sampled == 0 {
        let bound: f64 = parts.iter().map(|p| p.bound.max).sum();
        let known: f64 = parts
            .iter()
            .map(|p| p.bound.max * p.bound.hit_probability)
            .sum();
        let (lo, hi) = bounded_mean_interval(summary.sampled_mean, bound, n, alpha);
        // No mean exceeds `known`; the interval still holds the estimate.
        let m = summary.sampled_mean;
        let (lo, hi) = (lo.min(m), hi.min(known.max(m)));
        return HonestInterval {
            std_error,
            ci: finite((lo + delta, hi + delta), summary.mean),
            kind: IntervalKind::Bounded,
            warning,
        };
    }
    let groups = (u64::from(!above.is_empty()) + u64::from(!below.is_empty())).max(1);
    let alpha_rare = alpha * RARE_SHARE / groups as f64;
    let clt_level = 1.0 - alpha * (1.0 - RARE_SHARE);
    let (clt_lo, clt_hi) = clt(clt_level, std_error);
    let se = std_error + above.std_error(n, summary.source) + below.std_error(n, summary.source);
    let (lo, hi) = clt(clt_level, se);
    let lo = lo - above.observed_share(n) - below.share_upper(n, alpha_rare) - count_slack;
    let hi = hi + above.share_upper(n, alpha_rare) + below.observed_share(n) + count_slack;
    // The sampled parts are never negative: E ≥ δ.
    let ci = (lo.max(delta), hi);
    let half_width = 0.5 * (clt_hi - clt_lo);
    let moved = (clt_lo - ci.0).max(ci.1 - clt_hi);
    let negligible = moved <= NEGLIGIBLE * half_width;
    HonestInterval {
        std_error,
        ci: finite(ci, summary.mean),
        kind: if negligible {
            IntervalKind::CentralLimit
        } else {
            IntervalKind::RareEvent
        },
        warning: if negligible { None } else { warning },
    }
}

/// The interval with its ends made finite: an end that overflowed (a value
/// bound beyond f64, e.g. area sampling 1e-200 m under a light) becomes
/// f64::MAX (no finite bound) or 0, and the estimate stays inside.
fn finite((lo, hi): (f64, f64), mean: f64) -> (f64, f64) {
    let lo = if lo.is_finite() { lo.min(mean) } else { 0.0 };
    let hi = if hi.is_nan() {
        f64::MAX
    } else {
        hi.min(f64::MAX).max(mean)
    };
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tally(max: f64, shape: PartShape, hits: u64) -> PartTally {
        PartTally {
            replicate_hits: None,
            emitter: 0,
            bound: PartBound {
                max,
                shape,
                hit_probability: 1.0,
                name: "test part",
            },
            hits,
        }
    }

    fn summary(n: u64, mean: f64, std_error: f64) -> SampleSummary {
        SampleSummary {
            n,
            mean,
            sampled_mean: mean,
            delta: 0.0,
            std_error,
            source: ErrorSource::Samples,
            systematic: 0.0,
        }
    }

    /// 0 hits in 10⁵ samples of a part bounded by π: one-sided
    /// [0, π(1 − 0.01^(1/N))], with the warning.
    #[test]
    fn zero_hits_give_the_one_sided_rare_event_bound() {
        let parts = [tally(std::f64::consts::PI, PartShape::TwoValued, 0)];
        let h = honest_interval(&summary(100_000, 0.0, 0.0), &parts, LEVEL);
        assert_eq!(h.kind, IntervalKind::Bounded);
        assert_eq!(h.warning.map(|w| w.cause), Some(RareCause::NoHits));
        assert_eq!(h.ci.0, 0.0);
        let exact = -std::f64::consts::PI * (0.01f64.ln() * 1e-5).exp_m1();
        assert!(
            h.ci.1 >= exact && h.ci.1 <= exact * (1.0 + 1e-9),
            "{:?}",
            h.ci
        );
    }

    /// A rare part beside a well-sampled one: the CLT interval widened by
    /// the rare part's bounds, at the shared level; a negligible one widens
    /// it by less than a tenth of its half-width and raises no warning.
    #[test]
    fn a_rare_part_widens_the_clt_interval() {
        let quiet = [
            tally(1.0, PartShape::Bounded, 50_000),
            tally(1e-3, PartShape::Bounded, 0),
        ];
        let h = honest_interval(&summary(100_000, 0.5, 1e-3), &quiet, LEVEL);
        assert_eq!((h.kind, h.warning), (IntervalKind::CentralLimit, None));
        let p = hit_probability_upper(0, 100_000, 0.001);
        let q = ConfidenceInterval::new(0.5, 1e-3, 100_000, 1.0 - 0.009).quantile;
        assert!((h.ci.1 - (0.5 + q * 1e-3 + 1e-3 * p)).abs() < 1e-15);
        let parts = [
            tally(1.0, PartShape::Bounded, 50_000),
            tally(10.0, PartShape::Bounded, 0),
        ];
        let h = honest_interval(&summary(100_000, 0.5, 1e-3), &parts, LEVEL);
        assert_eq!(h.kind, IntervalKind::RareEvent);
        let q = ConfidenceInterval::new(0.5, 1e-3, 100_000, 1.0 - 0.009).quantile;
        let p = hit_probability_upper(0, 100_000, 0.001);
        assert!((h.ci.0 - (0.5 - q * 1e-3)).abs() < 1e-15);
        assert!((h.ci.1 - (0.5 + q * 1e-3 + 10.0 * p)).abs() < 1e-15);
    }

    /// A rare part whose bound overflows (an emitter of radiance near
    /// f64::MAX), for independent samples and for replicates alike. With
    /// no event its spread and its observed share are 0, not ∞·0: the
    /// lower end is the CLT one (the part can only add to the mean) and
    /// the upper end f64::MAX. With events, the standard error is infinite
    /// and the interval the whole of [0, f64::MAX]. (Fuzz seed 1, case
    /// 176: both panicked in builds with debug assertions, on a NaN or
    /// infinite standard error, and gave [0, f64::MAX] through a NaN in
    /// release builds.)
    #[test]
    fn an_overflowing_rare_part_gives_a_finite_interval() {
        for (source, dof_n) in [
            (ErrorSource::Samples, 100_000),
            (ErrorSource::Replicates(16), 16),
        ] {
            for events in [0, 3] {
                let parts = [
                    tally(1.0, PartShape::Bounded, 50_000),
                    tally(f64::INFINITY, PartShape::Bounded, events),
                ];
                let s = SampleSummary {
                    source,
                    ..summary(100_000, 0.5, 1e-3)
                };
                let h = honest_interval(&s, &parts, LEVEL);
                let case = format!("{source:?}, {events} events: {:?}", h.ci);
                // The CLT part's lower end at the shared level, computed
                // the same way: equal to the bit.
                let q = ConfidenceInterval::new(0.5, 1e-3, dof_n, 1.0 - 0.009).quantile;
                let lower = if events == 0 { 0.5 - q * 1e-3 } else { 0.0 };
                assert_eq!(h.ci, (lower, f64::MAX), "{case}");
                assert_eq!(h.std_error, 1e-3, "{case}");
            }
        }
    }

    /// A constant part (cosine sampling of a sky): the CLT interval with the
    /// rounding floor as standard error, no warning.
    #[test]
    fn a_constant_part_is_exact_to_the_rounding_floor() {
        let pi = std::f64::consts::PI;
        let parts = [tally(pi, PartShape::Constant, 1 << 20)];
        let h = honest_interval(&summary(1 << 20, pi, 0.0), &parts, LEVEL);
        assert_eq!(h.kind, IntervalKind::CentralLimit);
        assert_eq!(h.std_error, mean_rounding_floor(pi, 1 << 20));
        assert!(h.ci.0 < pi && pi < h.ci.1);
    }

    /// Every sample equal to a two-valued part's maximum (no miss): bounded
    /// interval, one-sided below.
    #[test]
    fn no_miss_of_a_two_valued_part_is_not_exactness() {
        let pi = std::f64::consts::PI;
        let parts = [tally(pi, PartShape::TwoValued, 1000)];
        let h = honest_interval(&summary(1000, pi, 0.0), &parts, LEVEL);
        assert_eq!(h.kind, IntervalKind::Bounded);
        assert_eq!(
            h.warning.map(|w| w.cause),
            Some(RareCause::FewMisses { misses: 0 })
        );
        assert!(h.ci.0 < pi * (1.0 - 4e-3) && h.ci.1 >= pi);
    }

    /// Randomized QMC with the same count in every replicate: widened by
    /// c/n, with a warning; with counts that differ, the plain t interval.
    #[test]
    fn a_count_every_replicate_shares_widens_the_interval() {
        let mut part = tally(2.0, PartShape::Bounded, 16 * 41);
        let rqmc = SampleSummary {
            source: ErrorSource::Replicates(16),
            ..summary(16 * 8192, 0.01, 1e-8)
        };
        let plain = honest_interval(&rqmc, &[part], LEVEL);
        assert_eq!(
            (plain.kind, plain.warning),
            (IntervalKind::CentralLimit, None)
        );
        part.replicate_hits = Some(41);
        let h = honest_interval(&rqmc, &[part], LEVEL);
        assert_eq!(h.kind, IntervalKind::RareEvent);
        assert_eq!(
            h.warning.map(|w| w.cause),
            Some(RareCause::FixedCount { per_replicate: 41 })
        );
        assert!(h.ci.1 - 0.01 >= 2.0 / 8192.0 && 0.01 - h.ci.0 >= 2.0 / 8192.0);
    }

    #[test]
    fn heavy_tails_use_the_bounded_interval() {
        let parts = [tally(
            1e6,
            PartShape::HeavyTailed {
                core_probability: 1e-6,
            },
            1000,
        )];
        let h = honest_interval(&summary(1000, 0.5, 1e-3), &parts, LEVEL);
        assert_eq!(h.kind, IntervalKind::Bounded);
        assert!(matches!(
            h.warning.map(|w| w.cause),
            Some(RareCause::HeavyTail { .. })
        ));
        assert!(h.ci.1 > 10.0);
    }
}
