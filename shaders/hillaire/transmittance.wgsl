// Pass: transmittance table, exp(−∫ extinction) from (h, mu) to the top of the atmosphere.

@group(1) @binding(0) var transmittance_out: texture_storage_2d_array<rgba32float, write>;

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= TRANSMITTANCE_SIZE) || id.z >= batch_count() {
        return;
    }
    let hm = transmittance_h_mu_from_texel(vec2<f32>(id.xy));
    let t_max = distance_to_top(hm.x, hm.y);
    let n = globals.steps_a.x;
    var depth = vec4<f32>(0.0);
    for (var i = 0u; i < n; i++) {
        let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, i, n);
        let at = altitude_along(hm.x, hm.y, 0.5 * (seg.x + seg.y));
        depth += medium(id.z, at.x).extinction * (seg.y - seg.x);
    }
    textureStore(transmittance_out, id.xy, id.z, exp(-depth));
}
