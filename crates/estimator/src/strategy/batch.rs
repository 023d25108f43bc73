//! Batch kernels: one emitter's estimate F = L cos θ / p for a whole block
//! of samples, in structure-of-arrays form.
//!
//! [`PreparedEmitter::evaluate_u`] decides per sample which technique runs,
//! which kind of emitter is looked up and which light sampler draws: three
//! `match`es inside the loop, which keep the compiler from vectorising it.
//! [`PreparedEmitter::add_batch`] makes those decisions once per block and
//! then runs a loop specialised for the (technique, emitter kind) pair over
//! arrays of coordinates (`ux`, `uy`, and `vx`, `vy` for the light sample of
//! MIS): every call in it is inlined, so the loop vectorises where its
//! arithmetic is branch-free (warps, frames, the cone of a sphere or sky
//! cap, ray–sphere and ray–plane tests) and is compiled for the instruction
//! set the caller runs it with ([`lambert_sampling::isa::Isa::run`]). Each
//! loop computes the same operations in the same order as `evaluate_u`, so
//! the values are the same to the bit (the estimator's pinned-value tests
//! check it). Light sampling of a sphere takes the shortcut of the cone in
//! its own frame, F = L Ω max(n_local·ω_local, 0) (the pdf is the constant
//! 1/Ω), as the estimator always has, and since 2026-12 draws n_local·ω_local
//! without ω, with the azimuth measured from n_local's projection
//! ([`ConeCosine`]): the same distribution of values, not the same value
//! for the same u.

use glam::{DVec2, DVec3};
use lambert_geometry::f64::{PolygonFromOrigin, SphereFromOutside};
use lambert_light::emitter::{Emitter, PolygonLight};
use lambert_light::receiver::Receiver;
use lambert_sampling::f64::{
    pdf_cosine_hemisphere, pdf_uniform_hemisphere, pdf_uniform_sphere, sample_cosine_hemisphere,
    sample_uniform_hemisphere, ConeCosine, LightSample, LightSampler, PolygonAreaSampler,
    PolygonSolidAngle, SphereSolidAngle, SphericalFan, TabulatedDiskSolidAngle, UniformSolidAngle,
};
use lambert_sampling::isa::Isa;

use super::cone_mis::ConeMis;
use super::cone_window::CosineWindow;
use super::emitter_light::{
    disk_table_direction, sample_cap, sample_disk, sample_disk_table, sample_polygon, sample_sky,
    sample_solid_angle, sample_sphere,
};
use super::listing::{grouped_values, list_set_bits};
use super::{
    EmitterArea, EmitterLight, EmitterProjected, Heuristic, LightDirection, PartHits,
    PreparedEmitter, Store, Technique,
};

impl PreparedEmitter {
    /// [`add_batch`](Self::add_batch) compiled for instruction set `isa`
    /// ([`Isa::run_without_gfni`]: the kernels have no bit reversal, so a
    /// GFNI processor runs the AVX-512 copy): the same values to the bit in
    /// every set.
    ///
    /// This is the one place the f64 kernels are instantiated, once per
    /// set. It is never inlined, so a chunk loop that calls it per block
    /// (independent samples, each sequence, the f32 path's f64 emitters)
    /// shares these copies instead of carrying its own: inlining every
    /// kernel into every chunk loop multiplied the estimator's build time
    /// by the number of loops, for no gain (the call is once per block of
    /// hundreds of samples).
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub fn add_batch_in(
        &self,
        isa: Isa,
        receiver: &Receiver,
        ux: &[f64],
        uy: &[f64],
        vx: &[f64],
        vy: &[f64],
        out: &mut [f64],
        store: Store,
    ) -> PartHits {
        isa.run_without_gfni(
            #[inline(always)]
            || self.add_batch(receiver, ux, uy, vx, vy, out, store),
        )
    }

