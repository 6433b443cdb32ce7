// Pass: Nishita et al.'s (1996) intensity volume, the light scattered once
// (shared/intensity_volume_order1.wgsl along shared/intensity_volume_march.wgsl). Twin of
// model::methods::shared::intensity_volume::compute_single.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let v = intensity_volume_texel(invocation);
    if !inside_intensity_volume(v) {
        return;
    }
    intensity_volume_lut[intensity_index(v)] = intensity_march(v);
}
