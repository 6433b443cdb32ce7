// Pass (once per order n ≥ 2): the last order becomes the one the next is gathered from
// (haber/next_order.wgsl rewrites delta_intensity_lut). Twin of model::methods::haber::build.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let v = intensity_volume_texel(invocation);
    if !inside_intensity_volume(v) {
        return;
    }
    let i = intensity_index(v);
    previous_intensity_lut[i] = delta_intensity_lut[i];
}
