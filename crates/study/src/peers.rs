//! The summary's comparison of lambert's own strategies — projected
//! solid-angle sampling and the closed-form control variate — with the best
//! strategy a pbrt-v4 or Mitsuba 3 renderer offers for the same emitter,
//! per scene.
//!
//! **What counts as pbrt-v4/Mitsuba-style.** Both renderers sample a light
//! by its solid angle where they can (the cone a sphere subtends, Shirley et
//! al. 1996; spherical triangles and rectangles, Arvo 1995 and Ureña et
//! al. 2013, for triangles and quads in pbrt-v4), by area otherwise (disks,
//! and polygons in Mitsuba 3), and combine light and BSDF (cosine) samples
//! by multiple importance sampling (Veach & Guibas 1995). Here those are
//! the `light`, `area`, `mis` (power heuristic) and `mis-balance`
//! strategies. (lambert's `light` on a disk samples its spherical ellipse,
//! Guillén et al. 2017, which neither renderer has; `area` stands for what
//! they do there.) The baseline of a scene is whichever of these, over
//! every sequence of the study, reaches 0.1 % relative RMSE soonest.
//!
//! **Exact estimators.** A zero-variance estimator (every replicate's
//! error 0, or a relative RMSE at the rounding level, ≤ 1e-12: projected
//! sampling of an unoccluded uniform light, the control variate without
//! occluders) reaches any error with one sample; its time to 0.1 % is then
//! the time of one sample (ns/sample), not 0, and its efficiency 1/(V·T)
//! is unbounded (a V of rounding errors would make it ~1e25 times the
//! baseline's, a meaningless figure). That one sample's time is the
//! group's ns/sample at the largest N, which spreads the estimator's
//! one-off preparation at the receiver (the closed form, the sampler's
//! setup: about 1 µs for a closed form) over N samples; a lone sample
//! pays that preparation in full, so the speed-ups of exact estimators
//! are those of a renderer that takes many samples per shading point.
//! Other groups take the summary's
//! time to 0.1 % as it is (from the fit of RMSE against N; a group within
//! 0.1 % at every N is bounded by its smallest N: extrapolating below it
//! by N^-½ would flatter randomized QMC, whose error falls faster). The table says "exact" there, gives
//! the speed-up as the baseline's time over one sample's, and leaves the
//! ε ratio as ∞.

use std::fmt::Write;

use lambert_estimator::strategy::{Heuristic, Strategy};

use crate::fit::LogLogFit;
use crate::results::sequence_label;
use crate::summary::GroupSummary;

/// The strategies a pbrt-v4/Mitsuba 3 renderer offers (module docs).
pub const PEER_STRATEGIES: [Strategy; 4] = [
    Strategy::Light,
    Strategy::Area,
    Strategy::Mis(Heuristic::Power),
    Strategy::Mis(Heuristic::Balance),
];

/// The relative RMSE at or below which a group counts as exact: the
/// rounding level of its sums (the zero-variance tests' bound, 1e-12),
/// where efficiency 1/(V·T) measures rounding, not sampling.
pub const EXACT_REL_RMSE: f64 = 1e-12;

/// Whether a group is exact: every replicate's error 0 (the fit says so),
/// or its relative RMSE at the largest N at most [`EXACT_REL_RMSE`].
fn is_exact(g: &GroupSummary) -> bool {
    g.fit == Some(LogLogFit::Exact) || g.final_rel_rmse.is_some_and(|e| e <= EXACT_REL_RMSE)
}

/// lambert's own strategies, compared against the peers' best.
pub const OWN_STRATEGIES: [Strategy; 2] = [Strategy::Projected, Strategy::ControlVariate];

/// One group's time to 0.1 %, made comparable: an exact estimator's is the
/// time of one sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeToTarget {
    /// Seconds (one thread).
    pub seconds: f64,
    /// Whether the estimator is exact (one sample suffices).
    pub exact: bool,
}

