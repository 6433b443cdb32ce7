// What the sky pass of a march per pixel draws along a direction (render::methods::
// moving_sky_pass): in frames drawn in tiles (SKY_TILE > 1, a view in motion on a software
// GPU) from inside the atmosphere, the moving sky, the model's own radiance on the sky-view
// grid (shared/moving_sky.wgsl), looked up; otherwise the march itself. Twin of
// model::methods::shared::moving_sky::radiance.

fn view_radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    if SKY_TILE > 1u && !ABOVE_ATMOSPHERE {
        let up = normalize(globals.camera_position.xyz);
        let h = globals.camera_position.w;
        let angles = sun_relative_angles(up, dir, globals.sun.xyz);
        let t = sky_view_taps(layer, h, angles.x, angles.y, sees_ground(h, dot(dir, up)));
        return blend(moving_sky_lut[t.i.x], moving_sky_lut[t.i.y], moving_sky_lut[t.i.z],
            moving_sky_lut[t.i.w], t.w);
    }
    return radiance(layer, dir);
}
