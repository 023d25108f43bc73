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

/// The pixels of one tile of an [`Image`] ([`Image::tiles_mut`]),
/// writable on their own: a piece of each of the tile's rows, with the
/// tile's own coordinates (0, 0 at its top left pixel).
#[derive(Debug)]
pub(crate) struct TileMut<'a> {
    /// The image columns [x0, x1) and rows [y0, y1) of the tile.
    pub(crate) x: (u32, u32),
    pub(crate) y: (u32, u32),
    rows: Vec<TileRow<'a>>,
}

/// A tile's piece of one image row, in every layer.
#[derive(Debug)]
struct TileRow<'a> {
    rgb: &'a mut [[f32; 3]],
    irradiance: &'a mut [f32],
    std_error: Option<&'a mut [f32]>,
}

impl TileMut<'_> {
    /// Stores the tile's pixels, given row by row (as many as it has).
    #[inline]
    pub(crate) fn set_all(&mut self, pixels: &[Pixel]) {
        let width = (self.x.1 - self.x.0) as usize;
        for (row, pixels) in self.rows.iter_mut().zip(pixels.chunks(width)) {
            for (i, p) in pixels.iter().enumerate() {
                row.rgb[i] = p.rgb.to_f32();
                row.irradiance[i] = p.irradiance as f32;
                if let Some(s) = &mut row.std_error {
                    s[i] = p.std_error as f32;
                }
            }
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

    /// The image cut into square tiles of side `side` (those at the
    /// right and bottom edges may be narrower), row of tiles by row of
    /// tiles, each writable on its own: a renderer fills them in
    /// parallel, straight into the image.
    ///
    /// # Panics
    /// If `side` is 0.
    pub(crate) fn tiles_mut(&mut self, side: u32) -> Vec<TileMut<'_>> {
        assert!(side > 0, "tiles of at least one pixel");
        let (w, h, t) = (self.width, self.height, side);
        let mut tiles: Vec<TileMut<'_>> = (0..h.div_ceil(t))
            .flat_map(|ty| {
                (0..w.div_ceil(t)).map(move |tx| TileMut {
                    x: (tx * t, (tx * t + t).min(w)),
                    y: (ty * t, (ty * t + t).min(h)),
                    rows: Vec::with_capacity(t.min(h) as usize),
                })
            })
            .collect();
        let width = w as usize;
        let tiles_per_row = w.div_ceil(t) as usize;
        let mut std_error = self.std_error.as_mut().map(|s| s.chunks_mut(width));
        let rows = self
            .rgb
            .chunks_mut(width)
            .zip(self.irradiance.chunks_mut(width));
        for (y, (rgb, irradiance)) in rows.enumerate() {
            let mut std_error = std_error
                .as_mut()
                .and_then(|s| s.next())
                .map(|s| s.chunks_mut(t as usize));
            let pieces = rgb
                .chunks_mut(t as usize)
                .zip(irradiance.chunks_mut(t as usize));
            let first = y / t as usize * tiles_per_row;
            for (tile, (rgb, irradiance)) in tiles[first..].iter_mut().zip(pieces) {
                tile.rows.push(TileRow {
                    rgb,
                    irradiance,
                    std_error: std_error.as_mut().and_then(|s| s.next()),
                });
            }
        }
        tiles
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
