//! Whitted tracing a tile at a time, generation by generation: the camera
//! rays of every pixel of the tile, then all their reflected and refracted
//! rays, and so on, each generation's nearest hits and shadow rays tested
//! as one batch (Laine, Karras & Aila, "Megakernels considered harmful:
//! wavefront path tracing on GPUs", HPG 2013, for the organisation).
//!
//! A batch is tested shape by shape in loops the compiler vectorises (the
//! geometry crate's `nearest_in_batch` and `occludes_in_batch`), compiled
//! for the widest instruction set the processor has
//! ([`lambert_sampling::isa::Isa`]); a scene with a BVH is searched ray by
//! ray inside the same batches. Between the hit tests and shading, the
//! rays are grouped by the primitive they hit, so that each material is
//! shaded in a loop of its own with its shape known.
//!
//! **The image is the recursive tracer's, to the bit.** Each ray is shaded
//! by the same functions in the same order of operations; what changes is
//! when. The recursion computes a hit's radiance as
//! `c = base + w₁·L(child₁) + w₂·L(child₂)` after its children return;
//! here every hit becomes a node holding its base colour, its weights and
//! its children's indices, and once the deepest generation is done the
//! nodes are combined from the last to the first (children always come
//! after their parent), each by that same expression. Scenes with area
//! emitters, whose per-pixel estimates draw seeds in the recursion's
//! order, are traced by the recursive tracer.

use glam::DVec3;
use lambert_geometry::f64::{Hit, Intersect, Ray, RayBatch};
use lambert_sampling::isa::Isa;

use super::context::{DeltaLight, Direct, RayCounts};
use super::{Pixel, RenderConfig};
use crate::camera::Camera;
use crate::color::Rgb;
use crate::material::{Material, Surface};
use crate::optics::{fresnel_dielectric, reflect, refract};
use crate::scene::Scene;
use crate::shape::Shape;
use crate::texture::Texture;

/// No primitive, no child.
const NONE: u32 = u32::MAX;

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

/// A hit of the current generation, between its shadow rays and its
/// shading.
#[derive(Clone, Copy, Debug)]
struct Pending {
    /// Its ray's index in the generation.
    ray: u32,
    /// Its delta lights with cos > 0 (or NaN): `lights[first..end]`, one
    /// shadow ray each, in the scene's order of emitters.
    first: u32,
    end: u32,
    /// The hit, with its surface parameters where the material's texture
    /// varies (zero otherwise).
    hit: Hit,
}

/// What a thread reuses from tile to tile.
#[derive(Debug, Default)]
pub(super) struct Scratch {
    /// The generation being traced, its nodes, and the same rays in
    /// structure-of-arrays form for the batch tests.
    rays: Vec<Ray>,
    ray_nodes: Vec<u32>,
    batch: RayBatch,
    next_rays: Vec<Ray>,
    next_nodes: Vec<u32>,
    nearest: Vec<f64>,
    ids: Vec<u32>,
    /// The generation's rays grouped by the primitive they hit (misses
    /// last): primitive k's are `order[runs[k]..runs[k + 1]]`.
    order: Vec<u32>,
    runs: Vec<u32>,
    /// Primitive k's hits are `pending[hit_runs[k]..hit_runs[k + 1]]`.
    hit_runs: Vec<u32>,
    pending: Vec<Pending>,
    shadow: Vec<Ray>,
    shadow_t_max: Vec<f64>,
    blocked: Vec<bool>,
    lights: Vec<DeltaLight>,
    nodes: Vec<Node>,
    first_irradiance: Vec<f64>,
    /// The last tile's pixels, row by row.
    pixels: Vec<Pixel>,
}

impl Scratch {
    /// The pixels of the tile [`tile`] traced last, row by row.
    pub(super) fn pixels(&self) -> &[Pixel] {
        &self.pixels
    }
}

/// Whether `scene` is traced here in `whitted` mode: every emitter is a
/// delta light (area emitters' estimates are the recursive tracer's).
pub(super) fn applies(scene: &Scene) -> bool {
    !scene.has_area_emitters()
}

