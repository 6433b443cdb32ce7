//! Elek (2009) pass "single scattering": Rayleigh and Mie single scattering of every texel,
//! without phase functions, along the texel's ray with the sun in the view's half-plane; seeds
//! the last-order tables and the sums. Twin of `shaders/elek/single_scattering.wgsl`.

pub use crate::methods::shared::ray::single_scattering;
