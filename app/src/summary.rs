//! A scene's summary per wavelength: the vertical optical depth of each constituent from the
//! camera to space, the aerosol's single-scattering albedo and asymmetry, and the direct
//! transmittance of sunlight from the top of the atmosphere to the camera. Shown by
//! `atmoscope info` and by the explorer.

use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::geometry::{Ray, direction_from_angles};
use atmoscope_model::{Atmosphere, Scene};
use glam::DVec3;
use serde::Serialize;

#[derive(Serialize, Debug, Clone, Copy)]
pub struct OpticalDepthRow {
    pub rayleigh: f64,
    pub ozone: f64,
    pub aerosol: f64,
    pub total: f64,
}

#[derive(Serialize, Debug)]
pub struct WavelengthRow {
    pub wavelength_nm: f64,
    /// Vertical optical depth from the camera's altitude to space.
    pub optical_depth: OpticalDepthRow,
    pub aerosol_ssa: f64,
    pub aerosol_g: f64,
    /// Direct transmittance from the top of the atmosphere to the camera along the sun direction.
    pub direct_transmittance: f64,
    /// Direct transmittance from the camera along the horizontal out of the atmosphere: what
    /// a ray skimming the ground keeps.
    pub horizontal_transmittance: f64,
    /// Extinction coefficient of each constituent at the camera, m⁻¹.
    pub extinction_at_camera_per_m: OpticalDepthRow,
}

#[derive(Serialize, Debug)]
pub struct Info {
    pub scene: String,
    pub camera_altitude_m: f64,
    pub sun_elevation_deg: f64,
    pub sun_azimuth_deg: f64,
    pub aerosol_type: String,
    pub aod550: f64,
    pub ozone_column_du: f64,
    pub air_profile: String,
    pub ozone_profile: String,
    pub wavelengths: Vec<WavelengthRow>,
}

/// Computes the report for a scene.
pub fn compute(scene: &Scene, wavelengths_nm: &[f64]) -> Info {
    let atm = Atmosphere::for_scene(&scene);
    let sun = scene.sun.angles();
    let camera = DVec3::new(0.0, 0.0, atm.bottom_radius_m + scene.camera.altitude_m);
    let sun_dir = direction_from_angles(sun.elevation_deg, sun.azimuth_deg);
    let wavelengths = wavelengths_nm
        .iter()
        .map(|&w| {
            let optics = atm.optics(w);
            let tau = atm.vertical_optical_depth(&optics, scene.camera.altitude_m);
            WavelengthRow {
                wavelength_nm: w,
                optical_depth: OpticalDepthRow {
                    rayleigh: tau.rayleigh,
                    ozone: tau.ozone,
                    aerosol: tau.aerosol,
                    total: tau.total(),
                },
                aerosol_ssa: optics.aerosol_ssa,
                aerosol_g: optics.aerosol_g,
                direct_transmittance: atm.transmittance_to_sun(&optics, camera, sun_dir),
                extinction_at_camera_per_m: {
                    let c = atm.coefficients(&optics, scene.camera.altitude_m);
                    let aerosol = c.aerosol_scattering + c.aerosol_absorption;
                    OpticalDepthRow {
                        rayleigh: c.rayleigh_scattering,
                        ozone: c.ozone_absorption,
                        aerosol,
                        total: c.extinction(),
                    }
                },
                horizontal_transmittance: (-atm
                    .optical_depth(&optics, &Ray::new(camera, DVec3::X))
                    .total())
                .exp(),
            }
        })
        .collect();
    Info {
        scene: scene.name.clone(),
        camera_altitude_m: scene.camera.altitude_m,
        sun_elevation_deg: sun.elevation_deg,
        sun_azimuth_deg: sun.azimuth_deg,
        aerosol_type: scene.atmosphere.aerosol.kind.cli_name().into(),
        aod550: if scene.atmosphere.aerosol.kind == AerosolType::None {
            0.0
        } else {
            scene.atmosphere.aerosol.aod550
        },
        ozone_column_du: atm.ozone_column_du,
        air_profile: scene.atmosphere.air_profile.cli_name().into(),
        ozone_profile: scene.atmosphere.ozone.profile.cli_name().into(),
        wavelengths,
    }
}
