//! Atmoscope's GPU side: the wgpu engine. Every function takes a `wgpu::Device` and `Queue`
//! from its caller, so the same code renders into the explorer's window, into files from the
//! command line, and in tests. This crate never depends on egui.
//!
//! Data flow: `Scene` → `model::methods::hillaire::Params` (f64) → [`uniforms`] (f32 GPU
//! structs and a generated WGSL [`prelude`]) → the passes of [`hillaire`] → [`views`] textures.

pub mod engine;
pub mod gpu;
pub mod hillaire;
pub mod prelude;
pub mod readback;
pub mod uniforms;
pub mod views;

pub use engine::{Engine, EngineError, FrameStats, Inputs, Pass, TimingSource};
pub use gpu::{GpuContext, GpuError};
pub use hillaire::Table;
pub use uniforms::DisplayMode;
pub use views::View;

/// The wgpu version this crate is built against, for callers and tests.
pub use wgpu;
