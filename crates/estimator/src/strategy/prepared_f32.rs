//! One emitter prepared for the f32 estimator: its samplers and shape in
//! f32, moved so that the receiver is the origin, a bound on the f32
//! error of its estimate, or the reason it runs in f64 instead.
//!
//! **Why the receiver is the origin.** f32 carries about 7 digits of a
//! coordinate. A light at (1e4, 0, 1e4) seen from a receiver at
//! (1e4, 0, 1e4 − 10) has, in f32, its position relative to the receiver
//! known to ~1e-3 m, 1e-4 of its distance, if the difference is formed in
//! f32; formed in f64 and then rounded, it is known to 1e-7 of its
//! distance. Every shape is therefore translated in f64 and only then
//! rounded to f32 (pbrt-v4 makes the same choice for its camera-relative
//! rendering space, §5.1.1).
//!
//! **Why the radiance stays in f64.** Every emitter here is uniform: its
//! one-sample value is F = L·g with g = V(ω) cos θ/p (V ∈ {0, 1} whether
//! the direction sees the emitter) for the hemisphere, light, area and
//! projected techniques, and the weighted sum of two such terms for MIS.
//! g is bounded (by 2π, π, Ω, 4π, 3π/2 or 2π; area sampling by A/d²_min)
//! whatever L is, so the f32 kernel computes g and the value L·g is formed
//! in f64 when g is widened: the f32 range (~3.4e38) never limits L.

use glam::{DVec3, Vec3};
use lambert_geometry::f32::{ConvexPolygon, Disk, Frame, Sphere};
use lambert_light::emitter::Emitter;
use lambert_light::receiver::Receiver;
use lambert_sampling::f32::{
    ConeCosine, DiskAreaSampler, DiskSolidAngle, PolygonAreaSampler, PolygonLightSampler,
    PolygonSolidAngle, ProjectedCap, ProjectedPolygon, ProjectedPolygonSampler, ProjectedSphere,
    SphereAreaSampler, SphereSolidAngle, TabulatedDiskSolidAngle, TabulatedProjectedPolygon,
    UniformCone,
};
use std::fmt;

use super::cone_mis::ConeMisF32;
use super::cone_window::CosineWindowF32;
use super::{ControlVariate, EmitterLight, EmitterProjected, PreparedEmitter, Technique};

/// The largest bound on the relative error of an emitter's f32 estimate
/// (its systematic part, [`PreparedEmitterF32::error_bound`] over the
/// emitter's closed-form irradiance) for which the f32 path runs it: 2⁻¹³
/// ≈ 1.2e-4, a thousand f32 roundings. An emitter whose bound is larger
/// runs in f64 ([`FallbackReason::ErrorBound`]).
pub const F32_MAX_RELATIVE_ERROR: f64 = 1.0 / 8192.0;

/// ε of f32, 2⁻²³, as f64.
const EPS32: f64 = f32::EPSILON as f64;

/// Coordinates (relative to the receiver) beyond which an emitter runs in
/// f64: squares of lengths (|v|², the hit tests' discriminants) stay
/// below the f32 maximum ~3.4e38 and above its smallest normal ~1.2e-38.
const F32_COORDINATE_RANGE: (f64, f64) = (1e-15, 1e15);

/// Why the f32 estimator runs one emitter in f64.
#[derive(Clone, Debug, PartialEq)]
pub enum FallbackReason {
    /// The bound on the f32 error of the emitter's estimate, relative to
    /// its closed-form irradiance, exceeds [`F32_MAX_RELATIVE_ERROR`]:
    /// typically an emitter small or far away for a technique that tests
    /// whether a direction hits it (the band of misjudged directions along
    /// its outline is large against its solid angle), or one seen nearly
    /// edge-on or grazing the horizon.
    ErrorBound {
        /// The bound, relative.
        relative: f64,
    },
    /// The emitter's irradiance is 0 or has no closed form at this
    /// receiver, so no relative bound exists (f64 costs nothing there:
    /// such an emitter is wholly below the horizon or dark from here).
    NoClosedForm,
    /// A length of the emitter, relative to the receiver, outside
    /// [1e-15, 1e15] m: its squares would leave the f32 range.
    Range {
        /// The length, m.
        length: f64,
    },
    /// The emitter's shape or sampler could not be built in f32 (rounding
    /// made a polygon non-planar, or a receiver just outside a sphere
    /// lands inside it).
    Unbuildable {
        /// The sampler or shape's own error.
        error: String,
    },
}

