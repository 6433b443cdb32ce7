// Pass: sky-view table at the camera's altitude, in the sun's azimuth frame: in-scattered
// radiance to the top or the ground (Hillaire 2020 §5.3); each texel's march split across
// MARCH_SPLIT invocations (common/group.wgsl).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, MARCH_SPLIT)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_split(workgroup, local);
    let inside = all(id.xy < SKY_VIEW_SIZE) && id.z < batch_count();
    var part = nothing_marched();
    if inside {
        let h = globals.camera_position.w;
        let mu_s = globals.sun.w;
        let angles = sky_view_angles_from_texel(h, vec2<f32>(id.xy));
        let omega = direction_from_phi_theta(angles.x, angles.y);
        let mu = omega.z;
        let nu = dot(omega, local_sun(mu_s));
        let t_max = distance_to_boundary(h, mu);
        let n = globals.steps_a.w;
        part = integrate_inscattering_steps(id.z, vec4<f32>(h, mu, mu_s, nu), 0.0, t_max,
            march_run(local.z, MARCH_SPLIT, n), n, SPACING_QUADRATIC);
    }
    let l = split_join(index, part);
    if inside && local.z == 0u {
        let i = (id.z * SKY_VIEW_SIZE.y + id.y) * SKY_VIEW_SIZE.x + id.x;
        sky_view_lut[i] = l.radiance * batches[id.z].solar_irradiance;
    }
}
