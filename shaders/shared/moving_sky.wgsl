// Pass: the moving sky of a march per pixel (render::methods::moving_sky_pass). The pass's own
// file is the model's sky file, whose radiance(layer, dir) this evaluates at the directions of
// the sky-view grid (common/sky_view.wgsl) at the camera's altitude, azimuth measured from the
// sun's: the sky and the sunlit ground as the still frame draws them, at 192 × 108 directions
// instead of every pixel. Frames in tiles look their pixels up in it
// (views/moving_sky_radiance.wgsl). Twin of model::methods::shared::moving_sky::compute_lut.

// The unit world direction at azimuth `phi` from the sun's and zenith angle `theta` about `up`.
fn direction_from_sun_azimuth(up: vec3<f32>, sun: vec3<f32>, phi: f32, theta: f32) -> vec3<f32> {
    var across = sun - up * dot(sun, up);
    if length(across) <= VERTICAL_RAD {
        // The sun at the zenith or the nadir: every azimuth is the same.
        let other = select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), abs(up.x) > 0.9);
        across = cross(up, other);
    }
    let towards_sun = normalize(across);
    let aside = cross(up, towards_sun);
    return up * cos(theta) + (towards_sun * cos(phi) + aside * sin(phi)) * sin(theta);
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
) {
    let id = dispatched_split(workgroup, local);
    if any(id.xy >= SKY_VIEW_SIZE) || id.z >= batch_count() {
        return;
    }
    let h = globals.camera_position.w;
    let angles = sky_view_angles_from_texel(h, vec2<f32>(id.xy));
    let dir = direction_from_sun_azimuth(normalize(globals.camera_position.xyz), globals.sun.xyz,
        angles.x, angles.y);
    moving_sky_lut[(id.z * SKY_VIEW_SIZE.y + id.y) * SKY_VIEW_SIZE.x + id.x] = radiance(id.z, dir);
}
