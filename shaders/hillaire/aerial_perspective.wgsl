// Pass: aerial-perspective volume. One workgroup per ground-bound direction of the sun-aligned
// frame (a column of the volume): its invocations march the slices' segments side by side, on
// past the ground (where the march takes the ground's medium and light), so that a pixel
// between two rows reads both at its own ground; then each writes (in-scattered radiance,
// transmittance) at the end of its slices, gathering the segments in front of them in the
// order a single march adds them. Twin of model::methods::hillaire::aerial_perspective.

var<workgroup> segment_radiance: array<vec4<f32>, AERIAL_PERSPECTIVE_SIZE.z>;
var<workgroup> segment_transmittance: array<vec4<f32>, AERIAL_PERSPECTIVE_SIZE.z>;

@compute @workgroup_size(TEXEL_GROUP_SIZE, 1, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_texel(workgroup);
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
    let depth = AERIAL_PERSPECTIVE_SIZE.z;
    for (var k = index; k < depth; k += TEXEL_GROUP_SIZE) {
        var start = 0.0;
        if k > 0u {
            start = aerial_perspective_slice_distance(k - 1u);
        }
        let end = aerial_perspective_slice_distance(k);
        let l = integrate_inscattering(layer,
            vec4<f32>(h, mu, mu_s, nu), start, end, globals.steps_b.x, SPACING_UNIFORM);
        segment_radiance[k] = l.radiance * e;
        segment_transmittance[k] = l.transmittance;
    }
    workgroupBarrier();
    let size = AERIAL_PERSPECTIVE_SIZE;
    for (var k = index; k < depth; k += TEXEL_GROUP_SIZE) {
        var inscattered = vec4<f32>(0.0);
        var throughput = vec4<f32>(1.0);
        for (var j = 0u; j <= k; j++) {
            inscattered += throughput * segment_radiance[j];
            throughput *= segment_transmittance[j];
        }
        let i = ((layer * depth + k) * size.y + id.y) * size.x + id.x;
        aerial_perspective_inscattering_lut[i] = inscattered;
        aerial_perspective_transmittance_lut[i] = throughput;
    }
}
