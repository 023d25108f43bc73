//! The f32 block kernels: one emitter's estimate for a block of samples,
//! the per-sample arithmetic in f32.
//!
//! The layout is that of the f64 kernels ([`PreparedEmitter::add_batch`]):
//! the decisions (technique, emitter kind, sampler) are made once per
//! block, and a loop specialised for them runs over coordinate arrays
//! with every call inlined, to be compiled for the instruction set of the
//! caller's [`Isa::run`](lambert_sampling::isa::Isa::run) — with twice the
//! lanes, since an f32 takes half the bits. Each sample's geometric factor
//! g = V(ω) cos θ/p (or MIS's weighted sum of two) is formed in f32 and
//! added to the sample's f64 value as L·g, L the emitter's radiance
//! ([`PreparedEmitterF32`]'s docs say why L stays in f64).
//!
//! **What differs from the f64 kernels** (the expectation is the same; the
//! values are f32's):
//! - solid-angle samples of a sphere, a sky cap, a disk or a polygon are
//!   not looked up again: a direction drawn inside the emitter's solid
//!   angle sees it (the sampler draws only the emitter), and whether it
//!   sees the emitting side is one test per emitter, not per sample. Only
//!   cos θ ≤ 0 scores 0. Where f64 casts a ray and may miss a direction
//!   drawn a rounding error outside the outline, f32 does not;
//! - MIS weights are always formed from the ratio r = p_b/p_a, as
//!   1/(1 + r) or 1/(1 + r²): the f32 range is too short for p_a² (a
//!   light of 1e-19 sr overflows it);
//! - uniform and cosine samples multiply by the constant 1/p (2π, π)
//!   rather than divide by the density.

use glam::{Vec2, Vec3};
use lambert_geometry::f32::{Frame, Intersect, PolygonFromOrigin, Ray, SphereFromOutside};
use lambert_sampling::f32::{
    pdf_cosine_hemisphere, sample_cosine_hemisphere, sample_uniform_hemisphere,
    sample_uniform_sphere, ConeCosine, DirectionSample, LightSample, LightSampler,
    PolygonAreaSampler, PolygonSolidAngle, SphericalFan, UniformCone, UniformSolidAngle,
};
use lambert_sampling::isa::Isa;

use super::batch::MAX_SPHERICAL_FAN;
use super::cone_mis::ConeMisF32;
use super::cone_window::CosineWindowF32;
use super::listing::{grouped_values, list_set_bits};
use super::prepared_f32::{Area, Light, PreparedEmitterF32, Projected, Shape};
use super::{Heuristic, PartHits, Store, Technique};

use std::f32::consts::PI;

/// One block's f32 coordinates, cut to one length: `u` (`ux`, `uy`) and
/// MIS's second point `v` (`vx`, `vy`; a copy of `u`'s slices for the
/// techniques that read one point, so that every span can be cut from
/// all four alike), and how [`accumulate`] stores the values.
struct Block<'a> {
    ux: &'a [f32],
    uy: &'a [f32],
    vx: &'a [f32],
    vy: &'a [f32],
    store: Store,
}

/// Samples per pass of [`accumulate`]'s two loops: their f32 parts (2 KB)
/// stay in the first-level cache between the loops.
const SPAN: usize = 256;

/// `out[i] += L·g(u_i, v_i)` with `g` the sum of a sample's `P` parts,
/// formed in f32 and widened to f64 (`out[i] = …` with
/// [`Store::Overwrite`]); returns how many samples had each part non-zero
/// (at most two parts).
///
/// Two loops per [`SPAN`] samples: the first forms the parts and their
/// sum in f32 and counts the non-zero parts in 32-bit lanes, the second
/// adds the sums to the f64 values. A single loop that also touched the
/// f64 values ran with as many lanes as f64 has: half those an f32 vector
/// holds, so the f32 arithmetic ran at half width (measured: 4-lane `xmm`
/// f32 code under AVX2). The values are the same to the bit.
///
/// The first loop reads coordinates from slices cut to the span's length,
/// so the compiler sees every index in bounds: indexing the whole block
/// by `span·SPAN + k` left it a bounds check per sample, and a loop that
/// may exit early keeps its last vector's worth of samples in scalar code
/// (measured: 32 of every 256 samples, half the kernel's time).
#[inline(always)]
fn accumulate<const P: usize>(
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
    parts: impl Fn(Vec2, Vec2) -> [f32; P],
) -> PartHits {
    const { assert!(P == 1 || P == 2) };
    accumulate_spans(
        radiance,
        block,
        out,
        #[inline(always)]
        |[ux, uy, vx, vy], sums| {
            let mut counts = [0u32; 2];
            // An index loop: every slice here has length `sums.len()`, which
            // the compiler relates to `k < len` (it does not to a slice
            // iterator's pointer range).
            for k in 0..sums.len() {
                let g = parts(Vec2::new(ux[k], uy[k]), Vec2::new(vx[k], vy[k]));
                counts[0] += u32::from(g[0] != 0.0);
                sums[k] = if P == 1 {
                    g[0]
                } else {
                    counts[1] += u32::from(g[P - 1] != 0.0);
                    g[0] + g[P - 1]
                };
            }
            counts
        },
    )
}

