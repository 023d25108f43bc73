//! What a technique knows in advance about its one-sample estimate: a bound
//! on each sampled part's value, and the shape of its distribution.
//!
//! A sample of one emitter's estimate is the value of one direction drawn by
//! the technique, or, for MIS, the sum of two *parts*: the weighted value of
//! a cosine-sampled direction and that of a light-sampled one. Every part is
//! non-negative and bounded by what the geometry allows (L the emitter's
//! radiance, Ω the solid angle the light sampler draws from, p_c = cos θ/π
//! and p_l the two densities):
//!
//! | technique | part | value | bound |
//! |---|---|---|---|
//! | uniform hemisphere | direction | 2πL cos θ | 2πL |
//! | cosine hemisphere | direction | πL on a hit, else 0 | πL (two values only) |
//! | light: sky | direction | 4πL cos θ | 4πL |
//! | light: cap, sphere, polygon, disk | direction | LΩ cos θ | LΩ |
//! | projected: cap, sphere, polygon | direction | L Ω⊥ | L Ω⊥ (the same value in every sample, to rounding) |
//! | control variate | direction | E_u without occluders | E_u (constant) |
//! | area | point | L cos θ cos θ_l A / d² | L·A·\|h\|/d_min³ (planar), L·A/d_min² (sphere) |
//! | MIS, balance | cosine / light | L cos θ/(p_c + p_l) | min(πL, B_l) each |
//! | MIS, power | cosine | L cos θ p_c/(p_c² + p_l²) | min(πL, B_l/2, B_l²/(πL)) |
//! | MIS, power | light | L cos θ p_l/(p_c² + p_l²) | min(B_l, πL/2) |
//!
//! (d_min the distance from the receiver to the emitter, h its height above
//! the emitter's plane, A the area, B_l the light technique's bound; the MIS
//! bounds use p_c² + p_l² ≥ 2p_c p_l and L cos θ/p_l ≤ B_l, which holds
//! wherever the emitter is seen because every light sampler here has p_l > 0
//! there.)
//!
//! **Heavy tails.** Area sampling's bound grows as 1/d_min² as the receiver
//! approaches the emitter, and the large values come only from the small
//! *core* of the emitter near the receiver. With A the area, the points
//! within 2·d_min of the receiver, which carry most of the estimate (for a
//! disk overhead at height h, 3/4 of E comes from the points within 2h), cover a
//! fraction at most q = min(1, 3π d_min²/A) of the emitter. The variance is
//! finite but grows without bound as d_min → 0 (∝ A/d_min² relative), and
//! while N·q is small the core is rarely or never sampled: the sample mean
//! is then far too small and the sample variance, which has not seen the
//! tail either, hides it. That is why `auto` never uses area sampling alone
//! (under MIS its weights bound the value by 3πL/2), and why an estimate
//! with N·q below [`CLT_MIN_EVENTS`](crate::interval::CLT_MIN_EVENTS) uses
//! the interval from the bound instead of the sample variance
//! ([`crate::interval`]).

use glam::DVec3;
use lambert_geometry::f64::{ConvexPolygon, Disk};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use std::f64::consts::PI;

use super::{ControlVariate, EmitterArea, EmitterLight, EmitterProjected, Heuristic, Technique};

/// How one part's values are distributed, as far as the technique knows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PartShape {
    /// Anywhere in [0, max].
    Bounded,
    /// Only 0 (a miss) or exactly `max` (a hit): cosine sampling of a
    /// uniform emitter.
    TwoValued,
    /// Always exactly `max`: cosine sampling of a radiance that fills the
    /// receiver's hemisphere (a sky): the estimate is exact.
    Constant,
    /// In [0, max], the large values only from a core of the emitter that a
    /// sample reaches with probability at most `core_probability` (area
    /// sampling near the emitter; module docs).
    HeavyTailed {
        /// q = min(1, 3π d_min²/A).
        core_probability: f64,
    },
}

/// A bound on one part of a technique's one-sample estimate of one emitter
/// (module docs), in W/m².
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PartBound {
    /// Every value of the part lies in [0, max].
    pub max: f64,
    /// How the values are distributed.
    pub shape: PartShape,
    /// An upper bound on the probability that the part is not 0 in a
    /// sample, known from the geometry: Ω/(2π) for a uniform-hemisphere
    /// direction and Ω/π for a cosine-sampled one (Ω the emitter's solid
    /// angle from the receiver; the cosine density is at most 1/π), 1 for
    /// the light and area samplers. Hence E(part) ≤ max·hit_probability
    /// always, whatever the samples say.
    pub hit_probability: f64,
    /// What the part is, for messages: "uniform-hemisphere sample",
    /// "cosine sample", "light sample", "area sample", "MIS cosine half",
    /// "MIS light half".
    pub name: &'static str,
}

/// Relative slack on the bounds: the values are computed in floating point
/// (a cosine may round to 1 + ε, a density to 1/Ω(1 − ε)).
const ROUNDING_SLACK: f64 = 1.0 + 16.0 * f64::EPSILON;

