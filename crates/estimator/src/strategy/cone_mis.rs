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
//! - the **light-sampled** direction ω′ is drawn in the cone's frame, where
//!   the receiver's normal n′ gives cos θ = n′·ω′ and p_c = max(cos θ, 0)/π;
//!   since nothing else of ω′ is needed, [`ConeCosine`] draws cos θ alone,
//!   with ω′'s azimuth measured from n′'s projection (the same distribution,
//!   one polynomial instead of two: MIS on the speed table's sphere took
//!   0.83× the time in f64 and 0.96× in f32, against the direction's dot
//!   product, in one A/B run).
//!
//! Each half then takes one division, so that the light half's value does
//! not depend on the cosine half's: the values are those of two
//! [`Heuristic::weighted`] calls, as the general MIS path computes them.
//! Neither direction is rotated into the world, nor is a density evaluated by
//! a test against the emitter. And because a cosine-sampled direction that
//! misses the emitter contributes exactly 0 and nothing else, the batch
//! kernels compute the cosine half's warp only for the samples that
//! [`CosineWindow`] shows may see the cone (when the emitter is small, a
//! few per cent of them), listed and gathered into whole vectors; the f32
//! kernel with a window built for f32 ([`CosineWindowF32`]).
//!
//! **Values before 2026-12:** the light half drew ω′ with its azimuth
//! measured from the cone frame's x axis, and took n′·ω′. The f64 halves
//! shared one division,
//! r = 1/(D₁D₂), N₁/D₁ = N₁·D₂r, N₂/D₂ = N₂·D₁r
//! ([`Heuristic::weighted_pair`]), an ulp or two from the present values;
//! it made every light-sampled value wait for the cosine half's
//! denominator, so no cosine half could be skipped.
//!
//! The weights rescale both densities by one power of two, fixed per cone:
//! the one that brings max(1/Ω, 1/π), an upper bound of every density here,
//! into [1, 2) ([`Heuristic::weighted`] picks it per sample from the two
//! densities at hand). A power of two commutes with rounding in the normal
//! range, so the values are those of the per-sample scaling to the bit; what
//! goes is the per-sample exponent extraction, clamp and guards. With the
//! light density scaled into [1/4, 2), neither half's denominator can
//! underflow or overflow where the direction sees the emitter, and a
//! cosine-sampled direction that misses it has value 0 (1 stands in for a
//! denominator of 0 there).
//!
//! The same commuting puts the scale where it costs nothing: the product
//! (N/D)·scale is computed as (scale·N)/D, with scale·L and scale/π formed
//! once per cone, so that no multiply per sample is spent on it (four
//! fewer per MIS sample: 3.89 → 3.86 ns in f64).

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::cone_window::{CosineWindow, CosineWindowF32};
use super::Heuristic;
#[cfg(doc)]
use lambert_sampling::f64::ConeCosine;

