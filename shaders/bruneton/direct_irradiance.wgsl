// Pass: direct sunlight on a horizontal surface (the delta irradiance the first scattering
// density reads); clears the sky-irradiance sum. Twin of
// model::methods::bruneton::direct_irradiance.

fn cosine_factor(mu_s: f32) -> f32 {
    let a = SUN_ANGULAR_RADIUS_RAD;
    if mu_s < -a {
        return 0.0;
    }
    if mu_s > a {
        return mu_s;
    }
    return (mu_s + a) * (mu_s + a) / (4.0 * a);
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= IRRADIANCE_SIZE) || id.z >= batch_count() {
        return;
    }
    let hm = irradiance_h_mu_s(vec2<f32>(id.xy));
    let i = (id.z * IRRADIANCE_SIZE.y + id.y) * IRRADIANCE_SIZE.x + id.x;
    delta_irradiance_lut[i] = batches[id.z].solar_irradiance * transmittance(id.z, hm.x, hm.y) * cosine_factor(hm.y);
    irradiance_lut[i] = vec4<f32>(0.0);
}
