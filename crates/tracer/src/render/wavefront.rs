//! Whitted tracing a tile at a time, generation by generation: the camera
//! rays of every pixel of the tile, then all their reflected and refracted
//! rays, and so on (Laine, Karras & Aila, "Megakernels considered harmful:
//! wavefront path tracing on GPUs", HPG 2013, for the organisation).
//!
//! A generation is held in structure-of-arrays form (one array per
//! coordinate) and most of its work runs as loops over those arrays whose
//! bodies have no branch, which the compiler vectorises: the nearest hits
//! (the geometry crate's `nearest_in_batch`, shape by shape), the hit
//! records, the shadow rays toward each delta light and their test
//! (`occludes_in_batch`), the direct irradiance, and the reflected and
//! refracted rays with their Fresnel weights. They are compiled for the
//! widest instruction set the processor has ([`Isa`]). What remains per
//! ray is a short pass of decisions: the material's case, the texture, the
//! highlights, which children to follow.
//!
//! **The image is the recursive tracer's, to the bit.** Every value is
//! computed by the same functions with the same operations in the same
//! order (a loop computes a value for every ray and keeps it only where the
//! recursive tracer would have computed it, which changes nothing for the
//! rays it is kept for); vectorising changes how many rays an instruction
//! works on, not what it computes for each. The recursion computes a hit's
//! radiance as `c = base + w₁·L(child₁) + w₂·L(child₂)` after its children
//! return; here every hit becomes a node holding its base colour, its
//! weights and its children's indices, and once the deepest generation is
//! done the nodes are combined from the last to the first (children always
//! come after their parent), each by that same expression. Scenes with area
//! emitters, whose per-pixel estimates draw seeds in the recursion's order,
//! are traced by the recursive tracer.

use glam::DVec3;
use lambert_geometry::f64::{offset_origin, Hit, Intersect, Ray, RayBatch};
use lambert_light::emitter::Emitter;
use lambert_sampling::isa::Isa;

use super::context::{DeltaLight, Direct, RayCounts};
use super::{Pixel, RenderConfig};
use crate::aggregate::Aggregate;
use crate::camera::Camera;
use crate::color::Rgb;
use crate::material::Surface;
use crate::optics::{fresnel_dielectric, reflect, refract};
use crate::scene::Scene;
use crate::shape::Shape;

/// No primitive, no child.
const NONE: u32 = u32::MAX;

/// Above this many primitives, hit records are built ray by ray (one
/// vectorised loop per primitive over all rays would cost more).
const RECORDS_BY_PRIMITIVE: usize = 8;

/// How a node's radiance combines its base colour with its children's.
#[derive(Clone, Copy, Debug)]
enum Weights {
    /// c = base + reflectance·L(reflected).
    Mirror(Rgb),
    /// c = base + L(reflected)·F + L(refracted)·(1 − F).
    Dielectric(f64),
}

/// One ray's hit (or miss) in the tree of rays of a tile.
#[derive(Clone, Copy, Debug)]
struct Node {
    /// The radiance along the ray once combined; before that, the base
    /// colour (the hit's own light: highlights, or all of it for leaves).
    radiance: Rgb,
    weights: Weights,
    /// Reflected and refracted child nodes ([`NONE`] if not traced).
    children: [u32; 2],
}

impl Node {
    fn leaf(radiance: Rgb) -> Node {
        Node {
            radiance,
            weights: Weights::Dielectric(0.0),
            children: [NONE; 2],
        }
    }
}

/// A 3-vector per ray: x, y and z arrays.
#[derive(Clone, Debug, Default)]
struct Lanes3 {
    x: Vec<f64>,
    y: Vec<f64>,
    z: Vec<f64>,
}

impl Lanes3 {
    /// `n` zero vectors.
    fn reset(&mut self, n: usize) {
        for v in [&mut self.x, &mut self.y, &mut self.z] {
            v.clear();
            v.resize(n, 0.0);
        }
    }

