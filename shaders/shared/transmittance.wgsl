// Pass: transmittance table, exp(−∫ extinction) from (h, mu) to the top of the atmosphere.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= TRANSMITTANCE_SIZE) || id.z >= batch_count() {
        return;
    }
    let hm = transmittance_h_mu_from_texel(vec2<f32>(id.xy));
    let t_max = distance_to_top(hm.x, hm.y);
    let n = globals.steps_a.x;
    let b = batches[id.z];
    var depth = vec4<f32>(0.0);
    for (var i = 0u; i < n; i++) {
        let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, i, n);
        let at = altitude_along(hm.x, hm.y, 0.5 * (seg.x + seg.y));
        depth += medium(b, at.x).extinction * (seg.y - seg.x);
    }
    transmittance_lut[(id.z * TRANSMITTANCE_SIZE.y + id.y) * TRANSMITTANCE_SIZE.x + id.x] = exp(-depth);
}
