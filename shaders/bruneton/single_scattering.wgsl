// Pass: Rayleigh and Mie single scattering without phase functions, integrated along each
// texel's ray; seeds the deltas and the sums. Twin of model::methods::bruneton::single_scattering.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let v = volume_texel(id);
    if any(v.xy >= SCATTERING_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let c = scattering_coords(v.x, v.y, v.z);
    let b = batches[layer];
    let n = globals.steps_b.z;
    var rayleigh = vec4<f32>(0.0);
    var mie = vec4<f32>(0.0);
    for (var k = 0u; k < 2u * (n + 1u); k++) {
        let sample = ray_sample(c, k, n);
        let d = sample.x;
        let at = along(c, d);
        let tr = sample.y * transmittance_between(layer, c.h, c.mu, d)
            * sun_transmittance(layer, at.x, at.z);
        let m = medium(b, at.x);
        rayleigh += tr * m.rayleigh_scattering;
        mie += tr * m.aerosol_scattering;
    }
    let k = scattering_index(layer, v.x, v.y, v.z);
    let r = rayleigh * b.solar_irradiance;
    let s = mie * b.solar_irradiance;
    delta_rayleigh_lut[k] = r;
    delta_mie_lut[k] = s;
    scattering_lut[k] = r;
    single_mie_lut[k] = s;
}
