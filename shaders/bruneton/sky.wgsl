// Pass: the view with Bruneton (2017): the scattering tables times their phase functions and
// the ground lit by the sun and the sky irradiance; from above the atmosphere the look-up starts where the ray enters it (entry
// point: views/sky.wgsl). Twin of model::methods::bruneton::sky.

fn ground_radiance(layer: u32, mu_s_g: f32) -> vec4<f32> {
    let b = batches[layer];
    return b.ground_albedo / PI * (b.solar_irradiance * sun_transmittance(layer, 0.0, mu_s_g) * max(mu_s_g, 0.0)
        + read_irradiance(layer, 0.0, mu_s_g));
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let b = batches[layer];
    let camera = camera_coords(dir);
    if !camera.hit {
        return vec4<f32>(0.0);
    }
    let c = camera.c;
    let s = read_scattering(scattering_cell(layer, scattering_texel(c)));
    let inscattered = s.scattering * rayleigh_phase(c.nu, b.rayleigh_depolarisation)
        + s.single_mie * aerosol_phase(c.nu, layer);
    if c.ground {
        let g = ground_hit(layer, c);
        return inscattered + g.transmittance * ground_radiance(layer, g.mu_s);
    }
    return inscattered;
}
