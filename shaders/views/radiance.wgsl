// What the sky pass's entry point (views/sky.wgsl) draws along a direction: the model's own
// radiance, in every frame.

fn view_radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    return radiance(layer, dir);
}
