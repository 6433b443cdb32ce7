// Pass: sky irradiance on horizontal ground per unit solar irradiance, ∫ L·cos θ dΩ over the
// upper hemisphere on rings about the sun (GROUND_IRRADIANCE_DIRECTIONS: rings at γ = π·u²
// from the sun, dense near it, × azimuths about it; the half on one side of the sun's vertical
// plane, counted twice; directions below the horizon skipped). One
// workgroup per texel, its invocations sharing the directions.
// Twin of model::methods::hillaire::ground_irradiance.

@compute @workgroup_size(TEXEL_GROUP_SIZE, 1, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_texel(workgroup);
    if id.x >= GROUND_IRRADIANCE_SIZE || id.y >= 1u || id.z >= batch_count() {
        return;
    }
    let mu_s = ground_irradiance_mu_s_from_texel(f32(id.x));
    let sun = local_sun(mu_s);
    // A frame about the sun (local_sun lies in the x–z plane).
    let across = vec3<f32>(0.0, 1.0, 0.0);
    let up = cross(sun, across);
    let n_rings = GROUND_IRRADIANCE_DIRECTIONS.x;
    let n_azimuths = GROUND_IRRADIANCE_DIRECTIONS.y;
    var sum = vec4<f32>(0.0);
    // The azimuths on one side of the sun's vertical plane, each standing for its mirror too.
    let half = n_azimuths / 2u;
    for (var k = index; k < n_rings * half; k += TEXEL_GROUP_SIZE) {
        let i = k / half;
        let j = k % half;
        let u0 = f32(i) / f32(n_rings);
        let u1 = f32(i + 1u) / f32(n_rings);
        let um = 0.5 * (u0 + u1);
        let gamma = PI * um * um;
        let weight = 4.0 * PI * (cos(PI * u0 * u0) - cos(PI * u1 * u1)) / f32(n_azimuths);
        let a = 2.0 * PI * (f32(j) + 0.5) / f32(n_azimuths) - 0.5 * PI;
        let dir = sun * cos(gamma) + (across * cos(a) + up * sin(a)) * sin(gamma);
        let mu = dir.z;
        if mu <= 0.0 {
            continue;
        }
        let t_max = distance_to_top(0.0, mu);
        let l = integrate_inscattering(id.z,
            vec4<f32>(0.0, mu, mu_s, cos(gamma)), 0.0, t_max, globals.steps_a.z, SPACING_QUADRATIC);
        sum += l.radiance * (mu * weight);
    }
    let sums = group_sums(index, sum, vec4<f32>(0.0));
    if index == 0u {
        ground_irradiance_lut[id.z * GROUND_IRRADIANCE_SIZE + id.x] = sums[0];
    }
}
