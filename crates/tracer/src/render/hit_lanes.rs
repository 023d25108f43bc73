//! The hits of a run of rays on one primitive, and their shadow rays,
//! computed in structure-of-arrays lanes: the hit records in one loop,
//! then, emitter by emitter, the light each hit sees and the shadow ray
//! toward it in another. With the shape and the emitter fixed for a whole
//! loop, and no branch inside it, the compiler vectorises both (compiled
//! for the widest instruction set, [`Isa::run`]); the scalar code asked
//! for the emitter's and the shape's kind, and pushed each shadow ray,
//! hit by hit.
//!
//! Every value is computed by the same expressions, in the same order, as
//! [`Intersect::hit_at`], [`DeltaLight::seen_from`] and
//! [`Scene::shadow_ray`](crate::scene::Scene::shadow_ray), so the records
//! are theirs to the bit (the wavefront tracer's test against the
//! recursive tracer checks it).

use glam::{DVec2, DVec3};
use lambert_geometry::f64::{offset_origin, Hit, Intersect, Ray, SHADOW_EPSILON};
use lambert_light::emitter::Emitter;
use lambert_sampling::isa::Isa;

use super::context::DeltaLight;
use crate::material::{Material, Surface};
use crate::texture::Texture;

/// A hit waiting for its shadow rays' verdicts, then for its shading.
#[derive(Clone, Copy, Debug)]
pub(super) struct Pending {
    /// Its ray's index in the generation.
    pub ray: u32,
    /// Its delta lights with cos > 0 (or NaN): `lights[first..end]`, one
    /// shadow ray each, in the scene's order of emitters.
    pub first: u32,
    pub end: u32,
    /// The hit, with its surface parameters where the material's texture
    /// varies (zero otherwise).
    pub hit: Hit,
}

/// Where [`HitLanes::record`] appends: the hits, and the shadow rays with
/// their limits and lights.
pub(super) struct Recorded<'a> {
    pub pending: &'a mut Vec<Pending>,
    pub shadow: &'a mut Vec<Ray>,
    pub shadow_t_max: &'a mut Vec<f64>,
    pub lights: &'a mut Vec<DeltaLight>,
}

/// The lanes of one run (reused from run to run): the rays, their hit
/// records, and per (emitter, hit) the light and its shadow ray, at index
/// emitter·m + hit for a run of m hits.
#[derive(Debug, Default)]
pub(super) struct HitLanes {
    origin: [Vec<f64>; 3],
    direction: [Vec<f64>; 3],
    t: Vec<f64>,
    point: [Vec<f64>; 3],
    normal: [Vec<f64>; 3],
    error: [Vec<f64>; 3],
    to_light: [Vec<f64>; 3],
    distance: Vec<f64>,
    scale: Vec<f64>,
    cos: Vec<f64>,
    shadow_origin: [Vec<f64>; 3],
    t_max: Vec<f64>,
    /// Whether the light counts: it is a delta light, the material takes
    /// direct light there, and cos > 0 (or NaN).
    counts: Vec<bool>,
}

/// Sets every vector's length to `n` (contents are overwritten).
fn size<T: Copy + Default>(vectors: &mut [&mut Vec<T>], n: usize) {
    for v in vectors {
        v.clear();
        v.resize(n, T::default());
    }
}

/// The vector of lane `j` of three arrays.
#[inline(always)]
fn at(a: &[Vec<f64>; 3], j: usize) -> DVec3 {
    DVec3::new(a[0][j], a[1][j], a[2][j])
}

/// Stores `v` in lane `j` of three arrays.
#[inline(always)]
fn put(a: &mut [Vec<f64>; 3], j: usize, v: DVec3) {
    (a[0][j], a[1][j], a[2][j]) = v.into();
}

