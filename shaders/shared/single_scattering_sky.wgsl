// Pass: the view with a table-free single-scattering model (nishita, trapezoid): single
// scattering marched along each pixel's ray, lit at every sample through the model's own
// transmittance towards the sun, and the sunlit ground behind; from above the atmosphere the
// march starts where the ray enters it (entry point: views/sky.wgsl). The model's common file
// defines sun_transmittance_of_model(layer, h, mu_s); globals.model.x is the view march's
// sample count. Twin of model::methods::shared::single_scattering_sky.

fn view_steps() -> u32 {
    return u32(globals.model.x);
}


fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let up = normalize(globals.camera_position.xyz);
    let sun = globals.sun.xyz;
    let nu = dot(dir, sun);
    var h0 = globals.camera_position.w;
    var mu0 = dot(dir, up);
    var mu_s0 = dot(sun, up);
    var ground: bool;
    if ABOVE_ATMOSPHERE {
        let entry = entry_into_atmosphere(h0, mu0, mu_s0, nu);
        if entry.z == 0.0 {
            return vec4<f32>(0.0);
        }
        h0 = thickness();
        mu0 = entry.x;
        mu_s0 = entry.y;
        ground = hits_ground(h0, mu0);
    } else {
        ground = sees_ground(h0, mu0);
    }
    let b = batches[layer];
    let phase_r = rayleigh_phase(nu, b.rayleigh_depolarisation);
    let phase_a = aerosol_phase(nu, b.aerosol_g);
    let r0 = big_r + h0;
    var t_max = distance_to_top(h0, mu0);
    if ground {
        t_max = distance_to_ground(h0, mu0);
    }
    let n = view_steps();
    let dt = t_max / f32(n);
    var inscattered = vec4<f32>(0.0);
    var throughput = vec4<f32>(1.0);
    for (var s = 0u; s < n; s++) {
        let t = (f32(s) + 0.5) * dt;
        let at = altitude_along(h0, mu0, t);
        let mu_s_t = clamp((r0 * mu_s0 + t * nu) / at.y, -1.0, 1.0);
        let m = medium(b, at.x);
        let sun_t = sun_transmittance_of_model(layer, at.x, mu_s_t);
        let source = (m.rayleigh_scattering * phase_r + m.aerosol_scattering * phase_a) * sun_t;
        inscattered += throughput * segment_weight(m.extinction, dt) * source;
        throughput *= exp(-m.extinction * dt);
    }
    var l = inscattered * b.solar_irradiance;
    if ground {
        let mu_s_g = clamp((r0 * mu_s0 + t_max * nu) / big_r, -1.0, 1.0);
        let sun_g = sun_transmittance_of_model(layer, 0.0, mu_s_g);
        l += throughput * b.ground_albedo / PI * b.solar_irradiance * sun_g * max(mu_s_g, 0.0);
    }
    return l;
}

// The sun's disk seen from any altitude: from where its ray enters the atmosphere when the
// camera is above it (twin of SingleScattering::sun_seen_from).
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    if h <= thickness() {
        return sun_transmittance_of_model(layer, h, mu_s);
    }
    let entry = entry_into_atmosphere(h, mu_s, mu_s, 1.0);
    if entry.z == 0.0 {
        return vec4<f32>(1.0);
    }
    return sun_transmittance_of_model(layer, thickness(), entry.x);
}
