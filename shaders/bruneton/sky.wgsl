// Pass: the view with Bruneton (2017): the scattering tables times their phase functions, the
// sun's disk through the transmittance table or the ground lit by the sun and the sky
// irradiance; from above the atmosphere the look-up starts where the ray enters it (entry
// point: views/sky.wgsl). Twin of model::methods::bruneton::sky.

fn ground_radiance(layer: u32, mu_s_g: f32) -> vec4<f32> {
    let b = batches[layer];
    return b.ground_albedo / PI * (b.solar_irradiance * sun_transmittance(layer, 0.0, mu_s_g) * max(mu_s_g, 0.0)
        + read_irradiance(layer, 0.0, mu_s_g));
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let b = batches[layer];
    let up = normalize(globals.camera_position.xyz);
    let sun = globals.sun.xyz;
    var h = globals.camera_position.w;
    var mu = dot(dir, up);
    var mu_s = dot(sun, up);
    let nu = clamp(dot(dir, sun), -1.0, 1.0);
    let disk = sun_disk(dir, sun);
    if ABOVE_ATMOSPHERE {
        let entry = entry_into_atmosphere(h, mu, mu_s, nu);
        if entry.z == 0.0 {
            return b.solar_irradiance * disk;
        }
        h = thickness();
        mu = entry.x;
        mu_s = entry.y;
    }
    var c: Coords;
    c.h = h;
    c.mu = mu;
    c.mu_s = mu_s;
    c.nu = nu;
    c.ground = hits_ground(h, mu);
    let t = scattering_taps(layer, scattering_texel(c));
    let inscattered = read_scattering(t) * rayleigh_phase(nu, b.rayleigh_depolarisation)
        + read_single_mie(t) * aerosol_phase(nu, b.aerosol_g);
    if c.ground {
        let d = distance_to_ground(h, mu);
        let mu_s_g = clamp(((big_r + h) * mu_s + d * nu) / big_r, -1.0, 1.0);
        return inscattered + transmittance_between(layer, h, mu, d) * ground_radiance(layer, mu_s_g);
    }
    return inscattered + transmittance(layer, h, mu) * b.solar_irradiance * disk;
}