/// [`accumulate`]'s spans and second loop around a first loop given whole:
/// `span([ux, uy, vx, vy], sums)` writes each sample's f32 sum of parts to
/// `sums` (every slice of one length, at most [`SPAN`]) and returns how
/// many samples had each part non-zero.
#[inline(always)]
fn accumulate_spans(
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
    mut span: impl FnMut([&[f32]; 4], &mut [f32]) -> [u32; 2],
) -> PartHits {
    let mut hits = [0u64; 2];
    let mut sums = [0.0f32; SPAN];
    for (index, out) in out.chunks_mut(SPAN).enumerate() {
        let len = out.len();
        let at = index * SPAN..index * SPAN + len;
        let (ux, uy) = (&block.ux[at.clone()], &block.uy[at.clone()]);
        let (vx, vy) = (&block.vx[at.clone()], &block.vy[at]);
        let sums = &mut sums[..len];
        let counts = span([ux, uy, vx, vy], sums);
        match block.store {
            Store::Add => {
                for (o, &g) in out.iter_mut().zip(sums.iter()) {
                    *o += radiance * f64::from(g);
                }
            }
            Store::Overwrite => {
                for (o, &g) in out.iter_mut().zip(sums.iter()) {
                    *o = radiance * f64::from(g);
                }
            }
        }
        hits[0] += u64::from(counts[0]);
        hits[1] += u64::from(counts[1]);
    }
    hits
}

/// `out[i] += L·g(u_i)` (g widened to f64), counting the non-zero g.
#[inline(always)]
fn single(radiance: f64, block: &Block<'_>, out: &mut [f64], g: impl Fn(Vec2) -> f32) -> PartHits {
    accumulate(
        radiance,
        block,
        out,
        #[inline(always)]
        |u, _| [g(u)],
    )
}

/// Light sampling through a polygon's solid-angle sampler in one of its
/// inline forms ([`UniformSolidAngle`]): cos θ/p per sample, the sampler
/// copied into the loop so that its constants stay in registers.
#[inline(always)]
fn solid_angle_light(
    sampler: &impl UniformSolidAngle,
    normal: Vec3,
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    let sampler = &{ *sampler };
    scored(
        normal,
        radiance,
        block,
        out,
        #[inline(always)]
        |u| sampler.sample_direction(u),
    )
}

/// What light sampling scores of a drawn sample: its direction and that
/// direction's density, 0 where the sampler drew nothing.
trait DirectionAndDensity {
    /// (ω, p(ω)).
    fn direction_and_density(&self) -> (Vec3, f32);
}

impl DirectionAndDensity for DirectionSample {
    #[inline(always)]
    fn direction_and_density(&self) -> (Vec3, f32) {
        (self.direction, self.pdf)
    }
}

impl DirectionAndDensity for LightSample {
    #[inline(always)]
    fn direction_and_density(&self) -> (Vec3, f32) {
        (self.direction, self.pdf)
    }
}

/// No sample: density 0, which [`cos_over_pdf`] scores 0, the value the
/// kernels gave a `None` before they shared [`scored`].
impl DirectionAndDensity for Option<LightSample> {
    #[inline(always)]
    fn direction_and_density(&self) -> (Vec3, f32) {
        match self {
            Some(s) => (s.direction, s.pdf),
            None => (Vec3::ZERO, 0.0),
        }
    }
}

/// cos θ/p of every sample `sample(u)` draws ([`cos_over_pdf`]), stored
/// by [`single`]: the loop of every sampler scored by its direction and
/// density alone. Callers mark `sample` `#[inline(always)]`: a closure
/// left to the compiler was called out of line, outside the kernel's
/// instruction set, and made these loops about ten times slower.
#[inline(always)]
fn scored<S: DirectionAndDensity>(
    normal: Vec3,
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
    sample: impl Fn(Vec2) -> S,
) -> PartHits {
    single(
        radiance,
        block,
        out,
        #[inline(always)]
        |u| {
            let (direction, pdf) = sample(u).direction_and_density();
            cos_over_pdf(normal, direction, pdf)
        },
    )
}

/// cos θ/p of a direction drawn with density `pdf`, 0 if cos θ ≤ 0 or the
/// density is not positive and finite.
#[inline(always)]
fn cos_over_pdf(normal: Vec3, direction: Vec3, pdf: f32) -> f32 {
    let cos = normal.dot(direction);
    if cos > 0.0 && pdf > 0.0 && pdf.is_finite() {
        cos / pdf
    } else {
        0.0
    }
}

