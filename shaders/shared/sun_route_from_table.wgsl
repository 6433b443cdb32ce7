// The way to the sun as the moving sky of a nested march takes it: exp(−depth) of the optical
// depth blended from the model's own table (shared/sun_route_table.wgsl), on the
// transmittance table's mapping (common/transmittance.wgsl); twin of
// SunRoute::transmittance_in_motion.

fn sun_transmittance_by_way(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let visible = sun_visible_fraction(h, mu_s);
    if visible <= 0.0 {
        return vec4<f32>(0.0);
    }
    let t = taps(TRANSMITTANCE_SIZE, layer, transmittance_texel_from_h_mu(h, mu_s));
    let depth = blend(sun_route_lut[t.i.x], sun_route_lut[t.i.y], sun_route_lut[t.i.z],
        sun_route_lut[t.i.w], t.w);
    return exp(-depth) * visible;
}