impl fmt::Display for FallbackReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FallbackReason::ErrorBound { relative } => write!(
                f,
                "its f32 error bound {relative:.2e} (relative) exceeds {F32_MAX_RELATIVE_ERROR:.2e}"
            ),
            FallbackReason::NoClosedForm => f.write_str(
                "its irradiance here is 0 or has no closed form, so its f32 error cannot be bounded",
            ),
            FallbackReason::Range { length } => write!(
                f,
                "a length of {length:e} m relative to the receiver is outside the f32 range [1e-15, 1e15]"
            ),
            FallbackReason::Unbuildable { error } => {
                write!(f, "its f32 sampler cannot be built: {error}")
            }
        }
    }
}

/// An emitter that the f32 estimator runs in f64, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct F32Fallback {
    /// Its index in the scene's `emitters`.
    pub emitter: usize,
    /// Its kind (`sphere`, `disk`, …).
    pub kind: &'static str,
    /// Why.
    pub reason: FallbackReason,
}

impl fmt::Display for F32Fallback {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "emitters[{}] (a {}) runs in f64: {}",
            self.emitter, self.kind, self.reason
        )
    }
}

/// What a direction is tested against to know whether it sees the
/// emitter (the radiance lookup, as a yes/no: the emitters are uniform).
#[derive(Clone, Debug)]
pub(super) enum Shape {
    /// Every direction.
    Sky,
    /// The directions of a cone about an axis.
    Cap(Frame, UniformCone),
    /// A sphere.
    Sphere(Sphere),
    /// A disk.
    Disk(Disk),
    /// A convex polygon.
    Polygon(ConvexPolygon),
}

/// The f32 solid-angle sampler ([`EmitterLight`]'s kinds).
#[derive(Clone, Debug)]
pub(super) enum Light {
    Sky,
    /// A sky cap, with the cosines between the receiver's normal and its
    /// directions ([`ConeCosine`], built once here, not per block).
    Cap(Frame, UniformCone, ConeCosine),
    /// A sphere's cone, with the cosines as for [`Light::Cap`].
    Sphere(SphereSolidAngle, ConeCosine),
    Polygon(PolygonSolidAngle),
    /// Tabulated: this path is for many samples at one receiver.
    Disk(TabulatedDiskSolidAngle),
    None,
}

/// The f32 area sampler.
#[derive(Clone, Debug)]
pub(super) enum Area {
    Sphere(SphereAreaSampler),
    Disk(DiskAreaSampler),
    Polygon(PolygonAreaSampler),
    None,
}

/// The f32 projected-solid-angle sampler ([`EmitterProjected`]'s kinds).
#[derive(Clone, Debug)]
pub(super) enum Projected {
    Sky,
    Cap(ProjectedCap),
    Sphere(ProjectedSphere),
    /// Tabulated: this path is for many samples at one receiver.
    Polygon(Box<TabulatedProjectedPolygon>),
    PolygonFan(ProjectedPolygonSampler),
    None,
}

/// One emitter prepared for the f32 estimator at one receiver (module
/// docs): the technique of its f64 [`PreparedEmitter`], its samplers and
/// shape in f32 in coordinates whose origin is the receiver, its radiance
/// (f64), and a bound on the f32 error of its estimate.
#[derive(Clone, Debug)]
pub struct PreparedEmitterF32 {
    pub(super) technique: Technique,
    /// L, W/m²/sr.
    pub(super) radiance: f64,
    /// The receiver's unit normal and frame, rounded to f32.
    pub(super) normal: Vec3,
    pub(super) frame: Frame,
    pub(super) shape: Shape,
    /// Whether a sampled direction that lies in the emitter's solid angle
    /// sees its emitting side (false: a one-sided disk or polygon seen
    /// from behind).
    pub(super) lit: bool,
    pub(super) light: Light,
    pub(super) area: Area,
    pub(super) projected: Projected,
    /// The control variate's closed form, when every sample is that value.
    pub(super) constant: Option<f64>,
    /// MIS on a sphere or sky cap seen from its lit side: the two halves in
    /// their own frames ([`ConeMisF32`], radiance 1) and the window of
    /// cosine samples that may see the cone, built once here (the window
    /// costs inverse sines and tangents).
    pub(super) cone_mis: Option<(ConeMisF32, CosineWindowF32)>,
    error_bound: f64,
}

