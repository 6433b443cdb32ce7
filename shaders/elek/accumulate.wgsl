// Pass (once per order k ≥ 2): adds the order just computed to the sums. Apart from the multiple
// scattering pass because a pass binds at most six tables beside group 0. Twin of
// model::methods::elek::accumulate.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= ELEK_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let k = elek_index(v.w, v.x, v.y, v.z);
    rayleigh_scattering_lut[k] += delta_rayleigh_lut[k];
    mie_scattering_lut[k] += delta_mie_lut[k];
}