/// `ConeMis` (f64) and `ConeMisF32` (the f32 estimator's, whose values
/// leave the radiance out: it multiplies the sum by L in f64).
macro_rules! cone_mis {
    ($name:ident, $real:ident, $v2:ty, $v3:ty, $p:ident, $scale:path) => {
        /// One receiver's view of a uniform cone emitter, ready for MIS
        /// samples (module docs).
        #[derive(Clone, Copy, Debug)]
        pub(super) struct $name {
            /// The emitter's radiance L (W·m⁻²·sr⁻¹) times the power of
            /// two `scale` that brings max(1/Ω, 1/π) into [1, 2): the
            /// values' final product with the power of two, moved onto a
            /// factor every numerator has (module docs).
            scaled_radiance: $real,
            /// The cosines between the receiver's normal, in the cone's
            /// frame, and the cone's directions.
            cosine: lambert_sampling::$p::ConeCosine,
            /// The cone's axis in the receiver's frame.
            axis: $v3,
            /// 2(1 − cos θ_max), widened by a few ulps (as
            /// `UniformCone::pdf` widens its rim): |ω − a|² ≤ this is
            /// inside.
            rim: $real,
            /// 1/π times `scale`: the cosine density per unit cos θ, scaled
            /// (as are all densities here).
            scaled_cosine_pdf: $real,
            /// The light density 1/Ω per steradian, times `scale`.
            light_pdf: $real,
            /// Whether 1/Ω is a positive finite density (a cone so small
            /// that 1/Ω overflows has none, and contributes 0 by either
            /// half, as [`Heuristic::weighted`] gives for such a density).
            drawn: bool,
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
                let light_pdf = 1.0 / cone.solid_angle();
                let scale = $scale(light_pdf.max(1.0 / std::$real::consts::PI));
                $name {
                    scaled_radiance: radiance * scale,
                    scaled_cosine_pdf: (1.0 / std::$real::consts::PI) * scale,
                    cosine: lambert_sampling::$p::ConeCosine::new(
                        cone,
                        cone_frame.to_local(receiver.z),
                    ),
                    axis: receiver.to_local(cone_frame.z),
                    rim: 2.0 * cone.one_minus_cos_theta_max() * (1.0 + 8.0 * $real::EPSILON),
                    light_pdf: light_pdf * scale,
                    drawn: light_pdf > 0.0 && light_pdf < $real::INFINITY,
                }
            }

            /// The weighted values of the cosine-sampled direction from
            /// `u` and of the light-sampled one from `v` (each 0 where its
            /// direction misses the emitter or lies below the horizon):
            /// w·f/p = N/D·scale with, for the power heuristic,
            /// N = f·a and D = a² + b² (balance: N = f, D = a + b), a the
            /// scaled density of the sample's own technique and b the
            /// other's, a division each:
            /// [`cosine_value`](Self::cosine_value) and
            /// [`light_value`](Self::light_value).
            // The f32 kernels call the halves themselves (with the cone's
            // density checked once per block); the tests call this one.
            #[cfg_attr(not(test), allow(dead_code))]
            #[inline(always)]
            pub(super) fn parts(&self, h: Heuristic, u: $v2, v: $v2) -> ($real, $real) {
                if self.drawn {
                    (self.cosine_value(h, u), self.light_value(h, v))
                } else {
                    (0.0, 0.0)
                }
            }

            /// The cosine-sampled half's value from `u`, the first of
            /// [`parts`](Self::parts) to the bit.
            #[inline(always)]
            pub(super) fn cosine_value(&self, h: Heuristic, u: $v2) -> $real {
                let (n, d) = self.cosine_quotient(h, u);
                n / d
            }

            /// The light-sampled half's value from `v`, the second of
            /// [`parts`](Self::parts) to the bit.
            #[inline(always)]
            pub(super) fn light_value(&self, h: Heuristic, v: $v2) -> $real {
                let (n, d) = self.light_quotient(h, v);
                n / d
            }

            /// Whether the cone has a positive finite density 1/Ω; where it
            /// has none, both halves are 0 ([`parts`](Self::parts)).
            #[inline(always)]
            pub(super) fn is_drawn(&self) -> bool {
                self.drawn
            }

            /// The cosine-sampled half's (N, D) from `u` ([`parts`](Self::parts)).
            #[inline(always)]
            fn cosine_quotient(&self, h: Heuristic, u: $v2) -> ($real, $real) {
                use lambert_sampling::$p::sample_cosine_hemisphere;
                let w = sample_cosine_hemisphere(u);
                let p_cos = w.z.max(0.0) * self.scaled_cosine_pdf;
                let inside = (w - self.axis).length_squared() <= self.rim;
                let (l_cos, p_light) = if inside {
                    (self.scaled_radiance * w.z, self.light_pdf)
                } else {
                    (0.0, 0.0)
                };
                let (n_cos, d_cos) = Self::quotient(h, l_cos, p_cos, p_light);
                // Inside the cone D ≥ b² ≥ 1/16. Outside, N = 0 and D = a²
                // may be 0 or subnormal (a tiny cone's scale makes a tiny):
                // below √(smallest normal), 1 stands in, so that the value
                // is 0, not NaN. A scene of normal range never has so small
                // a D, so the values stay those of the per-sample scaling.
                let d_cos = if d_cos >= $real::MIN_POSITIVE.sqrt() {
                    d_cos
                } else {
                    1.0
                };
                (n_cos, d_cos)
            }

            /// The light-sampled half's (N, D) from `v` ([`parts`](Self::parts)).
            #[inline(always)]
            fn light_quotient(&self, h: Heuristic, v: $v2) -> ($real, $real) {
                let cos = self.cosine.sample(v).max(0.0);
                Self::quotient(
                    h,
                    self.scaled_radiance * cos,
                    self.light_pdf,
                    cos * self.scaled_cosine_pdf,
                )
            }

            /// (N, D) of one half for integrand value `f`, own scaled
            /// density `a` and the other's `b` ([`parts`](Self::parts)).
            #[inline(always)]
            fn quotient(h: Heuristic, f: $real, a: $real, b: $real) -> ($real, $real) {
                match h {
                    Heuristic::Balance => (f, a + b),
                    Heuristic::Power => (f * a, a * a + b * b),
                }
            }
        }
    };
}

