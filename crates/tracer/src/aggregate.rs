//! All the primitives of a scene, and the nearest-hit and shadow queries
//! over them: brute force for a few primitives, a BVH above
//! [`BVH_THRESHOLD`].

use lambert_geometry::f64::{Hit, Ray};

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
        let (p, _) = best?;
        // The same decision as hit_distance, so the record exists.
        p.shape.intersect(ray, f64::INFINITY).map(|h| (h, p))
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
