// García Liñán (2023): the functions the method's passes share. Twins of
// model::methods::garcia_linan (same mapping, same steps, same arithmetic in f32).
// globals.model[0] holds the fitted constants: (L_ms scale, a, b, reference wavelength in nm).

// L_ms per lane at sun zenith cosine mu_s: scale·(λ_ref/λ)⁴ / (1 + a·exp(−b·mu_s)).
fn multiple_scattering_fit(layer: u32, mu_s: f32) -> vec4<f32> {
    let c = globals.model[0];
    let logistic = c.x / (1.0 + c.y * exp(-c.z * mu_s));
    let ratio = vec4<f32>(c.w) / batches[layer].wavelengths_nm;
    let r2 = ratio * ratio;
    return logistic * r2 * r2;
}

// Solid angle of the ground seen from altitude h: 2π(1 − √(r² − R²)/r).
fn ground_solid_angle(h: f32) -> f32 {
    let r = bottom_radius() + h;
    return max(2.0 * PI * (1.0 - sqrt(rho_squared(max(h, 0.0))) / r), 0.0);
}

// L_g per lane: the sunlit ground straight below as a Lambertian disk.
fn ground_bounce(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let albedo = batches[layer].ground_albedo;
    let t_ground_sun = sun_transmittance(layer, 0.0, mu_s);
    let t_vertical = min(transmittance_ground_to_top(layer) / max(transmittance(layer, h, 1.0), vec4<f32>(1e-30)),
        vec4<f32>(1.0));
    let k = ground_solid_angle(h) / (4.0 * PI) * max(mu_s, 0.0) / PI;
    return k * albedo * t_ground_sun * t_vertical;
}

// The higher orders the shared march (common/march.wgsl) adds: L_g + L_ms.
fn psi(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return ground_bounce(layer, h, mu_s) + multiple_scattering_fit(layer, mu_s);
}

// ---- sky texture: azimuth from the sun (linear), elevation (quadratic towards the horizontal) ----

fn sky_texture_texel_from_angles(phi: f32, e: f32) -> vec2<f32> {
    let l = sign(e) * sqrt(min(abs(e) / (0.5 * PI), 1.0));
    return vec2<f32>(clamp(phi / PI, 0.0, 1.0), 0.5 * (1.0 - l)) * vec2<f32>(SKY_TEXTURE_SIZE - 1u);
}

fn sky_texture_angles_from_texel(f: vec2<f32>) -> vec2<f32> {
    let x = f / vec2<f32>(SKY_TEXTURE_SIZE - 1u);
    let l = 1.0 - 2.0 * x.y;
    return vec2<f32>(PI * x.x, sign(l) * l * l * 0.5 * PI);
}

fn sky_texture(layer: u32, phi: f32, e: f32) -> vec4<f32> {
    let t = taps(SKY_TEXTURE_SIZE, layer, sky_texture_texel_from_angles(phi, e));
    return blend(sky_texture_lut[t.i.x], sky_texture_lut[t.i.y], sky_texture_lut[t.i.z],
        sky_texture_lut[t.i.w], t.w);
}
