// The way to the sun as the still frame takes it: marched, or by the closed form, at every
// sample (shared/sun_route.wgsl).

fn sun_transmittance_by_way(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return sun_transmittance_marched(layer, h, mu_s);
}
