//! Random scenes that exercise the hard cases: every emitter kind, several
//! emitters, placements relative to the receiver (above, below, straddling
//! or in its plane, grazing, at the receiver itself), sizes from 5e-324 to
//! 1.8e308 relative to their distance, degenerate and near-degenerate
//! shapes, vectors of any length, and — in a quarter of the scenes — one
//! deliberately invalid field.
//!
//! Generation is structure-aware: emitters are placed relative to the
//! receiver so that random numbers still produce lights that are seen,
//! clipped by the horizon or touching the receiver, rather than only
//! far-away noise.

use glam::DVec3;
use rand::Rng;
use std::f64::consts::PI;

use crate::numbers::{coordinate, invalid_magnitude, log_uniform, magnitude, non_finite, signed};
use crate::scene::{SceneFile, Table, Value};

/// The emitter kinds of the scene format, as a file spells them (kept
/// here, not taken from the library, so that the fuzzer tests the format a
/// user writes).
pub const KINDS: [&str; 7] = [
    "sky",
    "sky_cap",
    "sphere",
    "disk",
    "polygon",
    "point",
    "directional",
];

/// Probability that a scene carries exactly one deliberately invalid field.
pub const INVALID_FRACTION: f64 = 0.25;

/// A random scene: a receiver, one to five emitters, and with probability
/// [`INVALID_FRACTION`] one invalid field.
pub fn scene<R: Rng>(rng: &mut R) -> SceneFile {
    let point = receiver_point(rng);
    let normal = random_direction(rng);
    let mut receiver = Table::default();
    receiver.set("point", Value::Vector(point.to_array()));
    receiver.set("normal", Value::Vector(scaled(rng, normal)));
    let count = match rng.random_range(0..10) {
        0..=3 => 1,
        4..=6 => 2,
        7..=8 => 3,
        _ => rng.random_range(4..=5),
    };
    let emitters = (0..count)
        .map(|_| {
            let kind = KINDS[rng.random_range(0..KINDS.len())];
            emitter(rng, kind, point, normal)
        })
        .collect();
    let mut file = SceneFile {
        extra: Vec::new(),
        receiver: Some(receiver),
        emitters,
    };
    if rng.random_bool(INVALID_FRACTION) {
        make_invalid(rng, &mut file);
    }
    file
}

/// The receiver's point: the origin (50 %), an ordinary point (20 %) or a
/// point with extreme coordinates (30 %).
fn receiver_point<R: Rng>(rng: &mut R) -> DVec3 {
    match rng.random_range(0..10) {
        0..=4 => DVec3::ZERO,
        5..=6 => DVec3::new(
            rng.random_range(-10.0..10.0),
            rng.random_range(-10.0..10.0),
            rng.random_range(-10.0..10.0),
        ),
        _ => DVec3::new(coordinate(rng), coordinate(rng), coordinate(rng)),
    }
}