    /// Adds this emitter's estimate for samples `i` of a block to `out[i]`
    /// (or stores it there, with [`Store::Overwrite`]):
    /// `out[i] += F((ux[i], uy[i]), (vx[i], vy[i]))`, the value of
    /// [`evaluate_u`](Self::evaluate_u) to the bit (the light shortcut for
    /// spheres aside, module docs), over the shortest of the slices (`vx`,
    /// `vy` are read only by MIS). Returns how many samples had a non-zero
    /// value in each part.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn add_batch(
        &self,
        receiver: &Receiver,
        ux: &[f64],
        uy: &[f64],
        vx: &[f64],
        vy: &[f64],
        out: &mut [f64],
        store: Store,
    ) -> PartHits {
        let p = receiver.point;
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
        if let Technique::Mis(h) = self.technique {
            if let Some((cone, window)) = self.cone_mis_window(receiver) {
                // One loop per heuristic, each with its choice made at
                // compile time rather than tested in the loop.
                return match h {
                    Heuristic::Balance => {
                        cone_mis_batch(&cone, &window, Heuristic::Balance, &block, out)
                    }
                    Heuristic::Power => {
                        cone_mis_batch(&cone, &window, Heuristic::Power, &block, out)
                    }
                };
            }
        }
        if self.technique == Technique::Projected {
            if let Some(hits) = self.projected_whole_batch(receiver, &block, out) {
                return hits;
            }
        }
        match (&self.light, &self.emitter) {
            (EmitterLight::Sphere(cone), Emitter::Sphere(e)) => {
                if self.technique == Technique::Light {
                    return sphere_cone_batch(cone, e.radiance, receiver.normal, &block, out);
                }
                // A local copy stays in registers (see `technique_batch`).
                let cone = &cone.clone();
                let light = hoisted(
                    #[inline(always)]
                    |u| sample_sphere(cone, u),
                );
                let pdf = hoisted(
                    #[inline(always)]
                    |w| cone.pdf(w),
                );
                // From outside, the prepared test: the sphere's answers
                // without its roots (`SphereFromOutside`), the same values
                // as `radiance_toward`.
                if let Some(seen) = SphereFromOutside::new(&e.sphere, p) {
                    let radiance = e.radiance;
                    let lit = hoisted(
                        #[inline(always)]
                        |w| if seen.hits(w) { radiance } else { 0.0 },
                    );
                    return technique_batch(self, receiver, lit, light, pdf, &block, out);
                }
                let lit = hoisted(
                    #[inline(always)]
                    |w| e.radiance_toward(p, w),
                );
                technique_batch(self, receiver, lit, light, pdf, &block, out)
            }
            (EmitterLight::Sky, Emitter::Sky(e)) => technique_batch(
                self,
                receiver,
                #[inline(always)]
                |_| e.radiance,
                // Closures, not the functions: passed as function items,
                // their call shims were left out of line once the kernel
                // grew (a scalar call per sample: 5 → 21 ns in f64).
                #[allow(clippy::redundant_closure)]
                #[inline(always)]
                |u| sample_sky(u),
                #[allow(clippy::redundant_closure)]
                #[inline(always)]
                |w| pdf_uniform_sphere(w),
                &block,
                out,
            ),
            (EmitterLight::Cap(frame, cone), Emitter::SkyCap(e)) => {
                // Local copies, as for the sphere: read through references
                // into `self`, every technique's loop stayed scalar (f64
                // light sampling of a cap 17 ns a sample, f32 2.1).
                let (frame, cone, e) = (&{ *frame }, &{ *cone }, &{ *e });
                technique_batch(
                    self,
                    receiver,
                    #[inline(always)]
                    |w| e.radiance_toward(w),
                    #[inline(always)]
                    |u| sample_cap(frame, cone, u),
                    #[inline(always)]
                    |w| cone.pdf(frame.to_local(w)),
                    &block,
                    out,
                )
            }
            (EmitterLight::Polygon(poly), Emitter::Polygon(e)) => {
                // Light sampling and MIS with the light sampler specialised
                // to what the polygon looks like from here, inline in the
                // loop (so it vectorises): one spherical triangle of a
                // triangle light, or the spherical rectangle of a
                // rectangle, each with its own vertex count's lookup, and a
                // fan of up to `MAX_SPHERICAL_FAN` triangles in fixed lanes
                // (`SphericalFan`) with the padded lookup. Only those two
                // techniques are compiled for them (each pairing is one
                // more copy of the loops per instruction set). The rest,
                // and larger fans, take `PolygonSolidAngle::sample`, which
                // looks the fan's triangle up per sample.
                if let (Some(single), Some(lit)) =
                    (poly.single_triangle(), polygon_lookup::<3>(e, p))
                {
                    if let Some(hits) = solid_angle_batch(self, receiver, lit, &single, &block, out)
                    {
                        return hits;
                    }
                }
                if let (PolygonSolidAngle::Rectangle(r), Some(lit)) =
                    (poly, polygon_lookup::<4>(e, p))
                {
                    if let Some(hits) = solid_angle_batch(self, receiver, lit, r, &block, out) {
                        return hits;
                    }
                }
                if let (Some(fan), Some(lit)) = (
                    SphericalFan::<MAX_SPHERICAL_FAN>::new(poly),
                    polygon_lookup::<MAX_PADDED_VERTICES>(e, p),
                ) {
                    if let Some(hits) = solid_angle_batch(self, receiver, lit, &fan, &block, out) {
                        return hits;
                    }
                }
                let light = hoisted(
                    #[inline(always)]
                    |u| sample_polygon(poly, u),
                );
                let pdf = hoisted(
                    #[inline(always)]
                    |w| poly.pdf(w),
                );
                if let Some(lit) = polygon_lookup::<3>(e, p) {
                    return technique_batch(self, receiver, lit, light, pdf, &block, out);
                }
                if let Some(lit) = polygon_lookup::<4>(e, p) {
                    return technique_batch(self, receiver, lit, light, pdf, &block, out);
                }
                if let Some(lit) = polygon_lookup::<MAX_PADDED_VERTICES>(e, p) {
                    return technique_batch(self, receiver, lit, light, pdf, &block, out);
                }
                technique_batch(
                    self,
                    receiver,
                    #[inline(always)]
                    |w| e.radiance_toward(p, w),
                    light,
                    pdf,
                    &block,
                    out,
                )
            }
            (EmitterLight::Disk(d), Emitter::Disk(e)) => technique_batch(
                self,
                receiver,
                #[inline(always)]
                |w| e.radiance_toward(p, w),
                #[inline(always)]
                |u| sample_disk(d, u),
                #[inline(always)]
                |w| d.pdf(w),
                &block,
                out,
            ),
            (EmitterLight::DiskTable(d), Emitter::Disk(e)) => {
                let lit = hoisted(
                    #[inline(always)]
                    |w| e.radiance_toward(p, w),
                );
                if let Some(hits) = disk_table_batch(self, receiver, d, lit, &block, out) {
                    return hits;
                }
                technique_batch(
                    self,
                    receiver,
                    lit,
                    #[inline(always)]
                    |u| sample_disk_table(d, u),
                    #[inline(always)]
                    |w| d.pdf(w),
                    &block,
                    out,
                )
            }
            // No light sampler (an invisible light): light samples are
            // none, the other techniques still look the emitter up.
            _ => technique_batch(
                self,
                receiver,
                #[inline(always)]
                |w| self.emitter.radiance_toward(p, w),
                #[inline(always)]
                |_| None,
                #[inline(always)]
                |_| 0.0,
                &block,
                out,
            ),
        }
    }
}

