// Pass: the sky texture at the camera's altitude (García Liñán 2023 §5.2–5.3): single
// scattering plus L_g and L_ms, marched to the top or the ground; each texel's march split
// across MARCH_SPLIT invocations (common/group.wgsl).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, MARCH_SPLIT)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_split(workgroup, local);
    let inside = all(id.xy < SKY_TEXTURE_SIZE) && id.z < batch_count();
    var part = nothing_marched();
    if inside {
        let h = min(globals.camera_position.w, thickness());
        let mu_s = globals.sun.w;
        let angles = sky_texture_angles_from_texel(vec2<f32>(id.xy));
        let omega = direction_from_phi_theta(angles.x, 0.5 * PI - angles.y);
        let mu = omega.z;
        let nu = dot(omega, local_sun(mu_s));
        let t_max = distance_to_boundary(h, mu);
        let n = globals.steps_a.w;
        part = integrate_inscattering_steps(id.z, vec4<f32>(h, mu, mu_s, nu), 0.0, t_max,
            march_run(local.z, MARCH_SPLIT, n), n, SPACING_UNIFORM);
    }
    let l = split_join(index, part);
    if inside && local.z == 0u {
        let i = (id.z * SKY_TEXTURE_SIZE.y + id.y) * SKY_TEXTURE_SIZE.x + id.x;
        sky_texture_lut[i] = l.radiance * batches[id.z].solar_irradiance;
    }
}