    /// The first `n` lanes, as slices the loops index without checks.
    #[inline(always)]
    fn view(&self, n: usize) -> View3<'_> {
        View3(&self.x[..n], &self.y[..n], &self.z[..n])
    }

    /// The first `n` lanes, writable.
    #[inline(always)]
    fn view_mut(&mut self, n: usize) -> ViewMut3<'_> {
        ViewMut3(&mut self.x[..n], &mut self.y[..n], &mut self.z[..n])
    }

    #[inline(always)]
    fn get(&self, i: usize) -> DVec3 {
        DVec3::new(self.x[i], self.y[i], self.z[i])
    }
}

/// Read-only lanes of 3-vectors.
#[derive(Clone, Copy)]
struct View3<'a>(&'a [f64], &'a [f64], &'a [f64]);

impl View3<'_> {
    #[inline(always)]
    fn at(&self, i: usize) -> DVec3 {
        DVec3::new(self.0[i], self.1[i], self.2[i])
    }
}

/// Writable lanes of 3-vectors.
struct ViewMut3<'a>(&'a mut [f64], &'a mut [f64], &'a mut [f64]);

impl ViewMut3<'_> {
    /// Lane i becomes `v` where `keep` is false.
    #[inline(always)]
    fn set_where(&mut self, i: usize, put: bool, v: DVec3) {
        self.0[i] = if put { v.x } else { self.0[i] };
        self.1[i] = if put { v.y } else { self.1[i] };
        self.2[i] = if put { v.z } else { self.2[i] };
    }

    #[inline(always)]
    fn set(&mut self, i: usize, v: DVec3) {
        self.0[i] = v.x;
        self.1[i] = v.y;
        self.2[i] = v.z;
    }
}

/// What a thread reuses from tile to tile: the generation being traced and
/// everything computed for it, one entry per ray.
#[derive(Debug, Default)]
pub(super) struct Scratch {
    rays: Vec<Ray>,
    ray_nodes: Vec<u32>,
    batch: RayBatch,
    nearest: Vec<f64>,
    ids: Vec<u32>,
    // Hit records.
    point: Lanes3,
    normal: Lanes3,
    error: Lanes3,
    facing: Lanes3,
    front: Vec<bool>,
    // Per ray: whether its material takes direct light, and the relative
    // index of refraction η_i/η_t (dielectrics; 1 for the rest).
    lit: Vec<bool>,
    eta: Vec<f64>,
    // The shadow rays toward one delta light.
    shadow: RayBatch,
    shadow_t_max: Vec<f64>,
    light_e: Vec<f64>,
    active: Vec<bool>,
    blocked: Vec<bool>,
    // Direct light.
    irradiance: Vec<f64>,
    highlight: Vec<Rgb>,
    // Children.
    reflected: Lanes3,
    reflected_origin: Lanes3,
    refracted: Lanes3,
    refracted_origin: Lanes3,
    refracts: Vec<bool>,
    fresnel: Vec<f64>,
    // The tree.
    next_rays: Vec<Ray>,
    next_nodes: Vec<u32>,
    nodes: Vec<Node>,
    first_irradiance: Vec<f64>,
}

/// Whether `scene` is traced here in `whitted` mode: every emitter is a
/// delta light (area emitters' estimates are the recursive tracer's).
pub(super) fn applies(scene: &Scene) -> bool {
    !scene.has_area_emitters()
}

