// Single scattering alone: no higher orders for the table-free sky pass
// (shared/single_scattering_sky.wgsl) to add.

fn psi(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return vec4<f32>(0.0);
}
