// Pass (once per order k ≥ 2): order k of every texel, the gathered order k − 1 times the local
// scattering coefficients, integrated along the texel's ray through the transmittance; becomes
// the last order (the accumulate pass adds it to the sums). Twin of
// model::methods::elek::multiple_scattering.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= ELEK_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let b = batches[layer];
    let c = elek_coords(v.x, v.y, v.z);
    let n = globals.steps_b.z;
    var rayleigh = vec4<f32>(0.0);
    var mie = vec4<f32>(0.0);
    for (var k = 0u; k < 2u * (n + 1u); k++) {
        let sample = ray_sample(c, k, n);
        let d = sample.x;
        let at = along(c, d);
        let t = elek_taps(layer, elek_texel(at.x, at.y, at.z));
        let tr = sample.y * transmittance_between(layer, c.h, c.mu, d);
        let m = medium(b, at.x);
        rayleigh += tr * m.rayleigh_scattering * read_gathered_rayleigh(t);
        mie += tr * m.aerosol_scattering * read_gathered_mie(t);
    }
    let k = elek_index(layer, v.x, v.y, v.z);
    delta_rayleigh_lut[k] = rayleigh;
    delta_mie_lut[k] = mie;
}
