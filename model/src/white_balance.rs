//! White balance: the display treats a chosen light as white by a chromatic adaptation
//! transform (Bradford's cone space, as in ICC profiles; Lam 1985) from that light's white
//! to D65, applied to linear sRGB before exposure. The whites: none (D65 itself), the sun's
//! direct light at the ground when overhead through the scene's atmosphere ("the sun at
//! noon"), or a blackbody at a colour temperature.

use crate::Atmosphere;
use crate::colour::{D65_WHITE, Xyz, linear_srgb_to_xyz, spectrum_to_xyz, xyz_to_linear_srgb};
use crate::constants::{
    BOLTZMANN_J_PER_K, PLANCK_J_S, SPEED_OF_LIGHT_M_PER_S, VISIBLE_MAX_NM, VISIBLE_MIN_NM,
};
use crate::scene::{Scene, WhiteBalance};
use crate::spectrum::Spectrum;
use glam::{DMat3, DVec3};

/// Bradford's cone response matrix (rows), XYZ → sharpened LMS.
pub const BRADFORD: [[f64; 3]; 3] = [
    [0.8951, 0.2664, -0.1614],
    [-0.7502, 1.7135, 0.0367],
    [0.0389, -0.0685, 1.0296],
];

/// Wavelength step of the spectral whites, nm.
const STEP_NM: f64 = 5.0;

fn wavelengths() -> Vec<f64> {
    let n = ((VISIBLE_MAX_NM - VISIBLE_MIN_NM) / STEP_NM) as usize;
    (0..=n)
        .map(|i| VISIBLE_MIN_NM + i as f64 * STEP_NM)
        .collect()
}

fn normalised(xyz: Xyz) -> Xyz {
    Xyz {
        x: xyz.x / xyz.y,
        y: 1.0,
        z: xyz.z / xyz.y,
    }
}

fn white_of(values: impl Fn(f64) -> f64) -> Xyz {
    let w = wavelengths();
    let v = w.iter().map(|&l| values(l)).collect();
    match Spectrum::new(w, v) {
        Ok(s) => normalised(spectrum_to_xyz(&s)),
        Err(_) => D65_WHITE,
    }
}

/// The white (Y = 1) of a blackbody at `kelvin` (Planck's law).
pub fn blackbody_white(kelvin: f64) -> Xyz {
    let (h, c, k) = (PLANCK_J_S, SPEED_OF_LIGHT_M_PER_S, BOLTZMANN_J_PER_K);
    white_of(|nm| {
        let l = nm * 1e-9;
        1.0 / (l.powi(5) * ((h * c / (l * k * kelvin)).exp() - 1.0))
    })
}

/// The white (Y = 1) of the sun's direct light at the ground with the sun overhead, through
/// `atmosphere`.
pub fn noon_sun_white(atmosphere: &Atmosphere) -> Xyz {
    let solar = atmosphere.solar_spectrum.spectrum();
    white_of(|nm| {
        let tau = atmosphere
            .vertical_optical_depth(&atmosphere.optics(nm), 0.0)
            .total();
        solar.sample(nm) * (-tau).exp()
    })
}

fn rows(m: [[f64; 3]; 3]) -> DMat3 {
    DMat3::from_cols_array_2d(&m).transpose()
}

/// The matrix (rows, on linear sRGB) that shows light of the colour `white` as D65 white.
pub fn adaptation(white: Xyz) -> [[f64; 3]; 3] {
    let to_xyz = DMat3::from_cols(
        DVec3::from(xyz_array(linear_srgb_to_xyz([1.0, 0.0, 0.0]))),
        DVec3::from(xyz_array(linear_srgb_to_xyz([0.0, 1.0, 0.0]))),
        DVec3::from(xyz_array(linear_srgb_to_xyz([0.0, 0.0, 1.0]))),
    );
    let bradford = rows(BRADFORD);
    let from = bradford * DVec3::from(xyz_array(white));
    let to = bradford * DVec3::from(xyz_array(D65_WHITE));
    let scale = DMat3::from_diagonal(to / from);
    let m = to_xyz.inverse() * bradford.inverse() * scale * bradford * to_xyz;
    m.transpose().to_cols_array_2d()
}

fn xyz_array(c: Xyz) -> [f64; 3] {
    [c.x, c.y, c.z]
}

/// The identity: no white balance.
pub const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The white balance matrix of `scene` (the noon sun's white computed with `noon_white` when
/// the scene asks for it, so that a caller can keep it with its atmosphere).
pub fn matrix_with(scene: &Scene, noon_white: impl FnOnce() -> Xyz) -> [[f64; 3]; 3] {
    match scene.display.white_balance {
        WhiteBalance::None => IDENTITY,
        WhiteBalance::SunAtNoon => adaptation(noon_white()),
        WhiteBalance::Temperature { kelvin } => {
            let k = crate::scene::limits::WHITE_BALANCE_KELVIN;
            adaptation(blackbody_white(kelvin.clamp(k.min, k.max)))
        }
    }
}

/// The white balance matrix of `scene`.
pub fn matrix(scene: &Scene) -> [[f64; 3]; 3] {
    matrix_with(scene, || {
        noon_sun_white(&Atmosphere::new(&scene.atmosphere))
    })
}

/// `m` applied to linear sRGB.
pub fn apply(m: &[[f64; 3]; 3], rgb: [f64; 3]) -> [f64; 3] {
    m.map(|r| r[0] * rgb[0] + r[1] * rgb[1] + r[2] * rgb[2])
}

/// The linear sRGB of a white (for tests and the UI's swatch).
pub fn srgb_of(white: Xyz) -> [f64; 3] {
    xyz_to_linear_srgb(white)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// D65 white stays white under any balance to D65; the light a balance is set for comes
    /// out neutral; a 6504 K blackbody is near D65; candlelight is red and the noon sun, seen
    /// through air that scatters blue away, slightly warm.
    #[test]
    fn white_balance_maps_its_white_to_neutral_and_keeps_d65() {
        let d65 = srgb_of(D65_WHITE);
        assert!(d65.iter().all(|c| (c - 1.0).abs() < 1e-3), "{d65:?}");
        let same = apply(&adaptation(D65_WHITE), d65);
        assert!(
            same.iter().zip(d65).all(|(a, b)| (a - b).abs() < 1e-12),
            "{same:?}"
        );
        for kelvin in [2000.0, 3200.0, 5000.0, 9000.0] {
            let white = blackbody_white(kelvin);
            let shown = apply(&adaptation(white), srgb_of(white));
            assert!(
                shown.iter().all(|c| (c - 1.0).abs() < 1e-6),
                "{kelvin} K: {shown:?}"
            );
            // …and a D65 white then looks like the opposite of that light.
            let d = apply(&adaptation(white), d65);
            assert!((d[2] > d[0]) == (kelvin < 6504.0), "{kelvin} K: {d:?}");
        }
        let near = srgb_of(blackbody_white(6504.0));
        assert!(near.iter().all(|c| (c - 1.0).abs() < 0.1), "{near:?}");
        let candle = srgb_of(blackbody_white(1900.0));
        assert!(candle[0] > 2.0 * candle[2], "{candle:?}");
        let sun = srgb_of(noon_sun_white(&Atmosphere::new(
            &Scene::default().atmosphere,
        )));
        assert!(sun[0] > sun[2] && sun[2] > 0.6 * sun[0], "{sun:?}");
        assert_eq!(matrix(&Scene::default()), IDENTITY);
    }
}