/// Traces the tile [x0, x1) × [y0, y1): its pixels, row by row, go to
/// [`Scratch::pixels`]; returns the rays traced for them.
///
/// The whole tile runs inside one [`Isa::run`], compiled for the selected
/// instruction set: the camera rays, the grouping and the shading between
/// the intersection kernels are then compiled for it too, not only the
/// kernels (measured on the `whitted` frame: 12 % fewer instructions).
/// The image is the same to the bit (no operation is fused or reordered).
pub(super) fn tile(
    scene: &Scene,
    camera: &Camera,
    config: &RenderConfig,
    isa: Isa,
    x: (u32, u32),
    y: (u32, u32),
    s: &mut Scratch,
) -> RayCounts {
    isa.run_without_gfni(
        #[inline(always)]
        || trace_tile(scene, camera, config, isa, x, y, s),
    )
}

/// [`tile`]'s body, inlined into the instruction set it runs in.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn trace_tile(
    scene: &Scene,
    camera: &Camera,
    config: &RenderConfig,
    isa: Isa,
    (x0, x1): (u32, u32),
    (y0, y1): (u32, u32),
    s: &mut Scratch,
) -> RayCounts {
    let mut counts = RayCounts::default();
    s.rays.clear();
    s.ray_nodes.clear();
    s.nodes.clear();
    camera.pixel_rays((x0, x1), (y0, y1), &mut s.rays);
    let pixels = s.rays.len();
    s.ray_nodes.extend(0..pixels as u32);
    // Every node is written when its ray is shaded; this only sizes.
    s.nodes.resize(pixels, Node::leaf(Rgb::BLACK));
    counts.camera = pixels as u64;
    s.first_irradiance.clear();
    s.first_irradiance.resize(pixels, 0.0);
    let mut depth = 0;
    while !s.rays.is_empty() {
        generation(scene, config, isa, depth, s, &mut counts);
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
    s.pixels.clear();
    s.pixels
        .extend(
            s.nodes[..pixels]
                .iter()
                .zip(&s.first_irradiance)
                .map(|(node, &irradiance)| Pixel {
                    rgb: node.radiance,
                    irradiance,
                    std_error: 0.0,
                }),
        );
    counts
}

/// Groups the rays of the generation by the primitive they hit, misses
/// last (a counting sort on `s.ids`, stable): shading then runs material
/// by material, each in its own loop, instead of switching on the
/// material and shape ray by ray (on the `whitted` scene the rays of a
/// generation alternate between the board, the glass and the sky, and
/// the switches were the tracer's most mispredicted branches).
fn group_by_primitive(primitives: usize, s: &mut Scratch) {
    let slot = |id: u32| if id == NONE { primitives } else { id as usize };
    s.runs.clear();
    s.runs.resize(primitives + 2, 0);
    for &id in &s.ids {
        s.runs[slot(id) + 1] += 1;
    }
    for k in 0..=primitives {
        s.runs[k + 1] += s.runs[k];
    }
    s.order.clear();
    s.order.resize(s.ids.len(), 0);
    // The next free place of each run, in `hit_runs` for now.
    s.hit_runs.clear();
    s.hit_runs.extend_from_slice(&s.runs[..=primitives]);
    for (i, &id) in s.ids.iter().enumerate() {
        let k = slot(id);
        s.order[s.hit_runs[k] as usize] = i as u32;
        s.hit_runs[k] += 1;
    }
}

/// The hit records of the rays `run` that hit `shape` (material
/// `material`), and the shadow ray toward each delta light above each
/// hit that the material shades with direct light.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn record_hits<S: Intersect>(
    shape: &S,
    material: &Material,
    scene: &Scene,
    run: &[u32],
    rays: &[Ray],
    nearest: &[f64],
    s: &mut Recorded,
) {
    let textured = matches!(material.surface, Surface::Diffuse(Texture::Checker { .. }));
    for &i in run {
        let ray = &rays[i as usize];
        let t = nearest[i as usize];
        let mut hit = shape.hit_at(ray, t);
        if textured {
            hit.uv = shape.surface_parameters(ray, t);
        }
        let front = hit.is_front(ray.direction);
        let lit = match material.surface {
            Surface::Emitter { .. } => false,
            Surface::Diffuse(_) => true,
            Surface::Mirror(_) => material.highlight.is_some(),
            Surface::Dielectric { .. } => material.highlight.is_some() && front,
        };
        let first = s.lights.len();
        if lit {
            let normal = hit.facing_normal(ray.direction);
            for e in scene.emitters() {
                let Some(light) = DeltaLight::seen_from(e, hit.point, normal) else {
                    continue;
                };
                if light.cos <= 0.0 {
                    continue;
                }
                let (shadow, t_max) = Scene::shadow_ray(&hit, light.direction, light.distance);
                s.shadow.push(shadow);
                s.shadow_t_max.push(t_max);
                s.lights.push(light);
            }
        }
        s.pending.push(Pending {
            ray: i,
            first: first as u32,
            end: s.lights.len() as u32,
            hit,
        });
    }
}

