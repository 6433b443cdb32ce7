//! The scattering tables at the camera: the 2D slice (nu, mu) of each 4D table at the camera's
//! altitude and sun zenith cosine, built when those change (as Hillaire's sky view is). Every
//! ray from a camera inside the atmosphere starts at that altitude with that sun, and a look-up
//! is multilinear in the table's four texel coordinates, so blending in r and mu_s once here
//! and then only in nu and mu per pixel gives what the 4D look-up gives, from four texels of
//! each table instead of sixteen. Twin of `shaders/bruneton/camera_slice.wgsl`; the sky pass
//! reads it unless a ray can start with the sun below the tables or above the atmosphere.

use super::{
    Coords, Lanes, Lut, Params, SCATTERING_MU, SCATTERING_MU_S, SCATTERING_NU, SCATTERING_SIZE,
    TableSpec, Viewpoint, mu_s_texel, mu_texel, nu_texel, r_texel,
};
use crate::methods::Inputs;
use crate::methods::shared::lut::split;
use crate::wavelengths::LANES;

/// The slice's size: nu slices × mu texels of the 4D tables.
pub const CAMERA_SLICE_SIZE: [u32; 2] = [SCATTERING_NU, SCATTERING_MU];

const fn camera_table(id: &'static str, label: &'static str) -> TableSpec {
    TableSpec {
        id,
        label,
        size: [CAMERA_SLICE_SIZE[0], CAMERA_SLICE_SIZE[1], 1],
        axes: [
            "x: view–sun cosine ν, −1 (left) to 1 (right)",
            "y: view zenith cosine μ as in the 4D tables: rays to the ground, then rays to the sky",
            "",
        ],
        invalidated_by: Inputs::ATMOSPHERE.union(Inputs::VIEWPOINT),
        transmittance: false,
        describe_texel: |p, h, [x, y, _]| {
            let nu = -1.0 + 2.0 * x / f64::from(SCATTERING_NU - 1);
            let c = super::scattering_coords_from_texel(p, 0.0, y, r_texel(p, h));
            format!(
                "ν = {nu:.3}, μ = {:.4}{} at the camera",
                c.mu,
                if c.ground { " (to the ground)" } else { "" }
            )
        },
    }
}

/// The scattering table (Rayleigh + orders ≥ 2) at the camera.
pub const CAMERA_SCATTERING: TableSpec =
    camera_table("camera-scattering", "scattering at the camera");
/// The single-Mie table at the camera.
pub const CAMERA_SINGLE_MIE: TableSpec =
    camera_table("camera-single-mie", "single Mie at the camera");

/// The slice of the 4D table `lut` at viewpoint `vp`: texel (nu slice, mu) blended over the
/// texels around the camera's r and mu_s.
pub fn compute_camera_slice(p: &Params, spec: &TableSpec, lut: &Lut, vp: Viewpoint) -> Lut {
    let (j0, j1, tx) = split(mu_s_texel(p, vp.mu_s), SCATTERING_MU_S as usize);
    let (z0, z1, tz) = split(r_texel(p, vp.h), SCATTERING_SIZE[2] as usize);
    Lut::from_spec(spec, p.batches.len(), |layer, _, y, x| {
        let mut v = Lanes::ZERO;
        for (z, wz) in [(z0, 1.0 - tz), (z1, tz)] {
            for (j, wx) in [(j0, 1.0 - tx), (j1, tx)] {
                let t = lut.texel(layer, x * SCATTERING_MU_S as usize + j, y, z);
                for l in 0..LANES {
                    v[l] += wz * wx * t[l];
                }
            }
        }
        v
    })
}

/// Looks up a camera slice for the ray of `c`, which starts at the slice's viewpoint: linear
/// in nu between slices, then in mu, as the 4D look-up is.
pub fn camera_slice(p: &Params, slice: &Lut, layer: usize, c: Coords) -> Lanes {
    slice.bilinear(layer, nu_texel(c.nu), mu_texel(p, c.h, c.mu, c.ground), 0)
}

#[cfg(test)]
mod tests {
    use super::super::{SCATTERING, Tables, scattering};
    use super::*;
    use crate::methods::SkyModel;
    use crate::methods::shared::lut::tests::rough_table;
    use crate::methods::shared::optics::tests::{VIEWPOINTS_INSIDE, params};

    /// A twin moved to another viewpoint reads there what the 4D tables read, for both tables.
    #[test]
    fn a_twin_moved_to_a_viewpoint_slices_its_tables_there() {
        let p = params().with_scattering_orders(1);
        let mut tables = Tables::compute(&p, Viewpoint { h: 0.0, mu_s: 1.0 });
        let vp = Viewpoint {
            h: 8000.0,
            mu_s: 0.1,
        };
        let before = tables.camera_scattering.clone();
        assert!(tables.move_to(vp));
        assert_ne!(tables.camera_scattering.data, before.data);
        let c = Coords {
            h: vp.h,
            mu: 0.2,
            mu_s: vp.mu_s,
            nu: 0.5,
            ground: false,
        };
        for (slice, lut) in [
            (&tables.camera_scattering, &tables.scattering),
            (&tables.camera_single_mie, &tables.single_mie),
        ] {
            let (a, b) = (camera_slice(&p, slice, 0, c), scattering(&p, lut, 0, c));
            assert!(b[0] > 0.0);
            for l in 0..LANES {
                assert!((a[l] - b[l]).abs() <= 1e-12 * b[l], "{a:?} against {b:?}");
            }
        }
    }

    /// From a viewpoint inside the atmosphere, the slice's look-up gives the 4D look-up for
    /// every direction, at texel centres and between them, on the ground half and the sky half.
    #[test]
    fn the_slice_reads_what_the_four_dimensional_table_reads_at_the_camera() {
        let p = params();
        let layers = p.batches.len();
        let lut = rough_table(&SCATTERING, layers);
        for vp in VIEWPOINTS_INSIDE {
            let slice = compute_camera_slice(&p, &CAMERA_SCATTERING, &lut, vp);
            for (mu, nu) in [
                (0.9, 0.8),
                (-0.5, -0.3),
                (0.01, 0.999),
                (-0.02, -1.0),
                (0.3, 0.0),
            ] {
                let ground = crate::geometry::hits_ground(vp.h, mu, p.bottom_radius_m);
                let c = Coords {
                    h: vp.h,
                    mu,
                    mu_s: vp.mu_s,
                    nu,
                    ground,
                };
                for layer in 0..layers {
                    let (a, b) = (
                        camera_slice(&p, &slice, layer, c),
                        scattering(&p, &lut, layer, c),
                    );
                    for l in 0..LANES {
                        assert!(
                            (a[l] - b[l]).abs() <= 1e-9 * b[l].abs().max(1.0),
                            "{vp:?} mu {mu} nu {nu}: {a:?} against {b:?}"
                        );
                    }
                }
            }
        }
    }
}
