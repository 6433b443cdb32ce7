// Single scattering alone: no higher orders for the table-free sky pass
// (shared/single_scattering_sky.wgsl) to add, and no skylight on the ground.

fn higher_orders(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    return array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
}

fn ground_skylight(layer: u32, mu_s_g: f32) -> vec4<f32> {
    return vec4<f32>(0.0);
}
