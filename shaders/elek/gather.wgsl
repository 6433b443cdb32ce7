// Pass (once per order k ≥ 2): the last order's Rayleigh and Mie tables gathered over the
// sphere with each one's phase function towards the texel's view; one look-up per zenith ring
// (the tables have no azimuth), half the azimuths counted twice. Twin of
// model::methods::elek::gather.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= ELEK_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let b = batches[layer];
    let a = elek_h_mu_mu_s(v.x, v.y, v.z);
    let mu = a.y;
    let n = globals.steps_b.w;
    let step = PI / f32(n);
    let sin_v = sqrt(max(1.0 - mu * mu, 0.0));
    var rayleigh = vec4<f32>(0.0);
    var mie = vec4<f32>(0.0);
    for (var l = 0u; l < n; l++) {
        let theta = (f32(l) + 0.5) * step;
        let sin_t = sin(theta);
        let cos_t = cos(theta);
        let t = elek_taps(layer, elek_texel(a.x, cos_t, a.z));
        var w_r = vec4<f32>(0.0);
        var w_m = vec4<f32>(0.0);
        for (var k = 0u; k < n; k++) {
            let phi = (f32(k) + 0.5) * step;
            let nu = clamp(sin_t * cos(phi) * sin_v + cos_t * mu, -1.0, 1.0);
            w_r += rayleigh_phase(nu, b.rayleigh_depolarisation);
            w_m += aerosol_phase(nu, layer);
        }
        let d_omega = 2.0 * step * step * sin_t;
        rayleigh += read_delta_rayleigh(t) * w_r * d_omega;
        mie += read_delta_mie(t) * w_m * d_omega;
    }
    let k = elek_index(layer, v.x, v.y, v.z);
    gathered_rayleigh_lut[k] = rayleigh;
    gathered_mie_lut[k] = mie;
}
