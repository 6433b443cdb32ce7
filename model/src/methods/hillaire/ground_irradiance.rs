//! Sky irradiance on the ground per unit solar irradiance, E(mu_s): our addition to Hillaire
//! (2020), whose ground is lit by the sun alone. Twin of `shaders/hillaire/ground_irradiance.wgsl`.

use super::{
    Lanes, Lut, Params, Spacing, TableSpec, integrate_inscattering, mu_s_axis_coordinate,
    mu_s_axis_mu_s,
};
use crate::geometry::distance_to_top;
use crate::methods::Inputs;
use crate::methods::shared::local_sun;
use glam::DVec3;
use std::f64::consts::PI;

/// Ground irradiance table size (mu_s), on the twilight-dense axis of [`super::MU_S_AXIS_U`].
pub const GROUND_IRRADIANCE_SIZE: u32 = 64;
/// Directions of the ground irradiance integral: 16 rings about the sun, at angles
/// γ = π·u² from it (u the ring's stratum: dense near the sun, where aerosol's forward peak
/// is), × 16 azimuths about it. Only the half on one side of the sun's vertical plane is
/// integrated (its mirror image has the same zenith angle and angle to the sun), twice over, and
/// of those the ones below the horizon are skipped. The azimuths are a multiple of 4, so that
/// half is the same grid's own directions.
pub const GROUND_IRRADIANCE_DIRECTIONS: [u32; 2] = [16, 16];
const _: () = assert!(GROUND_IRRADIANCE_DIRECTIONS[1] % 4 == 0);

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

/// Sky irradiance on horizontal ground per unit solar irradiance, ∫ L·cos θ dΩ over the upper
/// hemisphere, on the rings about the sun of [`GROUND_IRRADIANCE_DIRECTIONS`].
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
    let [n_rings, n_azimuths] = GROUND_IRRADIANCE_DIRECTIONS;
    let mut sum = Lanes::ZERO;
    for i in 0..n_rings {
        // Each direction stands for itself and its mirror image.
        for j in 0..n_azimuths / 2 {
            let a = 2.0 * PI * (j as f64 + 0.5) / n_azimuths as f64 - 0.5 * PI;
            let e = direction_irradiance(p, t, ms, layer, mu_s, i, a);
            sum = sum + (e * 2.0);
        }
    }
    sum
}

/// The irradiance on the ground from the direction at azimuth `a` (rad) about the sun on ring
/// `ring`: L·cos θ times the direction's solid angle; zero below the horizon.
fn direction_irradiance(
    p: &Params,
    t: &Lut,
    ms: &Lut,
    layer: usize,
    mu_s: f64,
    ring: u32,
    a: f64,
) -> Lanes {
    let [n_rings, n_azimuths] = GROUND_IRRADIANCE_DIRECTIONS;
    let sun = local_sun(mu_s);
    // A frame about the sun (local_sun lies in the x–z plane).
    let across = DVec3::Y;
    let up = sun.cross(across);
    let (u0, u1) = (
        ring as f64 / n_rings as f64,
        (ring + 1) as f64 / n_rings as f64,
    );
    let gamma = PI * (0.5 * (u0 + u1)).powi(2);
    let ring_solid_angle = 2.0 * PI * ((PI * u0 * u0).cos() - (PI * u1 * u1).cos());
    let weight = ring_solid_angle / n_azimuths as f64;
    let dir = sun * gamma.cos() + (across * a.cos() + up * a.sin()) * gamma.sin();
    let mu = dir.z;
    if mu <= 0.0 {
        return Lanes::ZERO;
    }
    let t_max = distance_to_top(0.0, mu, p.bottom_radius_m, p.top_radius_m);
    let (l, _) = integrate_inscattering(
        p,
        t,
        ms,
        layer,
        (0.0, mu, mu_s, gamma.cos()),
        (0.0, t_max),
        p.steps.ground_irradiance,
        Spacing::Quadratic,
    );
    l * (mu * weight)
}

