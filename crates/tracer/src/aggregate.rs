//! All the primitives of a scene, and the nearest-hit and shadow queries
//! over them: brute force for a few primitives, a BVH above
//! [`BVH_THRESHOLD`].

use lambert_geometry::f64::{Hit, Ray, RayBatch};

use crate::bvh::Bvh;
use crate::shape::Shape;

/// The number of bounded primitives above which a scene gets a BVH.
///
/// Measured with the criterion benches `tracer_bvh_scenes` and
/// `tracer_bvh_threshold` (one thread, a loaded 2-core machine, so ratios
/// only): on the `whitted` scene (3 bounded primitives: two spheres and a
/// large parallelogram that most rays hit) brute force renders a ray-cast
/// frame 1.44× faster than the BVH (29.0 ms against 41.8 ms at 256×256);
/// on the `cornell` box (41: triangles, parallelograms, the light) the BVH
/// is 4.2× faster (1.62 s against 6.73 s, 64 light samples per pixel).
/// Against n random triangles in a cube, where many rays miss everything,
/// the BVH's root box already pays at n = 1 (1.19×) and wins 2.2× at n = 4,
/// 1.4× at 8, 2.1× at 16, 4.4× at 64: a triangle test costs ~300
/// instructions, a box test ~30. Spheres and planar shapes that cover
/// most of the view (the classic scenes) favour brute force at a few
/// primitives; at 4 and below brute force is kept.
pub const BVH_THRESHOLD: usize = 4;

/// A shape with its material (an index into the scene's materials).
#[derive(Clone, Debug, PartialEq)]
pub struct Primitive {
    /// The shape.
    pub shape: Shape,
    /// The index of its material in the scene.
    pub material: u32,
}

/// How the bounded primitives are searched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Acceleration {
    /// A BVH above [`BVH_THRESHOLD`] primitives, brute force below.
    Auto,
    /// Always brute force.
    BruteForce,
    /// Always a BVH.
    Bvh,
}

/// The primitives of a scene: the bounded ones (in BVH leaf order when
/// there is a BVH) and the unbounded planes, always tested one by one.
#[derive(Clone, Debug)]
pub struct Aggregate {
    bounded: Vec<Primitive>,
    bvh: Option<Bvh>,
    unbounded: Vec<Primitive>,
}

impl Aggregate {
    /// The aggregate of `primitives`, with a BVH when there are more than
    /// [`BVH_THRESHOLD`] bounded ones.
    pub fn new(primitives: Vec<Primitive>) -> Self {
        Aggregate::with_acceleration(primitives, Acceleration::Auto)
    }

    /// The aggregate of `primitives`, searched as `acceleration` says.
    pub fn with_acceleration(primitives: Vec<Primitive>, acceleration: Acceleration) -> Self {
        let (bounded, unbounded): (Vec<_>, Vec<_>) = primitives
            .into_iter()
            .partition(|p| p.shape.bounds().is_some());
        let use_bvh = match acceleration {
            Acceleration::Auto => bounded.len() > BVH_THRESHOLD,
            Acceleration::BruteForce => false,
            Acceleration::Bvh => true,
        };
        if !use_bvh {
            return Aggregate {
                bounded,
                bvh: None,
                unbounded,
            };
        }
        let boxes: Vec<_> = bounded
            .iter()
            .map(|p| p.shape.bounds().expect("partitioned as bounded"))
            .collect();
        let (bvh, order) = Bvh::build(&boxes);
        let mut slots: Vec<Option<Primitive>> = bounded.into_iter().map(Some).collect();
        let bounded = order
            .iter()
            .map(|&i| slots[i as usize].take().expect("a permutation"))
            .collect();
        Aggregate {
            bounded,
            bvh: Some(bvh),
            unbounded,
        }
    }

    /// Whether a BVH is used.
    pub fn has_bvh(&self) -> bool {
        self.bvh.is_some()
    }

    /// The number of primitives.
    pub fn len(&self) -> usize {
        self.bounded.len() + self.unbounded.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every primitive (bounded ones first).
    pub fn primitives(&self) -> impl Iterator<Item = &Primitive> {
        self.bounded.iter().chain(&self.unbounded)
    }

    /// The nearest hit along `ray` before `t_max`, and the primitive hit.
    /// Distances are compared first (cheap); the hit record is built for
    /// the winner only.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<(Hit, &Primitive)> {
        let (p, t) = self.nearest(ray, t_max)?;
        let hit = Hit {
            uv: p.shape.surface_parameters(ray, t),
            ..p.shape.hit_at(ray, t)
        };
        Some((hit, p))
    }

