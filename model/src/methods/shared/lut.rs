//! The table container every model's lookup tables use, and the declaration of a table: its
//! size, what its axes mean and which scene inputs invalidate it. The GPU stores the same
//! texels in the same order (`shaders/common/lut.wgsl`).

use super::{Lanes, Params};
use crate::methods::Inputs;
use rayon::prelude::*;

/// A table as the registry declares it, once, for the engine, the LUT tab and the tests.
#[derive(Debug, Clone, Copy)]
pub struct TableSpec {
    /// Stable id (kebab case), also the WGSL buffer's name with `-` as `_` and `_lut` appended.
    pub id: &'static str,
    pub label: &'static str,
    /// Texels (x, y, z) of one layer; one layer per batch of four wavelengths.
    pub size: [u32; 3],
    /// What x, y and z (the slices) mean, for a reader of the LUT tab.
    pub axes: [&'static str; 3],
    /// The scene inputs whose change makes the table stale (directly, not through other tables).
    pub invalidated_by: Inputs,
    /// Whether the texels are transmittances (shown without exposure).
    pub transmittance: bool,
    /// The physical coordinates of fractional texel (x, y, z) as text, for a camera at
    /// altitude `h` (m): the inverse of the table's mapping.
    pub describe_texel: fn(&Params, f64, [f64; 3]) -> String,
}

impl TableSpec {
    /// Texels of one layer.
    pub fn texels_per_layer(&self) -> u64 {
        self.size.iter().map(|&n| u64::from(n)).product()
    }

    /// Whether only frames in motion read the table (the moving sky, `super::moving_sky`, and
    /// the nested marches' way to the sun it is built from): no CPU image is drawn from it, and
    /// a still frame leaves it unbuilt.
    pub fn motion_only(&self) -> bool {
        self.id == super::moving_sky::TABLE.id
            || self.id == super::single_scattering_sky::SUN_ROUTE_TABLE.id
    }

    /// Bytes of the table for `layers` batches (four f32 per texel on the GPU).
    pub fn bytes(&self, layers: usize) -> u64 {
        16 * self.texels_per_layer() * layers as u64
    }
}

/// A table of `layers` batches, each `depth` × `height` × `width` texels of four lanes.
#[derive(Debug, Clone, PartialEq)]
pub struct Lut {
    pub width: usize,
    pub height: usize,
    pub depth: usize,
    pub layers: usize,
    pub data: Vec<Lanes>,
}

impl Lut {
    /// An empty table of the size `spec` declares, for `layers` batches, filled by
    /// `f(layer, z, y, x)` in parallel.
    pub fn from_spec(
        spec: &TableSpec,
        layers: usize,
        f: impl Fn(usize, usize, usize, usize) -> Lanes + Sync,
    ) -> Lut {
        let [w, h, d] = spec.size;
        Lut::build(w, h, d, layers, f)
    }

    pub fn build(
        width: u32,
        height: u32,
        depth: u32,
        layers: usize,
        f: impl Fn(usize, usize, usize, usize) -> Lanes + Sync,
    ) -> Lut {
        let (w, h, d) = (width as usize, height as usize, depth as usize);
        let data = (0..layers * d * h * w)
            .into_par_iter()
            .map(|i| f(i / (d * h * w), (i / (h * w)) % d, (i / w) % h, i % w))
            .collect();
        Lut {
            width: w,
            height: h,
            depth: d,
            layers,
            data,
        }
    }

    /// Two tables of the size `spec` declares, written together: `f(layer, z, y, x)` gives
    /// the texel of each, in parallel (a pass with two outputs).
    pub fn pair_from_spec(
        spec: &TableSpec,
        layers: usize,
        f: impl Fn(usize, usize, usize, usize) -> (Lanes, Lanes) + Sync,
    ) -> (Lut, Lut) {
        let [w, h, d] = spec.size.map(|n| n as usize);
        let (a, b): (Vec<Lanes>, Vec<Lanes>) = (0..layers * d * h * w)
            .into_par_iter()
            .map(|i| f(i / (d * h * w), (i / (h * w)) % d, (i / w) % h, i % w))
            .unzip();
        let lut = |data| Lut {
            width: w,
            height: h,
            depth: d,
            layers,
            data,
        };
        (lut(a), lut(b))
    }

    /// The texel-by-texel sum of two tables of the same size.
    pub fn plus(&self, other: &Lut) -> Lut {
        Lut {
            data: self
                .data
                .iter()
                .zip(&other.data)
                .map(|(a, b)| *a + *b)
                .collect(),
            ..self.clone()
        }
    }

    /// Texel (x, y, z) of `layer`.
    pub fn texel(&self, layer: usize, x: usize, y: usize, z: usize) -> Lanes {
        self.data[((layer * self.depth + z) * self.height + y) * self.width + x]
    }

    /// Bilinear interpolation at fractional texel coordinates (clamped to the table), slice z.
    pub fn bilinear(&self, layer: usize, fx: f64, fy: f64, z: usize) -> Lanes {
        let (x0, x1, tx) = split(fx, self.width);
        let (y0, y1, ty) = split(fy, self.height);
        let a = self
            .texel(layer, x0, y0, z)
            .lerp(self.texel(layer, x1, y0, z), tx);
        let b = self
            .texel(layer, x0, y1, z)
            .lerp(self.texel(layer, x1, y1, z), tx);
        a.lerp(b, ty)
    }

    /// Trilinear interpolation at fractional texel coordinates (clamped to the table).
    pub fn trilinear(&self, layer: usize, fx: f64, fy: f64, fz: f64) -> Lanes {
        let (z0, z1, tz) = split(fz, self.depth);
        self.bilinear(layer, fx, fy, z0)
            .lerp(self.bilinear(layer, fx, fy, z1), tz)
    }
}

/// The two texels around fractional coordinate `f` on an axis of `n` texels (clamped to it) and
/// the weight of the second.
pub(crate) fn split(f: f64, n: usize) -> (usize, usize, f64) {
    let f = f.clamp(0.0, (n - 1) as f64);
    let i0 = f.floor() as usize;
    let i1 = (i0 + 1).min(n - 1);
    (i0, i1, f - i0 as f64)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A table of `spec`'s size whose every texel differs, smooth in no axis: a look-up that
    /// blends the wrong texels or weights cannot match another that blends the right ones.
    pub(crate) fn rough_table(spec: &TableSpec, layers: usize) -> Lut {
        Lut::from_spec(spec, layers, |layer, z, y, x| {
            let v = ((layer * 7919 + z * 104_729 + y * 31 + x) % 997) as f64;
            Lanes([v, v.sqrt(), 1.0 + v * v, (v * 0.37).sin()])
        })
    }
}
