//! Bruneton (2017) pass "single scattering": Rayleigh and Mie single scattering of every texel,
//! without phase functions, integrated along the view ray to the ground or the top by the
//! shared texel-ray integrator ([`crate::methods::shared::ray`]). Twin of
//! `shaders/bruneton/single_scattering.wgsl`.

pub use crate::methods::shared::ray::single_scattering;