impl ConeMis {
    /// Which cosine-sampled directions may see the cone, decided before
    /// their warp: the f64 kernel computes the cosine half of those only
    /// (module docs). Built apart from the cone,
    /// once per prepared emitter: it costs inverse sines and tangents.
    pub(super) fn window(&self) -> CosineWindow {
        CosineWindow::new(self.axis, self.rim)
    }
}

impl ConeMisF32 {
    /// Whether every light-sampled half is positive, so that a
    /// kernel may count every sample's light half as a hit without
    /// comparing: the cone is drawn, lies above the horizon
    /// ([`ConeCosine::is_above_horizon`](lambert_sampling::f32::ConeCosine::is_above_horizon):
    /// every cosine exceeds 2⁻¹⁰), and the scaled radiance is at
    /// least 2¹² times the smallest normal number. Then f = L′ cos θ
    /// is normal, the densities lie in [½, 2) (the larger of 1/Ω
    /// and 1/π is scaled into [1, 2), and 1/Ω ≥ 1/(2π) for a cone
    /// within a hemisphere), so N (f or f·a) is a positive normal
    /// number and D (a + b or a² + b²) lies in [¼, 8]: N/D > 0.
    /// (The f64 kernel keeps its count: skipping it there measured
    /// 1.03× slower, where the f32 kernel took 0.97× the time.)
    #[inline]
    pub(super) fn every_light_half_is_positive(&self) -> bool {
        self.drawn
            && self.cosine.is_above_horizon()
            && self.scaled_radiance >= f32::MIN_POSITIVE * 4096.0
    }

    /// [`ConeMis::window`] for the f32 warp and cone test: built from this
    /// cone's f32 axis and rim, with f32's margins.
    pub(super) fn window(&self) -> CosineWindowF32 {
        CosineWindowF32::new(self.axis.as_dvec3(), f64::from(self.rim))
    }
}

// The values of two `Heuristic::weighted` calls in f64, of two
// `Heuristic::weighted_f32` calls in f32.
cone_mis!(ConeMis, f64, DVec2, DVec3, f64, super::scale_to_unit);
cone_mis!(ConeMisF32, f32, Vec2, Vec3, f32, super::scale_to_unit_f32);

#[cfg(test)]
mod tests {
    use super::*;
    use lambert_geometry::f64::Frame;
    use lambert_sampling::f64::{pdf_cosine_hemisphere, sample_cosine_hemisphere, UniformCone};

