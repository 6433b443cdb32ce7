// Pass: aerial-perspective volume. One invocation marches one ground-bound direction of the
// sun-aligned frame and writes (in-scattered radiance, transmittance) at the end of every slice,
// on past the ground (where the march takes the ground's medium and light), so that a pixel
// between two rows reads both at its own ground. Twin of
// model::methods::hillaire::aerial_perspective.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= AERIAL_PERSPECTIVE_SIZE.xy) || id.z >= batch_count() {
        return;
    }
    let layer = id.z;
    let h = globals.camera_position.w;
    let mu_s = globals.sun.w;
    let angles = aerial_perspective_angles_from_texel(h, vec2<f32>(id.xy));
    let omega = direction_from_phi_theta(angles.x, angles.y);
    let mu = omega.z;
    let nu = dot(omega, local_sun(mu_s));
    let e = batches[layer].solar_irradiance;
    var inscattered = vec4<f32>(0.0);
    var throughput = vec4<f32>(1.0);
    var start = 0.0;
    let depth = AERIAL_PERSPECTIVE_SIZE.z;
    for (var k = 0u; k < depth; k++) {
        let end = aerial_perspective_slice_distance(k);
        let l = integrate_inscattering(layer,
            vec4<f32>(h, mu, mu_s, nu), start, end, globals.steps_b.x, SPACING_UNIFORM);
        inscattered += throughput * l.radiance * e;
        throughput *= l.transmittance;
        start = end;
        let size = AERIAL_PERSPECTIVE_SIZE;
        let i = ((layer * depth + k) * size.y + id.y) * size.x + id.x;
        aerial_perspective_inscattering_lut[i] = inscattered;
        aerial_perspective_transmittance_lut[i] = throughput;
    }
}
