// Pass: Rayleigh and Mie single scattering without phase functions along each texel's ray, the
// sun in the view's half-plane (common/ray.wgsl); seeds the last order and the sums. Twin of
// model::methods::elek::single_scattering.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= ELEK_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let s = single_scattering(layer, elek_coords(v.x, v.y, v.z));
    let k = elek_index(layer, v.x, v.y, v.z);
    delta_rayleigh_lut[k] = s.rayleigh;
    delta_mie_lut[k] = s.mie;
    rayleigh_scattering_lut[k] = s.rayleigh;
    mie_scattering_lut[k] = s.mie;
}
