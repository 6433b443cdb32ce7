// Pass: sky-view table at the camera's altitude, in the sun's azimuth frame: in-scattered
// radiance to the top or the ground (Hillaire 2020 §5.3).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= SKY_VIEW_SIZE) || id.z >= batch_count() {
        return;
    }
    let h = globals.camera_position.w;
    let mu_s = globals.sun.w;
    let angles = sky_view_angles_from_texel(h, vec2<f32>(id.xy));
    let omega = direction_from_phi_theta(angles.x, angles.y);
    let mu = omega.z;
    let nu = dot(omega, local_sun(mu_s));
    let t_max = distance_to_boundary(h, mu);
    let l = integrate_inscattering(id.z,
        vec4<f32>(h, mu, mu_s, nu), 0.0, t_max, globals.steps_a.w, SPACING_QUADRATIC);
    let i = (id.z * SKY_VIEW_SIZE.y + id.y) * SKY_VIEW_SIZE.x + id.x;
    sky_view_lut[i] = l.radiance * batches[id.z].solar_irradiance;
}
