//! A rendered image: linear RGB radiance, the irradiance at each pixel's
//! first hit, and (irradiance mode) its standard error, all in f32.

use crate::render::Pixel;

/// A rendered image, rows top to bottom. Layers: `rgb` (linear radiance,
/// W·m⁻²·sr⁻¹ per channel), `irradiance` (W/m² at the first hit) and, in
/// irradiance mode, `std_error` (the irradiance's standard error).
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    rgb: Vec<[f32; 3]>,
    irradiance: Vec<f32>,
    std_error: Option<Vec<f32>>,
}

/// A band of whole rows of an [`Image`] ([`Image::bands_mut`]), with
/// its own row numbers (0 at its top row).
#[derive(Debug)]
pub(crate) struct Band<'a> {
    width: usize,
    rgb: &'a mut [[f32; 3]],
    irradiance: &'a mut [f32],
    std_error: Option<&'a mut [f32]>,
}

impl Band<'_> {
    /// Stores a pixel (rounded to f32) at column `x` of the band's row `y`.
    #[inline]
    pub(crate) fn set(&mut self, x: u32, y: u32, p: &Pixel) {
        let i = y as usize * self.width + x as usize;
        self.rgb[i] = p.rgb.to_f32();
        self.irradiance[i] = p.irradiance as f32;
        if let Some(s) = &mut self.std_error {
            s[i] = p.std_error as f32;
        }
    }
}

impl Image {
    /// A black image, with a standard-error layer if `with_std_error`.
    pub fn new(width: u32, height: u32, with_std_error: bool) -> Self {
        let n = width as usize * height as usize;
        Image {
            width,
            height,
            rgb: vec![[0.0; 3]; n],
            irradiance: vec![0.0; n],
            std_error: with_std_error.then(|| vec![0.0; n]),
        }
    }

    /// The image from its layers (each `width × height` long, row-major,
    /// top row first); `None` if a length is wrong.
    pub fn from_layers(
        width: u32,
        height: u32,
        rgb: Vec<[f32; 3]>,
        irradiance: Vec<f32>,
        std_error: Option<Vec<f32>>,
    ) -> Option<Self> {
        let n = width as usize * height as usize;
        (rgb.len() == n && irradiance.len() == n && std_error.as_ref().is_none_or(|s| s.len() == n))
            .then_some(Image {
                width,
                height,
                rgb,
                irradiance,
                std_error,
            })
    }

    /// Width, pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height, pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    #[inline]
    fn index(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    /// Stores a pixel (rounded to f32).
    pub fn set(&mut self, x: u32, y: u32, p: &Pixel) {
        let i = self.index(x, y);
        self.rgb[i] = p.rgb.to_f32();
        self.irradiance[i] = p.irradiance as f32;
        if let Some(s) = &mut self.std_error {
            s[i] = p.std_error as f32;
        }
    }

    /// The image cut into bands of `rows` rows (the last may be
    /// shorter), top to bottom, each writable on its own: a renderer fills
    /// them in parallel.
    ///
    /// # Panics
    /// If `rows` is 0.
    pub(crate) fn bands_mut(&mut self, rows: u32) -> Vec<Band<'_>> {
        assert!(rows > 0, "bands of at least one row");
        let width = self.width as usize;
        let len = width * rows as usize;
        let mut std_error = self.std_error.as_mut().map(|s| s.chunks_mut(len));
        self.rgb
            .chunks_mut(len)
            .zip(self.irradiance.chunks_mut(len))
            .map(|(rgb, irradiance)| Band {
                width,
                rgb,
                irradiance,
                std_error: std_error.as_mut().and_then(|s| s.next()),
            })
            .collect()
    }

    /// The RGB radiance of pixel (x, y).
    pub fn rgb(&self, x: u32, y: u32) -> [f32; 3] {
        self.rgb[self.index(x, y)]
    }

    /// The irradiance at pixel (x, y).
    pub fn irradiance(&self, x: u32, y: u32) -> f32 {
        self.irradiance[self.index(x, y)]
    }

    /// The standard error at pixel (x, y), if the image has that layer.
    pub fn std_error(&self, x: u32, y: u32) -> Option<f32> {
        let i = self.index(x, y);
        self.std_error.as_ref().map(|s| s[i])
    }

    /// The RGB layer, row-major.
    pub fn rgb_layer(&self) -> &[[f32; 3]] {
        &self.rgb
    }

    /// The irradiance layer, row-major.
    pub fn irradiance_layer(&self) -> &[f32] {
        &self.irradiance
    }

    /// The standard-error layer, row-major, if any.
    pub fn std_error_layer(&self) -> Option<&[f32]> {
        self.std_error.as_deref()
    }

    /// Whether every value of every layer is finite.
    pub fn is_finite(&self) -> bool {
        self.rgb.iter().flatten().all(|v| v.is_finite())
            && self.irradiance.iter().all(|v| v.is_finite())
            && self
                .std_error
                .as_ref()
                .is_none_or(|s| s.iter().all(|v| v.is_finite()))
    }

    /// The mean over pixels with E > 0 of σ_E / E (0 without a
    /// standard-error layer or such pixels), summed in pixel order.
    pub fn mean_relative_std_error(&self) -> f64 {
        let Some(se) = &self.std_error else {
            return 0.0;
        };
        let (mut sum, mut n) = (0.0f64, 0u64);
        for (&e, &s) in self.irradiance.iter().zip(se) {
            if e > 0.0 {
                sum += s as f64 / e as f64;
                n += 1;
            }
        }
        if n == 0 {
            0.0
        } else {
            sum / n as f64
        }
    }
}