/// The pixels of the tile [x0, x1) × [y0, y1), row by row, and the rays
/// traced for them.
#[allow(clippy::too_many_arguments)]
pub(super) fn tile(
    scene: &Scene,
    camera: &Camera,
    config: &RenderConfig,
    isa: Isa,
    (x0, x1): (u32, u32),
    (y0, y1): (u32, u32),
    s: &mut Scratch,
) -> (Vec<Pixel>, RayCounts) {
    let mut counts = RayCounts::default();
    s.rays.clear();
    s.ray_nodes.clear();
    s.nodes.clear();
    for y in y0..y1 {
        for x in x0..x1 {
            s.ray_nodes.push(s.nodes.len() as u32);
            s.nodes.push(Node::leaf(Rgb::BLACK));
            s.rays.push(camera.pixel_ray(x, y));
        }
    }
    let pixels = s.nodes.len();
    counts.camera = pixels as u64;
    s.first_irradiance.clear();
    s.first_irradiance.resize(pixels, 0.0);
    let mut depth = 0;
    while !s.rays.is_empty() {
        isa.run(
            #[inline(always)]
            || generation(scene, config, depth, s, &mut counts),
        );
        std::mem::swap(&mut s.rays, &mut s.next_rays);
        std::mem::swap(&mut s.ray_nodes, &mut s.next_nodes);
        counts.secondary += s.rays.len() as u64;
        depth += 1;
    }
    // Children after parents: combine from the last node to the first.
    for k in (0..s.nodes.len()).rev() {
        let node = s.nodes[k];
        let child = |i: usize| s.nodes[node.children[i] as usize].radiance;
        let mut c = node.radiance;
        match node.weights {
            Weights::Mirror(reflectance) => {
                if node.children[0] != NONE {
                    c += reflectance * child(0);
                }
            }
            Weights::Dielectric(fresnel) => {
                if node.children[0] != NONE {
                    c += child(0) * fresnel;
                }
                if node.children[1] != NONE {
                    c += child(1) * (1.0 - fresnel);
                }
            }
        }
        s.nodes[k].radiance = c;
    }
    let out = (0..pixels)
        .map(|p| Pixel {
            rgb: s.nodes[p].radiance,
            irradiance: s.first_irradiance[p],
            std_error: 0.0,
        })
        .collect();
    (out, counts)
}

/// Traces the generation `s.rays` (at recursion `depth`): nearest hits,
/// shadow rays, shading; their reflected and refracted rays go to
/// `s.next_rays`.
#[inline(always)]
fn generation(
    scene: &Scene,
    config: &RenderConfig,
    depth: u32,
    s: &mut Scratch,
    counts: &mut RayCounts,
) {
    let n = s.rays.len();
    let aggregate = scene.aggregate();
    s.batch.assign(&s.rays);
    s.nearest.clear();
    s.nearest.resize(n, f64::INFINITY);
    s.ids.clear();
    s.ids.resize(n, NONE);
    aggregate.nearest_in_batch(&s.batch, &mut s.nearest, &mut s.ids);
    records(aggregate, s);
    materials(scene, s);
    s.irradiance.clear();
    s.irradiance.resize(n, 0.0);
    s.highlight.clear();
    s.highlight.resize(n, Rgb::BLACK);
    for e in scene.emitters() {
        counts.shadow += match e {
            Emitter::Point(p) => delta_light(scene, s, |at, n| DeltaLight::point(p, at, n)),
            Emitter::Directional(d) => {
                delta_light(scene, s, |_, n| (DeltaLight::directional(d, n), true))
            }
            _ => 0,
        };
    }
    if depth < config.max_depth {
        children(s);
    }
    shade(scene, config, depth, s);
}

/// The hit records (point, geometric normal, error bound) of the rays that
/// hit something, which side of the surface each arrived on, and the
/// normal facing it. Rays that hit nothing get unused values.
#[inline(always)]
fn records(aggregate: &Aggregate, s: &mut Scratch) {
    let n = s.rays.len();
    for lanes in [&mut s.point, &mut s.normal, &mut s.error, &mut s.facing] {
        lanes.reset(n);
    }
    if aggregate.len() <= RECORDS_BY_PRIMITIVE {
        for k in 0..aggregate.len() as u32 {
            match &aggregate.primitive(k).shape {
                Shape::Sphere(shape) => records_of(shape, k, s),
                Shape::Plane(shape) => records_of(shape, k, s),
                Shape::Disk(shape) => records_of(shape, k, s),
                Shape::Parallelogram(shape) => records_of(shape, k, s),
                // Their records repeat the test, with branches: ray by ray.
                Shape::Triangle(_) | Shape::Polygon(_) => one_by_one(aggregate, Some(k), s),
            }
        }
    } else {
        one_by_one(aggregate, None, s);
    }
    let rays = &s.rays[..n];
    let normal = s.normal.view(n);
    let mut facing = s.facing.view_mut(n);
    s.front.clear();
    s.front.resize(n, false);
    let front = &mut s.front[..n];
    for i in 0..n {
        let d = rays[i].direction;
        let hit_normal = normal.at(i);
        // Hit::is_front and Hit::facing_normal.
        let is_front = d.dot(hit_normal) < 0.0;
        front[i] = is_front;
        facing.set(i, if is_front { hit_normal } else { -hit_normal });
    }
}

