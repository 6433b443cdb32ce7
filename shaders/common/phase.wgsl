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

// The tabulated phase function at each lane's fractional row `node` (twin of
// model::phase::tabulated): ln p linear in u = √(θ/π) within a row, p linear between rows.
fn tabulated_phase(nu: f32, node: vec4<f32>) -> vec4<f32> {
    let n = MIE_PHASE_ANGLES;
    let x = sqrt(acos(clamp(nu, -1.0, 1.0)) / PI) * f32(n - 1u);
    let i = min(u32(x), n - 2u);
    let t = x - f32(i);
    var p = vec4<f32>(0.0);
    for (var c = 0u; c < 4u; c++) {
        let row = clamp(node[c], 0.0, f32(MIE_PHASE_ROWS - 1u));
        let r0 = min(u32(row), MIE_PHASE_ROWS - 1u);
        let r1 = min(r0 + 1u, MIE_PHASE_ROWS - 1u);
        let a = exp(mix(mie_phase_ln(r0 * n + i), mie_phase_ln(r0 * n + i + 1u), t));
        let b = exp(mix(mie_phase_ln(r1 * n + i), mie_phase_ln(r1 * n + i + 1u), t));
        p[c] = a + (row - f32(r0)) * (b - a);
    }
    return p;
}

// The scene's aerosol phase function for the lanes of batch `layer`.
fn aerosol_phase(nu: f32, layer: u32) -> vec4<f32> {
    if !has_aerosol() {
        return vec4<f32>(0.0);
    }
    let b = batches[layer];
    if globals.options.x == PHASE_CORNETTE_SHANKS {
        return cornette_shanks(nu, b.aerosol_g);
    }
    if globals.options.x == PHASE_MIE {
        return tabulated_phase(nu, b.aerosol_phase_node);
    }
    return henyey_greenstein(nu, b.aerosol_g);
}
