// Pass: Preetham et al.'s (1999) analytic daylight: the Perez distribution in xyY for the
// sky, spread over the batch's wavelengths as the solar spectrum times a quadratic, and the
// direct sun on the Lambertian ground (entry point: views/sky.wgsl). Twin of
// model::methods::preetham::sky. The published constants come from the prelude; globals.model
// holds the turbidity.

fn turbidity() -> f32 { return globals.model[0].x; }

// Perez F(θ, γ) for (Y, x, y) at turbidity t.
fn perez(t: f32, cos_theta: f32, gamma: f32) -> vec3<f32> {
    let a = PREETHAM_PEREZ_SLOPE[0] * t + PREETHAM_PEREZ_INTERCEPT[0];
    let b = PREETHAM_PEREZ_SLOPE[1] * t + PREETHAM_PEREZ_INTERCEPT[1];
    let c = PREETHAM_PEREZ_SLOPE[2] * t + PREETHAM_PEREZ_INTERCEPT[2];
    let d = PREETHAM_PEREZ_SLOPE[3] * t + PREETHAM_PEREZ_INTERCEPT[3];
    let e = PREETHAM_PEREZ_SLOPE[4] * t + PREETHAM_PEREZ_INTERCEPT[4];
    let cos_gamma = cos(gamma);
    return (1.0 + a * exp(b / max(cos_theta, PREETHAM_MIN_COS_THETA)))
        * (1.0 + c * exp(d * gamma) + e * cos_gamma * cos_gamma);
}

// Zenith luminance (kcd/m²) and chromaticity x, y.
fn preetham_zenith(t: f32, theta_s: f32) -> vec3<f32> {
    let chi = (PREETHAM_CHI.x - t / PREETHAM_CHI.y) * (PI - 2.0 * theta_s);
    let k = PREETHAM_ZENITH_LUMINANCE;
    let y = (k.x * t + k.y) * tan(chi) + k.z * t + k.w;
    let powers_t = vec3<f32>(t * t, t, 1.0);
    let powers_theta = vec4<f32>(theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0);
    let x_rows = vec3<f32>(
        dot(PREETHAM_ZENITH_X[0], powers_theta),
        dot(PREETHAM_ZENITH_X[1], powers_theta),
        dot(PREETHAM_ZENITH_X[2], powers_theta),
    );
    let y_rows = vec3<f32>(
        dot(PREETHAM_ZENITH_Y[0], powers_theta),
        dot(PREETHAM_ZENITH_Y[1], powers_theta),
        dot(PREETHAM_ZENITH_Y[2], powers_theta),
    );
    return vec3<f32>(y, dot(powers_t, x_rows), dot(powers_t, y_rows));
}

// The sky's XYZ in the renderer's unit; twin of preetham::sky::xyz.
fn preetham_xyz(t: f32, mu: f32, mu_s: f32, nu: f32) -> vec3<f32> {
    let theta_s = acos(clamp(mu_s, 0.0, 1.0));
    let gamma = acos(clamp(nu, -1.0, 1.0));
    let ratio = perez(t, mu, gamma) / perez(t, 1.0, theta_s);
    let z = preetham_zenith(t, theta_s);
    let luminance = max(z.x * ratio.x, 0.0) * PREETHAM_KCD_PER_M2;
    let x = z.y * ratio.y;
    let y = z.z * ratio.z;
    if y <= 0.0 {
        return vec3<f32>(0.0);
    }
    return vec3<f32>(x / y, 1.0, (1.0 - x - y) / y) * luminance;
}

// The batch's lanes of E_sun(λ)·(c₀ + c₁u + c₂u²) whose colour is `xyz`; twin of
// preetham::sky::spread.
fn preetham_spread(layer: u32, xyz: vec3<f32>) -> vec4<f32> {
    let c = PREETHAM_SPECTRAL_BASIS * xyz;
    let b = batches[layer];
    let u = (b.wavelengths_nm - PREETHAM_BASIS.x) / PREETHAM_BASIS.y;
    return b.solar_irradiance * (c.x + c.y * u + c.z * u * u);
}

// The sun's direct beam at the ground; twin of preetham::sun_transmittance.
fn preetham_beam(layer: u32, t: f32, mu_s: f32) -> vec4<f32> {
    if mu_s <= 0.0 {
        return vec4<f32>(0.0);
    }
    let theta_deg = degrees(acos(min(mu_s, 1.0)));
    let k = PREETHAM_AIR_MASS;
    let m = 1.0 / (mu_s + k.x * pow(k.y - theta_deg, -k.z));
    let beta = PREETHAM_HAZE.y * t + PREETHAM_HAZE.z;
    let um = batches[layer].wavelengths_nm * 1e-3;
    let tau = PREETHAM_SUN_RAYLEIGH.x * pow(um, vec4<f32>(-PREETHAM_SUN_RAYLEIGH.y))
        + beta * pow(um, vec4<f32>(-PREETHAM_HAZE.x));
    return exp(-tau * m);
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let h = globals.camera_position.w;
    let up = normalize(globals.camera_position.xyz);
    let sun = globals.sun.xyz;
    let mu = dot(dir, up);
    let mu_s = dot(sun, up);
    let nu = dot(dir, sun);
    let t = turbidity();
    if !sees_ground(h, mu) {
        return preetham_spread(layer, preetham_xyz(t, mu, mu_s, nu));
    }
    let d = distance_to_ground(h, mu);
    let mu_s_g = clamp(((big_r + h) * mu_s + d * nu) / big_r, -1.0, 1.0);
    let b = batches[layer];
    let lit = sun_visible_fraction(0.0, mu_s_g) * max(mu_s_g, 0.0) / PI;
    return b.ground_albedo * b.solar_irradiance * preetham_beam(layer, t, mu_s_g) * lit;
}

// The sun's disk through the direct-beam transmittance, where the planet does not hide it.
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return preetham_beam(layer, turbidity(), mu_s) * sun_visible_fraction(h, mu_s);
}
