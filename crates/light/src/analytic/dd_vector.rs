//! 3-vectors of double-doubles, for the few closed forms evaluated in
//! double-double when their cancellation is inherent (a far light seen at a
//! grazing elevation, a light seen nearly edge-on): the same formulas as
//! in f64, with every component carrying ~106 bits.

use super::double_double::Dd;
use glam::DVec3;
use std::ops::{Add, Mul, Sub};

/// A vector of three double-doubles.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Dd3 {
    pub(crate) x: Dd,
    pub(crate) y: Dd,
    pub(crate) z: Dd,
}

impl Dd3 {
    /// 0.
    pub(crate) const ZERO: Dd3 = Dd3 {
        x: Dd::ZERO,
        y: Dd::ZERO,
        z: Dd::ZERO,
    };

    /// v exactly.
    pub(crate) fn from_f64(v: DVec3) -> Dd3 {
        Dd3 {
            x: Dd::from(v.x),
            y: Dd::from(v.y),
            z: Dd::from(v.z),
        }
    }

    /// a − b exactly (TwoSum per component).
    pub(crate) fn difference(a: DVec3, b: DVec3) -> Dd3 {
        Dd3 {
            x: Dd::sum(a.x, -b.x),
            y: Dd::sum(a.y, -b.y),
            z: Dd::sum(a.z, -b.z),
        }
    }

    /// self·o.
    pub(crate) fn dot(self, o: Dd3) -> Dd {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// self × o.
    pub(crate) fn cross(self, o: Dd3) -> Dd3 {
        Dd3 {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// |self|.
    pub(crate) fn length(self) -> Dd {
        self.dot(self).sqrt()
    }

    /// self · s.
    pub(crate) fn scale(self, s: Dd) -> Dd3 {
        Dd3 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

impl Add for Dd3 {
    type Output = Dd3;
    fn add(self, o: Dd3) -> Dd3 {
        Dd3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl Sub for Dd3 {
    type Output = Dd3;
    fn sub(self, o: Dd3) -> Dd3 {
        Dd3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

impl Mul<Dd> for Dd3 {
    type Output = Dd3;
    fn mul(self, s: Dd) -> Dd3 {
        self.scale(s)
    }
}