    /// `w` (in the cone's frame) rotated about the cone's axis by the
    /// azimuth of the receiver's normal in that frame: the light direction
    /// whose cosine `ConeCosine` gives.
    fn about_normal(w: DVec3, cone_frame: &Frame, receiver: &Frame) -> DVec3 {
        let n = cone_frame.to_local(receiver.z);
        let (s, c) = n.y.atan2(n.x).sin_cos();
        DVec3::new(c * w.x - s * w.y, s * w.x + c * w.y, w.z)
    }

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
                // Light half, in world space: the cone's direction with
                // its azimuth measured from the normal's projection.
                let wl =
                    cone_frame.from_local(about_normal(cone.sample(v), &cone_frame, &receiver));
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

    /// The weights with the scale fixed per cone are those of the scale
    /// picked per sample (two [`Heuristic::weighted`] calls in f64, two
    /// [`Heuristic::weighted_f32`] in f32) to the bit: for a wide cone
    /// (1/Ω < 1/π, scale set by the cosine density's bound), a middling and
    /// a narrow one, both heuristics, both outcomes of the cone test.
    #[test]
    fn the_fixed_scale_gives_the_per_sample_values_exactly() {
        use lambert_geometry::f32::Frame as Frame32;
        use lambert_sampling::f32::{
            pdf_cosine_hemisphere as pdf_cos32, sample_cosine_hemisphere as cos32,
            UniformCone as Cone32,
        };
        use std::f64::consts::PI;
        let receiver = Frame::from_normal(DVec3::new(0.1, 0.2, 0.95).normalize());
        let axis = DVec3::new(0.3, -0.2, 0.8).normalize();
        let cone_frame = Frame::from_normal(axis);
        let receiver32 = Frame32::from_normal(receiver.z.as_vec3());
        let cone_frame32 = Frame32::from_normal(axis.as_vec3());
        for theta_max in [1.4, 0.5, 0.01] {
            let cone = UniformCone::from_theta_max(theta_max).unwrap();
            let cone32 = Cone32::from_theta_max(theta_max as f32).unwrap();
            let m = ConeMis::new(1.5, &cone_frame, &cone, &receiver);
            let m32 = ConeMisF32::new(1.5, &cone_frame32, &cone32, &receiver32);
            let (p_l, p_l32) = (1.0 / cone.solid_angle(), 1.0 / cone32.solid_angle());
            let (a, a32) = (m.axis, m32.axis);
            let (rim, rim32) = (m.rim, m32.rim);
            let (n, n32) = (m.cosine, m32.cosine);
            let mut inside = [0usize; 2];
            for i in 0..2000u32 {
                let u = DVec2::new(
                    (f64::from(i) + 0.5) / 2000.0,
                    (f64::from(i * 761 % 2000) + 0.5) / 2000.0,
                );
                let v = DVec2::new(u.y, u.x);
                for h in [Heuristic::Balance, Heuristic::Power] {
                    let w = sample_cosine_hemisphere(u);
                    let hit = (w - a).length_squared() <= rim;
                    inside[usize::from(hit)] += 1;
                    let (l_cos, p_light) = if hit { (1.5 * w.z, p_l) } else { (0.0, 0.0) };
                    let cos = n.sample(v).max(0.0);
                    let want = (
                        h.weighted(l_cos, pdf_cosine_hemisphere(w), p_light),
                        h.weighted(1.5 * cos, p_l, cos * (1.0 / PI)),
                    );
                    assert_eq!(m.parts(h, u, v), want, "{h:?} θ {theta_max} u {u}");
                    let (u32_, v32) = (u.as_vec2(), v.as_vec2());
                    let w = cos32(u32_);
                    let hit = (w - a32).length_squared() <= rim32;
                    let (l_cos, p_light) = if hit { (1.5 * w.z, p_l32) } else { (0.0, 0.0) };
                    let cos = n32.sample(v32).max(0.0);
                    let want = (
                        h.weighted_f32(l_cos, pdf_cos32(w), p_light),
                        h.weighted_f32(1.5 * cos, p_l32, cos * (1.0 / std::f32::consts::PI)),
                    );
                    assert_eq!(m32.parts(h, u32_, v32), want, "f32 {h:?} θ {theta_max}");
                }
            }
            // Both outcomes of the cone test were exercised.
            assert!(inside[0] > 0 && inside[1] > 0, "θ {theta_max}: {inside:?}");
        }
    }