/// The stand-in for a light sample that was not drawn, in the branch-free
/// MIS loop: any unit direction and density 1 (its value is discarded).
const NO_LIGHT_DIRECTION: LightDirection = LightDirection {
    direction: DVec3::Z,
    pdf: 1.0,
};

/// One block's coordinates, cut to one length: `u` (`ux`, `uy`) and MIS's
/// second point `v` (`vx`, `vy`; a copy of `u`'s slices for the techniques
/// that read one point, so that [`Block::each`] cuts all four alike).
struct Block<'a> {
    ux: &'a [f64],
    uy: &'a [f64],
    vx: &'a [f64],
    vy: &'a [f64],
    /// How the values are stored in `out` ([`Store`]).
    store: Store,
}

impl Block<'_> {
    /// Stores `f(i, u_i, v_i)` in `out[i]` ([`Store`]) for every sample
    /// of the block, in order, with one loop per way of storing.
    ///
    /// An index loop over slices cut to `out`'s length, so that the
    /// compiler sees every index in bounds. Indexing the block's arrays
    /// by an iterator's count left a bounds check per sample, and a
    /// vectorised loop that may exit early runs its last vector's worth
    /// of samples in scalar code (measured on the f32 kernels: 32 of every
    /// 256 samples, half the time).
    #[inline(always)]
    fn each(&self, out: &mut [f64], mut f: impl FnMut(usize, DVec2, DVec2) -> f64) {
        let n = out.len();
        let (ux, uy) = (&self.ux[..n], &self.uy[..n]);
        let (vx, vy) = (&self.vx[..n], &self.vy[..n]);
        // The two loops written out: a shared closure for the value was
        // not inlined, and ran outside the caller's instruction set.
        match self.store {
            Store::Add => {
                for i in 0..n {
                    out[i] += f(i, DVec2::new(ux[i], uy[i]), DVec2::new(vx[i], vy[i]));
                }
            }
            Store::Overwrite => {
                for i in 0..n {
                    out[i] = f(i, DVec2::new(ux[i], uy[i]), DVec2::new(vx[i], vy[i]));
                }
            }
        }
    }
}

/// Light sampling of a sphere through its cone: F = L Ω max(n_local·ω, 0)
/// with n_local the normal rotated into the cone's frame once, and
/// n_local·ω drawn by [`ConeCosine`] (the azimuth measured from n_local's
/// projection), which never builds ω.
#[inline(always)]
fn sphere_cone_batch(
    sphere: &SphereSolidAngle,
    radiance: f64,
    normal: DVec3,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    let scale = radiance * sphere.solid_angle();
    let cosine = ConeCosine::new(sphere.cone(), sphere.frame().to_local(normal));
    if cosine.is_above_horizon() && scale >= f64::MIN_POSITIVE {
        // Every cosine exceeds 2⁻¹⁰ and the scale is normal, so each value
        // is positive: the clamp and the hit count of the loop below give
        // these values to the bit, and every sample hits.
        block.each(
            out,
            #[inline(always)]
            |_, u, _| scale * cosine.sample(u),
        );
        return [out.len() as u64, 0];
    }
    let mut hits = 0u64;
    block.each(
        out,
        #[inline(always)]
        |_, u, _| {
            let f = scale * cosine.sample(u).max(0.0);
            hits += u64::from(f != 0.0);
            f
        },
    );
    [hits, 0]
}

