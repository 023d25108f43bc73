//! A scene to trace: a camera, shapes with materials, emitters, and the
//! radiance of rays that escape.

use glam::{DVec2, DVec3};
use lambert_estimator::point::{estimate_at, PointConfig, PointEstimate};
use lambert_geometry::f64::{gamma, Hit, Ray, SHADOW_EPSILON};
use lambert_light::emitter::Emitter;
use lambert_light::Receiver;

use crate::aggregate::{Acceleration, Aggregate, Primitive};
use crate::camera::Camera;
use crate::color::Rgb;
use crate::error::TracerError;
use crate::material::{Material, Surface};
use crate::shape::Shape;

/// The index of a material in a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialId(pub u32);

/// A scene: a camera, primitives (shapes with materials; area emitters are
/// primitives too, visible to camera rays and occluding like any shape),
/// emitters (lambert-light's: point, directional, sphere, disk, polygon,
/// sky, sky cap), and a background radiance seen by rays that escape.
#[derive(Clone, Debug)]
pub struct Scene {
    camera: Camera,
    aggregate: Aggregate,
    materials: Vec<Material>,
    emitters: Vec<Emitter>,
    background: Rgb,
}

/// A ray's nearest hit, the material there and the shape hit.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit<'a> {
    /// The hit (from [`Scene::nearest_hit`], without its surface
    /// parameters: `uv` is zero).
    pub hit: Hit,
    /// Its material.
    pub material: &'a Material,
    /// The shape hit.
    pub shape: &'a Shape,
}

impl SurfaceHit<'_> {
    /// The surface parameters (u, v) of the hit of `ray` (the ray that
    /// found it): the `uv` [`Scene::intersect`] reports.
    #[inline]
    pub fn surface_parameters(&self, ray: &Ray) -> DVec2 {
        self.shape.surface_parameters(ray, self.hit.distance)
    }
}

impl Scene {
    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The same scene seen at another image size (errors name `width` or
    /// `height`).
    pub fn with_size(mut self, width: u32, height: u32) -> Result<Self, TracerError> {
        self.camera = self.camera.with_size(width, height)?;
        Ok(self)
    }

    /// The same scene with its primitives searched as `acceleration` says
    /// (for measurements: [`Acceleration::Auto`] is the default).
    pub fn with_acceleration(mut self, acceleration: Acceleration) -> Self {
        let primitives: Vec<Primitive> = self.aggregate.primitives().cloned().collect();
        self.aggregate = Aggregate::with_acceleration(primitives, acceleration);
        self
    }

    /// The emitters.
    pub fn emitters(&self) -> &[Emitter] {
        &self.emitters
    }

    /// Whether some emitter has extent (needs sampling): sphere, disk,
    /// polygon, sky or sky cap.
    pub fn has_area_emitters(&self) -> bool {
        self.emitters.iter().any(|e| !e.is_delta())
    }

    /// The primitives and their search structure.
    pub fn aggregate(&self) -> &Aggregate {
        &self.aggregate
    }

    /// The radiance seen by rays that escape the scene.
    pub fn background(&self) -> Rgb {
        self.background
    }

    /// The nearest hit along `ray` before `t_max`, with its surface
    /// parameters.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<SurfaceHit<'_>> {
        let mut sh = self.nearest_hit(ray, t_max)?;
        sh.hit.uv = sh.surface_parameters(ray);
        Some(sh)
    }

