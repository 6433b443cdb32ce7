//! The scattering tables at the camera: the row (mu) of each 3D table at the camera's altitude
//! and sun zenith cosine, built when those change. Every ray from a camera inside the
//! atmosphere starts at that altitude with that sun, and the look-up is trilinear in the
//! table's texel coordinates, so blending in mu_s and h once here and then only in mu per pixel
//! gives what the 3D look-up gives, from two texels of each table instead of eight (Bruneton's
//! camera slices, one axis fewer). Twin of `shaders/elek/camera_slice.wgsl`; the sky pass reads
//! it unless the camera is above the atmosphere, where rays start where they enter it.

use super::{H, Lanes, Lut, MU, MU_S, Params, TableSpec, Viewpoint, texel_from_h_mu_mu_s};
use crate::methods::Inputs;
use crate::methods::shared::lut::split;
use crate::wavelengths::LANES;

const fn camera_table(id: &'static str, label: &'static str) -> TableSpec {
    TableSpec {
        id,
        label,
        size: [MU, 1, 1],
        axes: [super::AXES[0], "", ""],
        invalidated_by: Inputs::ATMOSPHERE.union(Inputs::VIEWPOINT),
        transmittance: false,
        describe_texel: |_, _, [x, _, _]| {
            let mu = super::cosine_from_axis(x / f64::from(MU - 1));
            format!("μ = {mu:.4} at the camera")
        },
    }
}

/// Rayleigh in-scattering (every order, no phase) at the camera.
pub const CAMERA_RAYLEIGH: TableSpec = camera_table("camera-rayleigh", "Rayleigh at the camera");
/// Mie in-scattering (every order, no phase) at the camera.
pub const CAMERA_MIE: TableSpec = camera_table("camera-mie", "Mie at the camera");

/// The row of the 3D table `lut` at viewpoint `vp`: texel mu blended over the texels around
/// the camera's mu_s and h.
pub fn compute_camera_slice(p: &Params, spec: &TableSpec, lut: &Lut, vp: Viewpoint) -> Lut {
    let [_, fy, fz] = texel_from_h_mu_mu_s(p, vp.h, 0.0, vp.mu_s);
    let (y0, y1, ty) = split(fy, MU_S as usize);
    let (z0, z1, tz) = split(fz, H as usize);
    Lut::from_spec(spec, p.batches.len(), |layer, _, _, x| {
        let mut v = Lanes::ZERO;
        for (z, wz) in [(z0, 1.0 - tz), (z1, tz)] {
            for (y, wy) in [(y0, 1.0 - ty), (y1, ty)] {
                let t = lut.texel(layer, x, y, z);
                for l in 0..LANES {
                    v[l] += wz * wy * t[l];
                }
            }
        }
        v
    })
}

/// Looks up a camera slice along view zenith cosine `mu` from the slice's viewpoint: linear in
/// mu, as the 3D look-up is.
pub fn camera_slice(p: &Params, slice: &Lut, layer: usize, mu: f64) -> Lanes {
    let [fx, _, _] = texel_from_h_mu_mu_s(p, 0.0, mu, 0.0);
    slice.bilinear(layer, fx, 0.0, 0)
}

#[cfg(test)]
mod tests {
    use super::super::{RAYLEIGH, Tables, look_up};
    use super::*;
    use crate::methods::SkyModel;
    use crate::methods::shared::lut::tests::rough_table;
    use crate::methods::shared::optics::tests::{VIEWPOINTS_INSIDE, params};

    /// From a viewpoint inside the atmosphere, the slice's look-up gives the 3D look-up for
    /// every view zenith cosine, at texel centres and between them.
    #[test]
    fn the_slice_reads_what_the_three_dimensional_table_reads_at_the_camera() {
        let p = params();
        let layers = p.batches.len();
        let lut = rough_table(&RAYLEIGH, layers);
        // And the top of the atmosphere with the sun at the nadir: the tables' last texels.
        let top = Viewpoint {
            h: p.thickness_m(),
            mu_s: -1.0,
        };
        for vp in VIEWPOINTS_INSIDE.into_iter().chain([top]) {
            let slice = compute_camera_slice(&p, &CAMERA_RAYLEIGH, &lut, vp);
            for mu in [0.9, -0.5, 0.01, -0.02, 0.0, 1.0, -1.0, 0.3] {
                for layer in 0..layers {
                    let (a, b) = (
                        camera_slice(&p, &slice, layer, mu),
                        look_up(&p, &lut, layer, vp.h, mu, vp.mu_s),
                    );
                    for l in 0..LANES {
                        assert!(
                            (a[l] - b[l]).abs() <= 1e-9 * b[l].abs().max(1.0),
                            "{vp:?} mu {mu}: {a:?} against {b:?}"
                        );
                    }
                }
            }
        }
    }

    /// A twin moved to another viewpoint reads there what the 3D tables read, for both tables.
    #[test]
    fn a_twin_moved_to_a_viewpoint_slices_its_tables_there() {
        let p = params().with_scattering_orders(1);
        let mut tables = Tables::compute(&p, super::super::tests::GROUND_NOON);
        let vp = Viewpoint {
            h: 8000.0,
            mu_s: 0.1,
        };
        let before = tables.camera_rayleigh.clone();
        assert!(tables.move_to(vp));
        assert_ne!(tables.camera_rayleigh.data, before.data);
        for (slice, lut) in [
            (&tables.camera_rayleigh, &tables.rayleigh),
            (&tables.camera_mie, &tables.mie),
        ] {
            let (a, b) = (
                camera_slice(&p, slice, 0, 0.2),
                look_up(&p, lut, 0, vp.h, 0.2, vp.mu_s),
            );
            assert!(b[0] > 0.0);
            for l in 0..LANES {
                assert!((a[l] - b[l]).abs() <= 1e-12 * b[l], "{a:?} against {b:?}");
            }
        }
    }
}
