// Pass: the view with Elek (2009): the azimuth-free tables at the camera's altitude and angles,
// Rayleigh times the modified Rayleigh phase and Mie times the aerosol phase, the sun's disk
// through the transmittance table or the ground lit by the sun alone; from above the
// atmosphere the look-up starts where the ray enters it (entry point: views/sky.wgsl). Twin of
// model::methods::elek::sky.

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
    let t = elek_taps(layer, elek_texel(h, mu, mu_s));
    let inscattered = read_rayleigh_scattering(t) * modified_rayleigh_phase(nu)
        + read_mie_scattering(t) * aerosol_phase(nu, b.aerosol_g);
    if hits_ground(h, mu) {
        let d = distance_to_ground(h, mu);
        let mu_s_g = clamp(((big_r + h) * mu_s + d * nu) / big_r, -1.0, 1.0);
        return inscattered + transmittance_between(layer, h, mu, d) * sunlit_ground(layer, mu_s_g);
    }
    return inscattered + transmittance(layer, h, mu) * b.solar_irradiance * disk;
}