    /// The nearest hit along `ray` before `t_max`, without its surface
    /// parameters (`uv` is zero): the renderers ask for them
    /// ([`SurfaceHit::surface_parameters`]) only where a texture varies,
    /// which on a sphere saves an atan2 and an acos per hit.
    #[inline]
    pub fn nearest_hit(&self, ray: &Ray, t_max: f64) -> Option<SurfaceHit<'_>> {
        self.aggregate.nearest(ray, t_max).map(|(p, t)| SurfaceHit {
            hit: p.shape.hit_at(ray, t),
            material: &self.materials[p.material as usize],
            shape: &p.shape,
        })
    }

    /// Whether anything lies along `ray` before `t_max`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f64) -> bool {
        self.aggregate.occluded(ray, t_max)
    }

    /// Whether the segment leaving the surface at `hit` along the unit
    /// `direction` is clear of every primitive for `distance` (∞ for
    /// directional lights and skies): a shadow ray from the hit's
    /// error-bounded origin (pbrt-v4 §6.8.6), stopped [`SHADOW_EPSILON`]
    /// short of `distance` so that the emitter it aims at does not count.
    #[inline]
    pub fn visible(&self, hit: &Hit, direction: DVec3, distance: f64) -> bool {
        let (ray, t_max) = Scene::shadow_ray(hit, direction, distance);
        !self.occluded(&ray, t_max)
    }

    /// The shadow ray [`Scene::visible`] traces, and its limit.
    #[inline]
    pub fn shadow_ray(hit: &Hit, direction: DVec3, distance: f64) -> (Ray, f64) {
        let t_max = if distance.is_finite() {
            distance * (1.0 - SHADOW_EPSILON)
        } else {
            f64::INFINITY
        };
        (hit.spawn_ray(direction), t_max)
    }

    /// The material of `primitive` (one of this scene's).
    #[inline]
    pub fn material_of(&self, primitive: &Primitive) -> &Material {
        &self.materials[primitive.material as usize]
    }

    /// The irradiance E = ∫ L V cos θ dω at `point` with unit `normal`, a
    /// point on (or off) a surface of the scene, from every emitter, with
    /// visibility tested against the scene and estimated as `config` says
    /// (an irradiance probe). Shadow rays leave `point` past a rounding
    /// bound of γ₁|point| per component.
    ///
    /// # Errors
    /// A non-finite point or a zero normal (`receiver.point`,
    /// `receiver.normal`), or a configuration the estimator rejects.
    pub fn irradiance_at(
        &self,
        point: DVec3,
        normal: DVec3,
        config: &PointConfig,
    ) -> Result<PointEstimate, TracerError> {
        let receiver = Receiver::new(point, normal)?;
        let hit = Hit {
            distance: 0.0,
            point,
            normal: receiver.normal,
            error: point.abs() * gamma(1),
            uv: DVec2::ZERO,
        };
        let visible = |_: DVec3, w: DVec3, d: f64| self.visible(&hit, w, d);
        Ok(estimate_at(&receiver, &self.emitters, &visible, config)?)
    }

    /// The radiance arriving along a ray that hits nothing, travelling in
    /// the unit `direction`: the background plus the skies' radiance.
    #[inline]
    pub fn escaped(&self, direction: DVec3) -> Rgb {
        let mut c = self.background;
        for e in &self.emitters {
            if matches!(e, Emitter::Sky(_) | Emitter::SkyCap(_)) {
                c += Rgb::grey(e.radiance_toward(DVec3::ZERO, direction));
            }
        }
        c
    }
}

/// Builds a [`Scene`], validating it as a whole.
///
/// ```
/// use glam::DVec3;
/// use lambert_geometry::f64::Sphere;
/// use lambert_light::emitter::{Emitter, PointLight};
/// use lambert_tracer::{Camera, Material, Rgb, SceneBuilder, Shape};
/// let camera = Camera::new(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y, 40.0, 32, 32)?;
/// let mut b = SceneBuilder::new(camera);
/// let white = b.add_material(Material::diffuse(Rgb::grey(0.8)));
/// b.add_shape(Shape::Sphere(Sphere::new(DVec3::ZERO, 1.0)?), white);
/// b.add_emitter(Emitter::Point(PointLight::with_intensity(DVec3::new(0.0, 0.0, 4.0), 10.0)?));
/// let scene = b.build()?;
/// assert_eq!(scene.aggregate().len(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    camera: Camera,
    primitives: Vec<Primitive>,
    materials: Vec<Material>,
    emitters: Vec<Emitter>,
    background: Rgb,
    acceleration: Acceleration,
}

