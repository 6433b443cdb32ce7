// Pass: the Rayleigh and Mie tables at the camera, the rows (mu) of the 3D tables at the
// camera's altitude and sun zenith cosine: each texel blends the four texels around them in
// (mu_s, h). The sky pass then reads two texels of each along mu, what the 3D look-up of a ray
// from the camera gives. Twin of model::methods::elek::camera_slice.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if id.x >= ELEK_SIZE.x || id.y > 0u || id.z >= batch_count() {
        return;
    }
    let f = elek_texel(globals.camera_position.w, 0.0, globals.sun.w);
    let y = depth_taps(ELEK_SIZE.y, f.y);
    let z = depth_taps(ELEK_SIZE.z, f.z);
    var rayleigh = vec4<f32>(0.0);
    var mie = vec4<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        let upper = vec2<bool>((k >> 1u) == 1u, (k & 1u) == 1u);
        let w = select(1.0 - z.z, z.z, upper.x) * select(1.0 - y.z, y.z, upper.y);
        let i = elek_index(id.z, id.x, u32(select(y.x, y.y, upper.y)),
            u32(select(z.x, z.y, upper.x)));
        rayleigh += w * rayleigh_scattering_lut[i];
        mie += w * mie_scattering_lut[i];
    }
    camera_rayleigh_lut[id.z * ELEK_SIZE.x + id.x] = rayleigh;
    camera_mie_lut[id.z * ELEK_SIZE.x + id.x] = mie;
}
