//! The pinhole camera, and why its pixels measure radiance.
//!
//! # A pinhole pixel measures radiance
//!
//! Put a sensor element of area A_p at distance f behind a pinhole of area
//! A_h. Light reaches the element only along the rays that pass through
//! both; for a pixel at angle θ off the optical axis their étendue (the
//! product of area and solid angle that the bundle fills) is
//! G = A_h cos θ · A_p cos θ / (f / cos θ)² = A_h A_p cos⁴θ / f², and the
//! power the element receives from a scene of radiance L along those rays
//! is Φ = L G (radiance is power per unit étendue: L = d²Φ / (dA cos θ dω)).
//! G is a property of the camera alone, so a sensor calibrated by it reads
//! Φ / G = L. As the pinhole shrinks (A_h → 0) the bundle narrows to the
//! single ray through the pinhole and the pixel's centre, and the reading is
//! the radiance along that ray: a pinhole image is a picture of radiance.
//!
//! Radiance is constant along a ray in empty space: a surface patch dA seen
//! from distance d fills the solid angle dA cos θ / d² while the power it
//! sends into the pupil falls as 1/d², and the two cancel. So a camera
//! looking at a uniform emitter of radiance L reads L in every pixel the
//! emitter covers, at any distance and any angle (the test
//! `pinhole_pixels_read_radiance` shows it). What the image does not show
//! is irradiance: E = ∫ L cos θ dω needs the whole hemisphere at a point,
//! which is what the irradiance mode estimates at each pixel's first hit.
//!
//! Conventions: the image's row 0 is at the top; pixel (x, y) looks along
//! the ray through its centre, ((x + ½)/W, (y + ½)/H) of the image plane;
//! the vertical field of view is `fov_deg` and pixels are square.

use glam::DVec3;
use lambert_geometry::f64::Ray;

use crate::error::TracerError;

/// The largest image side accepted (2^16 pixels).
pub const MAX_SIDE: u32 = 1 << 16;

/// A pinhole camera: a position, an orthonormal viewing frame, a vertical
/// field of view and an image size in pixels.
///
/// ```
/// use glam::DVec3;
/// use lambert_tracer::Camera;
/// let cam = Camera::new(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, DVec3::Y, 40.0, 64, 48)?;
/// // The centre of the image looks at the target.
/// let ray = cam.ray(32.0, 24.0);
/// assert!((ray.direction - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-15);
/// # Ok::<(), lambert_tracer::TracerError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    position: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    fov_deg: f64,
    tan_half: f64,
    width: u32,
    height: u32,
}

impl Camera {
    /// The camera at `position` looking at `look_at`, with `up` giving the
    /// image's vertical (any vector not along the view), the vertical field
    /// of view `fov_deg` in (0, 180) degrees, and `width` × `height` pixels
    /// (each 1 … 65536). Errors name the field (`position`, `look_at`,
    /// `up`, `fov_deg`, `width`, `height`).
    pub fn new(
        position: DVec3,
        look_at: DVec3,
        up: DVec3,
        fov_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Self, TracerError> {
        lambert_geometry::validate::finite3("position", position)?;
        lambert_geometry::validate::finite3("look_at", look_at)?;
        lambert_geometry::validate::finite3("up", up)?;
        lambert_geometry::validate::finite("fov_deg", fov_deg)?;
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return Err(TracerError::new(
                "fov_deg",
                format!("must lie in (0, 180) degrees, got {fov_deg}"),
            ));
        }
        let view = look_at - position;
        let forward = view.normalize_or_zero();
        if forward == DVec3::ZERO || !forward.is_finite() {
            return Err(TracerError::new(
                "look_at",
                format!("must differ from the position {position}, got {look_at}"),
            ));
        }
        let right = forward.cross(up).normalize_or_zero();
        if right == DVec3::ZERO || !right.is_finite() || right.cross(forward).length() < 0.5 {
            return Err(TracerError::new(
                "up",
                format!("must not be zero or along the viewing direction {forward}, got {up}"),
            ));
        }
        let up = right.cross(forward);
        let camera = Camera {
            position,
            forward,
            right,
            up,
            fov_deg,
            tan_half: (0.5 * fov_deg).to_radians().tan(),
            width: 1,
            height: 1,
        };
        camera.with_size(width, height)
    }

