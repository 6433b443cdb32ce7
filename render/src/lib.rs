//! Atmoscope's GPU side: the wgpu engine. Every function takes a `wgpu::Device` and `Queue`
//! from its caller, so the same code renders into the explorer's window, into files from the
//! command line, and in tests. This crate never depends on egui.

pub mod gpu;

pub use gpu::{GpuContext, GpuError};

/// The wgpu version this crate is built against, for callers and tests.
pub use wgpu;
