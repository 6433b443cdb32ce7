//! Rendering methods, one module each (the GPU side mirrors these names in `render` and
//! `shaders/`). In f64 on the CPU; the path tracer is the ground truth every other method is
//! measured against.

pub mod hillaire;
pub mod path_tracer;
pub mod rng;
pub mod single_scattering;
