//! The fitting subcommands: `fit-wavelengths` (Spectral4's matrix and wavelengths against
//! SpectralN) and `fit-garcia-linan` (García Liñán's multiple-scattering constants against the
//! path tracer).

pub mod garcia_linan;
pub mod wavelengths;
