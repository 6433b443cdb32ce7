// The -ms rows' higher orders for the table-free sky pass (shared/single_scattering_sky.wgsl):
// Hillaire's isotropic Ψ_ms (hillaire/common.wgsl) for both constituents and every view, and
// no skylight on the ground. Twin of single_scattering_sky::HillaireHigherOrders.

fn higher_orders(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    let s = psi(layer, h, mu_s);
    return array<vec4<f32>, 2>(s, s);
}

fn ground_skylight(layer: u32, mu_s_g: f32) -> vec4<f32> {
    return vec4<f32>(0.0);
}
