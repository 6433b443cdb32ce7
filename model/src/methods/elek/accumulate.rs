//! Elek (2009) pass "accumulate": the order just computed added to the sums, texel by texel.
//! Twin of `shaders/elek/accumulate.wgsl`.

use super::Lut;

/// `sum` with `delta` (a table of the same size) added.
pub fn accumulate(sum: &Lut, delta: &Lut) -> Lut {
    sum.plus(delta)
}