    /// Where `every_light_half_is_positive` holds, the f32 light half is
    /// positive on a grid of samples with both ends, for cones wide and
    /// narrow (a radiance so small that the check fails included), both
    /// heuristics; the zero count below shows the grid reaches 0 where the
    /// horizon cuts the cone (the negative control: there the check fails).
    #[test]
    fn every_light_half_is_positive_where_the_check_holds() {
        use lambert_geometry::f32::Frame as Frame32;
        use lambert_sampling::f32::UniformCone as Cone32;
        let receiver = Frame32::from_normal(glam::Vec3::Z);
        let (mut held, mut zeros) = (0, 0);
        for (tilt_degrees, theta_max, radiance) in [
            (30.0f32, 0.1f32, 1.0f32),
            (30.0, 1.0, 1.0),
            (0.0, 1.5, 1.0),
            (60.0, 0.001, 1e-20),
            (60.0, 0.2, 1e-36),
            (80.0, 0.5, 1.0),
            (100.0, 0.3, 1.0),
        ] {
            let tilt = tilt_degrees.to_radians();
            let axis = glam::Vec3::new(tilt.sin(), 0.0, tilt.cos());
            let cone = Cone32::from_theta_max(theta_max).unwrap();
            let m = ConeMisF32::new(radiance, &Frame32::from_normal(axis), &cone, &receiver);
            let check = m.every_light_half_is_positive();
            let lowest = tilt + theta_max;
            let clear = lowest < std::f32::consts::FRAC_PI_2 - 0.01 && radiance > 1e-33;
            assert_eq!(
                check, clear,
                "tilt {tilt_degrees} θ {theta_max} L {radiance}"
            );
            for i in 0..=64 {
                for j in 0..=64 {
                    let v = glam::Vec2::new(i as f32 / 64.0, j as f32 / 64.0);
                    for h in [Heuristic::Balance, Heuristic::Power] {
                        let light = m.light_value(h, v);
                        if check {
                            assert!(light > 0.0, "tilt {tilt_degrees} θ {theta_max} {v}");
                        }
                        zeros += usize::from(light == 0.0);
                    }
                }
            }
            held += usize::from(check);
        }
        assert!(held >= 3 && zeros > 0, "held {held}, zeros {zeros}");
    }

    /// A cone of ~6e-300 sr, whose light density's square overflows: the
    /// light half is still L·cos θ·Ω (the weight is 1 to rounding) and the
    /// cosine half finite.
    #[test]
    fn a_tiny_cone_stays_finite() {
        // Cosine samples outside cones this narrow have scaled densities
        // whose squares are subnormal (1e-157) or 0 (1e-300): both halves
        // stay finite on a grid of samples (the first was a fuzz case, a
        // sphere 1.6e306 away of radius 4e227, that gave NaN).
        for one_minus_cos in [1e-300, 3.6e-158, 1e-157, 1e-100] {
            let frame = Frame::from_normal(DVec3::Z);
            let receiver = Frame::from_normal(DVec3::new(-0.03, -0.99, 0.07).normalize());
            let cone = UniformCone::from_one_minus_cos(one_minus_cos).unwrap();
            let m = ConeMis::new(0.008, &frame, &cone, &receiver);
            for i in 0..64 {
                for j in 0..64 {
                    let u = DVec2::new((f64::from(i) + 0.5) / 64.0, (f64::from(j) + 0.5) / 64.0);
                    for h in [Heuristic::Balance, Heuristic::Power] {
                        let (c, l) = m.parts(h, u, DVec2::new(u.y, u.x));
                        assert!(
                            c.is_finite() && l.is_finite(),
                            "{one_minus_cos} {h:?} {u}: {c} {l}"
                        );
                    }
                }
            }
        }
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
