// The floor pass of `atmoscope bench gpu`: the least a full-screen pass of the view's size and
// format costs (one write per pixel), against which every pass is reported as a multiple.

@group(0) @binding(0) var floor_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(floor_out);
    if any(id.xy >= size) {
        return;
    }
    textureStore(floor_out, id.xy, vec4<f32>(vec2<f32>(id.xy) / vec2<f32>(size), 0.0, 1.0));
}
