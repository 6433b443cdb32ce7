// Pass (once per order n ≥ 2): the sky irradiance of order n − 1 on a horizontal surface, the
// delta tables over the upper hemisphere; added to the sky-irradiance sum. Twin of
// model::methods::bruneton::indirect_irradiance.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= IRRADIANCE_SIZE) || id.z >= batch_count() {
        return;
    }
    let layer = id.z;
    let b = batches[layer];
    let hm = irradiance_h_mu_s(vec2<f32>(id.xy));
    let h = hm.x;
    let mu_s = hm.y;
    let n = globals.steps_b.w;
    let step = 0.5 * PI / f32(n);
    let sun = vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);
    let x_mu_s = mu_s_texel(mu_s);
    let x_r = r_texel(h);
    var e = vec4<f32>(0.0);
    for (var l = 0u; l < n; l++) {
        let theta = (f32(l) + 0.5) * step;
        let sin_t = sin(theta);
        let cos_t = cos(theta);
        let x_mu = mu_texel(h, cos_t, false);
        for (var k = 0u; k < 4u * n; k++) {
            let phi = (f32(k) + 0.5) * step;
            let w = vec3<f32>(cos(phi) * sin_t, sin(phi) * sin_t, cos_t);
            let nu = clamp(dot(w, sun), -1.0, 1.0);
            e += previous_order(b, layer, vec4<f32>(x_mu_s, nu_texel(nu), x_mu, x_r), nu) * cos_t * sin_t * step * step;
        }
    }
    let i = (layer * IRRADIANCE_SIZE.y + id.y) * IRRADIANCE_SIZE.x + id.x;
    delta_irradiance_lut[i] = e;
    irradiance_lut[i] += e;
}