impl PreparedEmitterF32 {
    /// The f32 form of `prepared` at `receiver`, or why it must run in f64
    /// (as `F32Fallback` with `emitter` 0: the caller sets the index).
    ///
    /// The error bound, in W/m², is
    ///
    /// B = L ε (32 Ω⊥ + 8 Ω + [hit test] 32 P) + L·(the projected
    /// sampler's own Ω⊥ error),
    ///
    /// ε = 2⁻²³, Ω the emitter's solid angle from the receiver, Ω⊥ its
    /// projected solid angle (its closed-form irradiance over L) and P the
    /// length of its outline on the unit sphere (docs/NUMERICS.md derives
    /// each term): a few roundings in every value's cos θ/p; the absolute
    /// error 8ε of cos θ, which matters where cos θ is small; and, for the
    /// techniques that test whether a direction hits the emitter (uniform,
    /// cosine, MIS's cosine part, area), directions within 16ε rad of the
    /// outline judged on the wrong side.
    pub fn new(prepared: &PreparedEmitter, receiver: &Receiver) -> Result<Self, FallbackReason> {
        let technique = prepared.technique;
        let emitter = &prepared.emitter;
        let radiance = emitter.strength();
        let closed = emitter
            .closed_form_irradiance(receiver)
            .filter(|e| e.is_finite() && *e > 0.0 && radiance > 0.0)
            .ok_or(FallbackReason::NoClosedForm)?;
        let normal = receiver.normal.as_vec3();
        let f = &receiver.frame;
        let frame = Frame {
            x: f.x.as_vec3(),
            y: f.y.as_vec3(),
            z: f.z.as_vec3(),
        };
        let p = receiver.point;
        let (shape, lit, outline) = shape_of(emitter, p)?;
        let control = prepared
            .control
            .as_ref()
            .map(|c: &ControlVariate| c.unoccluded);
        // What the technique draws from (the control variate's residual
        // sampler when it has no closed form).
        let draws = match (technique, control, &prepared.projected) {
            (Technique::ControlVariate, Some(_), _) => None,
            (Technique::ControlVariate, None, EmitterProjected::None) => Some(Technique::Light),
            (Technique::ControlVariate, None, _) => Some(Technique::Projected),
            (t, _, _) => Some(t),
        };
        let light = match draws {
            Some(Technique::Light | Technique::Mis(_)) => {
                light_of(&prepared.light, &shape, normal)?
            }
            _ => Light::None,
        };
        let area = match draws {
            Some(Technique::Area) => area_of(&shape),
            _ => Area::None,
        };
        let (projected, projected_error) = match draws {
            Some(Technique::Projected) => projected_of(&prepared.projected, &shape, receiver)?,
            _ => (Projected::None, 0.0),
        };
        let hit_test = matches!(
            draws,
            Some(
                Technique::UniformHemisphere
                    | Technique::CosineHemisphere
                    | Technique::Mis(_)
                    | Technique::Area
            )
        );
        let omega = solid_angle(&prepared.light);
        let projected_omega = closed / radiance;
        let error_bound = match draws {
            None => 0.0,
            Some(_) => {
                let hit = if hit_test { 32.0 * outline } else { 0.0 };
                radiance * (EPS32 * (32.0 * projected_omega + 8.0 * omega + hit) + projected_error)
            }
        };
        let relative = error_bound / closed;
        if !(relative <= F32_MAX_RELATIVE_ERROR) {
            return Err(FallbackReason::ErrorBound { relative });
        }
        let cone_mis = match (draws, &light, lit) {
            (Some(Technique::Mis(_)), Light::Cap(cone_frame, cone, _), true) => {
                Some(ConeMisF32::new(1.0, cone_frame, cone, &frame))
            }
            (Some(Technique::Mis(_)), Light::Sphere(s, _), true) => {
                Some(ConeMisF32::new(1.0, s.frame(), s.cone(), &frame))
            }
            _ => None,
        }
        .map(|cone| (cone, cone.window()));
        Ok(PreparedEmitterF32 {
            technique: match draws {
                Some(t) if technique == Technique::ControlVariate => t,
                _ => technique,
            },
            radiance,
            normal,
            frame,
            shape,
            lit,
            light,
            area,
            cone_mis,
            projected,
            constant: control,
            error_bound,
        })
    }

    /// The bound on the f32 error of this emitter's estimate, W/m²
    /// ([`PreparedEmitterF32::new`]): the estimate's systematic error
    /// beside the f64 rounding floor.
    pub fn error_bound(&self) -> f64 {
        self.error_bound
    }
}

