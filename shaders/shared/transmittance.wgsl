// Pass: transmittance table, exp(−∫ extinction) from (h, mu) to the top of the atmosphere; each
// texel's march split across MARCH_SPLIT invocations (common/group.wgsl).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, MARCH_SPLIT)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_split(workgroup, local);
    let inside = all(id.xy < TRANSMITTANCE_SIZE) && id.z < batch_count();
    let n = globals.steps_a.x;
    var depth = vec4<f32>(0.0);
    if inside {
        let hm = transmittance_h_mu_from_texel(vec2<f32>(id.xy));
        let t_max = distance_to_top(hm.x, hm.y);
        let b = batches[id.z];
        let run = march_run(local.z, MARCH_SPLIT, n);
        for (var i = run.x; i < run.y; i++) {
            let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, i, n);
            let at = altitude_along(hm.x, hm.y, 0.5 * (seg.x + seg.y));
            depth += medium(b, at.x).extinction * (seg.y - seg.x);
        }
    }
    depth = split_sum(index, depth);
    if inside && local.z == 0u {
        transmittance_lut[(id.z * TRANSMITTANCE_SIZE.y + id.y) * TRANSMITTANCE_SIZE.x + id.x] = exp(-depth);
    }
}
