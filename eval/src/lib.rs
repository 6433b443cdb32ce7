//! Atmoscope's evaluation tools, apart from the physics so that `atmoscope-model` builds with
//! cargo alone: image metrics against a reference ([`metrics`]: ΔE2000, FLIP through the
//! `nv-flip` crate, which builds C++), Leenman's (2025) comparison of sky models replayed
//! ([`leenman`]: his Earth, views and published tables) and the derivative-free optimizer the
//! fits use ([`optimize`]), and the models held against measured skies ([`measured`]).

pub mod leenman;
pub mod measured;
pub mod metrics;
pub mod optimize;
