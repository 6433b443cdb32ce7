//! Models held against measured skies: spectroradiometer scans of the sky dome in the format of
//! Kider et al. (2014) (`data/kider_2014/`, the day that ships), scored as Bruneton (2017)
//! scored eight clear-sky models on them.
//!
//! - [`files`] reads a folder of measured days, untrusted ([`aeronet`] its sun-photometer file);
//! - [`symmetry`] finds the sun's azimuth in the instrument's frame from the sky's symmetry;
//! - [`sky`] builds a scan's scene and evaluates a model's CPU twin or the path tracer there;
//! - [`retrieve`] finds the aerosol from AERONET, the pyranometer ([`broadband`]) or a fit;
//! - [`score`] measures the errors; [`run`] does it all for one scan.
//!
//! Nothing here is tuned to the shipped day: `atmoscope bench measured` runs it on any folder in
//! the same format.

pub mod aeronet;
pub mod broadband;
pub mod clock;
pub mod files;
pub mod retrieve;
pub mod run;
pub mod score;
pub mod sky;
pub mod symmetry;

/// The folder of the day that ships with the project (Kider et al. 2014, Cornell).
pub fn shipped_folder() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/kider_2014")
}
