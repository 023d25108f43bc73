//! Linear RGB radiance (or reflectance) triples.

use std::ops::{Add, AddAssign, Mul};

/// A linear RGB triple: radiance in W·m⁻²·sr⁻¹ per channel, or a
/// reflectance in [0, 1] per channel. Scalar radiances (lambert's emitters
/// are grey) are `Rgb::grey(L)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb {
    /// Red.
    pub r: f64,
    /// Green.
    pub g: f64,
    /// Blue.
    pub b: f64,
}

impl Rgb {
    /// Black (0, 0, 0).
    pub const BLACK: Rgb = Rgb::grey(0.0);
    /// White (1, 1, 1).
    pub const WHITE: Rgb = Rgb::grey(1.0);

    /// The triple (r, g, b).
    pub const fn new(r: f64, g: f64, b: f64) -> Self {
        Rgb { r, g, b }
    }

    /// The grey (v, v, v).
    pub const fn grey(v: f64) -> Self {
        Rgb { r: v, g: v, b: v }
    }

    /// From an array [r, g, b].
    pub const fn from_array(a: [f64; 3]) -> Self {
        Rgb::new(a[0], a[1], a[2])
    }

    /// The luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of linear sRGB
    /// primaries (ITU-R BT.709).
    #[inline]
    pub fn luminance(self) -> f64 {
        0.2126 * self.r + 0.7152 * self.g + 0.0722 * self.b
    }

    /// Whether every channel is 0.
    #[inline]
    pub fn is_black(self) -> bool {
        self.r == 0.0 && self.g == 0.0 && self.b == 0.0
    }

    /// The channels rounded to f32, as the image stores them.
    #[inline]
    pub fn to_f32(self) -> [f32; 3] {
        [self.r as f32, self.g as f32, self.b as f32]
    }
}

impl Add for Rgb {
    type Output = Rgb;
    #[inline]
    fn add(self, o: Rgb) -> Rgb {
        Rgb::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
}

impl AddAssign for Rgb {
    #[inline]
    fn add_assign(&mut self, o: Rgb) {
        *self = *self + o;
    }
}

impl Mul for Rgb {
    type Output = Rgb;
    #[inline]
    fn mul(self, o: Rgb) -> Rgb {
        Rgb::new(self.r * o.r, self.g * o.g, self.b * o.b)
    }
}

impl Mul<f64> for Rgb {
    type Output = Rgb;
    #[inline]
    fn mul(self, s: f64) -> Rgb {
        Rgb::new(self.r * s, self.g * s, self.b * s)
    }
}
