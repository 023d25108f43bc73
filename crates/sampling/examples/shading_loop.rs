//! The sampling crate inside a path tracer's shading loop, in f32 with the
//! tracer's own random number generator.
//!
//! A ground point under a sphere light of radius 1 whose center is 10 units
//! straight up, plus a dim uniform sky. For each shading point the loop
//! draws one light sample by solid angle and one cosine-weighted sky sample,
//! as a renderer's next-event estimation would, and accumulates
//! E = L_light·cos θ/p(ω) + L_sky·cos θ/p(ω). The closed forms are
//! E_light = L π sin²α (sin α = r/d) and E_sky = L_sky π.
//!
//! Run with `cargo run --release -p lambert-sampling --example shading_loop`.

use glam::{Vec2, Vec3};
use lambert_sampling::f32::{
    pdf_cosine_hemisphere, sample_cosine_hemisphere, Frame, SphereSolidAngle,
};

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

fn main() {
    let light_center = Vec3::new(0.0, 0.0, 10.0);
    let light_radius = 1.0f32;
    let light_radiance = 5.0f32;
    let sky_radiance = 0.2f32;
    let normal = Vec3::Z;
    let frame = Frame::from_normal(normal);

    let mut rng = Pcg32::new(42, 7);
    let n = 1_000_000;
    let mut sum = 0.0f64;
    for _ in 0..n {
        // Next-event estimation toward the sphere (solid-angle sampling).
        let light = SphereSolidAngle::new(Vec3::ZERO, light_center, light_radius)
            .expect("the shading point is outside the light");
        let s = light.sample(rng.next_2d());
        let cos_light = s.direction.dot(normal).max(0.0);
        let mut e = light_radiance * cos_light / s.pdf;

        // One cosine-weighted bounce direction, here lit by the sky
        // (the sphere occludes a little of it; ignored for clarity).
        let local = sample_cosine_hemisphere(rng.next_2d());
        let w = frame.from_local(local);
        e += sky_radiance * w.dot(normal) / pdf_cosine_hemisphere(local);
        sum += e as f64;
    }
    let estimate = sum / n as f64;
    let sin2_alpha = (light_radius / light_center.length()).powi(2) as f64;
    let pi = std::f64::consts::PI;
    let exact = light_radiance as f64 * pi * sin2_alpha + sky_radiance as f64 * pi;
    println!("estimated E = {estimate:.6} W/m²");
    println!("closed form = {exact:.6} W/m² (light Lπ sin²α + sky Lπ)");
    println!("relative error {:.2e}", (estimate - exact).abs() / exact);
}