/// The vectors [`record_hits`] fills.
struct Recorded<'a> {
    pending: &'a mut Vec<Pending>,
    shadow: &'a mut Vec<Ray>,
    shadow_t_max: &'a mut Vec<f64>,
    lights: &'a mut Vec<DeltaLight>,
}

/// Traces the generation `s.rays` (at recursion `depth`): nearest hits,
/// shadow rays, shading; their reflected and refracted rays go to
/// `s.next_rays`.
#[inline(always)]
fn generation(
    scene: &Scene,
    config: &RenderConfig,
    isa: Isa,
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
    isa.run_without_gfni(
        #[inline(always)]
        || aggregate.nearest_in_batch(&s.batch, &mut s.nearest, &mut s.ids),
    );
    let primitives = aggregate.len();
    group_by_primitive(primitives, s);

    // Rays that escape.
    let misses = s.runs[primitives] as usize..s.runs[primitives + 1] as usize;
    for &i in &s.order[misses] {
        let i = i as usize;
        s.nodes[s.ray_nodes[i] as usize] = Node::leaf(scene.escaped(s.rays[i].direction));
    }

    // The hits, primitive by primitive, and the shadow ray toward each
    // delta light above each.
    s.shadow.clear();
    s.shadow_t_max.clear();
    s.lights.clear();
    s.pending.clear();
    s.hit_runs.clear();
    s.hit_runs.push(0);
    for k in 0..primitives {
        let run = &s.order[s.runs[k] as usize..s.runs[k + 1] as usize];
        if !run.is_empty() {
            let primitive = aggregate.primitive(k as u32);
            let material = scene.material_of(primitive);
            let mut out = Recorded {
                pending: &mut s.pending,
                shadow: &mut s.shadow,
                shadow_t_max: &mut s.shadow_t_max,
                lights: &mut s.lights,
            };
            let (rays, nearest) = (&s.rays[..], &s.nearest[..]);
            match &primitive.shape {
                Shape::Sphere(x) => record_hits(x, material, scene, run, rays, nearest, &mut out),
                Shape::Plane(x) => record_hits(x, material, scene, run, rays, nearest, &mut out),
                Shape::Disk(x) => record_hits(x, material, scene, run, rays, nearest, &mut out),
                Shape::Triangle(x) => record_hits(x, material, scene, run, rays, nearest, &mut out),
                Shape::Parallelogram(x) => {
                    record_hits(x, material, scene, run, rays, nearest, &mut out)
                }
                Shape::Polygon(x) => {
                    record_hits(&**x, material, scene, run, rays, nearest, &mut out)
                }
            }
        }
        s.hit_runs.push(s.pending.len() as u32);
    }
    s.batch.assign(&s.shadow);
    s.blocked.clear();
    s.blocked.resize(s.shadow.len(), false);
    isa.run_without_gfni(
        #[inline(always)]
        || aggregate.occludes_in_batch(&s.batch, &s.shadow_t_max, &mut s.blocked),
    );
    counts.shadow += s.shadow.len() as u64;

    // Shading, material by material, and the next generation.
    s.next_rays.clear();
    s.next_nodes.clear();
    let deeper = depth < config.max_depth;
    let mut out = Shaded {
        first_child: s.nodes.len() as u32,
        nodes: &mut s.nodes,
        next_rays: &mut s.next_rays,
        next_nodes: &mut s.next_nodes,
    };
    let (rays, ray_nodes, lights, blocked) =
        (&s.rays[..], &s.ray_nodes[..], &s.lights[..], &s.blocked[..]);
    for k in 0..primitives {
        let hits = &s.pending[s.hit_runs[k] as usize..s.hit_runs[k + 1] as usize];
        if hits.is_empty() {
            continue;
        }
        let material = scene.material_of(aggregate.primitive(k as u32));
        let highlight = material.highlight.as_ref();
        // The direct light at a hit: its unblocked delta lights (none
        // where the material is not lit).
        let direct = |p: &Pending, normal: DVec3, wo: DVec3| {
            let mut direct = Direct::default();
            let range = p.first as usize..p.end as usize;
            for (light, &blocked) in lights[range.clone()].iter().zip(&blocked[range]) {
                if !blocked {
                    direct.add(light, normal, wo, highlight);
                }
            }
            direct
        };
        match material.surface {
            Surface::Emitter {
                radiance,
                two_sided,
            } => {
                for p in hits {
                    let i = p.ray as usize;
                    let front = p.hit.is_front(rays[i].direction);
                    let l = if front || two_sided { radiance } else { 0.0 };
                    out.nodes[ray_nodes[i] as usize] = Node::leaf(Rgb::grey(l));
                }
            }
            Surface::Diffuse(texture) => {
                for p in hits {
                    let i = p.ray as usize;
                    let d = rays[i].direction;
                    let direct = direct(p, p.hit.facing_normal(d), -d);
                    let node_index = ray_nodes[i] as usize;
                    if depth == 0 {
                        s.first_irradiance[node_index] = direct.irradiance;
                    }
                    let albedo = texture.at(p.hit.uv);
                    out.nodes[node_index] = Node::leaf(
                        albedo * (direct.irradiance / std::f64::consts::PI) + direct.highlight,
                    );
                }
            }
            Surface::Mirror(reflectance) => {
                for p in hits {
                    let i = p.ray as usize;
                    let d = rays[i].direction;
                    let normal = p.hit.facing_normal(d);
                    let base = direct(p, normal, -d).highlight;
                    let reflected = if deeper {
                        out.follow(&p.hit, reflect(d, normal))
                    } else {
                        NONE
                    };
                    out.nodes[ray_nodes[i] as usize] = Node {
                        radiance: base,
                        weights: Weights::Mirror(reflectance),
                        children: [reflected, NONE],
                    };
                }
            }
            Surface::Dielectric { ior } => {
                for p in hits {
                    let i = p.ray as usize;
                    let d = rays[i].direction;
                    let front = p.hit.is_front(d);
                    let normal = p.hit.facing_normal(d);
                    let wo = -d;
                    // Entering (front face): η_i/η_t = 1/ior; leaving: ior.
                    let eta = if front { 1.0 / ior } else { ior };
                    let base = direct(p, normal, wo).highlight;
                    let mut children = [NONE; 2];
                    let mut fresnel = 0.0;
                    if deeper {
                        fresnel = fresnel_dielectric(wo.dot(normal), eta);
                        children[0] = out.follow(&p.hit, reflect(d, normal));
                        if fresnel < 1.0 {
                            if let Some((t, _)) = refract(d, normal, eta) {
                                children[1] = out.follow(&p.hit, t);
                            }
                        }
                    }
                    out.nodes[ray_nodes[i] as usize] = Node {
                        radiance: base,
                        weights: Weights::Dielectric(fresnel),
                        children,
                    };
                }
            }
        }
    }
    // The next generation's nodes, written when its rays are shaded.
    let next = s.nodes.len() + s.next_rays.len();
    s.nodes.resize(next, Node::leaf(Rgb::BLACK));
}

/// Where shading writes: the tile's nodes and the next generation.
struct Shaded<'a> {
    /// The node of the next generation's first ray (its rays' nodes
    /// follow the tile's nodes so far, in the order they are spawned).
    first_child: u32,
    nodes: &'a mut [Node],
    next_rays: &'a mut Vec<Ray>,
    next_nodes: &'a mut Vec<u32>,
}

impl Shaded<'_> {
    /// Spawns the ray leaving `hit` along `direction` into the next
    /// generation; its node's index.
    #[inline(always)]
    fn follow(&mut self, hit: &Hit, direction: DVec3) -> u32 {
        let child = self.first_child + self.next_rays.len() as u32;
        self.next_rays.push(hit.spawn_ray(direction));
        self.next_nodes.push(child);
        child
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
                let counts = tile(scene, camera, config, isa, (x0, x1), (y0, y1), &mut scratch);
                total = total.plus(counts);
                for (k, &p) in scratch.pixels().iter().enumerate() {
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