/// A unit direction: uniform on the sphere (70 %) or along a coordinate
/// axis (30 %).
pub fn random_direction<R: Rng>(rng: &mut R) -> DVec3 {
    if rng.random_bool(0.3) {
        let mut v = [0.0; 3];
        v[rng.random_range(0..3)] = signed(rng, 1.0);
        return DVec3::from_array(v);
    }
    let z: f64 = rng.random_range(-1.0..=1.0);
    let phi = rng.random_range(0.0..2.0 * PI);
    let s = (1.0 - z * z).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// A direction relative to the receiver's normal `n`: in the upper
/// hemisphere (55 %), the lower one (15 %), in the receiver's plane (10 %),
/// grazing it from above or below at an angle from 1e-300 to 1e-3 (10 %),
/// or along ±n (10 %).
fn direction_from<R: Rng>(rng: &mut R, n: DVec3) -> DVec3 {
    let d = random_direction(rng);
    let tangent = (d - n * d.dot(n))
        .try_normalize()
        .unwrap_or(n.any_orthonormal_vector());
    match rng.random_range(0..20) {
        0..=10 => {
            if d.dot(n) < 0.0 {
                -d
            } else {
                d
            }
        }
        11..=13 => {
            if d.dot(n) > 0.0 {
                -d
            } else {
                d
            }
        }
        14..=15 => tangent,
        16..=17 => {
            let eps = log_uniform(rng, -300.0, -3.0);
            let eps = signed(rng, eps);
            (tangent + n * eps).normalize()
        }
        _ => signed(rng, 1.0) * n,
    }
}

/// `d` as written in a file: unit length (60 %) or scaled by a length
/// anywhere from 5e-324 to 1.8e308 (40 %; the scaled vector may underflow
/// or overflow componentwise, which is itself a case).
fn scaled<R: Rng>(rng: &mut R, d: DVec3) -> [f64; 3] {
    if rng.random_bool(0.6) {
        d.to_array()
    } else {
        (d * magnitude(rng)).to_array()
    }
}

/// A distance from the receiver: ordinary (60 %), any magnitude (25 %),
/// zero (10 %: at the receiver itself) or an edge value ≥ 1e300 (5 %).
fn distance<R: Rng>(rng: &mut R) -> f64 {
    match rng.random_range(0..20) {
        0..=11 => log_uniform(rng, -2.0, 3.0),
        12..=16 => magnitude(rng),
        17..=18 => 0.0,
        _ => log_uniform(rng, 300.0, 308.25),
    }
}

/// A size relative to a distance: mostly smaller (down to 1e-300 of it),
/// sometimes comparable or larger (up to 1e300 of it).
fn ratio<R: Rng>(rng: &mut R) -> f64 {
    match rng.random_range(0..10) {
        0..=5 => log_uniform(rng, -3.0, 0.0),
        6..=7 => log_uniform(rng, -300.0, 0.0),
        8 => log_uniform(rng, 0.0, 3.0),
        _ => log_uniform(rng, 0.0, 300.0),
    }
}

/// A size that is `ratio` times `distance`, or any magnitude when the
/// distance is zero or the product leaves the f64 range.
fn size<R: Rng>(rng: &mut R, distance: f64) -> f64 {
    let s = distance * ratio(rng);
    if s > 0.0 && s.is_finite() {
        s
    } else {
        magnitude(rng)
    }
}

/// The radiance (or intensity, flux, irradiance) of an emitter.
fn power<R: Rng>(rng: &mut R) -> Value {
    Value::Float(magnitude(rng))
}

fn vector(v: DVec3) -> Value {
    Value::Vector(v.to_array())
}

/// One emitter of `kind`, placed relative to the receiver at `p` facing
/// the unit normal `n`.
pub fn emitter<R: Rng>(rng: &mut R, kind: &str, p: DVec3, n: DVec3) -> Table {
    let mut t = Table::default();
    t.set("kind", Value::Text(kind.to_owned()));
    match kind {
        "sky" => t.set("radiance", power(rng)),
        "sky_cap" => sky_cap(rng, &mut t, n),
        "sphere" => {
            let dir = direction_from(rng, n);
            // A receiver at the centre is one case among many, not one in ten.
            let mut d = distance(rng);
            if d == 0.0 && rng.random_bool(0.8) {
                d = log_uniform(rng, -2.0, 3.0);
            }
            t.set("center", vector(p + dir * d));
            let radius = match rng.random_range(0..20) {
                // Receiver outside, near or far.
                0..=14 => size(rng, d).min(d * (1.0 - 1e-9)),
                // Receiver exactly on the sphere, or one ulp outside or inside.
                15 => d,
                16 => d * (1.0 - f64::EPSILON),
                17 => d * (1.0 + f64::EPSILON),
                _ => magnitude(rng),
            };
            t.set(
                "radius",
                Value::Float(if radius > 0.0 { radius } else { magnitude(rng) }),
            );
            t.set("radiance", power(rng));
        }
        "disk" => {
            let dir = direction_from(rng, n);
            let d = distance(rng);
            let radius = size(rng, d);
            let (center, normal) = if rng.random_bool(0.05) {
                // The receiver lies on the disk (in its plane, within it).
                let offset = n.any_orthonormal_vector() * radius * rng.random_range(0.0..1.0);
                (p + offset, signed(rng, 1.0) * n)
            } else {
                (p + dir * d, plane_normal(rng, dir, n))
            };
            t.set("center", vector(center));
            t.set("normal", Value::Vector(scaled(rng, normal)));
            t.set("radius", Value::Float(radius));
            t.set("radiance", power(rng));
            two_sided(rng, &mut t);
        }
        "polygon" => polygon(rng, &mut t, p, n),
        "point" => {
            let dir = direction_from(rng, n);
            let d = distance(rng);
            t.set("position", vector(p + dir * d));
            if rng.random_bool(0.6) {
                t.set("intensity", power(rng));
            } else {
                t.set("flux", power(rng));
            }
        }
        "directional" => {
            let dir = direction_from(rng, n);
            t.set("direction", Value::Vector(scaled(rng, dir)));
            t.set("irradiance", power(rng));
        }
        other => unreachable!("unknown kind {other}"),
    }
    t
}

/// The normal of a planar light centred in direction `dir` from the
/// receiver (normal `n`): facing the receiver (40 %), any direction (25 %),
/// parallel to the receiver's plane, so that the light stands on it
/// (15 %), or a random direction with one component scaled by 1e10 or
/// 1e-10 (20 %: nearly axis-aligned normals written with wild components).
fn plane_normal<R: Rng>(rng: &mut R, dir: DVec3, n: DVec3) -> DVec3 {
    match rng.random_range(0..20) {
        0..=7 => -dir,
        8..=12 => random_direction(rng),
        13..=15 => n.any_orthonormal_vector(),
        _ => {
            let mut v = random_direction(rng).to_array();
            let k = rng.random_range(0..3);
            v[k] *= if rng.random_bool(0.5) { 1e10 } else { 1e-10 };
            DVec3::from_array(v).normalize()
        }
    }
}

fn two_sided<R: Rng>(rng: &mut R, t: &mut Table) {
    match rng.random_range(0..3) {
        0 => t.set("two_sided", Value::Bool(true)),
        1 => t.set("two_sided", Value::Bool(false)),
        _ => {}
    }
}

fn sky_cap<R: Rng>(rng: &mut R, t: &mut Table, n: DVec3) {
    let axis = direction_from(rng, n);
    t.set("axis", Value::Vector(scaled(rng, axis)));
    let radians = match rng.random_range(0..10) {
        0..=4 => rng.random_range(0.0..PI),
        5..=6 => log_uniform(rng, -300.0, 0.0),
        7 => PI,
        _ => PI - log_uniform(rng, -16.0, -1.0),
    };
    if rng.random_bool(0.5) {
        t.set("half_angle", Value::Float(radians));
    } else {
        t.set(
            "half_angle_deg",
            Value::Float(radians.to_degrees().min(180.0)),
        );
    }
    t.set("radiance", power(rng));
}

/// A convex polygon light (regular n-gon, rectangle of any aspect, or
/// sliver triangle) in a plane at a random placement, or one of its
/// degenerate or near-degenerate variants (25 %): collinear vertices, a
/// vertex lifted out of the plane by 1e-16 to 1e-3 of the size, a
/// repeated vertex, two vertices swapped (non-convex), fewer than three
/// vertices.
fn polygon<R: Rng>(rng: &mut R, t: &mut Table, p: DVec3, n: DVec3) {
    let dir = direction_from(rng, n);
    let d = distance(rng);
    let s = size(rng, d);
    let (center, m) = if rng.random_bool(0.05) {
        // The receiver lies in the polygon's plane, inside it.
        (p, signed(rng, 1.0) * n)
    } else {
        (p + dir * d, plane_normal(rng, dir, n))
    };
    let u = m.any_orthonormal_vector();
    let v = m.cross(u);
    let local: Vec<(f64, f64)> = match rng.random_range(0..3) {
        0 => {
            let k = rng.random_range(3..=8);
            let phase = rng.random_range(0.0..2.0 * PI);
            (0..k)
                .map(|i| {
                    let a = phase + 2.0 * PI * i as f64 / k as f64;
                    (a.cos(), a.sin())
                })
                .collect()
        }
        1 => {
            let aspect = log_uniform(rng, 0.0, 12.0);
            let h = 1.0 / aspect;
            vec![(-1.0, -h), (1.0, -h), (1.0, h), (-1.0, h)]
        }
        _ => {
            let h = log_uniform(rng, -12.0, 0.0);
            vec![(-1.0, 0.0), (1.0, 0.0), (0.0, h)]
        }
    };
    let mut vertices: Vec<DVec3> = local
        .iter()
        .map(|&(a, b)| center + (u * a + v * b) * s)
        .collect();
    if rng.random_bool(0.5) {
        vertices.reverse();
    }
    if rng.random_bool(0.25) {
        let k = vertices.len();
        match rng.random_range(0..5) {
            0 => {
                for (i, x) in vertices.iter_mut().enumerate() {
                    *x = center + u * s * (i as f64 - 1.0);
                }
            }
            1 => {
                let eps = log_uniform(rng, -16.0, -3.0);
                vertices[rng.random_range(0..k)] += m * s * eps;
            }
            2 => {
                let i = rng.random_range(0..k);
                let x = vertices[i];
                vertices.insert(i, x);
            }
            3 => vertices.swap(0, 1 + rng.random_range(0..k - 1)),
            _ => vertices.truncate(rng.random_range(0..3)),
        }
    }
    t.set(
        "vertices",
        Value::Vectors(vertices.iter().map(|x| x.to_array()).collect()),
    );
    t.set("radiance", power(rng));
    two_sided(rng, t);
}

/// Fields that are not of one kind's list: what a careless edit adds.
const STRAY_KEYS: [&str; 6] = [
    "colour",
    "radius",
    "normal",
    "flux",
    "vertices",
    "intensity",
];

/// Makes exactly one thing about the file invalid: a non-finite, zero or
/// negative number, a zero vector, a missing required field, an unknown
/// or foreign key, two alternative fields at once, a misspelt kind, an
/// out-of-range angle, or no emitters at all.
fn make_invalid<R: Rng>(rng: &mut R, file: &mut SceneFile) {
    let choice = rng.random_range(0..9);
    if choice == 8 || file.emitters.is_empty() {
        file.emitters.clear();
        return;
    }
    let i = rng.random_range(0..file.emitters.len());
    let use_receiver = rng.random_bool(0.15);
    let table = if use_receiver {
        file.receiver.as_mut().expect("generated with a receiver")
    } else {
        &mut file.emitters[i]
    };
    let k = rng.random_range(0..table.fields.len());
    match choice {
        0..=2 => {
            // A bad number in a random numeric field.
            let (_, value) = &mut table.fields[k];
            match value {
                Value::Float(x) => *x = invalid_magnitude(rng),
                Value::Vector(v) => v[rng.random_range(0..3)] = non_finite(rng),
                Value::Vectors(vs) if !vs.is_empty() => {
                    let j = rng.random_range(0..vs.len());
                    vs[j][rng.random_range(0..3)] = non_finite(rng);
                }
                _ => table.put("radiance", Value::Float(invalid_magnitude(rng))),
            }
        }
        3 => {
            // A zero or underflowing vector.
            let zero = if rng.random_bool(0.5) { 0.0 } else { -0.0 };
            if let Some((_, v @ Value::Vector(_))) = table
                .fields
                .iter_mut()
                .find(|(k, _)| matches!(k.as_str(), "normal" | "axis" | "direction"))
            {
                *v = Value::Vector([zero, 0.0, zero]);
            } else {
                table.put("normal", Value::Vector([0.0, 0.0, 0.0]));
            }
        }
        4 => {
            // A missing field (any, `kind` included).
            let key = table.fields[k].0.clone();
            table.remove(&key);
        }
        5 => {
            let key = STRAY_KEYS[rng.random_range(0..STRAY_KEYS.len())];
            if table.get(key).is_none() {
                table.set(key, Value::Float(1.0));
            } else {
                table.put("colour", Value::Float(3.0));
            }
        }
        6 => {
            let spelling = ["Sphere", "spheres", "area", "", "point_light"];
            table.put(
                "kind",
                Value::Text(spelling[rng.random_range(0..spelling.len())].into()),
            );
        }
        _ => {
            // Alternatives given together, or an angle out of range.
            match table.text("kind") {
                Some("point") => {
                    table.put("intensity", Value::Float(1.0));
                    table.put("flux", Value::Float(1.0));
                }
                Some("sky_cap") => {
                    table.remove("half_angle");
                    table.remove("half_angle_deg");
                    match rng.random_range(0..3) {
                        0 => table.set("half_angle", Value::Float(PI * (1.0 + 1e-15))),
                        1 => table.set("half_angle_deg", Value::Float(180.000_001)),
                        _ => {
                            table.set("half_angle", Value::Float(0.5));
                            table.set("half_angle_deg", Value::Float(30.0));
                        }
                    }
                }
                _ => table.put("two_sided", Value::Text("yes".into())),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn every_kind_appears_and_every_scene_is_valid_toml() {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(7);
        let mut seen = std::collections::BTreeSet::new();
        for _ in 0..2000 {
            let file = scene(&mut rng);
            let text = file.to_toml();
            assert!(text.parse::<toml::Table>().is_ok(), "{text}");
            for e in &file.emitters {
                if let Some(kind) = e.text("kind") {
                    seen.insert(kind.to_owned());
                }
            }
        }
        for kind in KINDS {
            assert!(seen.contains(kind), "{kind} never generated");
        }
    }
}
