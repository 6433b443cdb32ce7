//! [`Lanes`]: one value per wavelength of a batch (`wavelengths::LANES` of them), with
//! lane-wise arithmetic, as a spectral renderer carries its samples (pbrt-v4's
//! `SampledSpectrum`). Every quantity a model computes per wavelength (radiance, optical
//! depth, transmittance, phase functions, irradiance) is a `Lanes`; the WGSL twins compute the
//! same four lanes as a `vec4<f32>`.

use crate::wavelengths::LANES;
use std::ops::{
    Add, AddAssign, Deref, DerefMut, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign,
};

/// One value per wavelength lane of a batch, in the unit of the quantity it holds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Lanes(pub [f64; LANES]);

impl Lanes {
    pub const ZERO: Lanes = Lanes([0.0; LANES]);
    pub const ONE: Lanes = Lanes([1.0; LANES]);

    /// Every lane `v`.
    pub const fn splat(v: f64) -> Lanes {
        Lanes([v; LANES])
    }

    /// Lane `i` is `f(i)`.
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> Lanes {
        Lanes(std::array::from_fn(f))
    }

    /// `f` of every lane.
    pub fn map(self, f: impl FnMut(f64) -> f64) -> Lanes {
        Lanes(self.0.map(f))
    }

    /// `f` of each lane of `self` and the same lane of `other`.
    pub fn zip_map(self, other: Lanes, mut f: impl FnMut(f64, f64) -> f64) -> Lanes {
        Lanes::from_fn(|i| f(self.0[i], other.0[i]))
    }

    /// e^x lane by lane: the transmittance of optical depth −x.
    pub fn exp(self) -> Lanes {
        self.map(f64::exp)
    }

    /// `self + (other − self) t`, lane by lane.
    pub fn lerp(self, other: Lanes, t: f64) -> Lanes {
        self.zip_map(other, |a, b| a + (b - a) * t)
    }

    /// The largest lane.
    pub fn max_lane(self) -> f64 {
        self.0.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    /// The sum of the lanes.
    pub fn sum(self) -> f64 {
        self.0.iter().sum()
    }

    /// Whether some lane is NaN.
    pub fn has_nan(self) -> bool {
        self.0.iter().any(|v| v.is_nan())
    }

    /// Whether every lane is finite.
    pub fn is_finite(self) -> bool {
        self.0.iter().all(|v| v.is_finite())
    }
}

impl From<[f64; LANES]> for Lanes {
    fn from(a: [f64; LANES]) -> Lanes {
        Lanes(a)
    }
}

impl From<Lanes> for [f64; LANES] {
    fn from(l: Lanes) -> [f64; LANES] {
        l.0
    }
}

impl Deref for Lanes {
    type Target = [f64; LANES];
    fn deref(&self) -> &[f64; LANES] {
        &self.0
    }
}

impl DerefMut for Lanes {
    fn deref_mut(&mut self) -> &mut [f64; LANES] {
        &mut self.0
    }
}

impl IntoIterator for Lanes {
    type Item = f64;
    type IntoIter = std::array::IntoIter<f64, LANES>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

impl<'a> IntoIterator for &'a Lanes {
    type Item = &'a f64;
    type IntoIter = std::slice::Iter<'a, f64>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.iter()
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $assign_trait:ident, $assign:ident, $op:tt) => {
        impl $trait for Lanes {
            type Output = Lanes;
            fn $method(self, o: Lanes) -> Lanes {
                self.zip_map(o, |a, b| a $op b)
            }
        }
        impl $trait<f64> for Lanes {
            type Output = Lanes;
            fn $method(self, k: f64) -> Lanes {
                self.map(|a| a $op k)
            }
        }
        impl $assign_trait for Lanes {
            fn $assign(&mut self, o: Lanes) {
                *self = *self $op o;
            }
        }
        impl $assign_trait<f64> for Lanes {
            fn $assign(&mut self, k: f64) {
                *self = *self $op k;
            }
        }
    };
}

lane_op!(Add, add, AddAssign, add_assign, +);
lane_op!(Sub, sub, SubAssign, sub_assign, -);
lane_op!(Mul, mul, MulAssign, mul_assign, *);
lane_op!(Div, div, DivAssign, div_assign, /);

macro_rules! scalar_op {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait<Lanes> for f64 {
            type Output = Lanes;
            fn $method(self, l: Lanes) -> Lanes {
                l.map(|a| self $op a)
            }
        }
    };
}

scalar_op!(Add, add, +);
scalar_op!(Sub, sub, -);
scalar_op!(Mul, mul, *);
scalar_op!(Div, div, /);

impl Neg for Lanes {
    type Output = Lanes;
    fn neg(self) -> Lanes {
        self.map(|a| -a)
    }
}

impl std::iter::Sum for Lanes {
    fn sum<I: Iterator<Item = Lanes>>(iter: I) -> Lanes {
        iter.fold(Lanes::ZERO, Add::add)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_is_lane_by_lane() {
        let a = Lanes([1.0, 2.0, 3.0, 4.0]);
        let b = Lanes([4.0, 3.0, 2.0, 1.0]);
        assert_eq!(a + b, Lanes::splat(5.0));
        assert_eq!(a - b, Lanes([-3.0, -1.0, 1.0, 3.0]));
        assert_eq!(a * b, Lanes([4.0, 6.0, 6.0, 4.0]));
        assert_eq!(a / b, Lanes([0.25, 2.0 / 3.0, 1.5, 4.0]));
        assert_eq!(2.0 * a, a * 2.0);
        assert_eq!(1.0 - a, Lanes([0.0, -1.0, -2.0, -3.0]));
        assert_eq!(12.0 / a, Lanes([12.0, 6.0, 4.0, 3.0]));
        assert_eq!(-a + a, Lanes::ZERO);
        assert_eq!(a.lerp(b, 0.5), Lanes::splat(2.5));
        assert_eq!([a, b].into_iter().sum::<Lanes>(), Lanes::splat(5.0));
        let mut c = a;
        c *= b;
        c -= 1.0;
        assert_eq!(c, Lanes([3.0, 5.0, 5.0, 3.0]));
        assert_eq!(a.max_lane(), 4.0);
        assert_eq!(a.sum(), 10.0);
    }

    #[test]
    fn a_nan_in_any_lane_is_found() {
        assert!(!Lanes::ONE.has_nan());
        let z = Lanes::ZERO / Lanes([0.0, 1.0, 1.0, 1.0]);
        assert!(z.has_nan());
        assert!(!z.is_finite());
        assert!((Lanes::ONE / 0.0).map(|v| if v.is_infinite() { 0.0 } else { v }) == Lanes::ZERO);
    }
}
