//! Atmoscope's GPU side: the wgpu engine. Every function takes a `wgpu::Device` and `Queue`
//! from its caller, so the same code renders into the explorer's window, into files from the
//! command line, and in tests. This crate never depends on egui.
//!
//! Data flow: `Scene` → `model::methods::shared::Params` (f64) → [`uniforms`] (f32 GPU structs
//! and a generated WGSL [`prelude`]) → the passes of the scene's model ([`methods`], compiled
//! by [`passes`], run by the [`engine`]) → [`views`] textures.

pub mod engine;
pub mod floor;
pub mod gpu;
pub mod methods;
pub mod passes;
pub mod prelude;
pub mod readback;
pub mod spec;
pub mod stress;
pub mod uniforms;
pub mod views;

pub use atmoscope_model::methods::Inputs;
pub use engine::{Engine, EngineError, FrameStats, MovingSkyStep, Spans, TimingSource};
pub use gpu::{GpuContext, GpuError};
pub use uniforms::DisplayMode;
pub use views::View;

/// The wgpu version this crate is built against, for callers and tests.
pub use wgpu;
