//! Hillaire (2020) §5.3: the sky-view table at the camera's altitude, azimuth from the sun ×
//! view zenith with the quadratic latitude mapping that puts texels near the horizon. Twin of
//! `shaders/hillaire/sky_view.wgsl`.

use super::{Lanes, Lut, Params, Spacing, TableSpec, Viewpoint, integrate_inscattering};
use crate::geometry::{distance_to_boundary, horizon_beta};
use crate::methods::Inputs;
use crate::methods::shared::{direction_from_phi_theta, local_sun};
use std::f64::consts::PI;

/// Sky-view table size (azimuth, zenith): 192 × 108 as in the paper; the height is even so that
/// the horizon falls between two rows and lookups never blend sky with ground.
pub const SKY_VIEW_SIZE: [u32; 2] = [192, 108];

pub const TABLE: TableSpec = TableSpec {
    id: "sky-view",
    label: "sky view",
    size: [SKY_VIEW_SIZE[0], SKY_VIEW_SIZE[1], 1],
    axes: [
        "x: azimuth from the sun φ, 0 (left) to 180° (right), √ spacing",
        "y: view zenith θ, zenith (top) to the horizon (middle) to nadir (bottom), quadratic towards the horizon",
        "",
    ],
    invalidated_by: Inputs::ATMOSPHERE.union(Inputs::VIEWPOINT),
    transmittance: false,
    describe_texel: |p, h, [x, y, _]| {
        let (phi, theta) = sky_view_angles_from_texel(p, h, x, y);
        format!(
            "φ = {:.1}°, θ = {:.2}°",
            phi.to_degrees(),
            theta.to_degrees()
        )
    },
};

/// Fractional texel coordinates of (azimuth from the sun φ ∈ [0, π], view zenith θ ∈ [0, π])
/// in the sky-view table at altitude `h`. Rows above the middle are sky, below are ground.
pub fn sky_view_texel_from_angles(p: &Params, h: f64, phi: f64, theta: f64) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let theta_h = PI - beta;
    let v = if theta < theta_h {
        0.5 * (1.0 - (1.0 - theta / theta_h).max(0.0).sqrt())
    } else {
        0.5 + 0.5 * ((theta - theta_h) / beta).clamp(0.0, 1.0).sqrt()
    };
    let u = (phi / PI).clamp(0.0, 1.0).sqrt();
    let [w, hh] = SKY_VIEW_SIZE;
    (u * (w - 1) as f64, v * (hh - 1) as f64)
}

/// (φ, θ) of the sky-view texel at fractional coordinates (fx, fy) for altitude `h`.
pub fn sky_view_angles_from_texel(p: &Params, h: f64, fx: f64, fy: f64) -> (f64, f64) {
    let beta = horizon_beta(h, p.bottom_radius_m);
    let theta_h = PI - beta;
    let [w, hh] = SKY_VIEW_SIZE;
    let (u, v) = (fx / (w - 1) as f64, fy / (hh - 1) as f64);
    let theta = if v < 0.5 {
        let c = 1.0 - 2.0 * v;
        theta_h * (1.0 - c * c)
    } else {
        let c = 2.0 * v - 1.0;
        theta_h + beta * c * c
    };
    (PI * u * u, theta)
}

/// Sky-view table: in-scattered radiance (W·m⁻²·sr⁻¹·nm⁻¹) to the top or the ground.
pub fn compute_sky_view_lut(p: &Params, t: &Lut, ms: &Lut, vp: Viewpoint) -> Lut {
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, y, x| {
        let (phi, theta) = sky_view_angles_from_texel(p, vp.h, x as f64, y as f64);
        let omega = direction_from_phi_theta(phi, theta);
        let (mu, nu) = (omega.z, omega.dot(local_sun(vp.mu_s)));
        let big_r = p.bottom_radius_m;
        let t_max = distance_to_boundary(vp.h, mu, big_r, p.top_radius_m);
        let (l, _) = integrate_inscattering(
            p,
            t,
            ms,
            layer,
            (vp.h, mu, vp.mu_s, nu),
            (0.0, t_max),
            p.steps.sky_view,
            Spacing::Quadratic,
        );
        l * p.batches[layer].solar_irradiance
    })
}

/// Looks up the sky view; `ground` picks the half of the table (never blended across).
pub fn sky_view(
    p: &Params,
    sv: &Lut,
    layer: usize,
    h: f64,
    phi: f64,
    theta: f64,
    ground: bool,
) -> Lanes {
    let (fx, fy) = sky_view_texel_from_angles(p, h, phi, theta);
    let half = (SKY_VIEW_SIZE[1] / 2) as f64;
    let fy = if ground {
        fy.max(half)
    } else {
        fy.min(half - 1.0)
    };
    sv.bilinear(layer, fx, fy, 0)
}
