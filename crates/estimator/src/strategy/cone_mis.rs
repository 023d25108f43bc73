//! MIS on an emitter whose light sampler is a uniform cone of directions: a
//! sphere's subtended cone or a sky cap (Veach & Guibas 1995, the two-sample
//! estimator; the cone as in Shirley & Wang 1996 / pbrt-v4 §6.2.4).
//!
//! Such an emitter has uniform radiance L and a constant light density
//! p_l = 1/Ω inside its cone, so both halves of the MIS sample reduce to a
//! few dot products, each kept in the frame where it is cheapest:
//!
//! - the **cosine-sampled** direction ω stays in the receiver's frame
//!   (cos θ = ω_z, p_c = ω_z/π), and sees the emitter iff
//!   |ω − a|² ≤ 2(1 − cos θ_max), a the cone's axis in that frame
//!   (|ω − a|² = 2(1 − ω·a) for unit vectors, and this form has no
//!   cancellation near the axis, nor a division);
//! - the **light-sampled** direction ω′ stays in the cone's frame, where the
//!   receiver's normal n′ gives cos θ = n′·ω′ and p_c = max(cos θ, 0)/π.
//!
//! The two halves then share one division ([`Heuristic::weighted_pair`]). Neither
//! direction is rotated into the world, nor is a density evaluated by a
//! test against the emitter.

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::Heuristic;

/// `ConeMis` (f64) and `ConeMisF32` (the f32 estimator's, whose values
/// leave the radiance out: it multiplies the sum by L in f64).
macro_rules! cone_mis {
    ($name:ident, $real:ident, $v2:ty, $v3:ty, $p:ident, $pair:expr) => {
        /// One receiver's view of a uniform cone emitter, ready for MIS
        /// samples (module docs).
        #[derive(Clone, Copy, Debug)]
        pub(super) struct $name {
            /// The emitter's radiance L (W·m⁻²·sr⁻¹).
            radiance: $real,
            /// The cone, about +z of its own frame.
            cone: lambert_sampling::$p::UniformCone,
            /// The cone's axis in the receiver's frame.
            axis: $v3,
            /// The receiver's normal in the cone's frame.
            normal: $v3,
            /// 2(1 − cos θ_max), widened by a few ulps (as
            /// `UniformCone::pdf` widens its rim): |ω − a|² ≤ this is
            /// inside.
            rim: $real,
            /// The light density 1/Ω per steradian.
            light_pdf: $real,
        }

        impl $name {
            /// The cone `cone` about +z of `cone_frame`, of radiance
            /// `radiance`, seen from a receiver whose frame is `receiver`
            /// (z = its normal).
            #[inline(always)]
            pub(super) fn new(
                radiance: $real,
                cone_frame: &lambert_geometry::$p::Frame,
                cone: &lambert_sampling::$p::UniformCone,
                receiver: &lambert_geometry::$p::Frame,
            ) -> Self {
                $name {
                    radiance,
                    cone: *cone,
                    axis: receiver.to_local(cone_frame.z),
                    normal: cone_frame.to_local(receiver.z),
                    rim: 2.0 * cone.one_minus_cos_theta_max() * (1.0 + 8.0 * $real::EPSILON),
                    light_pdf: 1.0 / cone.solid_angle(),
                }
            }

            /// The weighted values of the cosine-sampled direction from
            /// `u` and of the light-sampled one from `v` (each 0 where its
            /// direction misses the emitter or lies below the horizon).
            #[inline(always)]
            pub(super) fn parts(&self, h: Heuristic, u: $v2, v: $v2) -> ($real, $real) {
                use lambert_sampling::$p::{pdf_cosine_hemisphere, sample_cosine_hemisphere};
                let w = sample_cosine_hemisphere(u);
                let p_cos = pdf_cosine_hemisphere(w);
                let inside = (w - self.axis).length_squared() <= self.rim;
                let (l_cos, p_light) = if inside {
                    (self.radiance * w.z, self.light_pdf)
                } else {
                    (0.0, 0.0)
                };
                let cos = self.normal.dot(self.cone.sample(v)).max(0.0);
                $pair(
                    h,
                    (l_cos, p_cos, p_light),
                    (
                        self.radiance * cos,
                        self.light_pdf,
                        cos * (1.0 / std::$real::consts::PI),
                    ),
                )
            }
        }
    };
}

