//! Atmoscope's physics in f64, independent of any GPU: spectra and reference tables, the
//! constituents of the atmosphere (air, ozone, aerosols), ray geometry around the planet,
//! optical depth, colour science, the sun's position, and the `Scene` preset format.
//!
//! Data flows Scene → [`Atmosphere`] (optical properties at any wavelength) → renderers.

pub mod aerosol;
pub mod atmosphere;
pub mod camera;
pub mod colour;
pub mod constants;
pub mod csv_table;
pub mod display;
pub mod engine_atmosphere;
pub mod files;
pub mod geometry;
pub mod ground;
pub mod lanes;
pub mod methods;
pub mod mie;
pub mod ozone;
pub mod phase;
pub mod polarisation;
pub mod profiles;
pub mod quadrature;
pub mod rayleigh;
pub mod reference;
pub mod scene;
pub mod solar_spectrum;
pub mod spectrum;
pub mod sun_position;
pub mod views;
pub mod wavelengths;
pub mod white_balance;

pub use atmosphere::{Atmosphere, OpticalDepth, Optics};
pub use scene::{Scene, SceneError};
pub use spectrum::Spectrum;

/// Errors of the model's own constructors.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("invalid spectrum: {0}")]
    InvalidSpectrum(String),
}