/// The records of the rays whose nearest hit is primitive `k`, a `shape`
/// whose record has no branch: computed for every ray, kept for those.
#[inline(always)]
fn records_of<S: Intersect>(shape: &S, k: u32, s: &mut Scratch) {
    let n = s.rays.len();
    let (rays, t, ids) = (&s.rays[..n], &s.nearest[..n], &s.ids[..n]);
    let (mut point, mut normal, mut error) = (
        s.point.view_mut(n),
        s.normal.view_mut(n),
        s.error.view_mut(n),
    );
    for i in 0..n {
        let mine = ids[i] == k;
        let hit = shape.hit_at(&rays[i], t[i]);
        point.set_where(i, mine, hit.point);
        normal.set_where(i, mine, hit.normal);
        error.set_where(i, mine, hit.error);
    }
}

/// The records of the rays that hit primitive `k` (or any primitive, for
/// `None`), ray by ray.
fn one_by_one(aggregate: &Aggregate, k: Option<u32>, s: &mut Scratch) {
    for i in 0..s.rays.len() {
        let id = s.ids[i];
        if id == NONE || k.is_some_and(|k| k != id) {
            continue;
        }
        let hit = aggregate
            .primitive(id)
            .shape
            .hit_at(&s.rays[i], s.nearest[i]);
        for (lanes, v) in [
            (&mut s.point, hit.point),
            (&mut s.normal, hit.normal),
            (&mut s.error, hit.error),
        ] {
            lanes.x[i] = v.x;
            lanes.y[i] = v.y;
            lanes.z[i] = v.z;
        }
    }
}

/// Per ray, what its material asks of the vectorised passes: whether the
/// hit takes direct light (shadow rays), and η_i/η_t for dielectrics.
#[inline(always)]
fn materials(scene: &Scene, s: &mut Scratch) {
    let n = s.rays.len();
    s.lit.clear();
    s.lit.resize(n, false);
    s.eta.clear();
    s.eta.resize(n, 1.0);
    let aggregate = scene.aggregate();
    for i in 0..n {
        if s.ids[i] == NONE {
            continue;
        }
        let material = scene.material_of(aggregate.primitive(s.ids[i]));
        let front = s.front[i];
        s.lit[i] = match material.surface {
            Surface::Emitter { .. } => false,
            Surface::Diffuse(_) => true,
            Surface::Mirror(_) => material.highlight.is_some(),
            Surface::Dielectric { ior } => {
                // Entering (front face): η_i/η_t = 1/ior; leaving: ior.
                s.eta[i] = if front { 1.0 / ior } else { ior };
                material.highlight.is_some() && front
            }
        };
    }
}

