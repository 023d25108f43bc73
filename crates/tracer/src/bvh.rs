//! A bounding volume hierarchy over boxed primitives: binned
//! surface-area-heuristic construction and ordered traversal.
//!
//! Construction follows pbrt-v4 §7.3 (Pharr, Jakob & Humphreys): each node
//! splits its primitives along the axis of largest centroid extent at the
//! boundary of 16 bins that minimises the surface-area heuristic
//! C = c_t + (A_l N_l + A_r N_r) / A (MacDonald & Booth 1990, "Heuristics
//! for ray tracing using space subdivision"; c_t = 1/8 the cost of a
//! primitive test), and makes a leaf where no split is cheaper than
//! testing its primitives. The tree is stored depth-first in one array
//! (first child next to its parent, the second by index), and traversed
//! with a fixed stack, nearer child first by the ray's direction sign.
//!
//! Why our own and not a crate: the hierarchy must bound lambert's f64
//! shapes with boxes whose slab test is conservative under rounding (the
//! far distance enlarged by 1 + 2γ₃, [`Aabb::hit`]) so that watertight
//! triangles and error-bounded hits stay so; the kept BVH crates build f32
//! boxes (`obvhs`) or allocate a candidate list per ray (`bvh`).

use crate::aabb::Aabb;
use lambert_geometry::f64::Ray;

/// Most primitives in a leaf.
const MAX_LEAF: usize = 4;
/// SAH bins per split.
const BINS: usize = 16;
/// Cost of a node visit relative to a primitive test.
const TRAVERSAL_COST: f64 = 0.125;
/// Depth past which splits are by median count (bounds the depth, and so
/// the traversal stack, whatever the input).
const MEDIAN_DEPTH: usize = 48;
/// The traversal stack: MEDIAN_DEPTH + log2(u32::MAX) + margin.
const STACK: usize = 96;

/// One node: a leaf (count > 0) of the primitives `offset .. offset +
/// count`, or an interior node (count = 0) whose first child follows it
/// and whose second child is at `offset`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    offset: u32,
    count: u16,
    axis: u8,
}

/// A bounding volume hierarchy over primitives given by their boxes (see
/// the module docs). It stores indices only: [`Bvh::build`] returns the
/// order in which the caller must store its primitives so that each leaf's
/// are contiguous.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: Vec<Node>,
}

struct Item {
    bounds: Aabb,
    centroid: glam::DVec3,
    index: u32,
}