impl TimeToTarget {
    /// The group's time to 0.1 %, `None` where the summary has none (no
    /// closed form, no decreasing fit).
    pub fn of(g: &GroupSummary) -> Option<Self> {
        let one_sample = g.ns_per_sample * 1e-9;
        if is_exact(g) {
            return Some(TimeToTarget {
                seconds: one_sample,
                exact: true,
            });
        }
        let seconds = g.time_to_target?;
        Some(TimeToTarget {
            seconds,
            exact: false,
        })
    }
}

/// One scene's row of the comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct PeerRow {
    /// The scene.
    pub scene: String,
    /// The peers' best group (strategy, sequence, time).
    pub baseline: Option<(String, TimeToTarget, Option<f64>)>,
    /// For each of [`OWN_STRATEGIES`]: its best group over the sequences
    /// (sequence, time, efficiency), if the study ran it.
    pub own: Vec<Option<(String, TimeToTarget, Option<f64>)>>,
}

impl PeerRow {
    /// Baseline time over own strategy `i`'s time: how many times sooner
    /// it reaches 0.1 %.
    pub fn speed_up(&self, i: usize) -> Option<f64> {
        let (_, base, _) = self.baseline.as_ref()?;
        let (_, own, _) = self.own.get(i)?.as_ref()?;
        (own.seconds > 0.0).then(|| base.seconds / own.seconds)
    }

    /// Own strategy `i`'s efficiency over the baseline's: `Some(None)`
    /// where the own strategy has zero variance (unbounded ratio), `None`
    /// where either is missing or the baseline is exact too.
    pub fn efficiency_ratio(&self, i: usize) -> Option<Option<f64>> {
        let (_, _, base) = self.baseline.as_ref()?;
        let (_, _, own) = self.own.get(i)?.as_ref()?;
        match (base, own) {
            (Some(b), Some(o)) if *b > 0.0 => Some(Some(o / b)),
            (Some(_), None) => Some(None),
            _ => None,
        }
    }
}

/// The best (soonest to 0.1 %, then most efficient) of `groups` among
/// `strategies`: "strategy × sequence", its time and efficiency.
fn best<'a>(
    groups: impl Iterator<Item = &'a GroupSummary>,
    strategies: &[Strategy],
) -> Option<(String, TimeToTarget, Option<f64>)> {
    groups
        .filter(|g| strategies.contains(&g.strategy))
        .filter_map(|g| TimeToTarget::of(g).map(|t| (g, t)))
        .min_by(|(ga, a), (gb, b)| {
            a.seconds.total_cmp(&b.seconds).then_with(|| {
                let ea = ga.efficiency.unwrap_or(f64::INFINITY);
                let eb = gb.efficiency.unwrap_or(f64::INFINITY);
                eb.total_cmp(&ea)
            })
        })
        .map(|(g, t)| {
            let efficiency = if t.exact { None } else { g.efficiency };
            (
                format!(
                    "{} × {}",
                    g.strategy,
                    sequence_label(g.sequence, g.precision)
                ),
                t,
                efficiency,
            )
        })
}

/// The comparison's rows, one per scene with a closed form, in the order
/// the scenes first appear.
pub fn peer_rows(groups: &[GroupSummary]) -> Vec<PeerRow> {
    let mut scenes: Vec<&str> = Vec::new();
    for g in groups {
        if !scenes.contains(&g.scene.as_str()) && g.reference.is_some() {
            scenes.push(&g.scene);
        }
    }
    scenes
        .into_iter()
        .map(|scene| {
            let of_scene = || groups.iter().filter(move |g| g.scene == scene);
            PeerRow {
                scene: scene.to_owned(),
                baseline: best(of_scene(), &PEER_STRATEGIES),
                own: OWN_STRATEGIES
                    .iter()
                    .map(|s| best(of_scene(), std::slice::from_ref(s)))
                    .collect(),
            }
        })
        .collect()
}

/// A ratio with three significant figures: 4.00, 16.0, 4.00e4.
fn ratio_text(x: f64) -> String {
    if x < 10.0 {
        format!("{x:.2}")
    } else if x < 1000.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2e}")
    }
}