impl SceneBuilder {
    /// An empty scene seen by `camera`, with a black background.
    pub fn new(camera: Camera) -> Self {
        SceneBuilder {
            camera,
            primitives: Vec::new(),
            materials: Vec::new(),
            emitters: Vec::new(),
            background: Rgb::BLACK,
            acceleration: Acceleration::Auto,
        }
    }

    /// Adds a material (checked by [`SceneBuilder::build`]).
    pub fn add_material(&mut self, material: Material) -> MaterialId {
        self.materials.push(material);
        MaterialId(self.materials.len() as u32 - 1)
    }

    /// Adds a shape with a material.
    pub fn add_shape(&mut self, shape: Shape, material: MaterialId) -> &mut Self {
        self.primitives.push(Primitive {
            shape,
            material: material.0,
        });
        self
    }

    /// Adds an emitter. Sphere, disk and polygon emitters also become
    /// primitives with an emitting surface, seen by camera rays and
    /// occluding other emitters' light.
    pub fn add_emitter(&mut self, emitter: Emitter) -> &mut Self {
        let surface = |radiance, two_sided| Material {
            surface: Surface::Emitter {
                radiance,
                two_sided,
            },
            highlight: None,
        };
        let primitive = match &emitter {
            Emitter::Sphere(s) => Some((Shape::Sphere(s.sphere), surface(s.radiance, false))),
            Emitter::Disk(d) => Some((Shape::Disk(d.disk), surface(d.radiance, d.two_sided))),
            Emitter::Polygon(p) => Some((
                Shape::Polygon(Box::new(p.polygon.clone())),
                surface(p.radiance, p.two_sided),
            )),
            _ => None,
        };
        if let Some((shape, material)) = primitive {
            let id = self.add_material(material);
            self.add_shape(shape, id);
        }
        self.emitters.push(emitter);
        self
    }

    /// Sets the radiance seen by rays that escape (seen only: it lights
    /// nothing; a `sky` emitter lights the scene).
    pub fn background(&mut self, background: Rgb) -> &mut Self {
        self.background = background;
        self
    }

    /// Chooses how the primitives are searched (default: a BVH above
    /// [`BVH_THRESHOLD`](crate::aggregate::BVH_THRESHOLD) primitives).
    pub fn acceleration(&mut self, acceleration: Acceleration) -> &mut Self {
        self.acceleration = acceleration;
        self
    }

    /// The scene, checked: every material valid (errors name
    /// `materials[i].field`), the background finite and non-negative, and
    /// the camera not inside a sphere (`camera.position`).
    pub fn build(self) -> Result<Scene, TracerError> {
        for (i, m) in self.materials.iter().enumerate() {
            m.validate()
                .map_err(|e| e.within(&format!("materials[{i}]")))?;
        }
        let b = self.background;
        if ![b.r, b.g, b.b].iter().all(|v| v.is_finite() && *v >= 0.0) {
            return Err(TracerError::new(
                "background",
                format!(
                    "must be finite and non-negative, got [{}, {}, {}]",
                    b.r, b.g, b.b
                ),
            ));
        }
        let eye = self.camera.position();
        if let Some(p) = self.primitives.iter().find(|p| p.shape.encloses(eye)) {
            let Shape::Sphere(s) = &p.shape else {
                unreachable!("only spheres enclose")
            };
            return Err(TracerError::new(
                "camera.position",
                format!(
                    "{eye} is inside the sphere of radius {} about {}: the camera would see only its inside",
                    s.radius(),
                    s.center()
                ),
            ));
        }
        Ok(Scene {
            camera: self.camera,
            aggregate: Aggregate::with_acceleration(self.primitives, self.acceleration),
            materials: self.materials,
            emitters: self.emitters,
            background: self.background,
        })
    }
}