/// The direct light of one delta light at every lit hit (as
/// `Context::direct` adds it): a shadow ray toward it from each hit it is
/// above, one batch test, then E += (I/r²)·cos where it is seen, and the
/// highlight where the material has one. `light(point, n)` is the light
/// seen from a point with normal n, and whether it counts there. Returns
/// the shadow rays traced.
#[inline(always)]
fn delta_light(
    scene: &Scene,
    s: &mut Scratch,
    light: impl Fn(DVec3, DVec3) -> (DeltaLight, bool),
) -> u64 {
    let n = s.rays.len();
    s.shadow.resize(n);
    s.shadow_t_max.clear();
    s.shadow_t_max.resize(n, 0.0);
    s.light_e.clear();
    s.light_e.resize(n, 0.0);
    s.active.clear();
    s.active.resize(n, false);
    {
        let (point, normal, error, facing) = (
            s.point.view(n),
            s.normal.view(n),
            s.error.view(n),
            s.facing.view(n),
        );
        let (ids, lit) = (&s.ids[..n], &s.lit[..n]);
        let ([ox, oy, oz], [dx, dy, dz]) = s.shadow.lanes_mut();
        let mut origin = ViewMut3(&mut ox[..n], &mut oy[..n], &mut oz[..n]);
        let mut direction = ViewMut3(&mut dx[..n], &mut dy[..n], &mut dz[..n]);
        let (t_max, light_e, active) = (
            &mut s.shadow_t_max[..n],
            &mut s.light_e[..n],
            &mut s.active[..n],
        );
        for i in 0..n {
            let p = point.at(i);
            let (light, counts) = light(p, facing.at(i));
            let hit = Hit {
                distance: 0.0,
                point: p,
                normal: normal.at(i),
                error: error.at(i),
                uv: glam::DVec2::ZERO,
            };
            let (ray, limit) = Scene::shadow_ray(&hit, light.direction, light.distance);
            // Context::direct: a shadow ray unless cos ≤ 0.
            let on = (ids[i] != NONE) & lit[i] & counts & !(light.cos <= 0.0);
            active[i] = on;
            t_max[i] = if on { limit } else { 0.0 };
            origin.set(i, ray.origin);
            direction.set(i, light.direction);
            light_e[i] = light.scale * light.cos;
        }
    }
    s.blocked.clear();
    s.blocked.resize(n, false);
    let aggregate = scene.aggregate();
    aggregate.occludes_in_batch(&s.shadow, &s.shadow_t_max, &mut s.blocked);
    let mut traced = 0;
    let [dx, dy, dz] = s.shadow.directions();
    for i in 0..n {
        if !s.active[i] {
            continue;
        }
        traced += 1;
        if s.blocked[i] {
            continue;
        }
        // Direct::add, with the light already seen.
        s.irradiance[i] += s.light_e[i];
        let material = scene.material_of(aggregate.primitive(s.ids[i]));
        if let Some(h) = &material.highlight {
            let wo = -s.rays[i].direction;
            let half = (DVec3::new(dx[i], dy[i], dz[i]) + wo).normalize_or_zero();
            s.highlight[i] += h.brdf(s.facing.get(i).dot(half)) * s.light_e[i];
        }
    }
    traced
}

/// For every hit, the reflected ray, and for dielectrics the refracted ray
/// (when there is one) and the Fresnel reflectance, as the recursive tracer
/// computes them; the shading pass keeps those its materials follow.
#[inline(always)]
fn children(s: &mut Scratch) {
    let n = s.rays.len();
    for lanes in [
        &mut s.reflected,
        &mut s.reflected_origin,
        &mut s.refracted,
        &mut s.refracted_origin,
    ] {
        lanes.reset(n);
    }
    s.fresnel.clear();
    s.fresnel.resize(n, 0.0);
    s.refracts.clear();
    s.refracts.resize(n, false);
    let (point, normal, error, facing) = (
        s.point.view(n),
        s.normal.view(n),
        s.error.view(n),
        s.facing.view(n),
    );
    let (rays, eta) = (&s.rays[..n], &s.eta[..n]);
    let (mut reflected, mut reflected_origin) =
        (s.reflected.view_mut(n), s.reflected_origin.view_mut(n));
    let (mut refracted, mut refracted_origin) =
        (s.refracted.view_mut(n), s.refracted_origin.view_mut(n));
    let (fresnel, refracts) = (&mut s.fresnel[..n], &mut s.refracts[..n]);
    for i in 0..n {
        let d = rays[i].direction;
        let nf = facing.at(i);
        let (p, e, ng) = (point.at(i), error.at(i), normal.at(i));
        let r = reflect(d, nf);
        reflected.set(i, r);
        reflected_origin.set(i, offset_origin(p, e, ng, r));
        let f = fresnel_dielectric((-d).dot(nf), eta[i]);
        fresnel[i] = f;
        let (t, has) = match refract(d, nf, eta[i]) {
            Some((t, _)) => (t, true),
            None => (DVec3::ZERO, false),
        };
        refracts[i] = has & (f < 1.0);
        refracted.set(i, t);
        refracted_origin.set(i, offset_origin(p, e, ng, t));
    }
}