    /// The same camera with another image size (errors name `width` or
    /// `height`: each must be 1 … 65536).
    pub fn with_size(mut self, width: u32, height: u32) -> Result<Self, TracerError> {
        for (field, v) in [("width", width), ("height", height)] {
            if !(1..=MAX_SIDE).contains(&v) {
                return Err(TracerError::new(
                    field,
                    format!("must be 1 … {MAX_SIDE} pixels, got {v}"),
                ));
            }
        }
        self.width = width;
        self.height = height;
        Ok(self)
    }

    /// The pinhole.
    pub fn position(&self) -> DVec3 {
        self.position
    }

    /// The unit viewing direction.
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// The vertical field of view, degrees.
    pub fn fov_deg(&self) -> f64 {
        self.fov_deg
    }

    /// Image width, pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height, pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The ray from the pinhole through the image-plane point (x, y) in
    /// pixel units (x right from the left edge, y down from the top edge):
    /// pixel (i, j) is sampled at (i + ½, j + ½). Its direction is unit.
    #[inline]
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let h = self.height as f64;
        let sx = (2.0 * x - self.width as f64) / h * self.tan_half;
        let sy = (h - 2.0 * y) / h * self.tan_half;
        let d = self.forward + self.right * sx + self.up * sy;
        Ray::new(self.position, d.normalize())
    }

    /// The ray through the centre of pixel (`x`, `y`).
    #[inline]
    pub fn pixel_ray(&self, x: u32, y: u32) -> Ray {
        self.ray(x as f64 + 0.5, y as f64 + 0.5)
    }

    /// The rays through the centres of the pixels `[x0, x1) × [y0, y1)`,
    /// row by row, appended to `out`: [`Camera::pixel_ray`]'s rays to the
    /// bit. The unnormalised direction `(forward + right·sx) + up·sy` is a
    /// column term plus a row term, so each is computed once per column
    /// or row (`sx` and `sy` as in [`Camera::ray`]) and a pixel costs one
    /// addition and the normalisation.
    ///
    /// ```
    /// use glam::DVec3;
    /// use lambert_tracer::camera::Camera;
    /// let camera = Camera::new(DVec3::ZERO, DVec3::Z, DVec3::Y, 60.0, 8, 6).unwrap();
    /// let mut rays = Vec::new();
    /// camera.pixel_rays((2, 5), (1, 3), &mut rays);
    /// assert_eq!(rays.len(), 6);
    /// assert_eq!(rays[4].direction, camera.pixel_ray(3, 2).direction);
    /// ```
    pub fn pixel_rays(&self, (x0, x1): (u32, u32), (y0, y1): (u32, u32), out: &mut Vec<Ray>) {
        let h = self.height as f64;
        let columns: Vec<DVec3> = (x0..x1)
            .map(|x| {
                let sx = (2.0 * (x as f64 + 0.5) - self.width as f64) / h * self.tan_half;
                self.forward + self.right * sx
            })
            .collect();
        for y in y0..y1 {
            let sy = (h - 2.0 * (y as f64 + 0.5)) / h * self.tan_half;
            let row = self.up * sy;
            out.extend(
                columns
                    .iter()
                    .map(|&column| Ray::new(self.position, (column + row).normalize())),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Camera::pixel_rays`] gives [`Camera::pixel_ray`]'s rays to the bit,
    /// row by row, on odd sizes, off-centre rectangles and an oblique
    /// camera (whose three axes all contribute to every component).
    #[test]
    fn pixel_rays_are_pixel_ray_to_the_bit() {
        let camera = Camera::new(
            DVec3::new(0.3, -2.0, 1.7),
            DVec3::new(-0.4, 0.9, 0.2),
            DVec3::new(0.1, 0.2, 1.0),
            47.0,
            37,
            23,
        )
        .unwrap();
        for (x, y) in [
            ((0, 37), (0, 23)),
            ((5, 6), (22, 23)),
            ((13, 29), (3, 11)),
            ((4, 4), (0, 23)),
        ] {
            let mut rays = Vec::new();
            camera.pixel_rays(x, y, &mut rays);
            let want: Vec<Ray> = (y.0..y.1)
                .flat_map(|j| (x.0..x.1).map(move |i| camera.pixel_ray(i, j)))
                .collect();
            assert_eq!(rays.len(), want.len());
            for (got, want) in rays.iter().zip(&want) {
                assert_eq!(got.origin, want.origin);
                assert_eq!(
                    got.direction.to_array().map(f64::to_bits),
                    want.direction.to_array().map(f64::to_bits)
                );
            }
        }
    }
}