/// The emitter's solid angle Ω from the receiver, from its f64 light
/// sampler (4π for a sky; 0 without a sampler).
fn solid_angle(light: &EmitterLight) -> f64 {
    match light {
        EmitterLight::Sky => 4.0 * std::f64::consts::PI,
        EmitterLight::Cap(_, c) => c.solid_angle(),
        EmitterLight::Sphere(s) => s.solid_angle(),
        EmitterLight::Polygon(p) => p.solid_angle(),
        EmitterLight::Disk(d) => d.solid_angle(),
        EmitterLight::DiskTable(d) => d.solid_angle(),
        EmitterLight::None => 0.0,
    }
}

/// `v` (a length or coordinate relative to the receiver, m) if 0 or in
/// [`F32_COORDINATE_RANGE`].
fn in_range(v: f64) -> Result<f64, FallbackReason> {
    let a = v.abs();
    let (lo, hi) = F32_COORDINATE_RANGE;
    if a == 0.0 || (lo..=hi).contains(&a) {
        Ok(v)
    } else {
        Err(FallbackReason::Range { length: v })
    }
}

/// `v` relative to the receiver `p`, rounded to f32, each non-zero
/// component in range.
fn relative(v: DVec3, p: DVec3) -> Result<Vec3, FallbackReason> {
    let d = v - p;
    for c in d.to_array() {
        in_range(c)?;
    }
    in_range(d.length())?;
    Ok(d.as_vec3())
}

/// The angle between two directions from the origin (atan2 of |a × b| and
/// a·b: accurate for tiny angles).
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// The emitter's f32 shape relative to the receiver `p`, whether a
/// direction into its solid angle sees its emitting side, and the length P
/// of its outline on the unit sphere of directions (rad).
fn shape_of(emitter: &Emitter, p: DVec3) -> Result<(Shape, bool, f64), FallbackReason> {
    use std::f64::consts::PI;
    Ok(match emitter {
        Emitter::Sky(_) => (Shape::Sky, true, 0.0),
        Emitter::SkyCap(c) => {
            let h = c.cone.one_minus_cos_theta_max();
            let cone = UniformCone::from_one_minus_cos(h as f32).map_err(unbuildable)?;
            let frame = Frame {
                x: c.frame.x.as_vec3(),
                y: c.frame.y.as_vec3(),
                z: c.frame.z.as_vec3(),
            };
            let sin = (h * (2.0 - h)).max(0.0).sqrt();
            (Shape::Cap(frame, cone), true, 2.0 * PI * sin)
        }
        Emitter::Sphere(s) => {
            let r = in_range(s.sphere.radius())?;
            let c = relative(s.sphere.center(), p)?;
            let sphere = Sphere::new(c, r as f32).map_err(unbuildable)?;
            let sin = (r / (s.sphere.center() - p).length()).min(1.0);
            (Shape::Sphere(sphere), true, 2.0 * PI * sin)
        }
        Emitter::Disk(d) => {
            let r = in_range(d.disk.radius())?;
            let c = relative(d.disk.center(), p)?;
            let disk = Disk::new(c, d.disk.normal().as_vec3(), r as f32).map_err(unbuildable)?;
            let front = d.disk.normal().dot(p - d.disk.center()) > 0.0;
            // The rim seen from the receiver, as 64 chords' angles.
            let frame = lambert_geometry::f64::Frame::from_normal(d.disk.normal());
            let rim = |k: usize| {
                let phi = 2.0 * PI * k as f64 / 64.0;
                d.disk.center() - p + (frame.x * phi.cos() + frame.y * phi.sin()) * d.disk.radius()
            };
            let outline: f64 = (0..64).map(|k| angle(rim(k), rim(k + 1))).sum();
            (Shape::Disk(disk), d.two_sided || front, outline)
        }
        Emitter::Polygon(q) => {
            let vertices = q.polygon.vertices();
            let v32 = vertices
                .iter()
                .map(|&v| relative(v, p))
                .collect::<Result<Vec<_>, _>>()?;
            let polygon = ConvexPolygon::new(v32).map_err(unbuildable)?;
            let front = q.polygon.normal().dot(p - vertices[0]) > 0.0;
            let outline: f64 = (0..vertices.len())
                .map(|k| angle(vertices[k] - p, vertices[(k + 1) % vertices.len()] - p))
                .sum();
            (Shape::Polygon(polygon), q.two_sided || front, outline)
        }
        Emitter::Point(_) | Emitter::Directional(_) => {
            return Err(FallbackReason::NoClosedForm);
        }
    })
}