/// MIS on a sphere or sky cap ([`ConeMis`]): both halves in the frames
/// where they are cheapest, counted apart. Per span of [`MIS_SPAN`]
/// samples, in three passes (the f32 kernel's, `batch_f32::cone_mis_batch`):
///
/// 1. the light half of every sample, whole groups of [`MIS_GROUP`] (its
///    value is `0 + light`, the cosine half's exact 0 added, for every
///    sample whose cosine direction cannot see the cone), and a mask per
///    group of the samples whose cosine direction may see the cone
///    ([`CosineWindow::may_see`]);
/// 2. those samples listed by index;
/// 3. the cosine half of the listed samples only, gathered into whole
///    groups, and their values `cosine + light`.
///
/// The values are those of `cosine + light` per sample, to the bit (an
/// exact 0 plus `light` is `light` but for its sign, and `light` is never
/// −0), whatever the grouping.
///
/// Why: the window holds 1.3 % of the cosine samples of the speed table's
/// sphere, yet one group of eight in ten held one, and the former kernel
/// computed the cosine half for every lane of such a group: with the
/// cosine halves left out entirely (a sphere too small to be seen), MIS
/// took 0.90× the time.
#[inline(always)]
fn cone_mis_batch(
    cone: &ConeMis,
    window: &CosineWindow,
    h: Heuristic,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    // Local copies stay in registers (see `technique_batch`).
    let (cone, window) = (*cone, *window);
    let mut hits = [0u64; 2];
    if !cone.is_drawn() {
        // Both halves are 0 (`ConeMis::parts`); decided once, not per sample.
        out.iter_mut().for_each(|o| block.store.put(o, 0.0));
        return hits;
    }
    // Light hits counted per lane and added up at the end: counted into
    // one total, every group ended in a sum across its lanes (a horizontal
    // reduction the profile showed among the kernel's hottest lines).
    let mut lane_hits = [0u64; MIS_GROUP];
    let mut values = [0.0f64; MIS_SPAN];
    let mut listed = [0u16; MIS_SPAN];
    let mut gathered = [[0.0f64; MIS_SPAN]; 3];
    let mut masks = [0u8; MIS_SPAN / MIS_GROUP];
    for (index, out) in out.chunks_mut(MIS_SPAN).enumerate() {
        let len = out.len();
        let at = index * MIS_SPAN..index * MIS_SPAN + len;
        let (ux, uy) = (&block.ux[at.clone()], &block.uy[at.clone()]);
        let (vx, vy) = (&block.vx[at.clone()], &block.vy[at]);
        let values = &mut values[..len];
        // Pass 1.
        let whole = len / MIS_GROUP * MIS_GROUP;
        fn lanes(c: &[f64], whole: usize) -> &[[f64; MIS_GROUP]] {
            c[..whole].as_chunks::<MIS_GROUP>().0
        }
        let (value_groups, _) = values.as_chunks_mut::<MIS_GROUP>();
        let lights = lanes(vx, whole).iter().zip(lanes(vy, whole));
        let cosines = lanes(ux, whole).iter().zip(lanes(uy, whole));
        let groups = value_groups.iter_mut().zip(lights).zip(cosines);
        for (mask, ((values, (vx, vy)), (ux, uy))) in masks.iter_mut().zip(groups) {
            let mut may_see = 0u8;
            for k in 0..MIS_GROUP {
                let light = cone.light_value(h, DVec2::new(vx[k], vy[k]));
                lane_hits[k] += u64::from(light != 0.0);
                values[k] = 0.0 + light;
                may_see |= u8::from(window.may_see(DVec2::new(ux[k], uy[k]))) << k;
            }
            *mask = may_see;
        }
        // Pass 2.
        let mut count = list_set_bits(&masks[..whole / MIS_GROUP], MIS_GROUP, &mut listed, 0);
        for k in whole..len {
            let light = cone.light_value(h, DVec2::new(vx[k], vy[k]));
            hits[1] += u64::from(light != 0.0);
            values[k] = 0.0 + light;
            listed[count] = k as u16;
            count += usize::from(window.may_see(DVec2::new(ux[k], uy[k])));
        }
        // Pass 3: whole groups, the last one padded with coordinates left
        // from before (or zero), whose values are not used.
        let [gux, guy, cosines] = &mut gathered;
        let cosines = grouped_values::<f64, MIS_GROUP>(
            &listed[..count],
            (ux, uy),
            [gux, guy, cosines],
            #[inline(always)]
            |x, y| cone.cosine_value(h, DVec2::new(x, y)),
        );
        for (&k, &cosine) in listed[..count].iter().zip(cosines) {
            let k = usize::from(k);
            hits[0] += u64::from(cosine != 0.0);
            // `light + cosine`: the same bits as `cosine + light`
            // (addition commutes in IEEE arithmetic).
            values[k] += cosine;
        }
        match block.store {
            Store::Add => {
                for (o, &v) in out.iter_mut().zip(values.iter()) {
                    *o += v;
                }
            }
            Store::Overwrite => out.copy_from_slice(values),
        }
    }
    hits[1] += lane_hits.iter().sum::<u64>();
    hits
}

/// Samples per span of [`cone_mis_batch`]: its scratch (values, listed
/// indices, gathered coordinates and cosine halves) stays in the
/// first-level cache, and an index fits 16 bits.
const MIS_SPAN: usize = 256;

/// Samples per group of [`cone_mis_batch`]'s test: one AVX-512 vector of
/// f64 lanes, two of AVX2's.
const MIS_GROUP: usize = 8;

/// `f` itself: a closure given here can carry `#[inline(always)]` (an
/// attribute Rust accepts on a closure in argument position only), so that
/// it is compiled into the kernel's loop and instruction set.
#[inline(always)]
fn hoisted<A, R, F: Fn(A) -> R>(f: F) -> F {
    f
}

/// The most triangles of a polygon's spherical fan that light sampling
/// and MIS run in fixed lanes ([`SphericalFan`]), in f64 and f32: polygons
/// of up to eight vertices, as [`MAX_PADDED_VERTICES`] (a fan of `n`
/// vertices has `n − 2` triangles), and a seven-sided one cut by the
/// horizon. One size for all, padded: each size is one more copy of the
/// light and MIS loops per instruction set.
pub(super) const MAX_SPHERICAL_FAN: usize = 6;

/// The most vertices a polygon's ray test is prepared for
/// ([`polygon_lookup`], padded): polygons of 5 to 8 vertices share one
/// loop of 8 edges (one more copy of the loops per instruction set, not
/// four); larger ones take the general test.
const MAX_PADDED_VERTICES: usize = 8;

/// `PolygonLight::radiance_toward` from the point `origin`, for a polygon
/// of at most `N` vertices, with the ray test prepared once for that point
/// ([`PolygonFromOrigin::padded`]): the same answer to the bit, in a fixed,
/// branch-free edge loop that vectorises (the general test is a call per
/// sample into a loop over the vertices). `None` when the polygon has more
/// than `N` vertices.
#[inline(always)]
fn polygon_lookup<const N: usize>(
    polygon: &PolygonLight,
    origin: DVec3,
) -> Option<impl Fn(DVec3) -> f64> {
    let seen = PolygonFromOrigin::<N>::padded(&polygon.polygon, origin)?;
    let (radiance, two_sided, facing) = (
        polygon.radiance,
        polygon.two_sided,
        polygon.polygon.normal(),
    );
    Some(hoisted(
        #[inline(always)]
        move |w: DVec3| {
            if (two_sided | (w.dot(facing) < 0.0)) & seen.hits(w) {
                radiance
            } else {
                0.0
            }
        },
    ))
}