/// The decisions, ray by ray: each ray's node (leaf radiance, or base
/// colour, weights and children), the first hit's irradiance, and the next
/// generation.
#[inline(always)]
fn shade(scene: &Scene, config: &RenderConfig, depth: u32, s: &mut Scratch) {
    s.next_rays.clear();
    s.next_nodes.clear();
    let deeper = depth < config.max_depth;
    let aggregate = scene.aggregate();
    for i in 0..s.rays.len() {
        let ray = &s.rays[i];
        let node_index = s.ray_nodes[i] as usize;
        if s.ids[i] == NONE {
            s.nodes[node_index] = Node::leaf(scene.escaped(ray.direction));
            continue;
        }
        let primitive = aggregate.primitive(s.ids[i]);
        let material = scene.material_of(primitive);
        let front = s.front[i];
        let highlight = material.highlight.is_some();
        let direct = Direct {
            irradiance: s.irradiance[i],
            std_error: 0.0,
            highlight: s.highlight[i],
        };
        let mut follow = |direction: DVec3, origin: DVec3| -> u32 {
            let child = s.nodes.len() as u32;
            s.nodes.push(Node::leaf(Rgb::BLACK));
            s.next_rays.push(Ray::new(origin, direction));
            s.next_nodes.push(child);
            child
        };
        let node = match material.surface {
            Surface::Emitter {
                radiance,
                two_sided,
            } => Node::leaf(Rgb::grey(if front || two_sided { radiance } else { 0.0 })),
            Surface::Diffuse(texture) => {
                if depth == 0 {
                    s.first_irradiance[node_index] = direct.irradiance;
                }
                let albedo =
                    texture.at_lazy(|| primitive.shape.surface_parameters(ray, s.nearest[i]));
                Node::leaf(albedo * (direct.irradiance / std::f64::consts::PI) + direct.highlight)
            }
            Surface::Mirror(reflectance) => {
                let base = if highlight {
                    direct.highlight
                } else {
                    Rgb::BLACK
                };
                let reflected = if deeper {
                    follow(s.reflected.get(i), s.reflected_origin.get(i))
                } else {
                    NONE
                };
                Node {
                    radiance: base,
                    weights: Weights::Mirror(reflectance),
                    children: [reflected, NONE],
                }
            }
            Surface::Dielectric { .. } => {
                let base = if highlight && front {
                    direct.highlight
                } else {
                    Rgb::BLACK
                };
                let mut children = [NONE; 2];
                let mut fresnel = 0.0;
                if deeper {
                    fresnel = s.fresnel[i];
                    children[0] = follow(s.reflected.get(i), s.reflected_origin.get(i));
                    if s.refracts[i] {
                        children[1] = follow(s.refracted.get(i), s.refracted_origin.get(i));
                    }
                }
                Node {
                    radiance: base,
                    weights: Weights::Dielectric(fresnel),
                    children,
                }
            }
        };
        s.nodes[node_index] = node;
    }
}

#[cfg(test)]
mod tests {
    //! The image traced generation by generation is the recursive
    //! tracer's, to the bit, for every instruction set the processor has.

    use glam::DVec3;
    use lambert_geometry::f64::{ConvexPolygon, Disk, Parallelogram, Plane, Sphere, Triangle};
    use lambert_light::emitter::{DirectionalLight, Emitter, PointLight};
    use lambert_sampling::isa::Isa;

    use super::{tile, Scratch};
    use crate::aggregate::Acceleration;
    use crate::builtin;
    use crate::camera::Camera;
    use crate::color::Rgb;
    use crate::material::{Material, Surface};
    use crate::render::context::{Context, RayCounts};
    use crate::render::{whitted, Pixel, RenderConfig};
    use crate::scene::{Scene, SceneBuilder};
    use crate::shape::Shape;
    use crate::texture::Texture;