impl PartBound {
    fn bounded(max: f64) -> Self {
        PartBound {
            max: max * ROUNDING_SLACK,
            shape: PartShape::Bounded,
            hit_probability: 1.0,
            name: "light sample",
        }
    }

    fn named(mut self, name: &'static str) -> Self {
        self.name = name;
        self
    }

    /// With the hit probability of a hemisphere direction of density at
    /// most `density_max` toward an emitter of solid angle `solid_angle`.
    fn hit_at_most(mut self, solid_angle: f64, density_max: f64) -> Self {
        self.hit_probability = (solid_angle * density_max * ROUNDING_SLACK).min(1.0);
        self
    }

    /// The bounds of the parts that `technique` draws for `emitter` at
    /// `receiver` (one part, or two for MIS: cosine then light), given the
    /// prepared light, area and projected samplers and the control variate.
    pub fn of(
        technique: Technique,
        emitter: &Emitter,
        receiver: &Receiver,
        light: &EmitterLight,
        area: &EmitterArea,
        projected: &EmitterProjected,
        control: Option<&ControlVariate>,
    ) -> [Option<PartBound>; 2] {
        let l = radiance(emitter);
        let omega = solid_angle(emitter, receiver, light);
        match technique {
            Technique::UniformHemisphere => [
                Some(
                    Self::bounded(2.0 * PI * l)
                        .named("uniform-hemisphere sample")
                        .hit_at_most(omega, 0.5 / PI),
                ),
                None,
            ],
            Technique::CosineHemisphere => {
                let shape = if fills_hemisphere(emitter, receiver) {
                    PartShape::Constant
                } else {
                    PartShape::TwoValued
                };
                let part = PartBound {
                    max: PI * l * ROUNDING_SLACK,
                    shape,
                    hit_probability: 1.0,
                    name: "cosine sample",
                };
                [Some(part.hit_at_most(omega, 1.0 / PI)), None]
            }
            Technique::Light => [Some(light_bound(light, l)), None],
            Technique::Projected => [Some(projected_bound(projected, l)), None],
            Technique::ControlVariate => match (control, projected) {
                (Some(c), _) => [
                    Some(PartBound {
                        max: c.unoccluded.max(0.0),
                        shape: PartShape::Constant,
                        hit_probability: 1.0,
                        name: "closed form",
                    }),
                    None,
                ],
                (None, EmitterProjected::None) => [Some(light_bound(light, l)), None],
                (None, _) => [Some(projected_bound(projected, l)), None],
            },
            Technique::Area => [Some(area_bound(area, l).named("area sample")), None],
            Technique::Mis(h) => {
                let b_l = light_bound(light, l).max;
                let pi_l = PI * l;
                let cosine = if matches!(light, EmitterLight::None) {
                    // No light density anywhere: the cosine part is plain
                    // cosine sampling.
                    pi_l
                } else {
                    match h {
                        Heuristic::Balance => pi_l.min(b_l),
                        Heuristic::Power => pi_l.min(0.5 * b_l).min(b_l * b_l / pi_l),
                    }
                };
                let light_part = match h {
                    Heuristic::Balance => b_l.min(pi_l),
                    Heuristic::Power => b_l.min(0.5 * pi_l),
                };
                let cosine = Self::bounded(if l > 0.0 { cosine } else { 0.0 })
                    .named("MIS cosine half")
                    .hit_at_most(omega, 1.0 / PI);
                [
                    Some(cosine),
                    Some(Self::bounded(light_part).named("MIS light half")),
                ]
            }
        }
    }
}

/// The solid angle the emitter subtends at the receiver (its visible part
/// for a polygon clipped by the horizon), or 4π where unknown or unbounded
/// (a sky).
fn solid_angle(emitter: &Emitter, receiver: &Receiver, light: &EmitterLight) -> f64 {
    match (emitter, light) {
        (_, EmitterLight::Cap(_, cone)) => cone.solid_angle(),
        (_, EmitterLight::Sphere(s)) => s.solid_angle(),
        (_, EmitterLight::Polygon(p)) => p.solid_angle(),
        (Emitter::Disk(d), _) => d.disk.solid_angle_from(receiver.point),
        // A polygon wholly below the horizon (or edge-on) is never seen.
        (Emitter::Polygon(_), EmitterLight::None) => 0.0,
        _ => 4.0 * PI,
    }
}

/// The emitter's (uniform) radiance; 0 for delta lights.
fn radiance(emitter: &Emitter) -> f64 {
    match emitter {
        Emitter::Sky(s) => s.radiance,
        Emitter::SkyCap(c) => c.radiance,
        Emitter::Sphere(s) => s.radiance,
        Emitter::Disk(d) => d.radiance,
        Emitter::Polygon(p) => p.radiance,
        Emitter::Point(_) | Emitter::Directional(_) => 0.0,
    }
}

