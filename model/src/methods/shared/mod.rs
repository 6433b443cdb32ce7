//! What every table-based sky model shares: the per-batch optics and density profile
//! ([`optics`]), the table container with its declared axes ([`table`]), the transmittance table
//! in Bruneton's (2017) mapping with the sun's visible fraction ([`transmittance`]), the spacing
//! and weights of ray marches ([`march`]), the sun's disk ([`sun`]) and the integrals along a
//! table texel's ray ([`ray`]). Geometry in (h, mu) lives
//! in [`crate::geometry`]. WGSL twins are in `shaders/common/`.

pub mod exponential;
pub mod intensity_volume;
pub mod lut;
pub mod march;
pub mod moving_sky;
pub mod mu_s_axis;
pub mod optics;
pub mod polarisation;
pub mod ray;
pub mod segments_sky;
pub mod single_scattering_sky;
pub mod sun_disk;
pub mod sun_rows;
pub mod transmittance;

pub use lut::{Lut, TableSpec};
pub use march::{SMALL_OPTICAL_THICKNESS, Spacing, segment_weight};
pub use optics::{
    BATCH_MODEL_ROWS, BatchOptics, BatchRows, Medium, PROFILE_SAMPLES, Params, Steps, Viewpoint,
    viewpoint,
};
pub use sun_disk::sun_disk;

pub use crate::lanes::Lanes;
use glam::DVec3;

/// The Rayleigh phase function per lane of batch `layer` at view–sun cosine `nu`, sr⁻¹.
pub fn rayleigh_phase(p: &Params, layer: usize, nu: f64) -> Lanes {
    p.batches[layer]
        .rayleigh_depolarisation
        .map(|rho| crate::phase::rayleigh(nu, rho))
}

/// The aerosol phase function per lane of batch `layer` at view–sun cosine `nu`, sr⁻¹.
pub fn aerosol_phase(p: &Params, layer: usize, nu: f64) -> Lanes {
    p.aerosol_phase(layer, nu)
}

/// The sun's direction in a local frame where the view azimuth is measured from it: (x, 0, mu_s).
pub fn local_sun(mu_s: f64) -> DVec3 {
    DVec3::new((1.0 - mu_s * mu_s).max(0.0).sqrt(), 0.0, mu_s)
}

/// Unit direction at azimuth φ from the sun and zenith angle θ in the frame of [`local_sun`].
pub fn direction_from_phi_theta(phi: f64, theta: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// Within this angle of the vertical (rad) a direction's azimuth is taken as the sun's: f32
/// rounds an exactly vertical direction to one up to 3.5e-4 rad off, whose azimuth is noise
/// (found by `atmoscope stress` at the nadir from the top of the atmosphere).
pub const VERTICAL_RAD: f64 = 1e-3;

/// Azimuth from the sun φ ∈ [0, π] and zenith angle θ (rad) of the unit direction `dir` seen
/// from a point whose local vertical is `up`, with the sun in the unit direction `sun`: the
/// coordinates of the view tables.
pub fn sun_relative_angles(up: DVec3, dir: DVec3, sun: DVec3) -> (f64, f64) {
    let (mu, mu_s) = (dir.dot(up), sun.dot(up));
    let dir_t = dir - up * mu;
    let sun_t = sun - up * mu_s;
    let (a, b) = (dir_t.length(), sun_t.length());
    let cos_phi = if a > VERTICAL_RAD && b > VERTICAL_RAD {
        dir_t.dot(sun_t) / (a * b)
    } else {
        1.0
    };
    (cos_phi.clamp(-1.0, 1.0).acos(), mu.clamp(-1.0, 1.0).acos())
}

/// Where the ray (h, mu) from above the atmosphere enters it: the zenith cosines of the ray and
/// of the sun (`mu_s`, view–sun cosine `nu`) at the entry point on the top sphere, or None
/// when the ray misses the atmosphere.
pub fn entry_into_atmosphere(
    p: &Params,
    h: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
) -> Option<(f64, f64)> {
    let (r, top) = (p.bottom_radius_m + h, p.top_radius_m);
    let disc = r * r * mu * mu - (h - p.thickness_m()) * (r + top);
    if mu >= 0.0 || disc < 0.0 {
        return None;
    }
    let t_entry = -r * mu - disc.sqrt();
    Some((
        ((r * mu + t_entry) / top).clamp(-1.0, 1.0),
        ((r * mu_s + t_entry * nu) / top).clamp(-1.0, 1.0),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An exactly vertical direction as f32 rounds it (3.5e-4 rad off) has the sun's azimuth,
    /// as the exact one does: the GPU and its twin read the same texel at the nadir.
    #[test]
    fn a_vertical_direction_takes_the_suns_azimuth() {
        let up = DVec3::Z;
        let sun = DVec3::new(0.0, 0.99, -0.1).normalize();
        for dir in [-DVec3::Z, DVec3::new(3.5e-4, -2e-4, -1.0).normalize()] {
            let (phi, theta) = sun_relative_angles(up, dir, sun);
            assert_eq!(phi, 0.0, "{dir}");
            assert!(theta > 0.999 * std::f64::consts::PI, "{theta}");
        }
        let (phi, _) = sun_relative_angles(up, DVec3::new(0.1, 0.0, -1.0).normalize(), sun);
        assert!((phi - std::f64::consts::FRAC_PI_2).abs() < 1e-9, "{phi}");
    }
}