cone_mis!(ConeMis, f64, DVec2, DVec3, f64, Heuristic::weighted_pair);
cone_mis!(
    ConeMisF32,
    f32,
    Vec2,
    Vec3,
    f32,
    |h: Heuristic, a: (f32, f32, f32), b: (f32, f32, f32)| (
        h.weighted_f32(a.0, a.1, a.2),
        h.weighted_f32(b.0, b.1, b.2)
    )
);

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_geometry::f64::Frame;
    use lambert_sampling::f64::{pdf_cosine_hemisphere, sample_cosine_hemisphere, UniformCone};

    /// The two halves against the textbook two-sample estimator evaluated
    /// in world space (light pdf by the cone's own test, cosine pdf from
    /// the world direction): the same values to a few ulps.
    #[test]
    fn parts_match_the_world_space_estimator() {
        let receiver = Frame::from_normal(DVec3::new(0.2, -0.3, 0.9).normalize());
        let cone_frame = Frame::from_normal(DVec3::new(0.5, 0.1, 0.7).normalize());
        let cone = UniformCone::from_theta_max(0.6).unwrap();
        let m = ConeMis::new(2.5, &cone_frame, &cone, &receiver);
        let mut inside = 0;
        for i in 0..400 {
            let u = DVec2::new(
                (f64::from(i) + 0.5) / 400.0,
                (f64::from(i * 37 % 400) + 0.5) / 400.0,
            );
            let v = DVec2::new(u.y, u.x);
            for h in [Heuristic::Balance, Heuristic::Power] {
                let (c, l) = m.parts(h, u, v);
                // Cosine half, in world space.
                let local = sample_cosine_hemisphere(u);
                let w = receiver.from_local(local);
                let p_l = cone.pdf(cone_frame.to_local(w));
                let p_c = pdf_cosine_hemisphere(local);
                let want_c = if p_l > 0.0 {
                    h.weight(p_c, p_l) * 2.5 * local.z / p_c
                } else {
                    0.0
                };
                inside += usize::from(p_l > 0.0);
                // Light half, in world space.
                let wl = cone_frame.from_local(cone.sample(v));
                let cos = wl.dot(receiver.z).max(0.0);
                let p_c = pdf_cosine_hemisphere(receiver.to_local(wl));
                let want_l =
                    h.weight(1.0 / cone.solid_angle(), p_c) * 2.5 * cos * cone.solid_angle();
                // A few roundings on each side (rotations, weights): 1e-14 relative.
                for (got, want) in [(c, want_c), (l, want_l)] {
                    assert!(
                        (got - want).abs() <= 1e-14 * want.abs(),
                        "{h:?} {u}: {got} vs {want}"
                    );
                }
            }
        }
        // Both outcomes of the cone test were exercised.
        assert!(inside > 50 && inside < 750, "{inside}");
    }

    /// A cone of ~6e-300 sr, whose light density's square overflows: the
    /// light half is still L·cos θ·Ω (the weight is 1 to rounding) and the
    /// cosine half finite.
    #[test]
    fn a_tiny_cone_stays_finite() {
        let frame = Frame::from_normal(DVec3::Z);
        let cone = UniformCone::from_one_minus_cos(1e-300).unwrap();
        let m = ConeMis::new(1.0, &frame, &cone, &frame);
        for h in [Heuristic::Balance, Heuristic::Power] {
            let (c, l) = m.parts(h, DVec2::new(0.5, 0.5), DVec2::new(0.3, 0.7));
            assert!(c.is_finite(), "{h:?}: {c}");
            // cos θ = 1 to rounding inside so narrow a cone: 1e-15 relative.
            let want = cone.solid_angle();
            assert!((l / want - 1.0).abs() < 1e-15, "{h:?}: {l} vs {want}");
        }
    }
}