/// Whether the emitter's radiance reaches the receiver from every direction
/// of its hemisphere: a sky, or a sky cap containing the hemisphere (its
/// rim below the horizon everywhere, with a margin for rounding).
fn fills_hemisphere(emitter: &Emitter, receiver: &Receiver) -> bool {
    match emitter {
        Emitter::Sky(_) => true,
        Emitter::SkyCap(c) => {
            // The lowest value of axis·ω over the closed hemisphere is
            // −√(1 − (axis·n)²) when axis·n ≥ 0 (reached on the horizon).
            let a = c.axis.dot(receiver.normal);
            a >= 0.0 && -(1.0 - a * a).max(0.0).sqrt() > c.cone.cos_theta_max() + 1e-12
        }
        _ => false,
    }
}

/// The bound of light sampling (module docs' table).
fn light_bound(light: &EmitterLight, l: f64) -> PartBound {
    match light {
        EmitterLight::Sky => PartBound::bounded(4.0 * PI * l),
        EmitterLight::Cap(_, cone) => PartBound::bounded(l * cone.solid_angle()),
        EmitterLight::Sphere(s) => PartBound::bounded(l * s.solid_angle()),
        EmitterLight::Polygon(p) => PartBound::bounded(l * p.solid_angle()),
        EmitterLight::Disk(d) => PartBound::bounded(l * d.solid_angle()),
        EmitterLight::DiskTable(d) => PartBound::bounded(l * d.solid_angle()),
        EmitterLight::None => PartBound::bounded(0.0),
    }
}

/// The bound of projected sampling (module docs' table): L Ω⊥.
fn projected_bound(projected: &EmitterProjected, l: f64) -> PartBound {
    PartBound::bounded(l * projected.projected_solid_angle()).named("projected sample")
}

/// The bound of area sampling (module docs' table).
fn area_bound(area: &EmitterArea, l: f64) -> PartBound {
    match area {
        EmitterArea::Sphere(s, r) => {
            let sphere = s.sphere();
            let d_min = (sphere.distance_to_center(r.point) - sphere.radius()).max(0.0);
            let a = sphere.area();
            PartBound {
                max: l * a / (d_min * d_min) * ROUNDING_SLACK,
                shape: heavy(d_min, a),
                hit_probability: 1.0,
                name: "area sample",
            }
        }
        EmitterArea::Disk(s, r) => planar_area_bound(disk_distance(s.disk(), r.point), l),
        EmitterArea::Polygon(s, r) => {
            planar_area_bound(polygon_distance(s.polygon(), s.area(), r.point), l)
        }
        EmitterArea::None => PartBound::bounded(0.0),
    }
}

/// The area bound of a planar emitter: L·A·|h|/d_min³ = L·A/d_min²·(|h|/d_min),
/// 0 when the receiver is in the emitter's plane (every sample edge-on).
fn planar_area_bound(distance: PlanarDistance, l: f64) -> PartBound {
    let PlanarDistance {
        height,
        nearest,
        area,
    } = distance;
    if height == 0.0 {
        return PartBound::bounded(0.0);
    }
    PartBound {
        max: l * area / (nearest * nearest) * (height / nearest) * ROUNDING_SLACK,
        shape: heavy(nearest, area),
        hit_probability: 1.0,
        name: "light sample",
    }
}

fn heavy(d_min: f64, area: f64) -> PartShape {
    PartShape::HeavyTailed {
        core_probability: (3.0 * PI * d_min * d_min / area).min(1.0),
    }
}

/// The receiver's height above a planar emitter's plane, a lower bound on
/// its distance to the emitter, and the emitter's area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarDistance {
    /// |h| ≥ 0.
    pub height: f64,
    /// d_min ≥ |h|, a lower bound on the distance to the emitter.
    pub nearest: f64,
    /// The emitter's area A.
    pub area: f64,
}

/// The receiver's height above a disk's plane and its distance to the disk.
fn disk_distance(disk: &Disk, point: DVec3) -> PlanarDistance {
    let (h, s) = disk.height_and_offset(point);
    let outside = (s - disk.radius()).max(0.0);
    PlanarDistance {
        height: h,
        nearest: h.hypot(outside),
        area: disk.area(),
    }
}

/// The receiver's height above a polygon's plane and a lower bound on its
/// distance to the polygon: the larger of |h| and the distance to the ball
/// about the vertices' centroid that holds every vertex.
fn polygon_distance(polygon: &ConvexPolygon, area: f64, point: DVec3) -> PlanarDistance {
    let v = polygon.vertices();
    let h = polygon.normal().dot(point - v[0]).abs();
    let centroid = v.iter().copied().sum::<DVec3>() / v.len() as f64;
    let radius = v
        .iter()
        .map(|&x| (x - centroid).length())
        .fold(0.0, f64::max);
    PlanarDistance {
        height: h,
        nearest: h.max((point - centroid).length() - radius),
        area,
    }
}