impl Bvh {
    /// Builds the hierarchy over `bounds` (one box per primitive) and
    /// returns it with the primitive order: leaf primitive k is
    /// `order[k]` of the input.
    ///
    /// # Panics
    /// If there are more than u32::MAX primitives.
    pub fn build(bounds: &[Aabb]) -> (Bvh, Vec<u32>) {
        assert!(u32::try_from(bounds.len()).is_ok(), "too many primitives");
        let mut items: Vec<Item> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| Item {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
            })
            .collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * bounds.len().max(1)),
        };
        if !items.is_empty() {
            bvh.split(&mut items, 0, 0);
        }
        let order = items.iter().map(|i| i.index).collect();
        (bvh, order)
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Appends the subtree of `items` (at `offset` in the final order).
    fn split(&mut self, items: &mut [Item], offset: usize, depth: usize) {
        let bounds = items.iter().fold(Aabb::EMPTY, |b, i| b.union(i.bounds));
        let node = self.nodes.len();
        let n = items.len();
        let leaf = |bvh: &mut Bvh| {
            bvh.nodes.push(Node {
                bounds,
                offset: offset as u32,
                count: n as u16,
                axis: 0,
            })
        };
        if n <= 1 {
            return leaf(self);
        }
        let centroids = items
            .iter()
            .fold(Aabb::EMPTY, |b, i| b.with_point(i.centroid));
        let axis = centroids.largest_axis();
        let (lo, hi) = (centroids.min[axis], centroids.max[axis]);
        let separable = hi > lo;
        let sah = if separable && depth < MEDIAN_DEPTH {
            self.sah_split(items, &bounds, axis, lo, hi)
        } else {
            None
        };
        let mid = match sah {
            Some(m) => m,
            // A small leaf is cheaper, or every centroid is at one place
            // (no split separates them).
            None if n <= MAX_LEAF || (!separable && n <= u16::MAX as usize) => return leaf(self),
            // Too big for a leaf: split by count.
            None => median(items, axis),
        };
        self.nodes.push(Node {
            bounds,
            offset: 0,
            count: 0,
            axis: axis as u8,
        });
        let (left, right) = items.split_at_mut(mid);
        self.split(left, offset, depth + 1);
        self.nodes[node].offset = self.nodes.len() as u32;
        self.split(right, offset + mid, depth + 1);
    }

    /// The SAH split of `items` along `axis`: the partition point, or
    /// `None` when a leaf is cheaper (and small enough).
    fn sah_split(
        &self,
        items: &mut [Item],
        bounds: &Aabb,
        axis: usize,
        lo: f64,
        hi: f64,
    ) -> Option<usize> {
        let n = items.len();
        let scale = BINS as f64 / (hi - lo);
        let bin_of = |c: f64| (((c - lo) * scale) as usize).min(BINS - 1);
        let mut counts = [0usize; BINS];
        let mut boxes = [Aabb::EMPTY; BINS];
        for item in items.iter() {
            let b = bin_of(item.centroid[axis]);
            counts[b] += 1;
            boxes[b] = boxes[b].union(item.bounds);
        }
        // Costs of splitting after bin i, from sweeps in both directions.
        let mut left_area = [0.0; BINS];
        let mut left_count = [0usize; BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        for i in 0..BINS {
            acc = acc.union(boxes[i]);
            count += counts[i];
            left_area[i] = acc.surface_area();
            left_count[i] = count;
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0);
        let mut best = (f64::INFINITY, usize::MAX);
        for i in (1..BINS).rev() {
            acc = acc.union(boxes[i]);
            count += counts[i];
            let l = i - 1;
            if left_count[l] == 0 || count == 0 {
                continue;
            }
            let cost = left_area[l] * left_count[l] as f64 + acc.surface_area() * count as f64;
            if cost < best.0 {
                best = (cost, l);
            }
        }
        let area = bounds.surface_area();
        let split_cost = if area > 0.0 {
            TRAVERSAL_COST + best.0 / area
        } else {
            f64::INFINITY
        };
        if best.1 == usize::MAX || (n <= MAX_LEAF && split_cost >= n as f64) {
            return None;
        }
        let boundary = best.1;
        let mut mid = 0;
        for k in 0..n {
            if bin_of(items[k].centroid[axis]) <= boundary {
                items.swap(k, mid);
                mid += 1;
            }
        }
        (mid > 0 && mid < n).then_some(mid)
    }

    /// The primitive of the nearest hit along `ray` before `t_max`:
    /// `hit(k, t)` tests leaf primitive k for a hit closer than t and
    /// returns its distance. Returns (k, distance).
    #[inline]
    pub fn nearest<F>(&self, ray: &Ray, t_max: f64, mut hit: F) -> Option<(usize, f64)>
    where
        F: FnMut(usize, f64) -> Option<f64>,
    {
        let mut best = None;
        self.walk(ray, t_max, |k, t_max| {
            if let Some(t) = hit(k, *t_max) {
                *t_max = t;
                best = Some((k, t));
            }
            false
        });
        best
    }

    /// Whether any primitive is hit before `t_max`: `hit(k, t)` tests leaf
    /// primitive k. Stops at the first hit (shadow rays).
    #[inline]
    pub fn any<F>(&self, ray: &Ray, t_max: f64, mut hit: F) -> bool
    where
        F: FnMut(usize, f64) -> bool,
    {
        self.walk(ray, t_max, |k, t_max| hit(k, *t_max))
    }

    /// Visits the leaf primitives whose boxes the ray meets before the
    /// current `t_max`, nearer child first: `leaf(k, &mut t_max)` may
    /// shorten the ray, and returns true to stop (then `walk` returns
    /// true).
    #[inline]
    fn walk<F>(&self, ray: &Ray, mut t_max: f64, mut leaf: F) -> bool
    where
        F: FnMut(usize, &mut f64) -> bool,
    {
        if self.nodes.is_empty() {
            return false;
        }
        let inv = ray.direction.recip();
        let negative = [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0];
        let mut stack = [0u32; STACK];
        let mut top = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.bounds.hit(ray, inv, t_max) {
                if n.count > 0 {
                    let start = n.offset as usize;
                    for k in start..start + n.count as usize {
                        if leaf(k, &mut t_max) {
                            return true;
                        }
                    }
                } else {
                    let (near, far) = if negative[n.axis as usize] {
                        (n.offset as usize, node + 1)
                    } else {
                        (node + 1, n.offset as usize)
                    };
                    stack[top] = far as u32;
                    top += 1;
                    node = near;
                    continue;
                }
            }
            if top == 0 {
                return false;
            }
            top -= 1;
            node = stack[top] as usize;
        }
    }
}

