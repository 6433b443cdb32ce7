// Pass: the scattering and single-Mie tables at the camera, the 2D slices (nu, mu) of the 4D
// tables at the camera's altitude and sun zenith cosine: each texel blends the four texels
// around them in (r, mu_s). The sky pass then blends four texels of each in (nu, mu), what the
// 4D look-up of a ray from the camera gives. Twin of model::methods::bruneton::camera_slice.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let size = vec2<u32>(SCATTERING_NU, SCATTERING_SIZE.y);
    if any(id.xy >= size) || id.z >= batch_count() {
        return;
    }
    let j = depth_taps(SCATTERING_MU_S, mu_s_texel(globals.sun.w));
    let z = depth_taps(SCATTERING_SIZE.z, r_texel(globals.camera_position.w));
    var scattering = vec4<f32>(0.0);
    var single_mie = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        let upper = vec2<bool>((k >> 1u) == 1u, (k & 1u) == 1u);
        let w = select(1.0 - z.z, z.z, upper.x) * select(1.0 - j.z, j.z, upper.y);
        let i = scattering_index(id.z, id.x * SCATTERING_MU_S + u32(select(j.x, j.y, upper.y)), id.y,
            u32(select(z.x, z.y, upper.x)));
        scattering += w * scattering_lut[i];
        single_mie += w * single_mie_lut[i];
    }
    let out = (id.z * size.y + id.y) * size.x + id.x;
    camera_scattering_lut[out] = scattering;
    camera_single_mie_lut[out] = single_mie;
}