/// Area sampling of a polygon seen from the origin, whose receiver has the
/// unit normal `normal`: cos θ/p of each sample, as `through` scores the
/// sampler's `sample`. Through a [`PolygonAreaFan`](lambert_sampling::f32::PolygonAreaFan)
/// when the fan has 1 to [`MAX_FAN`] triangles (every polygon of up to six
/// vertices), whose loop vectorises (a sample of density 0, where `sample`
/// gives none, scores 0 in [`cos_over_pdf`]); the sampler's `sample`
/// otherwise, a call per sample. The same values either way (the f64
/// kernel's `polygon_area_batch`).
#[inline(always)]
fn polygon_area_batch(
    sampler: &PolygonAreaSampler,
    normal: Vec3,
    radiance: f64,
    through: &impl Fn(Option<LightSample>) -> f32,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    /// The loop through the fan of `N` triangles, if the polygon's has `N`.
    #[inline(always)]
    fn through_fan<const N: usize>(
        sampler: &PolygonAreaSampler,
        (normal, radiance): (Vec3, f64),
        block: &Block<'_>,
        out: &mut [f64],
    ) -> Option<PartHits> {
        let fan = sampler.fan::<N>(Vec3::ZERO, normal)?;
        Some(scored(
            normal,
            radiance,
            block,
            out,
            #[inline(always)]
            |u| fan.sample_or_zero(u),
        ))
    }
    // Plain branches, as in the f64 kernel.
    let at = (normal, radiance);
    if let Some(hits) = through_fan::<1>(sampler, at, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<2>(sampler, at, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<3>(sampler, at, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<MAX_FAN>(sampler, at, block, out) {
        return hits;
    }
    single(
        radiance,
        block,
        out,
        #[inline(always)]
        |u| through(sampler.sample(Vec3::ZERO, normal, u)),
    )
}

/// The most triangles of a polygon fan [`polygon_area_batch`] has a
/// vectorised loop for.
const MAX_FAN: usize = 4;

/// Solid-angle sampling of a cone (a sphere's or a sky cap's) in its own
/// frame: g = Ω max(n_local·ω_local, 0), n_local the receiver's normal
/// rotated into the cone's frame and n_local·ω_local drawn by `cosine`
/// ([`ConeCosine`], the azimuth measured from n_local's projection; built
/// once per prepared emitter), as the f64 kernel of a sphere does.
#[inline(always)]
fn cone_batch(
    cosine: &ConeCosine,
    cone: &UniformCone,
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    let cosine = *cosine;
    let omega = cone.solid_angle();
    if cosine.is_above_horizon() && omega >= f32::MIN_POSITIVE {
        // Every g is positive (a cosine above 2⁻¹⁰ times a normal Ω): the
        // same values without the clamp, and every sample hits.
        return accumulate_spans(
            radiance,
            block,
            out,
            #[inline(always)]
            |[ux, uy, _, _], sums| {
                for k in 0..sums.len() {
                    sums[k] = omega * cosine.sample(Vec2::new(ux[k], uy[k]));
                }
                [sums.len() as u32, 0]
            },
        );
    }
    single(
        radiance,
        block,
        out,
        #[inline(always)]
        |u| omega * cosine.sample(u).max(0.0),
    )
}

/// Samples whose directions [`in_direction_batches`] draws at a time
/// (three arrays of f32 on the stack, 3 KB).
const DISK_BATCH: usize = 256;

/// Directions drawn [`DISK_BATCH`] at a time, for the samplers whose
/// one-sample form does not vectorise but whose batch does
/// (`sample_directions` of the tabulated disk, the tabulated projected
/// polygon, projected caps and spheres), as the f64 kernels do:
/// `draw(sx, sy, dx, dy, dz)` fills a batch's directions from the points
/// (`sx[i]`, `sy[i]`), then `f(range, [dx, dy, dz], &mut out[range])` runs
/// the kernel over them; the hits it returns are added up. Measured on a
/// close disk (one thread, f32): light sampling 103 → 18 ns per sample,
/// MIS 115 → 22 (f64: 28–34 and 33–40).
#[inline(always)]
fn in_direction_batches(
    sx: &[f32],
    sy: &[f32],
    out: &mut [f64],
    mut draw: impl FnMut(&[f32], &[f32], &mut [f32], &mut [f32], &mut [f32]),
    mut f: impl FnMut(std::ops::Range<usize>, [&[f32]; 3], &mut [f64]) -> PartHits,
) -> PartHits {
    let mut directions = [[0.0f32; DISK_BATCH]; 3];
    let mut hits = [0u64; 2];
    for (k, out) in out.chunks_mut(DISK_BATCH).enumerate() {
        let m = out.len();
        let at = k * DISK_BATCH..k * DISK_BATCH + m;
        let [dx, dy, dz] = &mut directions;
        let (dx, dy, dz) = (&mut dx[..m], &mut dy[..m], &mut dz[..m]);
        draw(&sx[at.clone()], &sy[at.clone()], dx, dy, dz);
        let got = f(at, [dx, dy, dz], out);
        hits[0] += got[0];
        hits[1] += got[1];
    }
    hits
}

/// cos θ/p (as [`scored`] forms it, so the same values) of the directions
/// `draw` fills in batches ([`in_direction_batches`]), each of the density
/// `density` gives it: projected sampling of polygons, caps and spheres
/// and light sampling of a disk through their samplers' batches. The
/// directions pass through [`accumulate`] as a block whose first point
/// holds x and y and whose second holds z.
#[inline(always)]
fn drawn_batch(
    normal: Vec3,
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
    draw: impl FnMut(&[f32], &[f32], &mut [f32], &mut [f32], &mut [f32]),
    density: impl Fn(Vec3) -> f32,
) -> PartHits {
    in_direction_batches(
        block.ux,
        block.uy,
        out,
        draw,
        #[inline(always)]
        |_, [dx, dy, dz], out| {
            let drawn = Block {
                ux: dx,
                uy: dy,
                vx: dz,
                vy: dz,
                store: block.store,
            };
            accumulate(
                radiance,
                &drawn,
                out,
                #[inline(always)]
                |xy, z| {
                    let w = Vec3::new(xy.x, xy.y, z.x);
                    [cos_over_pdf(normal, w, density(w))]
                },
            )
        },
    )
}

/// MIS on a sphere or sky cap ([`ConeMisF32`]): both halves in the frames
/// where they are cheapest, counted apart. Per span, in three passes:
///
/// 1. the light half of every sample, whole vectors (its sum is `0 + light`,
///    the cosine half's exact 0 added, for every sample whose cosine
///    direction cannot see the cone);
/// 2. the samples whose cosine direction may see the cone
///    ([`CosineWindowF32::may_see`]) listed by index, from one 16-bit mask
///    per group of [`MIS_GROUP`];
/// 3. the cosine half of the listed samples only, gathered into whole
///    groups, and their sums `cosine + light`.
///
/// The values are those of `cosine + light` per sample, to the bit.
///
/// Why: a sphere's window holds a few per cent of the cosine samples, yet
/// one in three groups of sixteen held at least one of them, and the
/// former kernel (the cosine half for every lane of such a group) spent
/// two fifths of its time on those groups (profile of the f32 sphere light
/// 30° off the normal). Listed, the cosine half runs about once per span.
#[inline(always)]
fn cone_mis_batch(
    cone: &ConeMisF32,
    window: &CosineWindowF32,
    h: Heuristic,
    radiance: f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    if !cone.is_drawn() {
        // Both halves are 0 (`ConeMisF32::parts`); decided once, not per
        // sample.
        return accumulate(radiance, block, out, |_, _| [0.0, 0.0]);
    }
    // Local copies stay in registers.
    let (cone, window) = (*cone, *window);
    let every_light_hits = cone.every_light_half_is_positive();
    // Scratch of pass 3, cleared once per block, not per span.
    let mut lights = [0.0f32; SPAN];
    let mut listed = [0u16; SPAN];
    let mut gathered = [[0.0f32; SPAN]; 3];
    accumulate_spans(
        radiance,
        block,
        out,
        #[inline(always)]
        |[ux, uy, vx, vy], sums| {
            let len = sums.len();
            let lights = &mut lights[..len];
            // Pass 1. Counted per lane and added up once per span, unless
            // every light half is positive.
            let mut lane_hits = [0u32; MIS_GROUP];
            let (groups, _) = sums.as_chunks_mut::<MIS_GROUP>();
            let whole = groups.len() * MIS_GROUP;
            fn lanes(c: &[f32], whole: usize) -> &[[f32; MIS_GROUP]] {
                c[..whole].as_chunks::<MIS_GROUP>().0
            }
            let light_hits = if every_light_hits {
                for k in 0..len {
                    let light = cone.light_value(h, Vec2::new(vx[k], vy[k]));
                    lights[k] = light;
                    sums[k] = 0.0 + light;
                }
                len as u32
            } else {
                let (light_groups, _) = lights.as_chunks_mut::<MIS_GROUP>();
                let coordinates = lanes(vx, whole).iter().zip(lanes(vy, whole));
                let groups = groups.iter_mut().zip(light_groups).zip(coordinates);
                for ((sums, lights), (vx, vy)) in groups {
                    for k in 0..MIS_GROUP {
                        let light = cone.light_value(h, Vec2::new(vx[k], vy[k]));
                        lane_hits[k] += u32::from(light != 0.0);
                        lights[k] = light;
                        sums[k] = 0.0 + light;
                    }
                }
                let mut light_hits: u32 = lane_hits.iter().sum();
                for k in whole..len {
                    let light = cone.light_value(h, Vec2::new(vx[k], vy[k]));
                    light_hits += u32::from(light != 0.0);
                    lights[k] = light;
                    sums[k] = 0.0 + light;
                }
                light_hits
            };
            // Pass 2.
            let mut masks = [0u16; SPAN / MIS_GROUP];
            let groups = window.group_masks(&ux[..whole], &uy[..whole], &mut masks);
            let mut count = list_set_bits(&masks[..groups], MIS_GROUP, &mut listed, 0);
            for k in whole..len {
                listed[count] = k as u16;
                count += usize::from(window.may_see(Vec2::new(ux[k], uy[k])));
            }
            // Pass 3: whole groups, the last one padded with the previous
            // span's (or zero) coordinates, whose values are not used.
            let [gux, guy, cosines] = &mut gathered;
            let cosines = grouped_values::<f32, MIS_GROUP>(
                &listed[..count],
                (ux, uy),
                [gux, guy, cosines],
                #[inline(always)]
                |x, y| cone.cosine_value(h, Vec2::new(x, y)),
            );
            let mut cosine_hits = 0u32;
            for (&k, &cosine) in listed[..count].iter().zip(cosines) {
                let k = usize::from(k);
                cosine_hits += u32::from(cosine != 0.0);
                sums[k] = cosine + lights[k];
            }
            [cosine_hits, light_hits]
        },
    )
}

/// Samples per group of [`cone_mis_batch`]'s window test: one AVX-512
/// vector of f32 lanes, two of AVX2's.
const MIS_GROUP: usize = 16;
const _: () = assert!(
    MIS_GROUP == 16,
    "CosineWindowF32::group_masks works in groups of 16"
);

/// The closure itself, so that `#[inline(always)]` may sit on it.
#[inline(always)]
fn hoisted<A, R, F: Fn(A) -> R>(f: F) -> F {
    f
}

impl PreparedEmitterF32 {
    /// [`add_batch`](Self::add_batch) compiled for instruction set `isa`
    /// ([`Isa::run_without_gfni`], as the f64 kernels): the same values to the
    /// bit in every set. The one
    /// place the f32 kernels are instantiated, once per set, and never
    /// inlined, for the reason [`PreparedEmitter::add_batch_in`](super::PreparedEmitter::add_batch_in)
    /// gives.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub fn add_batch_in(
        &self,
        isa: Isa,
        ux: &[f32],
        uy: &[f32],
        vx: &[f32],
        vy: &[f32],
        out: &mut [f64],
        store: Store,
    ) -> PartHits {
        if self.constant.is_none() && self.across_horizon() {
            return self.across_horizon_in(isa, ux, uy, out, store);
        }
        isa.run_without_gfni(
            #[inline(always)]
            || self.add_batch(ux, uy, vx, vy, out, store),
        )
    }

    /// Whether this is projected sampling of a cap or sphere across the
    /// horizon, which [`add_batch_in`](Self::add_batch_in) runs apart
    /// ([`across_horizon_in`](Self::across_horizon_in)).
    fn across_horizon(&self) -> bool {
        self.technique == Technique::Projected
            && match &self.projected {
                Projected::Cap(cap) => cap.whole().is_none(),
                Projected::Sphere(s) => s.whole().is_none(),
                _ => false,
            }
    }

    /// Projected sampling of a cap or sphere across the horizon through
    /// the sampler's batch (`ProjectedCap::sample_directions`,
    /// `ProjectedSphere::sample_directions`: one branch-free segment solve
    /// per sample, the directions of `sample` to the bit), compiled for
    /// `isa` in a function of its own. Inlined into
    /// [`add_batch`](Self::add_batch) with the other kernels, its two
    /// copies of the batch changed how the compiler kept the others'
    /// values in registers: uniform-hemisphere sampling of a pentagon went
    /// 6.6 → 10.1 ns a sample (f32, AVX2). The same values as `add_batch`'s
    /// one-sample path for these emitters; the hits of the only part.
    #[inline(never)]
    fn across_horizon_in(
        &self,
        isa: Isa,
        ux: &[f32],
        uy: &[f32],
        out: &mut [f64],
        store: Store,
    ) -> PartHits {
        let n = ux.len().min(uy.len()).min(out.len());
        let block = Block {
            ux: &ux[..n],
            uy: &uy[..n],
            vx: &ux[..n],
            vy: &uy[..n],
            store,
        };
        let out = &mut out[..n];
        let (frame, normal, radiance) = (&{ self.frame }, self.normal, self.radiance);
        isa.run_without_gfni(
            #[inline(always)]
            || match &self.projected {
                Projected::Cap(cap) => {
                    let (cap, omega) = (&{ *cap }, cap.projected_solid_angle());
                    drawn_batch(
                        normal,
                        radiance,
                        &block,
                        out,
                        // The local directions turned into world space as
                        // they are drawn.
                        #[inline(always)]
                        |ux, uy, dx, dy, dz| {
                            cap.sample_directions(ux, uy, dx, dy, dz);
                            for k in 0..dx.len().min(dy.len()).min(dz.len()) {
                                let w = frame.from_local(Vec3::new(dx[k], dy[k], dz[k]));
                                (dx[k], dy[k], dz[k]) = (w.x, w.y, w.z);
                            }
                        },
                        #[inline(always)]
                        |w| normal.dot(w).max(0.0) / omega,
                    )
                }
                Projected::Sphere(s) => {
                    let sphere = &{ *s };
                    drawn_batch(
                        normal,
                        radiance,
                        &block,
                        out,
                        #[inline(always)]
                        |ux, uy, dx, dy, dz| sphere.sample_directions(ux, uy, dx, dy, dz),
                        #[inline(always)]
                        |w| sphere.sample_density(w),
                    )
                }
                _ => [0, 0],
            },
        )
    }

    /// Adds this emitter's estimate for samples `i` of a block to `out[i]`:
    /// `out[i] += L·g((ux[i], uy[i]), (vx[i], vy[i]))` with g in f32
    /// (module docs), over the shortest of the slices (`vx`, `vy` are read
    /// only by MIS); with [`Store::Overwrite`], `out[i] = L·g(…)` over the
    /// same samples, whatever `out` held. Returns how many samples had a
    /// non-zero value in each part
    /// ([`PreparedEmitter::parts`](super::PreparedEmitter::parts)).
    #[inline(always)]
    pub fn add_batch(
        &self,
        ux: &[f32],
        uy: &[f32],
        vx: &[f32],
        vy: &[f32],
        out: &mut [f64],
        store: Store,
    ) -> PartHits {
        let mis = matches!(self.technique, Technique::Mis(_));
        let mut n = ux.len().min(uy.len()).min(out.len());
        if mis {
            n = n.min(vx.len()).min(vy.len());
        }
        let block = Block {
            ux: &ux[..n],
            uy: &uy[..n],
            vx: if mis { &vx[..n] } else { &ux[..n] },
            vy: if mis { &vy[..n] } else { &uy[..n] },
            store,
        };
        let out = &mut out[..n];
        if let Some(c) = self.constant {
            for o in out.iter_mut() {
                *o = match store {
                    Store::Add => *o + c,
                    Store::Overwrite => c,
                };
            }
            return [if c != 0.0 { n as u64 } else { 0 }, 0];
        }
        let lit = self.lit;
        let origin = Vec3::ZERO;
        match &self.shape {
            Shape::Sky => self.technique_batch(
                #[inline(always)]
                |_| true,
                &block,
                out,
            ),
            Shape::Cap(frame, cone) => {
                let (frame, cone) = (&{ *frame }, &{ *cone });
                self.technique_batch(
                    #[inline(always)]
                    |w| cone.pdf(frame.to_local(w)) > 0.0,
                    &block,
                    out,
                )
            }
            Shape::Sphere(s) => {
                // From outside, the prepared test: the sphere's answers
                // without its roots (`SphereFromOutside`).
                if let Some(seen) = SphereFromOutside::new(s, origin) {
                    return self.technique_batch(
                        #[inline(always)]
                        |w| seen.hits(w),
                        &block,
                        out,
                    );
                }
                let s = &{ *s };
                self.technique_batch(
                    #[inline(always)]
                    |w| {
                        s.hit_distance(&Ray::new(origin, w), f32::INFINITY)
                            .is_some()
                    },
                    &block,
                    out,
                )
            }
            Shape::Disk(d) => {
                let d = &{ *d };
                self.technique_batch(
                    #[inline(always)]
                    |w| {
                        lit && d
                            .hit_distance(&Ray::new(origin, w), f32::INFINITY)
                            .is_some()
                    },
                    &block,
                    out,
                )
            }
            Shape::Polygon(q) => {
                // A triangle's or a quadrilateral's ray test prepared for
                // the receiver, as in the f64 kernels (`polygon_lookup`):
                // the same answers, in a fixed edge loop that vectorises
                // where the polygon's own test is a call per sample into a
                // loop over its vertices (measured: 10x the f64 time for
                // hemisphere sampling of a triangle, 33 against 3.1 ns).
                if let Some(seen) = PolygonFromOrigin::<3>::new(q, origin) {
                    return self.technique_batch(
                        #[inline(always)]
                        |w| lit && seen.hits(w),
                        &block,
                        out,
                    );
                }
                if let Some(seen) = PolygonFromOrigin::<4>::new(q, origin) {
                    return self.technique_batch(
                        #[inline(always)]
                        |w| lit && seen.hits(w),
                        &block,
                        out,
                    );
                }
                // 5 to 8 vertices: one loop of 8 edges, the last repeated
                // (`PolygonFromOrigin::padded`, as the f64 kernels do).
                if let Some(seen) = PolygonFromOrigin::<8>::padded(q, origin) {
                    return self.technique_batch(
                        #[inline(always)]
                        |w| lit && seen.hits(w),
                        &block,
                        out,
                    );
                }
                self.technique_batch(
                    #[inline(always)]
                    |w| {
                        lit && q
                            .hit_distance(&Ray::new(origin, w), f32::INFINITY)
                            .is_some()
                    },
                    &block,
                    out,
                )
            }
        }
    }

    /// The loop of this emitter's technique over a block, `sees(ω)` its
    /// hit test (already specialised to its kind).
    #[inline(always)]
    fn technique_batch(
        &self,
        sees: impl Fn(Vec3) -> bool,
        block: &Block<'_>,
        out: &mut [f64],
    ) -> PartHits {
        // Copies, not references, as in the f64 kernels' `technique_batch`:
        // loads through `&self` inside the hit test's branch became masked
        // gathers on every iteration.
        let (frame, normal, radiance) = (&{ self.frame }, self.normal, self.radiance);
        match self.technique {
            Technique::UniformHemisphere => single(
                radiance,
                block,
                out,
                #[inline(always)]
                |u| {
                    let w = frame.from_local(sample_uniform_hemisphere(u));
                    let cos = w.dot(normal);
                    if cos > 0.0 && sees(w) {
                        2.0 * PI * cos
                    } else {
                        0.0
                    }
                },
            ),
            Technique::CosineHemisphere => single(
                radiance,
                block,
                out,
                #[inline(always)]
                |u| {
                    let local = sample_cosine_hemisphere(u);
                    if local.z > 0.0 && sees(frame.from_local(local)) {
                        PI
                    } else {
                        0.0
                    }
                },
            ),
            Technique::Light => self.light_batch(block, out),
            // Resolved when prepared: a constant, or its residual sampler's
            // technique (light or projected). Nothing to add; a slot to
            // overwrite gets 0.
            Technique::ControlVariate => {
                if block.store == Store::Overwrite {
                    out.fill(0.0);
                }
                [0, 0]
            }
            Technique::Area => self.area_batch(block, out),
            Technique::Projected => self.projected_batch(block, out),
            Technique::Mis(h) => self.mis_batch(h, sees, block, out),
        }
    }

    /// Solid-angle sampling: cos θ/p of every direction the light sampler
    /// draws (module docs: no lookup). Cones (spheres, sky caps) in their
    /// own frame: g = Ω max(n_local·ω_local, 0).
    #[inline(always)]
    fn light_batch(&self, block: &Block<'_>, out: &mut [f64]) -> PartHits {
        let (normal, radiance) = (self.normal, if self.lit { self.radiance } else { 0.0 });
        match &self.light {
            Light::Sphere(s, cosine) => cone_batch(cosine, s.cone(), radiance, block, out),
            Light::Cap(_, cone, cosine) => cone_batch(cosine, cone, radiance, block, out),
            Light::Sky => single(
                radiance,
                block,
                out,
                #[inline(always)]
                |u| 4.0 * PI * normal.dot(sample_uniform_sphere(u)).max(0.0),
            ),
            // One spherical triangle, a spherical rectangle or a fan of up
            // to `MAX_SPHERICAL_FAN` triangles in fixed lanes
            // (`SphericalFan`) is sampled inline, as a vectorised loop (the
            // same values as `PolygonSolidAngle::sample`); a larger fan
            // looks its triangle up per sample.
            Light::Polygon(p) => {
                if let Some(t) = p.single_triangle() {
                    return solid_angle_light(&t, normal, radiance, block, out);
                }
                if let PolygonSolidAngle::Rectangle(r) = p {
                    return solid_angle_light(r, normal, radiance, block, out);
                }
                if let Some(fan) = SphericalFan::<MAX_SPHERICAL_FAN>::new(p) {
                    return solid_angle_light(&fan, normal, radiance, block, out);
                }
                scored(
                    normal,
                    radiance,
                    block,
                    out,
                    #[inline(always)]
                    |u| p.sample(u),
                )
            }
            Light::Disk(d) => {
                // Through the tabulated sampler's batch
                // (`TabulatedDiskSolidAngle::sample_directions`): branch-free
                // passes that vectorise where the one-sample `sample` (a
                // table lookup and a quadrature of varying length) does
                // not, the same directions to the bit, each of density 1/Ω.
                let pdf = 1.0 / d.solid_angle();
                drawn_batch(
                    normal,
                    radiance,
                    block,
                    out,
                    #[inline(always)]
                    |sx, sy, dx, dy, dz| d.sample_directions(sx, sy, dx, dy, dz),
                    #[inline(always)]
                    |_| pdf,
                )
            }
            Light::None => [0, 0],
        }
    }

    /// Area sampling: cos θ/p of the direction toward a uniform point of
    /// the emitter (p = p_A d²/|cos θ_l|); a point on a sphere's hidden
    /// side gives none.
    #[inline(always)]
    fn area_batch(&self, block: &Block<'_>, out: &mut [f64]) -> PartHits {
        let (normal, radiance) = (self.normal, if self.lit { self.radiance } else { 0.0 });
        let origin = Vec3::ZERO;
        let through = hoisted(
            #[inline(always)]
            |s: Option<lambert_sampling::f32::LightSample>| match s {
                Some(s) => cos_over_pdf(normal, s.direction, s.pdf),
                None => 0.0,
            },
        );
        match &self.area {
            // Every lane drawn, none dropped by a branch (density 0 where
            // `sample` gives none, which `cos_over_pdf` scores 0): the
            // loops vectorise.
            Area::Sphere(a) => scored(
                normal,
                radiance,
                block,
                out,
                #[inline(always)]
                |u| a.sample_or_zero(origin, u),
            ),
            Area::Disk(a) => scored(
                normal,
                radiance,
                block,
                out,
                #[inline(always)]
                |u| a.sample_or_zero(origin, u),
            ),
            Area::Polygon(a) => polygon_area_batch(a, normal, radiance, &through, block, out),
            Area::None => [0, 0],
        }
    }

    /// Projected-solid-angle sampling: cos θ/p = Ω⊥ (to a few ulps) for
    /// every direction drawn, the density formed from the same n·ω. Caps
    /// and spheres across the horizon take the one-sample path here;
    /// [`add_batch_in`](Self::add_batch_in) runs them through their
    /// batches instead ([`across_horizon_in`](Self::across_horizon_in)),
    /// with the same values.
    #[inline(always)]
    fn projected_batch(&self, block: &Block<'_>, out: &mut [f64]) -> PartHits {
        let (frame, normal, radiance) = (&self.frame, self.normal, self.radiance);
        let origin = Vec3::ZERO;
        match &self.projected {
            Projected::Sky => single(
                radiance,
                block,
                out,
                #[inline(always)]
                |u| {
                    let w = frame.from_local(sample_cosine_hemisphere(u));
                    cos_over_pdf(normal, w, normal.dot(w).max(0.0) / PI)
                },
            ),
            Projected::Cap(cap) => {
                let omega = cap.projected_solid_angle();
                // A cap wholly above the horizon: its closed form alone, in
                // a loop that vectorises (the same bits as `sample`).
                if let Some(whole) = cap.whole() {
                    let whole = &whole;
                    return single(
                        radiance,
                        block,
                        out,
                        #[inline(always)]
                        |u| {
                            let w = frame.from_local(whole.sample(u).direction);
                            cos_over_pdf(normal, w, normal.dot(w).max(0.0) / omega)
                        },
                    );
                }
                single(
                    radiance,
                    block,
                    out,
                    #[inline(always)]
                    |u| {
                        let w = frame.from_local(cap.sample(u).direction);
                        cos_over_pdf(normal, w, normal.dot(w).max(0.0) / omega)
                    },
                )
            }
            Projected::Sphere(s) => {
                // As for caps; and only the direction and density, which
                // is all the estimate needs (the same bits as `sample`).
                if let Some(whole) = s.whole() {
                    let whole = &whole;
                    return scored(
                        normal,
                        radiance,
                        block,
                        out,
                        #[inline(always)]
                        |u| whole.sample_direction(u),
                    );
                }
                scored(
                    normal,
                    radiance,
                    block,
                    out,
                    #[inline(always)]
                    |u| s.sample_direction(u),
                )
            }
            Projected::Polygon(p) => {
                // Through the tabulated sampler's batch
                // (`TabulatedProjectedPolygon::sample_directions`:
                // branch-free passes by sector), the same directions to the
                // bit as `sample`, each of the density `sample_density`
                // gives, from a copy of the sampler (see `mis_loop`).
                let plain = &{ *p.sampler() };
                drawn_batch(
                    normal,
                    radiance,
                    block,
                    out,
                    #[inline(always)]
                    |ux, uy, dx, dy, dz| p.sample_directions(ux, uy, dx, dy, dz),
                    #[inline(always)]
                    |w| plain.sample_density(w),
                )
            }
            Projected::PolygonFan(s) => scored(
                normal,
                radiance,
                block,
                out,
                #[inline(always)]
                |u| s.sample(origin, normal, u),
            ),
            Projected::None => [0, 0],
        }
    }

    /// MIS, dispatched once per block on the light sampler's kind, so that
    /// the loop calls that kind's sampler and density directly.
    #[inline(always)]
    fn mis_batch(
        &self,
        h: Heuristic,
        sees: impl Fn(Vec3) -> bool,
        block: &Block<'_>,
        out: &mut [f64],
    ) -> PartHits {
        let none = (Vec3::Z, 0.0);
        if let Some((cone, window)) = &self.cone_mis {
            // One loop per heuristic, its choice made at compile time
            // rather than tested in the loop (as in the f64 kernels).
            let radiance = self.radiance;
            return match h {
                Heuristic::Balance => {
                    cone_mis_batch(cone, window, Heuristic::Balance, radiance, block, out)
                }
                Heuristic::Power => {
                    cone_mis_batch(cone, window, Heuristic::Power, radiance, block, out)
                }
            };
        }
        match &self.light {
            Light::Sky => self.mis_loop(
                h,
                sees,
                #[inline(always)]
                |_| 1.0 / (4.0 * PI),
                #[inline(always)]
                |u| (sample_uniform_sphere(u), 1.0 / (4.0 * PI)),
                block,
                out,
            ),
            Light::Cap(frame, cone, _) => {
                // Copies, not references into `self` (as in `mis_loop`).
                let (frame, cone) = (&{ *frame }, &{ *cone });
                self.mis_loop(
                    h,
                    sees,
                    #[inline(always)]
                    |w| cone.pdf(frame.to_local(w)),
                    #[inline(always)]
                    |u| (frame.from_local(cone.sample(u)), 1.0 / cone.solid_angle()),
                    block,
                    out,
                )
            }
            Light::Sphere(s, _) => {
                let s = &{ *s };
                self.mis_loop(
                    h,
                    sees,
                    #[inline(always)]
                    |w| s.pdf(w),
                    #[inline(always)]
                    |u| {
                        (
                            s.frame().from_local(s.cone().sample(u)),
                            1.0 / s.solid_angle(),
                        )
                    },
                    block,
                    out,
                )
            }
            Light::Polygon(p) => {
                // As in `light_batch`: one triangle, a rectangle or a
                // fan in fixed lanes inline.
                if let Some(t) = p.single_triangle() {
                    return self.solid_angle_mis(h, sees, &t, block, out);
                }
                if let PolygonSolidAngle::Rectangle(r) = p {
                    return self.solid_angle_mis(h, sees, r, block, out);
                }
                if let Some(fan) = SphericalFan::<MAX_SPHERICAL_FAN>::new(p) {
                    return self.solid_angle_mis(h, sees, &fan, block, out);
                }
                self.mis_loop(
                    h,
                    sees,
                    #[inline(always)]
                    |w| p.pdf(w),
                    #[inline(always)]
                    |u| p.sample(u).map_or(none, |l| (l.direction, l.pdf)),
                    block,
                    out,
                )
            }
            Light::Disk(d) => {
                // The light halves first, from directions drawn in batches
                // (`in_direction_batches`); they then ride in the block's second
                // point, and the loop adds them to the cosine halves as
                // `mis_loop` does: the same sums, to the bit.
                let (frame, normal, lit) = (&{ self.frame }, self.normal, self.lit);
                let pdf = 1.0 / d.solid_angle();
                // The density's sampler copied, not read through `d`.
                let plain = &{ *d.sampler() };
                let mut lights = [0.0f32; DISK_BATCH];
                in_direction_batches(
                    block.vx,
                    block.vy,
                    out,
                    #[inline(always)]
                    |sx, sy, dx, dy, dz| d.sample_directions(sx, sy, dx, dy, dz),
                    #[inline(always)]
                    |at, [dx, dy, dz], out| {
                        let lights = &mut lights[..out.len()];
                        let n = lights.len();
                        let (dx, dy, dz) = (&dx[..n], &dy[..n], &dz[..n]);
                        for k in 0..n {
                            let dir = Vec3::new(dx[k], dy[k], dz[k]);
                            lights[k] = mis_light_half(h, frame, normal, lit, dir, pdf);
                        }
                        let lights = &*lights;
                        let part = Block {
                            ux: &block.ux[at.clone()],
                            uy: &block.uy[at],
                            vx: lights,
                            vy: lights,
                            store: block.store,
                        };
                        accumulate(
                            self.radiance,
                            &part,
                            out,
                            #[inline(always)]
                            |u, v| {
                                let cosine = mis_cosine_half(
                                    h,
                                    frame,
                                    normal,
                                    #[allow(clippy::redundant_closure)]
                                    #[inline(always)]
                                    |w| sees(w),
                                    #[inline(always)]
                                    |w| plain.pdf(w),
                                    u,
                                );
                                [cosine, v.x]
                            },
                        )
                    },
                )
            }
            Light::None => self.mis_loop(
                h,
                sees,
                #[inline(always)]
                |_| 0.0,
                #[inline(always)]
                |_| none,
                block,
                out,
            ),
        }
    }

    /// [`Self::mis_loop`] through a polygon's solid-angle sampler in one of
    /// its inline forms ([`UniformSolidAngle`]), copied into the loop so
    /// that its constants stay in registers.
    #[inline(always)]
    fn solid_angle_mis(
        &self,
        h: Heuristic,
        sees: impl Fn(Vec3) -> bool,
        sampler: &impl UniformSolidAngle,
        block: &Block<'_>,
        out: &mut [f64],
    ) -> PartHits {
        let sampler = &{ *sampler };
        self.mis_loop(
            h,
            sees,
            #[inline(always)]
            |w| sampler.density(w),
            #[inline(always)]
            |u| {
                let s = sampler.sample_direction(u);
                (s.direction, s.pdf)
            },
            block,
            out,
        )
    }

    /// MIS: the weighted cosine-sampled g from `u` plus the weighted
    /// light-sampled g from `v` (Veach & Guibas 1995), counted apart;
    /// `light_pdf` and `light_sample` are the light sampler's density and
    /// draw (density 0: nothing drawn).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn mis_loop(
        &self,
        h: Heuristic,
        sees: impl Fn(Vec3) -> bool,
        light_pdf: impl Fn(Vec3) -> f32,
        light_sample: impl Fn(Vec2) -> (Vec3, f32),
        block: &Block<'_>,
        out: &mut [f64],
    ) -> PartHits {
        // Copies, not references (see `technique_batch`).
        let (frame, normal, radiance, lit) =
            (&{ self.frame }, self.normal, self.radiance, self.lit);
        accumulate(
            radiance,
            block,
            out,
            #[inline(always)]
            |u, v| {
                // Through closures, not `&sees`: a call through a reference
                // can be left out of line (see the f64 `disk_table_batch`).
                let cosine = mis_cosine_half(
                    h,
                    frame,
                    normal,
                    #[allow(clippy::redundant_closure)]
                    #[inline(always)]
                    |w| sees(w),
                    #[allow(clippy::redundant_closure)]
                    #[inline(always)]
                    |w| light_pdf(w),
                    u,
                );
                let (dir, p_light) = light_sample(v);
                [cosine, mis_light_half(h, frame, normal, lit, dir, p_light)]
            },
        )
    }
}

/// MIS's cosine half (Veach & Guibas 1995): the direction w the cosine
/// hemisphere draws from `u`, weighted against the light sampler's density
/// `light_pdf(w)`; 0 where w is below the horizon or `sees(w)` is false.
#[inline(always)]
fn mis_cosine_half(
    h: Heuristic,
    frame: &Frame,
    normal: Vec3,
    sees: impl Fn(Vec3) -> bool,
    light_pdf: impl Fn(Vec3) -> f32,
    u: Vec2,
) -> f32 {
    let local = sample_cosine_hemisphere(u);
    let w = frame.from_local(local);
    let p_cos = pdf_cosine_hemisphere(local);
    let cos = normal.dot(w);
    if p_cos > 0.0 && cos > 0.0 && sees(w) {
        h.weighted_f32(cos, p_cos, light_pdf(w))
    } else {
        0.0
    }
}

/// MIS's light half: the light sample `dir` of density `p_light`, weighted
/// against the cosine hemisphere's density there; 0 if the light is not
/// lit from the receiver.
#[inline(always)]
fn mis_light_half(
    h: Heuristic,
    frame: &Frame,
    normal: Vec3,
    lit: bool,
    dir: Vec3,
    p_light: f32,
) -> f32 {
    let p_cos = pdf_cosine_hemisphere(frame.to_local(dir));
    if lit {
        h.weighted_f32(normal.dot(dir).max(0.0), p_light, p_cos)
    } else {
        0.0
    }
}