    /// The primitive with the nearest hit along `ray` before `t_max`, and
    /// the hit's distance (no hit record: [`Shape::hit_at`] builds it).
    #[inline]
    pub fn nearest(&self, ray: &Ray, t_max: f64) -> Option<(&Primitive, f64)> {
        let mut best: Option<(&Primitive, f64)> = None;
        let mut t_max = t_max;
        let test = |p: &'_ Primitive, t_max: f64| p.shape.hit_distance(ray, t_max);
        match &self.bvh {
            Some(bvh) => {
                if let Some((k, t)) = bvh.nearest(ray, t_max, |k, t| test(&self.bounded[k], t)) {
                    best = Some((&self.bounded[k], t));
                    t_max = t;
                }
            }
            None => {
                for p in &self.bounded {
                    if let Some(t) = test(p, t_max) {
                        best = Some((p, t));
                        t_max = t;
                    }
                }
            }
        }
        for p in &self.unbounded {
            if let Some(t) = test(p, t_max) {
                best = Some((p, t));
                t_max = t;
            }
        }
        best
    }

    /// Primitive `k` in the order of [`Aggregate::primitives`] (the ids
    /// the batch queries report).
    ///
    /// # Panics
    /// If `k` ≥ [`Aggregate::len`].
    #[inline]
    pub fn primitive(&self, k: u32) -> &Primitive {
        let k = k as usize;
        match self.bounded.get(k) {
            Some(p) => p,
            None => &self.unbounded[k - self.bounded.len()],
        }
    }

    /// [`Aggregate::nearest`] for every ray of a batch: where ray i meets a
    /// primitive at 0 < t < `nearest[i]`, `nearest[i]` becomes the nearest
    /// such t and `ids[i]` that primitive's index ([`Aggregate::primitive`]);
    /// rays that meet none keep both entries. The same decisions and
    /// distances as [`Aggregate::nearest`], to the bit; without a BVH the
    /// rays are tested shape by shape in vectorised loops.
    ///
    /// # Panics
    /// If `nearest` or `ids` is not as long as `rays`.
    #[inline(always)]
    pub fn nearest_in_batch(&self, rays: &RayBatch, nearest: &mut [f64], ids: &mut [u32]) {
        assert!(nearest.len() == rays.len() && ids.len() == rays.len());
        match &self.bvh {
            Some(bvh) => {
                for i in 0..rays.len() {
                    let ray = rays.get(i);
                    let test = |k: usize, t: f64| self.bounded[k].shape.hit_distance(&ray, t);
                    if let Some((k, t)) = bvh.nearest(&ray, nearest[i], test) {
                        nearest[i] = t;
                        ids[i] = k as u32;
                    }
                }
            }
            None => {
                for (k, p) in self.bounded.iter().enumerate() {
                    p.shape.nearest_in_batch(rays, k as u32, nearest, ids);
                }
            }
        }
        let offset = self.bounded.len();
        for (k, p) in self.unbounded.iter().enumerate() {
            p.shape
                .nearest_in_batch(rays, (offset + k) as u32, nearest, ids);
        }
    }

    /// [`Aggregate::occluded`] for every ray of a batch: sets `blocked[i]`
    /// when anything is hit along ray i before `t_max[i]` (rays already
    /// blocked stay so). A ray with `t_max[i]` ≤ 0 or NaN is never blocked
    /// (a caller switches rays off that way).
    ///
    /// # Panics
    /// If `t_max` or `blocked` is not as long as `rays`.
    #[inline(always)]
    pub fn occludes_in_batch(&self, rays: &RayBatch, t_max: &[f64], blocked: &mut [bool]) {
        assert!(t_max.len() == rays.len() && blocked.len() == rays.len());
        for p in &self.unbounded {
            p.shape.occludes_in_batch(rays, t_max, blocked);
        }
        match &self.bvh {
            Some(bvh) => {
                for i in 0..rays.len() {
                    // Nothing lies at 0 < t < t_max ≤ 0 (or NaN).
                    if !blocked[i] && t_max[i] > 0.0 {
                        let ray = rays.get(i);
                        let hits = |k: usize, t: f64| {
                            self.bounded[k].shape.hit_distance(&ray, t).is_some()
                        };
                        blocked[i] = bvh.any(&ray, t_max[i], hits);
                    }
                }
            }
            None => {
                for p in &self.bounded {
                    p.shape.occludes_in_batch(rays, t_max, blocked);
                }
            }
        }
    }

    /// Whether anything is hit along `ray` before `t_max` (shadow rays).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f64) -> bool {
        let hits = |p: &Primitive, t: f64| p.shape.hit_distance(ray, t).is_some();
        if self.unbounded.iter().any(|p| hits(p, t_max)) {
            return true;
        }
        match &self.bvh {
            Some(bvh) => bvh.any(ray, t_max, |k, t| hits(&self.bounded[k], t)),
            None => self.bounded.iter().any(|p| hits(p, t_max)),
        }
    }
}