/// Looks up the sky irradiance on the ground per unit solar irradiance.
pub fn ground_irradiance(gi: &Lut, layer: usize, mu_s: f64) -> Lanes {
    gi.bilinear(layer, ground_irradiance_texel_from_mu_s(mu_s), 0.0, 0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerosol::AerosolType;
    use crate::methods::hillaire::multiple_scattering::compute_multiple_scattering_lut;
    use crate::methods::shared::transmittance::compute_transmittance_lut;
    use crate::scene::{Quality, Scene, WavelengthSet};
    use crate::wavelengths::LANES;

    /// The integral over 64 × 128 cosine-weighted directions: the converged value.
    fn dense(p: &Params, t: &Lut, ms: &Lut, mu_s: f64) -> Lanes {
        let (n_theta, n_phi) = (64, 128);
        let sun = local_sun(mu_s);
        let mut sum = Lanes::ZERO;
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
                    0,
                    (0.0, mu, mu_s, nu),
                    (0.0, t_max),
                    p.steps.ground_irradiance,
                    Spacing::Quadratic,
                );
                sum = sum + l;
            }
        }
        sum * (PI / f64::from(n_theta * n_phi))
    }

    /// Spectral4 parameters of the default scene under `kind` aerosol at `aod` (550 nm), with
    /// its transmittance and multiple-scattering tables.
    fn hazy(kind: AerosolType, aod: f64, quality: Quality) -> (Params, Lut, Lut) {
        let mut scene = Scene::default();
        scene.atmosphere.aerosol.kind = kind;
        scene.atmosphere.aerosol.aod550 = aod;
        let p = Params::new(
            &crate::Atmosphere::for_scene(&scene),
            WavelengthSet::Spectral4,
            quality,
        );
        let t = compute_transmittance_lut(&p);
        let ms = compute_multiple_scattering_lut(&p, &t);
        (p, t, ms)
    }

    /// Integrating one side of the sun's vertical plane twice gives the whole grid of rings ×
    /// azimuths, in haze, sun high and low.
    #[test]
    fn the_mirror_half_of_the_azimuths_gives_the_whole_grid() {
        let (p, t, ms) = hazy(AerosolType::Rural, 0.3, Quality::Low);
        let [n_rings, n_azimuths] = GROUND_IRRADIANCE_DIRECTIONS;
        for mu_s in [0.9, 0.2, 0.02, -0.1] {
            let mut whole = Lanes::ZERO;
            for i in 0..n_rings {
                for j in 0..n_azimuths {
                    let a = 2.0 * PI * (j as f64 + 0.5) / n_azimuths as f64;
                    whole = whole + direction_irradiance(&p, &t, &ms, 0, mu_s, i, a);
                }
            }
            let half = compute_ground_irradiance(&p, &t, &ms, 0, mu_s);
            for i in 0..LANES {
                assert!(whole[i] > 0.0, "mu_s {mu_s}, lane {i}");
                let rel = (half[i] / whole[i] - 1.0).abs();
                assert!(rel < 1e-12, "mu_s {mu_s}, lane {i}: {rel:e}");
            }
        }
    }

    /// The rings about the sun catch aerosol's circumsolar peak: within 1.5 % of the converged
    /// integral in haze and dust at every sun (a cosine-weighted grid, blind to where the sun
    /// is, misses the peak's share at low sun).
    #[test]
    fn ground_irradiance_follows_the_converged_integral_at_low_sun_in_haze() {
        for (kind, aod) in [
            (AerosolType::Rural, 0.15),
            (AerosolType::Rural, 0.5),
            (AerosolType::DesertDust, 0.5),
        ] {
            let (p, t, ms) = hazy(kind, aod, Quality::Medium);
            for deg in [60.0f64, 10.0, 5.0, 2.0, -3.0] {
                let mu_s = deg.to_radians().sin();
                let (got, want) = (
                    compute_ground_irradiance(&p, &t, &ms, 0, mu_s),
                    dense(&p, &t, &ms, mu_s),
                );
                for i in 0..LANES {
                    assert!(
                        (got[i] / want[i] - 1.0).abs() < 0.015,
                        "{kind:?} AOD {aod}, sun {deg}°: {got:?} vs {want:?}"
                    );
                }
            }
        }
    }
}