    /// Every pixel's bits (radiance and first-hit irradiance), row by row.
    fn bits(pixels: &[Pixel]) -> Vec<[u64; 4]> {
        pixels
            .iter()
            .map(|p| {
                [
                    p.rgb.r.to_bits(),
                    p.rgb.g.to_bits(),
                    p.rgb.b.to_bits(),
                    p.irradiance.to_bits(),
                ]
            })
            .collect()
    }

    /// The recursive tracer's image and ray counts.
    fn recursive(scene: &Scene, config: &RenderConfig) -> (Vec<Pixel>, RayCounts) {
        let mut cx = Context::new(scene, config, &[]);
        let camera = scene.camera();
        let mut pixels = Vec::new();
        for y in 0..camera.height() {
            for x in 0..camera.width() {
                cx.start_pixel(u64::from(y * camera.width() + x));
                pixels.push(whitted::pixel(&cx, &camera.pixel_ray(x, y)).unwrap());
            }
        }
        (pixels, cx.counts())
    }

    /// The image traced generation by generation in tiles of side `t`
    /// (partial tiles at the right and bottom edges), row by row.
    fn by_generation(
        scene: &Scene,
        config: &RenderConfig,
        isa: Isa,
        t: u32,
    ) -> (Vec<Pixel>, RayCounts) {
        let camera = scene.camera();
        let (w, h) = (camera.width(), camera.height());
        let mut image = vec![Pixel::default(); (w * h) as usize];
        let mut total = RayCounts::default();
        let mut scratch = Scratch::default();
        for y0 in (0..h).step_by(t as usize) {
            for x0 in (0..w).step_by(t as usize) {
                let (x1, y1) = ((x0 + t).min(w), (y0 + t).min(h));
                let (pixels, counts) =
                    tile(scene, camera, config, isa, (x0, x1), (y0, y1), &mut scratch);
                total = total.plus(counts);
                for (k, p) in pixels.into_iter().enumerate() {
                    let (x, y) = (x0 + k as u32 % (x1 - x0), y0 + k as u32 / (x1 - x0));
                    image[(y * w + x) as usize] = p;
                }
            }
        }
        (image, total)
    }

