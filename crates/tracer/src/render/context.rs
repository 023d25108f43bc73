//! What every mode shares at one pixel: ray counts, shadow rays, and the
//! irradiance at a surface point from the scene's emitters, with
//! visibility.

use std::cell::Cell;

use glam::DVec3;
use lambert_estimator::point::{estimate_at, stream_seed, PointEstimate};
use lambert_geometry::f64::Hit;
use lambert_light::emitter::Emitter;
use lambert_light::Receiver;

use super::RenderConfig;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::Highlight;
use crate::scene::Scene;

/// Rays traced, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Rays from the camera.
    pub camera: u64,
    /// Reflected and refracted rays.
    pub secondary: u64,
    /// Shadow (visibility) rays.
    pub shadow: u64,
}

impl RayCounts {
    /// Every ray.
    pub fn total(&self) -> u64 {
        self.camera + self.secondary + self.shadow
    }

    /// The sum of two counts.
    pub fn plus(self, o: RayCounts) -> RayCounts {
        RayCounts {
            camera: self.camera + o.camera,
            secondary: self.secondary + o.secondary,
            shadow: self.shadow + o.shadow,
        }
    }
}

/// The light arriving directly at a surface point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Direct {
    /// The irradiance E (W/m²) from every emitter, with visibility.
    pub irradiance: f64,
    /// Its standard error (0 when only delta lights contribute).
    pub std_error: f64,
    /// The Blinn–Phong radiance from the delta lights (black without
    /// highlights).
    pub highlight: Rgb,
}

impl Direct {
    /// Adds the light of a delta light that the shading point sees (its
    /// shadow ray found nothing): E += (I/r²)·cos, and its Blinn–Phong
    /// highlight f(n·h)·E with h the half vector of the light's direction
    /// and `wo`.
    #[inline]
    pub(super) fn add(
        &mut self,
        light: &DeltaLight,
        n: DVec3,
        wo: DVec3,
        highlight: Option<&Highlight>,
    ) {
        let e_light = light.scale * light.cos;
        self.irradiance += e_light;
        if let Some(h) = highlight {
            let half = (light.direction + wo).normalize_or_zero();
            self.highlight += h.brdf(n.dot(half)) * e_light;
        }
    }
}

/// A delta light (point or directional) seen from a shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeltaLight {
    /// The unit direction toward the light.
    pub direction: DVec3,
    /// Its distance (∞ for a directional light).
    pub distance: f64,
    /// The irradiance it gives a surface facing it: I/r², or a directional
    /// light's E.
    pub scale: f64,
    /// n·direction, the cosine at the shading point.
    pub cos: f64,
}

impl DeltaLight {
    /// Emitter `e` seen from `point` with unit normal `n`, if it is a delta
    /// light (and, for a point light, not at `point` itself). The light
    /// counts, after its shadow ray, unless `cos` ≤ 0.
    #[inline]
    pub fn seen_from(e: &Emitter, point: DVec3, n: DVec3) -> Option<DeltaLight> {
        let (direction, distance, scale) = match e {
            Emitter::Point(p) => {
                let v = p.position - point;
                let r2 = v.length_squared();
                if !(r2 > 0.0) {
                    return None;
                }
                let r = r2.sqrt();
                (v / r, r, p.intensity / r2)
            }
            Emitter::Directional(d) => (d.direction, f64::INFINITY, d.irradiance),
            _ => return None,
        };
        Some(DeltaLight {
            direction,
            distance,
            scale,
            cos: n.dot(direction),
        })
    }
}

/// One pixel's tracer: the scene, the configuration, the pixel's seed and
/// its ray counts.
pub struct Context<'a> {
    pub(super) scene: &'a Scene,
    pub(super) config: &'a RenderConfig,
    /// The scene's emitters without delta lights (estimated by sampling).
    pub(super) area_emitters: &'a [Emitter],
    pixel_seed: u64,
    estimates: Cell<u64>,
    pub(super) camera: Cell<u64>,
    pub(super) secondary: Cell<u64>,
    shadow: Cell<u64>,
}

impl<'a> Context<'a> {
    pub(super) fn new(
        scene: &'a Scene,
        config: &'a RenderConfig,
        area_emitters: &'a [Emitter],
    ) -> Self {
        Context {
            scene,
            config,
            area_emitters,
            pixel_seed: 0,
            estimates: Cell::new(0),
            camera: Cell::new(0),
            secondary: Cell::new(0),
            shadow: Cell::new(0),
        }
    }

    /// Starts pixel `index` (its seed; counts go on accumulating).
    pub(super) fn start_pixel(&mut self, index: u64) {
        self.pixel_seed = stream_seed(self.config.estimate.seed, index);
        self.estimates.set(0);
    }

    /// The counts so far.
    pub(super) fn counts(&self) -> RayCounts {
        RayCounts {
            camera: self.camera.get(),
            secondary: self.secondary.get(),
            shadow: self.shadow.get(),
        }
    }

    /// [`Scene::visible`], counted as a shadow ray.
    #[inline]
    pub(super) fn visible(&self, hit: &Hit, direction: DVec3, distance: f64) -> bool {
        self.shadow.set(self.shadow.get() + 1);
        self.scene.visible(hit, direction, distance)
    }

    /// The direct light at `hit` on the side of the unit normal `n`
    /// (facing the viewer along `wo`): delta lights exactly, each with one
    /// shadow ray (and its highlight), plus the area emitters' irradiance
    /// estimated by the configured strategy and sequence when `areas`.
    pub(super) fn direct(
        &self,
        hit: &Hit,
        n: DVec3,
        wo: DVec3,
        highlight: Option<&Highlight>,
        areas: bool,
    ) -> Result<Direct, TracerError> {
        let mut out = Direct::default();
        for e in self.scene.emitters() {
            let Some(light) = DeltaLight::seen_from(e, hit.point, n) else {
                continue;
            };
            if light.cos <= 0.0 || !self.visible(hit, light.direction, light.distance) {
                continue;
            }
            out.add(&light, n, wo, highlight);
        }
        if areas && !self.area_emitters.is_empty() {
            let e = self.estimate(hit, n, self.area_emitters)?;
            out.irradiance += e.mean;
            out.std_error = e.std_error;
        }
        Ok(out)
    }

    /// The irradiance at `hit` with normal `n` from `emitters`, estimated
    /// with visibility (each call in a pixel draws its own seed).
    pub(super) fn estimate(
        &self,
        hit: &Hit,
        n: DVec3,
        emitters: &[Emitter],
    ) -> Result<PointEstimate, TracerError> {
        let k = self.estimates.get();
        self.estimates.set(k + 1);
        let config = self
            .config
            .estimate
            .with_seed(stream_seed(self.pixel_seed, k));
        let receiver = Receiver::new(hit.point, n)?;
        let visible = |_: DVec3, w: DVec3, d: f64| self.visible(hit, w, d);
        Ok(estimate_at(&receiver, emitters, &visible, &config)?)
    }

    /// The closed-form irradiance at `hit` with normal `n` from every
    /// emitter, ignoring occluders.
    pub(super) fn closed_form(&self, hit: &Hit, n: DVec3) -> Result<f64, TracerError> {
        let receiver = Receiver::new(hit.point, n)?;
        let mut sum = 0.0;
        for (i, e) in self.scene.emitters().iter().enumerate() {
            sum += e.try_closed_form_irradiance(&receiver).map_err(|err| {
                TracerError::new(
                    "--analytic",
                    format!("no closed form for emitters[{i}] at {}: {err}", hit.point),
                )
            })?;
        }
        Ok(sum)
    }
}
