//! The light-sampling API inside a path tracer's shading loop, in f32, with
//! the tracer's own random number generator and its own shadow rays.
//!
//! A floor (a plane) under a sphere light of radius 1 whose center is 10
//! units up, with a small sphere hanging between the two as an occluder.
//! The light sampler is built once; at each shading point the loop calls
//! `sample(point, normal, u)`, casts a shadow ray toward the returned point,
//! stopping short of it by the returned distance, and accumulates
//! E = L cos θ / p(ω) for the unblocked samples. The point right under the
//! light sees all of it (closed form E = Lπ sin²α, sin α = r/d); the point
//! whose view of the light passes the occluder's center is in its shadow.
//!
//! Run with `cargo run --release -p lambert-sampling --example shading_loop`.

use glam::{Vec2, Vec3};
use lambert_geometry::f32::{Intersect, Plane, Ray, Sphere};
use lambert_sampling::f32::{LightSampler, SphereLightSampler};

/// The tracer's own generator: PCG32 (O'Neill 2014), XSH-RR output.
struct Pcg32 {
    state: u64,
    inc: u64,
}

impl Pcg32 {
    fn new(seed: u64, stream: u64) -> Self {
        let mut rng = Pcg32 {
            state: 0,
            inc: (stream << 1) | 1,
        };
        rng.next_u32();
        rng.state = rng.state.wrapping_add(seed);
        rng.next_u32();
        rng
    }

    fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(6364136223846793005).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        xorshifted.rotate_right((old >> 59) as u32)
    }

    /// u ∈ [0,1)² in f32 from the top 24 bits (never rounds to 1).
    fn next_2d(&mut self) -> Vec2 {
        let scale = 1.0 / (1u32 << 24) as f32;
        Vec2::new(
            (self.next_u32() >> 8) as f32 * scale,
            (self.next_u32() >> 8) as f32 * scale,
        )
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let floor = Plane::new(Vec3::ZERO, Vec3::Z)?;
    let light_shape = Sphere::new(Vec3::new(0.0, 0.0, 10.0), 1.0)?;
    let light = SphereLightSampler::new(light_shape);
    let light_radiance = 5.0f32;
    let occluder = Sphere::new(Vec3::new(2.0, 0.0, 5.0), 0.5)?;

    let mut rng = Pcg32::new(42, 7);
    let n = 1_000_000;
    for x in [0.0f32, 4.0] {
        // The shading point, found as a renderer finds it: a camera ray
        // hits the floor (the hit carries the error bound that keeps the
        // shadow rays from re-hitting the floor).
        let camera = Ray::new(
            Vec3::new(x, -3.0, 2.0),
            Vec3::new(0.0, 3.0, -2.0).normalize(),
        );
        let hit = floor
            .intersect(&camera, f32::INFINITY)
            .expect("the camera sees the floor");
        let normal = hit.facing_normal(camera.direction);
        let (mut sum, mut blocked) = (0.0f64, 0u32);
        for _ in 0..n {
            let Some(s) = light.sample(hit.point, normal, rng.next_2d()) else {
                continue;
            };
            // The shadow ray runs to the light point, not beyond it.
            let Some((shadow, distance)) = hit.spawn_ray_to(s.point) else {
                continue;
            };
            if occluder.hit_distance(&shadow, distance).is_some() {
                blocked += 1;
                continue;
            }
            sum += (light_radiance * s.direction.dot(normal).max(0.0) / s.pdf) as f64;
        }
        let estimate = sum / n as f64;
        println!(
            "point ({x}, 0, 0): E = {estimate:.6} W/m², {:.1} % of light samples in shadow",
            100.0 * blocked as f64 / n as f64
        );
    }
    let sin2_alpha = (1.0f64 / 10.0).powi(2);
    let exact = light_radiance as f64 * std::f64::consts::PI * sin2_alpha;
    println!("closed form under the light, unoccluded: E = Lπ sin²α = {exact:.6} W/m²");
    Ok(())
}
