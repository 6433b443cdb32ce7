// The sun's disk of the table-based models, which the sky entry point (views/sky.wgsl) draws:
// the transmittance table along the sun's own ray. Twin of SkyModel::sun's default.

fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return sun_seen_from(layer, h, mu_s);
}
