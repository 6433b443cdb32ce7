// Pass: order 1 of Haber et al.'s (2005) orders (shared/intensity_volume_order1.wgsl along
// shared/intensity_volume_march.wgsl): the volume's sum, its last order and the order before it
// all start as order 1. Twin of model::methods::haber::build's first order.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let v = intensity_volume_texel(invocation);
    if !inside_intensity_volume(v) {
        return;
    }
    let i = intensity_index(v);
    let l = intensity_march(v);
    intensity_volume_lut[i] = l;
    delta_intensity_lut[i] = l;
    previous_intensity_lut[i] = l;
}
