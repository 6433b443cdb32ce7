// Pass: the view with Elek (2009): the azimuth-free tables at the camera's altitude and angles,
// Rayleigh times the modified Rayleigh phase and Mie times the aerosol phase, and the ground lit
// by the sun alone; from above the
// atmosphere the look-up starts where the ray enters it (entry point: views/sky.wgsl). Twin of
// model::methods::elek::sky.

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let b = batches[layer];
    let camera = camera_coords(dir);
    if !camera.hit {
        return vec4<f32>(0.0);
    }
    let c = camera.c;
    let t = elek_taps(layer, elek_texel(c.h, c.mu, c.mu_s));
    let inscattered = read_rayleigh_scattering(t) * modified_rayleigh_phase(c.nu)
        + read_mie_scattering(t) * aerosol_phase(c.nu, layer);
    if c.ground {
        let g = ground_hit(layer, c);
        return inscattered + g.transmittance * sunlit_ground(layer, g.mu_s);
    }
    return inscattered;
}
