// Pass (once per order n ≥ 2): the scattering density J of order n, the previous order's
// radiance from every direction (plus the ground lit by the delta irradiance) scattered towards
// the texel's view direction. Twin of model::methods::bruneton::scattering_density.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= SCATTERING_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let c = scattering_coords(v.x, v.y, v.z);
    let b = batches[layer];
    let r = bottom_radius() + c.h;
    let view = vec3<f32>(sqrt(max(1.0 - c.mu * c.mu, 0.0)), 0.0, c.mu);
    var s_x = 0.0;
    if view.x != 0.0 {
        s_x = (c.nu - c.mu * c.mu_s) / view.x;
    }
    let sun = vec3<f32>(s_x, sqrt(max(1.0 - s_x * s_x - c.mu_s * c.mu_s, 0.0)), c.mu_s);
    let n = globals.steps_b.w;
    let step = PI / f32(n);
    let m = medium(b, c.h);
    let x_mu_s = mu_s_texel(c.mu_s);
    let x_r = r_texel(c.h);
    var j = vec4<f32>(0.0);
    for (var l = 0u; l < n; l++) {
        let theta = (f32(l) + 0.5) * step;
        let sin_t = sin(theta);
        let cos_t = cos(theta);
        let ground = hits_ground(c.h, cos_t);
        var d_g = 0.0;
        var t_g = vec4<f32>(0.0);
        if ground {
            d_g = distance_to_ground(c.h, cos_t);
            t_g = transmittance_between(layer, c.h, cos_t, d_g);
        }
        let x_mu = mu_texel(c.h, cos_t, ground);
        let d_omega = step * step * sin_t;
        for (var k = 0u; k < 2u * n; k++) {
            let phi = (f32(k) + 0.5) * step;
            let w = vec3<f32>(cos(phi) * sin_t, sin(phi) * sin_t, cos_t);
            let nu = clamp(dot(sun, w), -1.0, 1.0);
            var radiance = previous_order(b, layer, vec4<f32>(x_mu_s, nu_texel(nu), x_mu, x_r), nu);
            if ground {
                let normal = normalize(vec3<f32>(0.0, 0.0, r) + w * d_g);
                radiance += t_g * b.ground_albedo / PI * read_delta_irradiance(layer, 0.0, dot(normal, sun));
            }
            let nu_v = clamp(dot(view, w), -1.0, 1.0);
            j += radiance * (m.rayleigh_scattering * rayleigh_phase(nu_v, b.rayleigh_depolarisation)
                + m.aerosol_scattering * aerosol_phase(nu_v, layer)) * d_omega;
        }
    }
    scattering_density_lut[scattering_index(layer, v.x, v.y, v.z)] = j;
}
