// Pass: display. The radiance image as shown (views/tone.wgsl), for frames that change only
// how the view is displayed (exposure, tone map, white balance, mode).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= globals.view.xy) {
        return;
    }
    textureStore(display_out, id.xy, displayed(id.xy, textureLoad(radiance_in, id.xy, 0)));
}
