//! García Liñán (2023) §5.2–5.3: the sky texture — the in-scattered radiance of every direction
//! seen from the camera, equirectangular around the sun's vertical with the elevation mapped
//! quadratically so that texels crowd at the horizon. Twin of
//! `shaders/garcia_linan/sky_texture.wgsl`.
//!
//! The thesis's texture spans the full azimuth (256 × 256); the sky is symmetric about the sun's
//! vertical, so this one stores azimuths from the sun over [0, π] in half the columns, at the
//! same resolution.

use super::{Constants, Lanes, Lut, Params, TableSpec, Viewpoint, integrate};
use crate::geometry::distance_to_boundary;
use crate::methods::Inputs;
use crate::methods::shared::{direction_from_phi_theta, local_sun};
use std::f64::consts::{FRAC_PI_2, PI};

/// Sky texture size (azimuth from the sun, elevation).
pub const SKY_TEXTURE_SIZE: [u32; 2] = [128, 256];

pub const TABLE: TableSpec = TableSpec {
    id: "sky-texture",
    label: "sky texture",
    size: [SKY_TEXTURE_SIZE[0], SKY_TEXTURE_SIZE[1], 1],
    axes: [
        "x: azimuth from the sun φ, 0 (left) to 180° (right), linear",
        "y: elevation, zenith (top) to the horizontal (middle) to nadir (bottom), quadratic towards the horizontal",
        "",
    ],
    // The light the sunlit ground below scatters back into the sky (`ground_bounce`).
    invalidated_by: Inputs::ATMOSPHERE
        .union(Inputs::VIEWPOINT)
        .union(Inputs::GROUND_ALBEDO),
    transmittance: false,
    describe_texel: |_, _, [x, y, _]| {
        let (phi, e) = sky_texture_angles_from_texel(x, y);
        format!(
            "φ = {:.1}°, elevation = {:.2}°",
            phi.to_degrees(),
            e.to_degrees()
        )
    },
};

/// Fractional texel coordinates of (azimuth from the sun φ ∈ [0, π], elevation e ∈ [−π/2, π/2]).
pub fn sky_texture_texel_from_angles(phi: f64, e: f64) -> (f64, f64) {
    let l = e.signum() * (e.abs() / FRAC_PI_2).min(1.0).sqrt();
    let [w, h] = SKY_TEXTURE_SIZE;
    (
        (phi / PI).clamp(0.0, 1.0) * (w - 1) as f64,
        0.5 * (1.0 - l) * (h - 1) as f64,
    )
}

/// (φ, elevation) of the texel at fractional coordinates (fx, fy).
pub fn sky_texture_angles_from_texel(fx: f64, fy: f64) -> (f64, f64) {
    let [w, h] = SKY_TEXTURE_SIZE;
    let l = 1.0 - 2.0 * fy / (h - 1) as f64;
    (PI * fx / (w - 1) as f64, l.signum() * l * l * FRAC_PI_2)
}

/// The sky texture: in-scattered radiance (W·m⁻²·sr⁻¹·nm⁻¹) from the camera to the top or the
/// ground, per direction; the camera's altitude is clamped to the top of the atmosphere.
pub fn compute_sky_texture(p: &Params, t: &Lut, c: &Constants, vp: Viewpoint) -> Lut {
    let h = vp.h.min(p.thickness_m());
    Lut::from_spec(&TABLE, p.batches.len(), |layer, _, y, x| {
        let (phi, e) = sky_texture_angles_from_texel(x as f64, y as f64);
        let omega = direction_from_phi_theta(phi, FRAC_PI_2 - e);
        let (mu, nu) = (omega.z, omega.dot(local_sun(vp.mu_s)));
        let t_max = distance_to_boundary(h, mu, p.bottom_radius_m, p.top_radius_m);
        let (l, _) = integrate(
            p,
            t,
            c,
            layer,
            (h, mu, vp.mu_s, nu),
            (0.0, t_max),
            p.steps.sky_view,
        );
        l * p.batches[layer].solar_irradiance
    })
}

/// Looks up the sky texture at (φ, elevation).
pub fn sky_texture(s: &Lut, layer: usize, phi: f64, e: f64) -> Lanes {
    let (fx, fy) = sky_texture_texel_from_angles(phi, e);
    s.bilinear(layer, fx, fy, 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sky_texture_mapping_round_trips_and_puts_the_horizontal_between_rows() {
        for &(phi, e) in &[(0.0, FRAC_PI_2), (0.4, 0.01), (2.0, -0.3), (PI, -FRAC_PI_2)] {
            let (fx, fy) = sky_texture_texel_from_angles(phi, e);
            let (phi2, e2) = sky_texture_angles_from_texel(fx, fy);
            assert!(
                (phi2 - phi).abs() < 1e-12 && (e2 - e).abs() < 1e-12,
                "{phi} {e}"
            );
        }
        let (_, fy) = sky_texture_texel_from_angles(0.0, 0.0);
        assert_eq!(fy, 0.5 * (SKY_TEXTURE_SIZE[1] - 1) as f64);
        // Texels crowd at the horizontal: the first row above it is within 0.01°.
        let (_, e) = sky_texture_angles_from_texel(0.0, fy.floor());
        assert!(e > 0.0 && e.to_degrees() < 0.01, "{}", e.to_degrees());
    }
}
