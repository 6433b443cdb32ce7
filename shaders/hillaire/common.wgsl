// Hillaire (2020): the functions every pass of the method shares. Twins of
// model::methods::hillaire (same mappings, same step placement, same arithmetic in f32).

// The sun-zenith axis of the Ψ_ms and ground-irradiance tables is in shared/mu_s_axis.wgsl.

// ---- multiple scattering ----

fn multiple_scattering_texel_from_h_mu_s(h: f32, mu_s: f32) -> vec2<f32> {
    return vec2<f32>(mu_s_axis_coordinate(mu_s), h / thickness()) * vec2<f32>(MULTIPLE_SCATTERING_SIZE - 1u);
}

fn multiple_scattering_h_mu_s_from_texel(f: vec2<f32>) -> vec2<f32> {
    let x = f / vec2<f32>(MULTIPLE_SCATTERING_SIZE - 1u);
    return vec2<f32>(x.y * thickness(), mu_s_axis_mu_s(x.x));
}

fn multiple_scattering(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let t = taps(MULTIPLE_SCATTERING_SIZE, layer, multiple_scattering_texel_from_h_mu_s(h, mu_s));
    return blend(multiple_scattering_lut[t.i.x], multiple_scattering_lut[t.i.y],
        multiple_scattering_lut[t.i.z], multiple_scattering_lut[t.i.w], t.w);
}

// ---- ground irradiance ----

fn ground_irradiance_texel_from_mu_s(mu_s: f32) -> f32 {
    return mu_s_axis_coordinate(mu_s) * f32(GROUND_IRRADIANCE_SIZE - 1u);
}

fn ground_irradiance_mu_s_from_texel(f: f32) -> f32 {
    return mu_s_axis_mu_s(f / f32(GROUND_IRRADIANCE_SIZE - 1u));
}

fn ground_irradiance(layer: u32, mu_s: f32) -> vec4<f32> {
    let f = vec2<f32>(ground_irradiance_texel_from_mu_s(mu_s), 0.0);
    let t = taps(vec2<u32>(GROUND_IRRADIANCE_SIZE, 1u), layer, f);
    return blend(ground_irradiance_lut[t.i.x], ground_irradiance_lut[t.i.y],
        ground_irradiance_lut[t.i.z], ground_irradiance_lut[t.i.w], t.w);
}

// ---- sky view and aerial perspective ----

fn sky_view(layer: u32, h: f32, phi: f32, theta: f32, ground: bool) -> vec4<f32> {
    let t = sky_view_taps(layer, h, phi, theta, ground);
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

// ---- the higher orders the shared march (common/march.wgsl) adds: Ψ_ms (paper eq. 11) ----

fn psi(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return multiple_scattering(layer, h, mu_s);
}