/// Partitions `items` at the median centroid along `axis`; returns the
/// split point (n/2).
fn median(items: &mut [Item], axis: usize) -> usize {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn unit_box(c: DVec3) -> Aabb {
        Aabb {
            min: c - DVec3::splat(0.25),
            max: c + DVec3::splat(0.25),
        }
    }

    /// The nearest hit through the tree equals the brute-force nearest for
    /// boxes treated as primitives (hit distance = slab entry).
    #[test]
    fn finds_what_brute_force_finds() {
        let mut boxes = Vec::new();
        for i in 0..1000u32 {
            let h = |k: u32| {
                ((i.wrapping_mul(2654435761).wrapping_add(k * 40503)) % 1000) as f64 / 100.0
            };
            boxes.push(unit_box(DVec3::new(h(1), h(2), h(3))));
        }
        let (bvh, order) = Bvh::build(&boxes);
        let mut seen = order.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..1000).collect::<Vec<u32>>());
        let entry = |b: &Aabb, ray: &Ray| -> Option<f64> {
            let inv = ray.direction.recip();
            let t0 = (b.min - ray.origin) * inv;
            let t1 = (b.max - ray.origin) * inv;
            let near = t0.min(t1).max_element();
            let far = t0.max(t1).min_element();
            (near <= far && near > 0.0).then_some(near)
        };
        for j in 0..200 {
            let a = j as f64 * 0.37;
            let ray = Ray::new(
                DVec3::new(-5.0, 5.0, 5.0),
                DVec3::new(1.0, 0.3 * a.sin(), 0.3 * a.cos()).normalize(),
            );
            let brute = boxes
                .iter()
                .filter_map(|b| entry(b, &ray))
                .fold(f64::INFINITY, f64::min);
            let found = bvh.nearest(&ray, f64::INFINITY, |k, t| {
                entry(&boxes[order[k] as usize], &ray).filter(|&d| d < t)
            });
            assert_eq!(found.map_or(f64::INFINITY, |f| f.1), brute, "ray {j}");
            let any = bvh.any(&ray, f64::INFINITY, |k, _| {
                entry(&boxes[order[k] as usize], &ray).is_some()
            });
            assert_eq!(any, brute.is_finite());
        }
    }

    #[test]
    fn empty_and_coincident_inputs() {
        let (bvh, order) = Bvh::build(&[]);
        assert!(order.is_empty());
        let ray = Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(bvh.nearest(&ray, f64::INFINITY, |_, _| Some(1.0)), None);
        // 100 identical boxes: one leaf.
        let boxes = vec![unit_box(DVec3::X * 3.0); 100];
        let (bvh, _) = Bvh::build(&boxes);
        assert!(bvh.node_count() >= 1);
        assert!(bvh.any(&ray, f64::INFINITY, |_, _| true));
    }
}
