// Pass: sky irradiance on horizontal ground per unit solar irradiance, E = π·mean(L) over
// cosine-weighted stratified directions of the upper hemisphere.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if id.x >= GROUND_IRRADIANCE_SIZE || id.y >= 1u || id.z >= batch_count() {
        return;
    }
    let mu_s = ground_irradiance_mu_s_from_texel(f32(id.x));
    let sun = local_sun(mu_s);
    let n_theta = GROUND_IRRADIANCE_DIRECTIONS.x;
    let n_phi = GROUND_IRRADIANCE_DIRECTIONS.y;
    var sum = vec4<f32>(0.0);
    for (var i = 0u; i < n_theta; i++) {
        let mu = sqrt((f32(i) + 0.5) / f32(n_theta));
        let s = sqrt(1.0 - mu * mu);
        for (var j = 0u; j < n_phi; j++) {
            let phi = 2.0 * PI * (f32(j) + 0.5) / f32(n_phi);
            let nu = dot(vec3<f32>(s * cos(phi), s * sin(phi), mu), sun);
            let t_max = distance_to_top(0.0, mu);
            let l = integrate_inscattering(id.z,
                vec4<f32>(0.0, mu, mu_s, nu), 0.0, t_max, globals.steps_a.z, SPACING_QUADRATIC);
            sum += l.radiance;
        }
    }
    ground_irradiance_lut[id.z * GROUND_IRRADIANCE_SIZE + id.x] = sum * (PI / f32(n_theta * n_phi));
}
