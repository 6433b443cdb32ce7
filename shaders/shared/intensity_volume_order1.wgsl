// Order 1 of an intensity volume (intensity_volume::compute_single): the sunlight through the
// transmittance table, scattered once towards the ray, and the sunlit ground.

fn order_source(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    let sun_t = sun_transmittance(layer, h, mu_s);
    return array<vec4<f32>, 2>(
        rayleigh_phase(nu, batches[layer].rayleigh_depolarisation) * sun_t,
        aerosol_phase(nu, layer) * sun_t,
    );
}

fn order_ground(layer: u32, mu_s_g: f32) -> vec4<f32> {
    return sun_transmittance(layer, 0.0, mu_s_g) * max(mu_s_g, 0.0);
}
