// Hillaire (2020): the functions every pass of the method shares. Twins of
// model::methods::hillaire (same mappings, same step placement, same arithmetic in f32).

struct Medium {
    rayleigh_scattering: vec4<f32>,
    aerosol_scattering: vec4<f32>,
    extinction: vec4<f32>,
}

// Profile values at altitude h, linear in x = sqrt(h / H); zero above the top.
fn densities(h: f32) -> vec3<f32> {
    if h > thickness() {
        return vec3<f32>(0.0);
    }
    let x = sqrt(max(h, 0.0) / thickness()) * f32(PROFILE_SAMPLES - 1u);
    let i = min(u32(floor(x)), PROFILE_SAMPLES - 2u);
    let f = x - f32(i);
    return mix(profile[i].xyz, profile[i + 1u].xyz, f);
}

// The batch is passed by value: load it once per invocation, not once per step.
fn medium(b: Batch, h: f32) -> Medium {
    let d = densities(h);
    var m: Medium;
    m.rayleigh_scattering = b.rayleigh_scattering * d.x;
    m.aerosol_scattering = b.aerosol_scattering * d.z;
    m.extinction = m.rayleigh_scattering + m.aerosol_scattering + b.ozone_absorption * d.y
        + b.aerosol_absorption * d.z;
    return m;
}

// ---- transmittance (Bruneton 2017 mapping) ----

fn transmittance_texel_from_h_mu(h: f32, mu: f32) -> vec2<f32> {
    let big_h = sqrt(rho_squared(thickness()));
    let rho = sqrt(rho_squared(max(h, 0.0)));
    let d = distance_to_top(h, mu);
    let d_min = thickness() - h;
    let d_max = rho + big_h;
    let x_mu = (d - d_min) / max(d_max - d_min, 1e-9);
    let x_r = rho / big_h;
    return vec2<f32>(x_mu, x_r) * vec2<f32>(TRANSMITTANCE_SIZE - 1u);
}