impl HitLanes {
    /// Records the hits of the rays `run` (indices into `rays`, hit at
    /// `nearest`) on `shape`, whose material is `material`, and the shadow
    /// ray toward each of `emitters` that counts at each hit, appending
    /// them to `out` in the order of `run`, each hit's lights in the order
    /// of `emitters`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn record<S: Intersect>(
        &mut self,
        isa: Isa,
        shape: &S,
        material: &Material,
        emitters: &[Emitter],
        run: &[u32],
        rays: &[Ray],
        nearest: &[f64],
        out: &mut Recorded,
    ) {
        let m = run.len();
        let lit = match material.surface {
            Surface::Emitter { .. } => false,
            Surface::Diffuse(_) => true,
            Surface::Mirror(_) | Surface::Dielectric { .. } => material.highlight.is_some(),
        };
        // Dielectrics take highlights on their front face only.
        let front_only = matches!(material.surface, Surface::Dielectric { .. });
        let lights = if lit { emitters.len() } else { 0 };
        {
            let [ox, oy, oz] = &mut self.origin;
            let [dx, dy, dz] = &mut self.direction;
            let [px, py, pz] = &mut self.point;
            let [nx, ny, nz] = &mut self.normal;
            let [ex, ey, ez] = &mut self.error;
            size(
                &mut [
                    ox,
                    oy,
                    oz,
                    dx,
                    dy,
                    dz,
                    &mut self.t,
                    px,
                    py,
                    pz,
                    nx,
                    ny,
                    nz,
                    ex,
                    ey,
                    ez,
                ],
                m,
            );
            let [lx, ly, lz] = &mut self.to_light;
            let [sx, sy, sz] = &mut self.shadow_origin;
            size(
                &mut [
                    lx,
                    ly,
                    lz,
                    &mut self.distance,
                    &mut self.scale,
                    &mut self.cos,
                    sx,
                    sy,
                    sz,
                    &mut self.t_max,
                ],
                m * lights,
            );
            size(&mut [&mut self.counts], m * lights);
        }
        for (j, &i) in run.iter().enumerate() {
            let ray = &rays[i as usize];
            put(&mut self.origin, j, ray.origin);
            put(&mut self.direction, j, ray.direction);
            self.t[j] = nearest[i as usize];
        }
        isa.run(
            #[inline(always)]
            || self.hits(shape, m),
        );
        for (e, emitter) in emitters[..lights].iter().enumerate() {
            isa.run(
                #[inline(always)]
                || self.lights(emitter, e * m, m, front_only),
            );
        }
        let textured = matches!(material.surface, Surface::Diffuse(Texture::Checker { .. }));
        for (j, &i) in run.iter().enumerate() {
            let t = self.t[j];
            let uv = if textured {
                shape.surface_parameters(&rays[i as usize], t)
            } else {
                DVec2::ZERO
            };
            let first = out.lights.len();
            for e in 0..lights {
                let q = e * m + j;
                if self.counts[q] {
                    let direction = at(&self.to_light, q);
                    out.shadow
                        .push(Ray::new(at(&self.shadow_origin, q), direction));
                    out.shadow_t_max.push(self.t_max[q]);
                    out.lights.push(DeltaLight {
                        direction,
                        distance: self.distance[q],
                        scale: self.scale[q],
                        cos: self.cos[q],
                    });
                }
            }
            out.pending.push(Pending {
                ray: i,
                first: first as u32,
                end: out.lights.len() as u32,
                hit: Hit {
                    distance: t,
                    point: at(&self.point, j),
                    normal: at(&self.normal, j),
                    error: at(&self.error, j),
                    uv,
                },
            });
        }
    }

    /// The hit records of lanes 0..m: [`Intersect::hit_at`] (its distance
    /// is t, its `uv` zero).
    #[inline(always)]
    fn hits<S: Intersect>(&mut self, shape: &S, m: usize) {
        // Every array cut to m first, so that no index is checked in the
        // loop (a check in it stops the compiler vectorising it).
        let [ox, oy, oz] = self.origin.each_ref().map(|v| &v[..m]);
        let [dx, dy, dz] = self.direction.each_ref().map(|v| &v[..m]);
        let t = &self.t[..m];
        let [px, py, pz] = self.point.each_mut().map(|v| &mut v[..m]);
        let [nx, ny, nz] = self.normal.each_mut().map(|v| &mut v[..m]);
        let [ex, ey, ez] = self.error.each_mut().map(|v| &mut v[..m]);
        for j in 0..m {
            let ray = Ray::new(
                DVec3::new(ox[j], oy[j], oz[j]),
                DVec3::new(dx[j], dy[j], dz[j]),
            );
            let hit = shape.hit_at(&ray, t[j]);
            (px[j], py[j], pz[j]) = hit.point.into();
            (nx[j], ny[j], nz[j]) = hit.normal.into();
            (ex[j], ey[j], ez[j]) = hit.error.into();
        }
    }

    /// Emitter `emitter` seen from the hits of lanes 0..m, stored at
    /// `base + j`: [`DeltaLight::seen_from`] with the normal facing the
    /// ray, and the shadow ray of
    /// [`Scene::shadow_ray`](crate::scene::Scene::shadow_ray) toward it.
    /// It counts where the light is a delta light seen from a point other
    /// than its own, cos is not ≤ 0 and, when `front_only`, the ray hit
    /// the front face.
    #[inline(always)]
    fn lights(&mut self, emitter: &Emitter, base: usize, m: usize, front_only: bool) {
        // (toward the light: its position or its unit direction; whether
        // it is a point light; its intensity or irradiance)
        let (toward, point_light, power) = match emitter {
            Emitter::Point(p) => (p.position, true, p.intensity),
            Emitter::Directional(d) => (d.direction, false, d.irradiance),
            _ => {
                self.counts[base..base + m].fill(false);
                return;
            }
        };
        let lanes = base..base + m;
        let [dx, dy, dz] = self.direction.each_ref().map(|v| &v[..m]);
        let [px, py, pz] = self.point.each_ref().map(|v| &v[..m]);
        let [nx, ny, nz] = self.normal.each_ref().map(|v| &v[..m]);
        let [ex, ey, ez] = self.error.each_ref().map(|v| &v[..m]);
        let [lx, ly, lz] = self.to_light.each_mut().map(|v| &mut v[lanes.clone()]);
        let [sx, sy, sz] = self.shadow_origin.each_mut().map(|v| &mut v[lanes.clone()]);
        let distance_out = &mut self.distance[lanes.clone()];
        let scale_out = &mut self.scale[lanes.clone()];
        let cos_out = &mut self.cos[lanes.clone()];
        let t_max = &mut self.t_max[lanes.clone()];
        let counts = &mut self.counts[lanes];
        for j in 0..m {
            let point = DVec3::new(px[j], py[j], pz[j]);
            let normal = DVec3::new(nx[j], ny[j], nz[j]);
            let front = DVec3::new(dx[j], dy[j], dz[j]).dot(normal) < 0.0;
            let facing = if front { normal } else { -normal };
            let (direction, distance, scale, seen) = if point_light {
                let v = toward - point;
                let r2 = v.length_squared();
                let r = r2.sqrt();
                (v / r, r, power / r2, r2 > 0.0)
            } else {
                (toward, f64::INFINITY, power, true)
            };
            let cos = facing.dot(direction);
            counts[j] = seen & !(cos <= 0.0) & (front | !front_only);
            (lx[j], ly[j], lz[j]) = direction.into();
            distance_out[j] = distance;
            scale_out[j] = scale;
            cos_out[j] = cos;
            t_max[j] = if distance.is_finite() {
                distance * (1.0 - SHADOW_EPSILON)
            } else {
                f64::INFINITY
            };
            let error = DVec3::new(ex[j], ey[j], ez[j]);
            (sx[j], sy[j], sz[j]) = offset_origin(point, error, normal, direction).into();
        }
    }
}
