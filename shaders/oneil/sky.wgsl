// Pass: O'Neil's (2005) sky (GPU Gems 2, ch. 16): the view ray in a few samples, every optical
// depth e^(−h/H)·H·scale(μ) from the fitted scale function; the chapter's ground formulation for
// rays that meet the ground (entry point: views/sky.wgsl). Twin of model::methods::oneil::sky.
// globals.model: p₀–p₃; p₄, H, the air's and the aerosol's ground densities; the samples.

// scale(μ) = exp(p(1 − μ)), the column to the top from the ground over H; twin of
// ScaleFit::scale.
fn oneil_scale(mu: f32) -> f32 {
    let p = globals.model[0];
    let p4 = globals.model[1].x;
    let x = 1.0 - mu;
    return exp(p.x + x * (p.y + x * (p.z + x * (p.w + x * p4))));
}

fn oneil_density(h: f32) -> f32 {
    return exp(-h / globals.model[1].y);
}

// Extinction per unit of the fit's column times H; twin of oneil::sky::extinction × H.
fn oneil_depth_per_column(layer: u32) -> vec4<f32> {
    let b = batches[layer];
    let m = globals.model[1];
    return (b.rayleigh_scattering * m.z + (b.aerosol_scattering + b.aerosol_absorption) * m.w) * m.y;
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let cc = camera_coords(dir);
    if !cc.hit {
        return vec4<f32>(0.0);
    }
    let c = cc.c;
    let big_r = bottom_radius();
    let b = batches[layer];
    let m = globals.model[1];
    let depth_per_column = oneil_depth_per_column(layer);
    let r0 = big_r + c.h;
    let n = u32(globals.model[2].x);
    var t_max = distance_to_top(c.h, c.mu);
    if c.ground {
        t_max = distance_to_ground(c.h, c.mu);
    }
    let dt = t_max / f32(n);
    let scattering_air = b.rayleigh_scattering * m.z;
    let scattering_aerosol = b.aerosol_scattering * m.w;
    if !c.ground {
        let start = oneil_density(c.h) * oneil_scale(c.mu);
        var front = vec4<f32>(0.0);
        for (var k = 0u; k < n; k++) {
            let t = (f32(k) + 0.5) * dt;
            let at = altitude_along(c.h, c.mu, t);
            let mu_k = clamp((r0 * c.mu + t) / at.y, -1.0, 1.0);
            let mu_s_k = clamp((r0 * c.mu_s + t * c.nu) / at.y, -1.0, 1.0);
            let density = oneil_density(at.x);
            let scatter = start + density * (oneil_scale(mu_s_k) - oneil_scale(mu_k));
            front += exp(-depth_per_column * scatter) * (density * dt);
        }
        let nu = c.nu;
        let phase_r = 0.75 * (1.0 + nu * nu) / (4.0 * PI);
        let g = b.aerosol_g;
        let phase_a = 1.5 * (1.0 - g * g) / (2.0 + g * g) * (1.0 + nu * nu)
            / pow(1.0 + g * g - 2.0 * g * nu, vec4<f32>(1.5)) / (4.0 * PI);
        return b.solar_irradiance * (scattering_air * phase_r + scattering_aerosol * phase_a) * front;
    }
    let at_g = altitude_along(c.h, c.mu, t_max);
    let mu_g = clamp((r0 * c.mu + t_max) / at_g.y, -1.0, 1.0);
    let mu_s_g = clamp((r0 * c.mu_s + t_max * c.nu) / at_g.y, -1.0, 1.0);
    let camera_scale = oneil_scale(-mu_g);
    let camera_offset = oneil_density(c.h) * camera_scale;
    let both = oneil_scale(mu_s_g) + camera_scale;
    var front = vec4<f32>(0.0);
    for (var k = 0u; k < n; k++) {
        let density = oneil_density(altitude_along(c.h, c.mu, (f32(k) + 0.5) * dt).x);
        front += exp(-depth_per_column * (density * both - camera_offset)) * (density * dt);
    }
    let in_scattered = b.solar_irradiance * (scattering_air + scattering_aerosol) / (4.0 * PI) * front;
    let through = exp(-depth_per_column * (both - camera_offset));
    return in_scattered + b.ground_albedo / PI * b.solar_irradiance * max(mu_s_g, 0.0) * through;
}

// The sun's disk through the fitted optical depth towards it, where the planet does not hide it.
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let h_in = min(h, top_radius() - bottom_radius());
    let depth = oneil_density(h_in) * oneil_scale(mu_s);
    return exp(-oneil_depth_per_column(layer) * depth) * sun_visible_fraction(h, mu_s);
}