fn transmittance_h_mu_from_texel(f: vec2<f32>) -> vec2<f32> {
    let x = f / vec2<f32>(TRANSMITTANCE_SIZE - 1u);
    let big_r = bottom_radius();
    let big_h = sqrt(rho_squared(thickness()));
    let rho = big_h * x.y;
    let h = rho * rho / (sqrt(rho * rho + big_r * big_r) + big_r);
    let r = big_r + h;
    let d_min = thickness() - h;
    let d_max = rho + big_h;
    let d = d_min + x.x * (d_max - d_min);
    var mu = 1.0;
    if d > 0.0 {
        mu = clamp((big_h * big_h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
    }
    return vec2<f32>(h, mu);
}

fn transmittance(layer: u32, h: f32, mu: f32) -> vec4<f32> {
    let t = taps(TRANSMITTANCE_SIZE, layer, transmittance_texel_from_h_mu(h, mu));
    return blend(transmittance_lut[t.i.x], transmittance_lut[t.i.y], transmittance_lut[t.i.z],
        transmittance_lut[t.i.w], t.w);
}

// Transmittance to the sun times the visible fraction of its disk above the horizon.
fn sun_transmittance(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let sin_h = bottom_radius() / (bottom_radius() + h);
    let cos_h = -sqrt(max(1.0 - sin_h * sin_h, 0.0));
    let edge = sin_h * SUN_ANGULAR_RADIUS_RAD;
    let visible = smoothstep(-edge, edge, mu_s - cos_h);
    return transmittance(layer, h, mu_s) * visible;
}

// ---- multiple scattering ----

fn multiple_scattering_texel_from_h_mu_s(h: f32, mu_s: f32) -> vec2<f32> {
    return vec2<f32>(mu_s * 0.5 + 0.5, h / thickness()) * vec2<f32>(MULTIPLE_SCATTERING_SIZE - 1u);
}

fn multiple_scattering_h_mu_s_from_texel(f: vec2<f32>) -> vec2<f32> {
    let x = f / vec2<f32>(MULTIPLE_SCATTERING_SIZE - 1u);
    return vec2<f32>(x.y * thickness(), clamp(x.x * 2.0 - 1.0, -1.0, 1.0));
}

fn multiple_scattering(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let t = taps(MULTIPLE_SCATTERING_SIZE, layer, multiple_scattering_texel_from_h_mu_s(h, mu_s));
    return blend(multiple_scattering_lut[t.i.x], multiple_scattering_lut[t.i.y],
        multiple_scattering_lut[t.i.z], multiple_scattering_lut[t.i.w], t.w);
}

// ---- ground irradiance ----

fn ground_irradiance_texel_from_mu_s(mu_s: f32) -> f32 {
    return (mu_s * 0.5 + 0.5) * f32(GROUND_IRRADIANCE_SIZE - 1u);
}

fn ground_irradiance_mu_s_from_texel(f: f32) -> f32 {
    return clamp(f / f32(GROUND_IRRADIANCE_SIZE - 1u) * 2.0 - 1.0, -1.0, 1.0);
}

fn ground_irradiance(layer: u32, mu_s: f32) -> vec4<f32> {
    let f = vec2<f32>(ground_irradiance_texel_from_mu_s(mu_s), 0.0);
    let t = taps(vec2<u32>(GROUND_IRRADIANCE_SIZE, 1u), layer, f);
    return blend(ground_irradiance_lut[t.i.x], ground_irradiance_lut[t.i.y],
        ground_irradiance_lut[t.i.z], ground_irradiance_lut[t.i.w], t.w);
}

// ---- sky view and aerial perspective ----

// β at the camera's altitude, the only altitude the sky view and aerial perspective are built
// for; computed once per frame in f64 (hillaire::horizon_beta).
fn horizon_beta(h: f32) -> f32 {
    return globals.camera.w;
}

fn sky_view_texel_from_angles(h: f32, phi: f32, theta: f32) -> vec2<f32> {
    let beta = horizon_beta(h);
    let theta_h = PI - beta;
    var v: f32;
    if theta < theta_h {
        v = 0.5 * (1.0 - sqrt(max(1.0 - theta / theta_h, 0.0)));
    } else {
        v = 0.5 + 0.5 * sqrt(clamp((theta - theta_h) / beta, 0.0, 1.0));
    }
    let u = sqrt(clamp(phi / PI, 0.0, 1.0));
    return vec2<f32>(u, v) * vec2<f32>(SKY_VIEW_SIZE - 1u);
}

fn sky_view_angles_from_texel(h: f32, f: vec2<f32>) -> vec2<f32> {
    let beta = horizon_beta(h);
    let theta_h = PI - beta;
    let x = f / vec2<f32>(SKY_VIEW_SIZE - 1u);
    var theta: f32;
    if x.y < 0.5 {
        let c = 1.0 - 2.0 * x.y;
        theta = theta_h * (1.0 - c * c);
    } else {
        let c = 2.0 * x.y - 1.0;
        theta = theta_h + beta * c * c;
    }
    return vec2<f32>(PI * x.x * x.x, theta);
}

fn sky_view(layer: u32, h: f32, phi: f32, theta: f32, ground: bool) -> vec4<f32> {
    var f = sky_view_texel_from_angles(h, phi, theta);
    let half = f32(SKY_VIEW_SIZE.y / 2u);
    if ground {
        f.y = max(f.y, half);
    } else {
        f.y = min(f.y, half - 1.0);
    }
    let t = taps(SKY_VIEW_SIZE, layer, f);
    return blend(sky_view_lut[t.i.x], sky_view_lut[t.i.y], sky_view_lut[t.i.z], sky_view_lut[t.i.w], t.w);
}

fn aerial_perspective_texel_from_angles(h: f32, phi: f32, theta: f32) -> vec2<f32> {
    let beta = horizon_beta(h);
    let v = sqrt(clamp((theta - (PI - beta)) / beta, 0.0, 1.0));
    let u = sqrt(clamp(phi / PI, 0.0, 1.0));
    let size = vec2<f32>(AERIAL_PERSPECTIVE_SIZE.xy);
    return vec2<f32>(u * (size.x - 1.0), v * size.y - 0.5);
}

fn aerial_perspective_angles_from_texel(h: f32, f: vec2<f32>) -> vec2<f32> {
    let beta = horizon_beta(h);
    let size = vec2<f32>(AERIAL_PERSPECTIVE_SIZE.xy);
    let x = vec2<f32>(f.x / (size.x - 1.0), (f.y + 0.5) / size.y);
    return vec2<f32>(PI * x.x * x.x, PI - beta + beta * x.y * x.y);
}

fn aerial_perspective_slice_distance(k: u32) -> f32 {
    let x = (f32(k) + 1.0) / f32(AERIAL_PERSPECTIVE_SIZE.z);
    return AERIAL_PERSPECTIVE_MAX_DISTANCE_M * x * x;
}

fn aerial_perspective_slice_from_distance(d: f32) -> f32 {
    return sqrt(max(d / AERIAL_PERSPECTIVE_MAX_DISTANCE_M, 0.0)) * f32(AERIAL_PERSPECTIVE_SIZE.z) - 1.0;
}

fn direction_from_phi_theta(phi: f32, theta: f32) -> vec3<f32> {
    return vec3<f32>(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}

fn local_sun(mu_s: f32) -> vec3<f32> {
    return vec3<f32>(sqrt(max(1.0 - mu_s * mu_s, 0.0)), 0.0, mu_s);
}

// ---- in-scattering along a ray ----

struct Inscattering {
    // per unit solar irradiance, sr⁻¹
    radiance: vec4<f32>,
    transmittance: vec4<f32>,
}

// (h, mu, mu_s, nu) start the ray; the march covers [t0, t1].
fn integrate_inscattering(
    layer: u32,
    start: vec4<f32>,
    t0: f32,
    t1: f32,
    steps: u32,
    spacing: u32,
) -> Inscattering {
    let h = start.x;
    let mu = start.y;
    let mu_s = start.z;
    let nu = start.w;
    let r = bottom_radius() + h;
    let b = batches[layer];
    let phase_r = rayleigh_phase(nu, b.rayleigh_depolarisation);
    let phase_a = aerosol_phase(nu, b.aerosol_g);
    var result: Inscattering;
    result.radiance = vec4<f32>(0.0);
    result.transmittance = vec4<f32>(1.0);
    for (var s = 0u; s < steps; s++) {
        let seg = march_segment(spacing, t0, t1, s, steps);
        let dt = seg.y - seg.x;
        let ts = 0.5 * (seg.x + seg.y);
        let at = altitude_along(h, mu, ts);
        let mu_s_t = clamp((r * mu_s + ts * nu) / at.y, -1.0, 1.0);
        let m = medium(b, at.x);
        let sun_t = sun_transmittance(layer, at.x, mu_s_t);
        let psi = multiple_scattering(layer, at.x, mu_s_t);
        let weight = result.transmittance * segment_weight(m.extinction, dt);
        let source = (m.rayleigh_scattering * phase_r + m.aerosol_scattering * phase_a) * sun_t
            + (m.rayleigh_scattering + m.aerosol_scattering) * psi;
        result.radiance += weight * source;
        result.transmittance *= exp(-m.extinction * dt);
    }
    return result;
}
