// Pass: Hosek & Wilkie's (2012) analytic sky: per lane, the nine-parameter distribution of the
// two bands around the lane, each scaled by its weighted radiance L_M, for the sky; the
// Lambertian ground's radiance under the fit's sun and sky for the ground (entry point:
// views/sky.wgsl). Twin of model::methods::hosek_wilkie::sky. The coefficients for the frame's
// sun arrive in batches[layer].model (model::methods::hosek_wilkie::batch_rows): rows 0–9 the
// lower band's A, B, C, D, E, F, G, I, H and L_M, rows 10–19 the upper band's, row 20 the sun's
// transmittance, row 21 the ground's radiance.

const HOSEK_WILKIE_ROW_UPPER: u32 = 10u;
const HOSEK_WILKIE_ROW_SUN: u32 = 20u;
const HOSEK_WILKIE_ROW_GROUND: u32 = 21u;

// F(θ, γ)·L_M of the band whose configuration starts at row `first`; twin of
// hosek_wilkie::distribution.
fn hosek_wilkie_band(layer: u32, first: u32, cos_theta: f32, gamma: f32) -> vec4<f32> {
    let m = &batches[layer].model;
    let a = (*m)[first];
    let b = (*m)[first + 1u];
    let c = (*m)[first + 2u];
    let d = (*m)[first + 3u];
    let e = (*m)[first + 4u];
    let f = (*m)[first + 5u];
    let g = (*m)[first + 6u];
    let i = (*m)[first + 7u];
    let h = (*m)[first + 8u];
    let scale = (*m)[first + 9u];
    let cos_gamma = cos(gamma);
    let chi = (1.0 + cos_gamma * cos_gamma) / pow(1.0 + h * h - 2.0 * h * cos_gamma, vec4<f32>(1.5));
    return (1.0 + a * exp(b / (cos_theta + 0.01)))
        * (c + d * exp(e * gamma) + f * cos_gamma * cos_gamma + g * chi + i * sqrt(cos_theta))
        * scale;
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let h = globals.camera_position.w;
    let up = normalize(globals.camera_position.xyz);
    let mu = dot(dir, up);
    if sees_ground(h, mu) {
        return batches[layer].model[HOSEK_WILKIE_ROW_GROUND];
    }
    let cos_theta = max(mu, 0.0);
    let gamma = acos(clamp(dot(dir, globals.sun.xyz), -1.0, 1.0));
    return hosek_wilkie_band(layer, 0u, cos_theta, gamma)
        + hosek_wilkie_band(layer, HOSEK_WILKIE_ROW_UPPER, cos_theta, gamma);
}

// The sun's disk through the fit's solar radiance function, where the planet does not hide it.
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return batches[layer].model[HOSEK_WILKIE_ROW_SUN] * sun_visible_fraction(h, mu_s);
}
