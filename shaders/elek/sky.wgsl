// Pass: the view with Elek (2009): the azimuth-free tables at the camera's altitude and angles,
// Rayleigh times the modified Rayleigh phase and Mie times the aerosol phase, and the ground lit
// by the sun alone; inside the atmosphere from the tables' rows at the camera
// (camera_slice.wgsl), from above it from the 3D tables where the ray enters it (entry point:
// views/sky.wgsl). Twin of model::methods::elek::sky, which reads the 3D tables: the same value.

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let b = batches[layer];
    let camera = camera_coords(dir);
    if !camera.hit {
        return vec4<f32>(0.0);
    }
    let c = camera.c;
    var rayleigh: vec4<f32>;
    var mie: vec4<f32>;
    if ABOVE_ATMOSPHERE {
        let t = elek_taps(layer, elek_texel(c.h, c.mu, c.mu_s));
        rayleigh = read_rayleigh_scattering(t);
        mie = read_mie_scattering(t);
    } else {
        // Only the mu coordinate is used; the compiler drops the others.
        let x = elek_texel(c.h, c.mu, c.mu_s).x;
        let t = taps(vec2<u32>(ELEK_SIZE.x, 1u), layer, vec2<f32>(x, 0.0));
        rayleigh = mix(camera_rayleigh_lut[t.i.x], camera_rayleigh_lut[t.i.y], t.w.x);
        mie = mix(camera_mie_lut[t.i.x], camera_mie_lut[t.i.y], t.w.x);
    }
    let inscattered = rayleigh * modified_rayleigh_phase(c.nu)
        + mie * aerosol_phase(c.nu, layer);
    if c.ground {
        let g = ground_hit(layer, c);
        return inscattered + g.transmittance * sunlit_ground(layer, g.mu_s);
    }
    return inscattered;
}
