// Pass: the nested marches' way to the sun tabulated for their moving sky: the optical depth
// by the model's way (shared/sun_route.wgsl) from each texel's (h, mu) of the transmittance
// table's grid to the top; the look-up blends depths, not transmittances. Twin of
// model::methods::shared::single_scattering_sky::SunRoute::table.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_id) local: vec3<u32>,
) {
    let id = dispatched_split(workgroup, local);
    if any(id.xy >= TRANSMITTANCE_SIZE) || id.z >= batch_count() {
        return;
    }
    let hm = transmittance_h_mu_from_texel(vec2<f32>(id.xy));
    sun_route_lut[(id.z * TRANSMITTANCE_SIZE.y + id.y) * TRANSMITTANCE_SIZE.x + id.x] =
        optical_depth_by_way(id.z, hm.x, hm.y);
}