/// [`technique_batch`]'s light-sampling techniques only (light, MIS):
/// their loops for a light sampler specialised to one shape, without
/// compiling every other technique's loop again for it. `None` for the
/// other techniques. The sampler is given each sample's index in the block
/// and its coordinates (`u` for light sampling, `v` for MIS), so that it
/// may read directions drawn beforehand ([`disk_table_batch`]).
#[inline(always)]
fn sampled_batch(
    emitter: &PreparedEmitter,
    receiver: &Receiver,
    radiance: impl Fn(DVec3) -> f64,
    light_sample: impl Fn(usize, DVec2) -> Option<LightDirection>,
    light_pdf: impl Fn(DVec3) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> Option<PartHits> {
    let radiance_cos = radiance_cos_of(receiver.normal, radiance);
    match emitter.technique {
        Technique::Light => Some(light_batch(
            emitter.light_radiance,
            receiver.normal,
            radiance_cos,
            light_sample,
            block,
            out,
        )),
        Technique::Mis(h) => Some(mis_batch(
            h,
            receiver,
            emitter.light_radiance,
            radiance_cos,
            light_sample,
            light_pdf,
            block,
            out,
        )),
        _ => None,
    }
}

/// [`sampled_batch`] through a polygon's solid-angle sampler in one of its
/// inline forms ([`UniformSolidAngle`]), copied into the loop so that its
/// constants stay in registers (through a reference, the compiler reloaded
/// them and did not vectorise).
#[inline(always)]
fn solid_angle_batch(
    emitter: &PreparedEmitter,
    receiver: &Receiver,
    radiance: impl Fn(DVec3) -> f64,
    sampler: &impl UniformSolidAngle,
    block: &Block<'_>,
    out: &mut [f64],
) -> Option<PartHits> {
    let sampler = &{ *sampler };
    sampled_batch(
        emitter,
        receiver,
        radiance,
        #[inline(always)]
        |_, u| sample_solid_angle(sampler, u),
        #[inline(always)]
        |w| sampler.density(w),
        block,
        out,
    )
}

/// Light sampling and MIS of a disk through its tabulated sampler: the
/// light directions of [`DISK_TABLE_BATCH`] samples at a time are drawn
/// first, by the sampler's batch
/// ([`TabulatedDiskSolidAngle::sample_directions`], which vectorises: the
/// per-sample sampler is a table lookup and a variable-length quadrature
/// that do not), and the light and MIS loops then read them. The same
/// directions and densities as [`sample_disk_table`], so the same values
/// to the bit. `None` for the other techniques.
#[inline(always)]
fn disk_table_batch(
    emitter: &PreparedEmitter,
    receiver: &Receiver,
    disk: &TabulatedDiskSolidAngle,
    radiance: impl Fn(DVec3) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> Option<PartHits> {
    let mis = match emitter.technique {
        Technique::Light => false,
        Technique::Mis(_) => true,
        _ => return None,
    };
    // The light sample's coordinates: u for light sampling, v for MIS.
    let (sx, sy) = if mis {
        (block.vx, block.vy)
    } else {
        (block.ux, block.uy)
    };
    let disk = &{ disk };
    // The density's sampler copied, not read through `disk`: MIS reads it
    // for every cosine direction, and through the reference its loop stayed
    // scalar (as the f32 kernels' did).
    let plain = &{ *disk.sampler() };
    in_direction_batches(
        block,
        (sx, sy),
        out,
        #[inline(always)]
        |sx, sy, dx, dy, dz| disk.sample_directions(sx, sy, dx, dy, dz),
        #[inline(always)]
        |part, [dx, dy, dz], out| {
            sampled_batch(
                emitter,
                receiver,
                // A closure, not `&radiance`: the call through the
                // reference was left out of line (a scalar call per
                // sample, 10 % of a close disk's MIS sample).
                #[allow(clippy::redundant_closure)]
                #[inline(always)]
                |w| radiance(w),
                #[inline(always)]
                |i, _| disk_table_direction(disk, DVec3::new(dx[i], dy[i], dz[i])),
                #[inline(always)]
                |w| plain.pdf(w),
                part,
                out,
            )
        },
    )
}

/// Directions drawn [`DISK_TABLE_BATCH`] at a time, for the samplers whose
/// one-sample form does not vectorise but whose batch does
/// (`sample_directions` of the tabulated disk, the tabulated projected
/// polygon, projected caps and spheres): `draw(sx, sy, dx, dy, dz)` fills
/// the batch's directions from the light sample's coordinates
/// `(sx, sy)`, then `score(part, [dx, dy, dz], out)` runs the kernel over
/// the same range of the block. Adds up the hits; `None` if `score` gives
/// none.
#[inline(always)]
fn in_direction_batches(
    block: &Block<'_>,
    (sx, sy): (&[f64], &[f64]),
    out: &mut [f64],
    mut draw: impl FnMut(&[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]),
    mut score: impl FnMut(&Block<'_>, [&[f64]; 3], &mut [f64]) -> Option<PartHits>,
) -> Option<PartHits> {
    let mut directions = [[0.0f64; DISK_TABLE_BATCH]; 3];
    let mut hits = [0u64; 2];
    let mut start = 0;
    while start < out.len() {
        let m = DISK_TABLE_BATCH.min(out.len() - start);
        let range = start..start + m;
        let [dx, dy, dz] = &mut directions;
        let (dx, dy, dz) = (&mut dx[..m], &mut dy[..m], &mut dz[..m]);
        draw(&sx[range.clone()], &sy[range.clone()], dx, dy, dz);
        let part = Block {
            ux: &block.ux[range.clone()],
            uy: &block.uy[range.clone()],
            vx: &block.vx[range.clone()],
            vy: &block.vy[range.clone()],
            store: block.store,
        };
        let got = score(&part, [&*dx, &*dy, &*dz], &mut out[range])?;
        hits[0] += got[0];
        hits[1] += got[1];
        start += m;
    }
    Some(hits)
}

/// `value(w)` of each direction w that `draw` fills in batches from the
/// block's u ([`in_direction_batches`]), through [`single`]: projected
/// sampling through the samplers' batches.
#[inline(always)]
fn drawn_values(
    block: &Block<'_>,
    out: &mut [f64],
    draw: impl FnMut(&[f64], &[f64], &mut [f64], &mut [f64], &mut [f64]),
    value: impl Fn(DVec3) -> f64,
) -> Option<PartHits> {
    in_direction_batches(
        block,
        (block.ux, block.uy),
        out,
        draw,
        #[inline(always)]
        |part, [dx, dy, dz], out| {
            Some(single(
                part,
                out,
                #[inline(always)]
                |i, _| value(DVec3::new(dx[i], dy[i], dz[i])),
            ))
        },
    )
}

impl PreparedEmitter {
    /// Projected sampling of a sphere or sky cap wholly above the horizon,
    /// in one branch-free loop (`WholeProjectedSphere`,
    /// `WholeProjectedCap`), of one across the horizon and of a polygon
    /// through its sampler's batch (`sample_directions`):
    /// [`EmitterProjected::sample`] and `projected_value`'s
    /// L max(n·ω, 0)/p to the bit. `None` for other emitters and for
    /// polygons of more vertices than one sampler takes (the one-sample
    /// path).
    #[inline(always)]
    fn projected_whole_batch(
        &self,
        receiver: &Receiver,
        block: &Block<'_>,
        out: &mut [f64],
    ) -> Option<PartHits> {
        let radiance = self.uniform_radiance();
        let normal = receiver.normal;
        // L (n·ω)/p of a drawn direction; 0 where `EmitterProjected::sample`
        // would draw none (a density that is not positive and finite).
        let value = hoisted(
            #[inline(always)]
            move |(direction, pdf): (DVec3, f64)| {
                let v = radiance * direction.dot(normal).max(0.0) / pdf;
                if pdf > 0.0 && pdf.is_finite() {
                    v
                } else {
                    0.0
                }
            },
        );
        match &self.projected {
            EmitterProjected::Cap(cap, r) => {
                let (frame, cap_normal) = (&{ r.frame }, r.normal);
                let omega = cap.projected_solid_angle();
                let cap_value = hoisted(
                    #[inline(always)]
                    move |local: DVec3| {
                        let w = frame.from_local(local);
                        value((w, cap_normal.dot(w).max(0.0) / omega))
                    },
                );
                if let Some(whole) = cap.whole() {
                    let whole = &whole;
                    return Some(single(
                        block,
                        out,
                        #[inline(always)]
                        |_, u| cap_value(whole.sample(u).direction),
                    ));
                }
                // Across the horizon: the cap's batch
                // (`ProjectedCap::sample_directions`), the directions of
                // `sample` to the bit.
                let cap = &{ *cap };
                drawn_values(
                    block,
                    out,
                    #[inline(always)]
                    |ux, uy, dx, dy, dz| cap.sample_directions(ux, uy, dx, dy, dz),
                    cap_value,
                )
            }
            EmitterProjected::Sphere(s) => {
                if let Some(whole) = s.whole() {
                    let whole = &whole;
                    return Some(single(
                        block,
                        out,
                        #[inline(always)]
                        |_, u| {
                            let d = whole.sample_direction(u);
                            value((d.direction, d.pdf))
                        },
                    ));
                }
                // Across the horizon: the sphere's batch
                // (`ProjectedSphere::sample_directions`), the directions of
                // `sample_direction` to the bit, and their density.
                let sphere = &{ *s };
                drawn_values(
                    block,
                    out,
                    #[inline(always)]
                    |ux, uy, dx, dy, dz| sphere.sample_directions(ux, uy, dx, dy, dz),
                    #[inline(always)]
                    |w| value((w, sphere.sample_density(w))),
                )
            }
            EmitterProjected::PolygonTable(p) => {
                // The batch of sector-sorted, branch-free passes
                // (`TabulatedProjectedPolygon::sample_directions`): the
                // directions of `sample`, to the bit, and their density
                // from a copy of the sampler.
                let plain = &{ *p.sampler() };
                drawn_values(
                    block,
                    out,
                    #[inline(always)]
                    |ux, uy, dx, dy, dz| p.sample_directions(ux, uy, dx, dy, dz),
                    #[inline(always)]
                    |w| value((w, plain.sample_density(w))),
                )
            }
            _ => None,
        }
    }
}

/// How many light directions [`disk_table_batch`] (and projected
/// sampling of a polygon) draws at a time (three arrays of f64 on the
/// stack, 3 KB).
const DISK_TABLE_BATCH: usize = 128;

/// L(ω) max(cos θ, 0) from the radiance lookup `radiance`, for the unit
/// normal `normal`. The lookup runs for every lane and the result is
/// selected (the same value): under the branch, the emitter's data were
/// reloaded by masked gathers on every iteration.
#[inline(always)]
fn radiance_cos_of(normal: DVec3, radiance: impl Fn(DVec3) -> f64) -> impl Fn(DVec3) -> f64 {
    hoisted(
        #[inline(always)]
        move |w: DVec3| {
            let cos = w.dot(normal);
            let l = radiance(w);
            if cos > 0.0 {
                l * cos
            } else {
                0.0
            }
        },
    )
}

/// Light sampling: L cos θ / p of every direction the light sampler draws,
/// with L known for every drawn direction (`light_radiance`) or looked up.
#[inline(always)]
fn light_batch(
    light_radiance: Option<f64>,
    normal: DVec3,
    radiance_cos: impl Fn(DVec3) -> f64,
    light_sample: impl Fn(usize, DVec2) -> Option<LightDirection>,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    // One loop per case, decided once: with the test inside, the loop did
    // not vectorise for AVX2 (measured on the uniform sky). The sampler
    // goes in through a closure, not as `&light_sample`: a call through
    // the reference was left out of line, a scalar call per sample
    // compiled for the baseline set (a sky cap's light sample took 22 ns
    // in f64 against 1.1 in f32).
    match light_radiance {
        Some(uniform) => drawn_light_values(
            #[allow(clippy::redundant_closure)]
            #[inline(always)]
            |i, u| light_sample(i, u),
            #[inline(always)]
            |s| uniform * s.direction.dot(normal).max(0.0) / s.pdf,
            block,
            out,
        ),
        None => drawn_light_values(
            #[allow(clippy::redundant_closure)]
            #[inline(always)]
            |i, u| light_sample(i, u),
            #[inline(always)]
            |s| radiance_cos(s.direction) / s.pdf,
            block,
            out,
        ),
    }
}

/// `value(s)` of every light direction `s` that `light_sample` draws, 0
/// where it draws none: branch-free, as in `mis_batch` (an undrawn lane
/// evaluates `value` on [`NO_LIGHT_DIRECTION`] and discards it).
#[inline(always)]
fn drawn_light_values(
    light_sample: impl Fn(usize, DVec2) -> Option<LightDirection>,
    value: impl Fn(LightDirection) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    single(
        block,
        out,
        #[inline(always)]
        |i, u| {
            let (s, drawn) = match light_sample(i, u) {
                Some(s) => (s, true),
                None => (NO_LIGHT_DIRECTION, false),
            };
            let v = value(s);
            if drawn {
                v
            } else {
                0.0
            }
        },
    )
}

/// `out[i] += f(i, u_i)` over the block, counting the non-zero values.
#[inline(always)]
fn single(block: &Block<'_>, out: &mut [f64], f: impl Fn(usize, DVec2) -> f64) -> PartHits {
    let mut hits = 0u64;
    block.each(
        out,
        #[inline(always)]
        |i, u, _| {
            let v = f(i, u);
            hits += u64::from(v != 0.0);
            v
        },
    );
    [hits, 0]
}

/// The loop of `emitter`'s technique over a block, with the emitter's
/// radiance lookup, light sampler and light density passed in (already
/// specialised to its kind). The arithmetic is
/// [`PreparedEmitter::evaluate_u`]'s, in the same order.
#[inline(always)]
fn technique_batch(
    emitter: &PreparedEmitter,
    receiver: &Receiver,
    radiance: impl Fn(DVec3) -> f64,
    light_sample: impl Fn(DVec2) -> Option<LightDirection>,
    light_pdf: impl Fn(DVec3) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    // Copies, not references: the compiler keeps a local's fields in
    // registers across the loop, where loads through a reference inside a
    // branch became masked gathers on every iteration.
    let frame = &{ receiver.frame };
    let normal = receiver.normal;
    // Through a closure, not `&radiance` (see `disk_table_batch`).
    let radiance_cos = radiance_cos_of(
        normal,
        #[allow(clippy::redundant_closure)]
        #[inline(always)]
        |w| radiance(w),
    );
    match emitter.technique {
        // Projected sampling (but for whole caps and spheres, which
        // `projected_whole_batch` took) and the control variate have no
        // block kernel: the one-sample path, sample by sample (the same
        // bits).
        Technique::Projected | Technique::ControlVariate => single(
            block,
            out,
            #[inline(always)]
            |_, u| emitter.evaluate_u(receiver, u, DVec2::ZERO),
        ),
        Technique::UniformHemisphere => single(
            block,
            out,
            #[inline(always)]
            |_, u| {
                let local = sample_uniform_hemisphere(u);
                radiance_cos(frame.from_local(local)) / pdf_uniform_hemisphere(local)
            },
        ),
        Technique::CosineHemisphere => single(
            block,
            out,
            #[inline(always)]
            |_, u| {
                let local = sample_cosine_hemisphere(u);
                let w = frame.from_local(local);
                let l = radiance(w);
                if local.z > 0.0 {
                    std::f64::consts::PI * l
                } else {
                    0.0
                }
            },
        ),
        Technique::Light => light_batch(
            emitter.light_radiance,
            normal,
            #[allow(clippy::redundant_closure)]
            #[inline(always)]
            |w| radiance_cos(w),
            #[inline(always)]
            |_, u| light_sample(u),
            block,
            out,
        ),
        Technique::Area => {
            if let Some(l) = emitter.area_radiance {
                return area_known_radiance_batch(&emitter.area, l, normal, block, out);
            }
            let through = hoisted(
                #[inline(always)]
                |s: Option<lambert_sampling::f64::LightSample>| match s {
                    Some(s) => radiance_cos(s.direction) / s.pdf,
                    None => 0.0,
                },
            );
            match &emitter.area {
                EmitterArea::Sphere(a, r) => single(
                    block,
                    out,
                    #[inline(always)]
                    |_, u| through(a.sample(r.point, r.normal, u)),
                ),
                EmitterArea::Disk(a, r) => single(
                    block,
                    out,
                    #[inline(always)]
                    |_, u| through(a.sample(r.point, r.normal, u)),
                ),
                EmitterArea::Polygon(a, r) => polygon_area_batch(
                    a,
                    r.point,
                    r.normal,
                    #[inline(always)]
                    |s| through(Some(s)),
                    block,
                    out,
                ),
                EmitterArea::None => [0, 0],
            }
        }
        Technique::Mis(h) => mis_batch(
            h,
            receiver,
            emitter.light_radiance,
            radiance_cos,
            #[inline(always)]
            |_, u| light_sample(u),
            light_pdf,
            block,
            out,
        ),
    }
}

/// Area sampling where every drawn point is known to see radiance `l`
/// ([`PreparedEmitter::area_radiance`]): L max(n·ω, 0)/p, no lookup.
/// Spheres and disks draw every lane and select on p > 0
/// (`sample_or_zero`), so the loop vectorises; a polygon picks its fan
/// triangle per sample and stays a scalar loop.
#[inline(always)]
fn area_known_radiance_batch(
    area: &EmitterArea,
    l: f64,
    normal: DVec3,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    let value = hoisted(
        #[inline(always)]
        |s: lambert_sampling::f64::LightSample| {
            let v = l * s.direction.dot(normal).max(0.0) / s.pdf;
            if s.pdf > 0.0 {
                v
            } else {
                0.0
            }
        },
    );
    match area {
        EmitterArea::Sphere(a, r) => {
            let (a, p) = (&{ *a }, r.point);
            single(
                block,
                out,
                #[inline(always)]
                |_, u| value(a.sample_or_zero(p, u)),
            )
        }
        EmitterArea::Disk(a, r) => {
            let (a, p) = (&{ *a }, r.point);
            single(
                block,
                out,
                #[inline(always)]
                |_, u| value(a.sample_or_zero(p, u)),
            )
        }
        EmitterArea::Polygon(a, r) => polygon_area_batch(a, r.point, r.normal, value, block, out),
        EmitterArea::None => [0, 0],
    }
}

/// Area sampling of a polygon over a block: `out[i] += value(s)` for each
/// light sample `s` the sampler gives (0 where it gives none). Through a
/// [`PolygonAreaFan`](lambert_sampling::f64::PolygonAreaFan) when the fan has 1 to [`MAX_FAN`] triangles (every
/// polygon of up to six vertices), whose loop vectorises; the sampler's
/// own `sample` otherwise, a call per sample. The same values either way.
#[inline(always)]
fn polygon_area_batch(
    sampler: &PolygonAreaSampler,
    point: DVec3,
    normal: DVec3,
    value: impl Fn(LightSample) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    /// The loop through the fan of `N` triangles, if the polygon's has `N`.
    #[inline(always)]
    fn through_fan<const N: usize>(
        sampler: &PolygonAreaSampler,
        (point, normal): (DVec3, DVec3),
        value: &impl Fn(LightSample) -> f64,
        block: &Block<'_>,
        out: &mut [f64],
    ) -> Option<PartHits> {
        let fan = sampler.fan::<N>(point, normal)?;
        Some(single(
            block,
            out,
            #[inline(always)]
            |_, u| {
                let s = fan.sample_or_zero(u);
                // `sample` gives a sample exactly where its density is
                // positive; the select drops the others' unspecified fields.
                if s.pdf > 0.0 {
                    value(s)
                } else {
                    0.0
                }
            },
        ))
    }
    // Plain branches, not `Option::or_else`: a closure not inlined would
    // take its loop out of the kernel's instruction set.
    let at = (point, normal);
    if let Some(hits) = through_fan::<1>(sampler, at, &value, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<2>(sampler, at, &value, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<3>(sampler, at, &value, block, out) {
        return hits;
    }
    if let Some(hits) = through_fan::<MAX_FAN>(sampler, at, &value, block, out) {
        return hits;
    }
    single(
        block,
        out,
        #[inline(always)]
        |_, u| match sampler.sample(point, normal, u) {
            Some(s) => value(s),
            None => 0.0,
        },
    )
}

/// The most triangles of a polygon fan [`polygon_area_batch`] has a
/// vectorised loop for.
const MAX_FAN: usize = 4;

/// MIS: the weighted cosine-sampled value from `u` plus the weighted
/// light-sampled value from `v` (Veach & Guibas 1995), counted apart.
///
/// (Spheres and sky caps, whose light sampler is a cone, take
/// [`cone_mis_batch`] instead.)
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn mis_batch(
    h: Heuristic,
    receiver: &Receiver,
    light_radiance: Option<f64>,
    radiance_cos: impl Fn(DVec3) -> f64,
    light_sample: impl Fn(usize, DVec2) -> Option<LightDirection>,
    light_pdf: impl Fn(DVec3) -> f64,
    block: &Block<'_>,
    out: &mut [f64],
) -> PartHits {
    let frame = &{ receiver.frame };
    let normal = receiver.normal;
    let (known_radiance, uniform) = (light_radiance.is_some(), light_radiance.unwrap_or(0.0));
    let mut hits = [0u64; 2];
    block.each(
        out,
        #[inline(always)]
        |i, u, v| {
            let local = sample_cosine_hemisphere(u);
            let w = frame.from_local(local);
            let p_cos = pdf_cosine_hemisphere(local);
            // Computed for every lane and selected: under a branch, the
            // compiler could not keep the light's data in registers and
            // reloaded it by masked gathers on every iteration.
            let p_light = light_pdf(w);
            let l_cos = radiance_cos(w);
            let weighted = h.weighted(l_cos, p_cos, p_light);
            let cosine = if p_cos > 0.0 { weighted } else { 0.0 };
            // Also branch-free, for the same reason (a direction and density
            // stand in where the sampler gave none; their value is not used).
            let (s, drawn) = match light_sample(i, v) {
                Some(s) => (s, true),
                None => (NO_LIGHT_DIRECTION, false),
            };
            let local = frame.to_local(s.direction);
            let p_cos = pdf_cosine_hemisphere(local);
            // The lookup is skipped where every light sample sees the
            // emitter (`light_sample_radiance`), as in `mis_parts`.
            let l_cos = if known_radiance {
                uniform * s.direction.dot(normal).max(0.0)
            } else {
                radiance_cos(s.direction)
            };
            let weighted = h.weighted(l_cos, s.pdf, p_cos);
            let light = if drawn { weighted } else { 0.0 };
            hits[0] += u64::from(cosine != 0.0);
            hits[1] += u64::from(light != 0.0);
            cosine + light
        },
    );
    hits
}
