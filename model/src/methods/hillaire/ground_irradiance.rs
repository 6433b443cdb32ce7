//! Sky irradiance on the ground per unit solar irradiance, E(mu_s): our addition to Hillaire
//! (2020), whose ground is lit by the sun alone. Twin of `shaders/hillaire/ground_irradiance.wgsl`.

use super::{
    Lanes, Lut, Params, Spacing, TableSpec, integrate_inscattering, mu_s_axis_coordinate,
    mu_s_axis_mu_s,
};
use crate::geometry::distance_to_top;
use crate::methods::Inputs;
use crate::methods::shared::{add, local_sun, scale};
use crate::wavelengths::LANES;
use glam::DVec3;
use std::f64::consts::PI;

/// Ground irradiance table size (mu_s), on the twilight-dense axis of [`super::MU_S_AXIS_U`].
pub const GROUND_IRRADIANCE_SIZE: u32 = 64;
/// Directions of the ground irradiance integral: 8 (cosine-weighted zenith) × 16 (azimuth).
pub const GROUND_IRRADIANCE_DIRECTIONS: [u32; 2] = [8, 16];

pub const TABLE: TableSpec = TableSpec {
    id: "ground-irradiance",
    label: "ground irradiance",
    size: [GROUND_IRRADIANCE_SIZE, 1, 1],
    axes: [
        "x: sun zenith cosine μ_s, −1 (left) to 1 (right), dense from −0.3 to 0.1",
        "one row",
        "",
    ],
    invalidated_by: Inputs::ATMOSPHERE,
    transmittance: false,
    describe_texel: |_, _, [x, _, _]| format!("μ_s = {:.4}", ground_irradiance_mu_s_from_texel(x)),
};

/// Fractional texel coordinate of mu_s in the ground irradiance table.
pub fn ground_irradiance_texel_from_mu_s(mu_s: f64) -> f64 {
    mu_s_axis_coordinate(mu_s) * (GROUND_IRRADIANCE_SIZE - 1) as f64
}

/// mu_s of the ground irradiance texel at fractional coordinate fx.
pub fn ground_irradiance_mu_s_from_texel(fx: f64) -> f64 {
    mu_s_axis_mu_s(fx / (GROUND_IRRADIANCE_SIZE - 1) as f64)
}

/// Sky irradiance on horizontal ground per unit solar irradiance, by cosine-weighted
/// stratified directions over the upper hemisphere (E = π·mean L).
pub fn compute_ground_irradiance_lut(p: &Params, t: &Lut, ms: &Lut) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, _, x| {
        let mu_s = ground_irradiance_mu_s_from_texel(x as f64);
        compute_ground_irradiance(p, t, ms, layer, mu_s)
    })
}

pub(crate) fn compute_ground_irradiance(
    p: &Params,
    t: &Lut,
    ms: &Lut,
    layer: usize,
    mu_s: f64,
) -> Lanes {
    let [n_theta, n_phi] = GROUND_IRRADIANCE_DIRECTIONS;
    let sun = local_sun(mu_s);
    let mut sum = [0.0; LANES];
    for i in 0..n_theta {
        let mu = ((i as f64 + 0.5) / n_theta as f64).sqrt();
        let s = (1.0 - mu * mu).sqrt();
        for j in 0..n_phi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
            let nu = DVec3::new(s * phi.cos(), s * phi.sin(), mu).dot(sun);
            let t_max = distance_to_top(0.0, mu, p.bottom_radius_m, p.top_radius_m);
            let (l, _) = integrate_inscattering(
                p,
                t,
                ms,
                layer,
                (0.0, mu, mu_s, nu),
                (0.0, t_max),
                p.steps.ground_irradiance,
                Spacing::Quadratic,
            );
            sum = add(sum, l);
        }
    }
    scale(sum, PI / (n_theta * n_phi) as f64)
}

/// Looks up the sky irradiance on the ground per unit solar irradiance.
pub fn ground_irradiance(gi: &Lut, layer: usize, mu_s: f64) -> Lanes {
    gi.bilinear(layer, ground_irradiance_texel_from_mu_s(mu_s), 0.0, 0)
}