    /// A shape of every kind with every surface: textured diffuse planes,
    /// disks and parallelograms, a glass sphere and a glass triangle
    /// (total internal reflection inside the sphere), a mirror polygon,
    /// highlights on some of each; a point light and a directional light;
    /// and `beads` more small spheres in a row.
    fn every_kind(beads: u32) -> Scene {
        let camera = Camera::new(
            DVec3::new(0.5, 2.5, 7.0),
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::Y,
            50.0,
            37,
            29,
        )
        .unwrap();
        let mut b = SceneBuilder::new(camera);
        let checker = |scale| Texture::Checker {
            even: Rgb::new(0.8, 0.7, 0.2),
            odd: Rgb::new(0.2, 0.3, 0.9),
            scale,
        };
        let diffuse = |texture| Material {
            surface: Surface::Diffuse(texture),
            highlight: None,
        };
        let shine = Rgb::grey(0.5);
        let board = b.add_material(diffuse(checker(2.0)));
        let tiles = b.add_material(diffuse(checker(5.0)).with_highlight(shine, 30.0));
        let matte = b.add_material(Material::diffuse(Rgb::new(0.5, 0.6, 0.7)));
        let glass = b.add_material(Material::dielectric(1.5).with_highlight(shine, 200.0));
        let plain_glass = b.add_material(Material::dielectric(1.33));
        let mirror = b.add_material(Material::mirror(Rgb::new(0.9, 0.8, 0.7)));
        let shiny_mirror =
            b.add_material(Material::mirror(Rgb::grey(0.95)).with_highlight(shine, 80.0));
        b.add_shape(
            Shape::Plane(Plane::new(DVec3::ZERO, DVec3::Y).unwrap()),
            board,
        );
        b.add_shape(
            Shape::Sphere(Sphere::new(DVec3::new(0.8, 0.7, 0.5), 0.7).unwrap()),
            glass,
        );
        b.add_shape(
            Shape::Sphere(Sphere::new(DVec3::new(-1.2, 0.5, -0.5), 0.5).unwrap()),
            shiny_mirror,
        );
        b.add_shape(
            Shape::Disk(
                Disk::new(DVec3::new(-2.0, 1.5, -2.0), DVec3::new(0.3, 0.2, 1.0), 0.9).unwrap(),
            ),
            tiles,
        );
        b.add_shape(
            Shape::Parallelogram(
                Parallelogram::new(
                    DVec3::new(1.0, 0.0, -3.0),
                    DVec3::new(2.0, 0.0, 0.5),
                    DVec3::new(0.0, 2.0, 0.0),
                )
                .unwrap(),
            ),
            tiles,
        );
        b.add_shape(
            Shape::Triangle(
                Triangle::new(
                    DVec3::new(-0.5, 0.1, 1.5),
                    DVec3::new(0.5, 0.1, 2.0),
                    DVec3::new(0.0, 1.2, 1.8),
                )
                .unwrap(),
            ),
            plain_glass,
        );
        b.add_shape(
            Shape::Polygon(Box::new(
                ConvexPolygon::new(
                    (0..5)
                        .map(|k| {
                            // A regular pentagon facing (1, 0, 0.3).
                            let a = f64::from(k) * std::f64::consts::TAU / 5.0;
                            let v = DVec3::new(-0.3, 0.0, 1.0).normalize();
                            DVec3::new(-2.8, 1.0, -0.5) + 0.8 * (a.cos() * DVec3::Y + a.sin() * v)
                        })
                        .collect(),
                )
                .unwrap(),
            )),
            mirror,
        );
        b.add_shape(
            Shape::Sphere(Sphere::new(DVec3::new(2.2, 0.3, 1.5), 0.3).unwrap()),
            matte,
        );
        for k in 0..beads {
            let centre = DVec3::new(-2.0 + 0.5 * f64::from(k), 0.2, 2.5);
            b.add_shape(Shape::Sphere(Sphere::new(centre, 0.2).unwrap()), matte);
        }
        b.add_emitter(Emitter::Point(
            PointLight::with_intensity(DVec3::new(-1.0, 4.0, 3.0), 40.0).unwrap(),
        ));
        b.add_emitter(Emitter::Directional(
            DirectionalLight::new(DVec3::new(0.4, 1.0, 0.3), 0.8).unwrap(),
        ));
        b.background(Rgb::new(0.1, 0.2, 0.4));
        b.build().unwrap()
    }

    #[test]
    fn the_image_is_the_recursive_tracers_to_the_bit() {
        let whitted = builtin::whitted().with_size(41, 33).unwrap();
        let (few, more) = (every_kind(0), every_kind(6));
        let scenes = [
            ("whitted", whitted.clone()),
            ("whitted, BVH", whitted.with_acceleration(Acceleration::Bvh)),
            // Eight primitives: hit records by primitive.
            (
                "every kind",
                few.clone().with_acceleration(Acceleration::BruteForce),
            ),
            ("every kind, BVH", few.with_acceleration(Acceleration::Bvh)),
            // Fourteen: hit records ray by ray.
            (
                "every kind and beads",
                more.clone().with_acceleration(Acceleration::BruteForce),
            ),
            (
                "every kind and beads, BVH",
                more.with_acceleration(Acceleration::Bvh),
            ),
        ];
        for (name, scene) in &scenes {
            assert!(super::applies(scene));
            for max_depth in [0, 1, 5] {
                let config = RenderConfig {
                    max_depth,
                    ..RenderConfig::default()
                };
                let (want, want_counts) = recursive(scene, &config);
                for isa in Isa::available() {
                    for t in [16, 7] {
                        let (got, counts) = by_generation(scene, &config, isa, t);
                        assert!(
                            bits(&got) == bits(&want),
                            "{name}, depth {max_depth}, {}, tiles of {t}",
                            isa.name()
                        );
                        assert_eq!(counts, want_counts, "{name}, depth {max_depth}");
                    }
                }
            }
        }
    }
}