fn time_text(t: &TimeToTarget) -> String {
    let s = t.seconds;
    let v = if s < 1e-3 {
        format!("{:.2} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    };
    if t.exact {
        format!("{v} (exact: one sample)")
    } else {
        v
    }
}

/// The Markdown section (empty when no scene has a closed form, or the
/// study ran none of the strategies compared).
pub fn peers_markdown(groups: &[GroupSummary]) -> String {
    let rows = peer_rows(groups);
    if rows
        .iter()
        .all(|r| r.baseline.is_none() || r.own.iter().all(Option::is_none))
    {
        return String::new();
    }
    let mut s = String::new();
    let _ = writeln!(s, "## lambert against pbrt-v4/Mitsuba-style strategies\n");
    let _ = writeln!(
        s,
        "Per scene, the predicted one-thread time to 0.1 % relative RMSE of the best of the \
         strategies a pbrt-v4 or Mitsuba 3 renderer offers (light = cone for spheres, spherical \
         triangle/rectangle for polygons; area; MIS power and balance; best over the \
         sequences) against lambert's projected-solid-angle sampling and closed-form control \
         variate (each at its best sequence). Speed-up: the baseline's time over the \
         strategy's. ε ratio: the strategy's efficiency 1/(V·T) over the baseline's. An exact \
         estimator (zero variance) reaches 0.1 % with one sample: its time is one sample's and \
         its ε ratio is ∞; that time is the ns/sample at the largest N, which spreads the \
         one-off preparation at the receiver (a closed form costs about 1 µs) over N samples. \
         These scenes have no occluders, where the control variate is its closed form.\n"
    );
    let _ = writeln!(
        s,
        "| scene | pbrt-v4/Mitsuba-style best | its time to 0.1 % | projected | speed-up | ε ratio | control-variate | speed-up | ε ratio |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        let (base_name, base_time) = match &r.baseline {
            Some((name, t, _)) => (name.clone(), time_text(t)),
            None => ("—".into(), "—".into()),
        };
        let _ = write!(s, "| {} | {} | {} |", r.scene, base_name, base_time);
        for i in 0..OWN_STRATEGIES.len() {
            let time = r
                .own
                .get(i)
                .and_then(Option::as_ref)
                .map_or_else(|| "—".into(), |(_, t, _)| time_text(t));
            let speed = r
                .speed_up(i)
                .map_or_else(|| "—".into(), |x| format!("{}×", ratio_text(x)));
            let eps = match r.efficiency_ratio(i) {
                Some(Some(x)) => ratio_text(x),
                Some(None) => "∞".into(),
                None => "—".into(),
            };
            let _ = write!(s, " {time} | {speed} | {eps} |");
        }
        let _ = writeln!(s);
    }
    let _ = writeln!(s);
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_estimator::estimation::SequenceKind;

    /// A hand-made group: `time` None with `exact` for a zero-variance one.
    fn group(
        scene: &str,
        strategy: Strategy,
        sequence: SequenceKind,
        time: Option<f64>,
        efficiency: Option<f64>,
        exact: bool,
    ) -> GroupSummary {
        GroupSummary {
            scene: scene.into(),
            strategy,
            sequence,
            precision: lambert_estimator::precision::Precision::F64,
            reference: Some(1.0),
            fit: Some(if exact {
                LogLogFit::Exact
            } else {
                LogLogFit::TooFewPoints
            }),
            ns_per_sample: 50.0,
            efficiency,
            final_rel_rmse: None,
            n_max: 1 << 14,
            time_to_target: if exact { Some(0.0) } else { time },
            warning_rows: vec![],
            spread_flags: vec![],
        }
    }

    /// Scene "a": the peers' best is MIS × Sobol (2 ms; light × independent
    /// 8 ms and area never reach the target); projected takes 0.5 ms
    /// (4× sooner, ε 16× the baseline's) and the control variate is exact
    /// (one sample of 50 ns: 2 ms / 50 ns = 40,000×, ε ∞). Scene "b" has
    /// no own strategy: no speed-up.
    #[test]
    fn baseline_is_the_best_peer_and_exact_estimators_take_one_sample() {
        use SequenceKind::*;
        let p = Strategy::Mis(Heuristic::Power);
        let groups = vec![
            group(
                "a",
                Strategy::Light,
                Independent,
                Some(8e-3),
                Some(1.0),
                false,
            ),
            group("a", Strategy::Area, Independent, None, Some(0.1), false),
            group("a", p, Sobol, Some(2e-3), Some(4.0), false),
            group(
                "a",
                Strategy::Projected,
                Independent,
                Some(5e-4),
                Some(64.0),
                false,
            ),
            group(
                "a",
                Strategy::Projected,
                Sobol,
                Some(9e-4),
                Some(30.0),
                false,
            ),
            group("a", Strategy::ControlVariate, Independent, None, None, true),
            group(
                "a",
                Strategy::CosineHemisphere,
                Independent,
                Some(1e-9),
                Some(1e9),
                false,
            ),
            group("b", Strategy::Light, Sobol, Some(1.0), Some(1.0), false),
        ];
        let rows = peer_rows(&groups);
        assert_eq!(rows.len(), 2);
        let a = &rows[0];
        // Cosine sampling is not a peer strategy: it is not the baseline.
        let (name, t, eps) = a.baseline.clone().unwrap();
        assert_eq!(
            (name.as_str(), t.seconds, eps),
            ("mis × sobol", 2e-3, Some(4.0))
        );
        assert_eq!(a.own[0].as_ref().unwrap().0, "projected × independent");
        assert_eq!(a.speed_up(0), Some(2e-3 / 5e-4));
        assert_eq!(a.efficiency_ratio(0), Some(Some(16.0)));
        let (_, cv, _) = a.own[1].clone().unwrap();
        // 50 ns × 1e-9 s/ns, as computed (not the literal 5e-8, an ulp away).
        assert_eq!(
            cv,
            TimeToTarget {
                seconds: 50.0 * 1e-9,
                exact: true
            }
        );
        assert_eq!(a.speed_up(1), Some(2e-3 / (50.0 * 1e-9)));
        assert_eq!(a.efficiency_ratio(1), Some(None));
        assert_eq!(
            (rows[1].speed_up(0), rows[1].efficiency_ratio(1)),
            (None, None)
        );
        let md = peers_markdown(&groups);
        assert!(md.contains("| a | mis × sobol | 2.00 ms | 500.00 µs | 4.00× | 16.0 | 0.05 µs (exact: one sample) | 4.00e4× | ∞ |"), "{md}");
        assert!(
            md.contains("| b | light × sobol | 1.00 s | — | — | — | — | — | — |"),
            "{md}"
        );
    }

    /// A relative RMSE at the rounding level counts as exact (one sample,
    /// ε ratio ∞, not 1/(V·T) of rounding errors); a small one that is not
    /// keeps the summary's time.
    #[test]
    fn rounding_level_errors_are_exact() {
        let mut near = group(
            "a",
            Strategy::Projected,
            SequenceKind::Independent,
            Some(1e-3),
            Some(1e25),
            false,
        );
        near.final_rel_rmse = Some(3e-16);
        assert_eq!(
            TimeToTarget::of(&near),
            Some(TimeToTarget {
                seconds: 50.0 * 1e-9,
                exact: true
            })
        );
        let mut small = near.clone();
        small.final_rel_rmse = Some(2.5e-4);
        assert_eq!(
            TimeToTarget::of(&small),
            Some(TimeToTarget {
                seconds: 1e-3,
                exact: false
            })
        );
        let groups = vec![
            group(
                "a",
                Strategy::Light,
                SequenceKind::Sobol,
                Some(1e-3),
                Some(2.0),
                false,
            ),
            near,
        ];
        assert_eq!(peer_rows(&groups)[0].efficiency_ratio(0), Some(None));
    }

    /// Without the compared strategies there is no section.
    #[test]
    fn no_section_without_own_strategies() {
        let groups = vec![group(
            "a",
            Strategy::Light,
            SequenceKind::Independent,
            Some(1.0),
            Some(1.0),
            false,
        )];
        assert_eq!(peers_markdown(&groups), "");
    }
}
