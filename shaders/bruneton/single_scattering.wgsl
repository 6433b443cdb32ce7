// Pass: Rayleigh and Mie single scattering without phase functions, integrated along each
// texel's ray (common/ray.wgsl); seeds the deltas and the sums. Twin of
// model::methods::bruneton::single_scattering.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= SCATTERING_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let s = single_scattering(layer, scattering_coords(v.x, v.y, v.z));
    let k = scattering_index(layer, v.x, v.y, v.z);
    delta_rayleigh_lut[k] = s.rayleigh;
    delta_mie_lut[k] = s.mie;
    scattering_lut[k] = s.rayleigh;
    single_mie_lut[k] = s.mie;
}
