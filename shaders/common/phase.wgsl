// Phase functions (sr⁻¹) per lane; twins of model::phase.

fn rayleigh_phase(nu: f32, rho: vec4<f32>) -> vec4<f32> {
    let gamma = rho / (2.0 - rho);
    return 3.0 / (16.0 * PI) * ((1.0 + 3.0 * gamma) + (1.0 - gamma) * nu * nu) / (1.0 + 2.0 * gamma);
}

fn henyey_greenstein(nu: f32, g: vec4<f32>) -> vec4<f32> {
    let denom = 1.0 + g * g - 2.0 * g * nu;
    return (1.0 - g * g) / (4.0 * PI * denom * sqrt(denom));
}

fn cornette_shanks(nu: f32, g: vec4<f32>) -> vec4<f32> {
    let denom = 1.0 + g * g - 2.0 * g * nu;
    return 3.0 / (8.0 * PI) * (1.0 - g * g) * (1.0 + nu * nu) / ((2.0 + g * g) * denom * sqrt(denom));
}

fn aerosol_phase(nu: f32, g: vec4<f32>) -> vec4<f32> {
    if !has_aerosol() {
        return vec4<f32>(0.0);
    }
    if globals.options.x == PHASE_CORNETTE_SHANKS {
        return cornette_shanks(nu, g);
    }
    return henyey_greenstein(nu, g);
}
