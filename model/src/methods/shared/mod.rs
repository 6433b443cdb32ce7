//! What every table-based sky model shares: the per-batch optics and density profile
//! ([`optics`]), the table container with its declared axes ([`table`]), the transmittance table
//! in Bruneton's (2017) mapping with the sun's visible fraction ([`transmittance`]), the spacing
//! and weights of ray marches ([`march`]) and the sun's disk ([`sun`]). Geometry in (h, mu) lives
//! in [`crate::geometry`]. WGSL twins are in `shaders/common/`.

pub mod march;
pub mod optics;
pub mod sun;
pub mod table;
pub mod transmittance;

pub use march::{SMALL_OPTICAL_THICKNESS, Spacing, segment_weight};
pub use optics::{BatchOptics, Medium, PROFILE_SAMPLES, Params, Steps, Viewpoint, viewpoint};
pub use sun::sun_disk;
pub use table::{Lut, TableSpec};

use crate::wavelengths::LANES;
use glam::DVec3;

/// Four lanes (wavelengths) of one batch.
pub type Lanes = [f64; LANES];

pub(crate) fn lerp(a: Lanes, b: Lanes, t: f64) -> Lanes {
    std::array::from_fn(|i| a[i] + (b[i] - a[i]) * t)
}

pub(crate) fn add(a: Lanes, b: Lanes) -> Lanes {
    std::array::from_fn(|i| a[i] + b[i])
}

pub(crate) fn mul(a: Lanes, b: Lanes) -> Lanes {
    std::array::from_fn(|i| a[i] * b[i])
}

pub(crate) fn scale(a: Lanes, k: f64) -> Lanes {
    a.map(|v| v * k)
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
