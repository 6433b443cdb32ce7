// Pass (once per order n ≥ 2): the radiance of order n, J integrated along each texel's ray
// through the transmittance, over the Rayleigh phase; becomes the delta the next order reads
// (with a zero Mie part) and is added to the scattering sum. Twin of
// model::methods::bruneton::multiple_scattering.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let v = volume_texel(id);
    if any(v.xy >= SCATTERING_SIZE.xy) || v.w >= batch_count() {
        return;
    }
    let layer = v.w;
    let c = scattering_coords(v.x, v.y, v.z);
    let n = globals.steps_b.z;
    var s = vec4<f32>(0.0);
    for (var k = 0u; k < 2u * (n + 1u); k++) {
        let sample = ray_sample(c, k, n);
        let d = sample.x;
        let at = along(c, d);
        var p: Coords;
        p.h = at.x;
        p.mu = at.y;
        p.mu_s = at.z;
        p.nu = c.nu;
        p.ground = c.ground;
        let j = read_scattering_density(scattering_cell(layer, scattering_texel(p)));
        s += sample.y * j * transmittance_between(layer, c.h, c.mu, d);
    }
    let k = scattering_index(layer, v.x, v.y, v.z);
    let delta = s / rayleigh_phase(c.nu, batches[layer].rayleigh_depolarisation);
    delta_rayleigh_lut[k] = delta;
    delta_mie_lut[k] = vec4<f32>(0.0);
    scattering_lut[k] += delta;
}