/// The f32 solid-angle sampler matching the f64 one (none where it has
/// none), from the receiver at the origin, built on the emitter's f32
/// `shape`.
fn light_of(light: &EmitterLight, shape: &Shape, normal: Vec3) -> Result<Light, FallbackReason> {
    Ok(match (light, shape) {
        (EmitterLight::Sky, _) => Light::Sky,
        (EmitterLight::Cap(..), Shape::Cap(frame, cone)) => {
            Light::Cap(*frame, *cone, ConeCosine::new(cone, frame.to_local(normal)))
        }
        (EmitterLight::Sphere(_), Shape::Sphere(sphere)) => {
            let s = SphereSolidAngle::new(Vec3::ZERO, sphere).map_err(unbuildable)?;
            let cosine = ConeCosine::new(s.cone(), s.frame().to_local(normal));
            Light::Sphere(s, cosine)
        }
        (EmitterLight::Disk(_) | EmitterLight::DiskTable(_), Shape::Disk(disk)) => {
            Light::Disk(TabulatedDiskSolidAngle::new(
                DiskSolidAngle::new(Vec3::ZERO, disk).map_err(unbuildable)?,
            ))
        }
        (EmitterLight::Polygon(_), Shape::Polygon(polygon)) => {
            let sampler = PolygonLightSampler::new(polygon.clone()).map_err(unbuildable)?;
            match sampler.at(Vec3::ZERO, normal) {
                PolygonSolidAngle::Fan { triangles, .. } if triangles.is_empty() => Light::None,
                prepared => Light::Polygon(prepared),
            }
        }
        _ => Light::None,
    })
}

/// The f32 area sampler of a shape.
fn area_of(shape: &Shape) -> Area {
    match shape {
        Shape::Sphere(s) => Area::Sphere(SphereAreaSampler::new(*s)),
        Shape::Disk(d) => Area::Disk(DiskAreaSampler::new(*d)),
        Shape::Polygon(q) => Area::Polygon(PolygonAreaSampler::new(q.clone())),
        Shape::Sky | Shape::Cap(..) => Area::None,
    }
}

/// The f32 projected sampler matching the f64 one, built on the
/// emitter's f32 `shape`, and its Ω⊥ error bound (sr).
fn projected_of(
    projected: &EmitterProjected,
    shape: &Shape,
    receiver: &Receiver,
) -> Result<(Projected, f64), FallbackReason> {
    let n = receiver.normal.as_vec3();
    let ulps = |omega: f64| 8.0 * EPS32 * omega;
    Ok(match (projected, shape) {
        (EmitterProjected::Sky(_), _) => (Projected::Sky, ulps(std::f64::consts::PI)),
        (EmitterProjected::Cap(..), Shape::Cap(frame, cone)) => {
            let axis = receiver
                .frame
                .to_local(frame.z.as_dvec3())
                .as_vec3()
                .normalize();
            let cap =
                ProjectedCap::new(axis, cone.one_minus_cos_theta_max()).map_err(unbuildable)?;
            let omega = f64::from(cap.projected_solid_angle());
            (Projected::Cap(cap), ulps(omega))
        }
        (EmitterProjected::Sphere(_), Shape::Sphere(sphere)) => {
            let sampler = ProjectedSphere::new(Vec3::ZERO, n, sphere).map_err(unbuildable)?;
            let omega = f64::from(sampler.projected_solid_angle());
            (Projected::Sphere(sampler), ulps(omega))
        }
        (
            EmitterProjected::Polygon(_) | EmitterProjected::PolygonTable(_),
            Shape::Polygon(polygon),
        ) => {
            let sampler = ProjectedPolygon::new(Vec3::ZERO, n, polygon).map_err(unbuildable)?;
            let error = f64::from(sampler.projected_solid_angle_error())
                + ulps(f64::from(sampler.projected_solid_angle()));
            (
                Projected::Polygon(Box::new(TabulatedProjectedPolygon::new(sampler))),
                error,
            )
        }
        (EmitterProjected::PolygonFan(_, _, omega), Shape::Polygon(polygon)) => (
            Projected::PolygonFan(ProjectedPolygonSampler::new(polygon.clone())),
            ulps(*omega),
        ),
        _ => (Projected::None, 0.0),
    })
}

/// A sampler or shape that f32 rounding keeps from being built.
fn unbuildable(e: impl fmt::Display) -> FallbackReason {
    FallbackReason::Unbuildable {
        error: e.to_string(),
    }
}
