// Nishita et al.'s (1996) intensity volumes (model::methods::shared::intensity_volume): the
// scattered radiance per unit solar irradiance at each (μ_s, h) for INTENSITY_DIRECTIONS
// directions fixed in the local frame (zenith, the sun's azimuth), each with its mirror image
// across the sun's vertical plane; and, as the higher orders of the table-free sky pass
// (shared/single_scattering_sky.wgsl), the light of intensity_volume_lut gathered towards the
// view and the skylight it sends onto the ground. Twin of the module's look-ups and gather.

// The texel (x: μ_s, y: h, z: direction, w: batch) of a Volume dispatch's invocation, and its
// index in a volume's buffer.
fn intensity_volume_texel(id: vec3<u32>) -> vec4<u32> {
    return vec4<u32>(id.x, id.y, id.z % INTENSITY_DIRECTIONS, id.z / INTENSITY_DIRECTIONS);
}

fn intensity_index(v: vec4<u32>) -> u32 {
    return ((v.w * INTENSITY_DIRECTIONS + v.z) * INTENSITY_VOLUME_SIZE.y + v.y) * INTENSITY_VOLUME_SIZE.x + v.x;
}

// Zenith cosine μ and azimuth from the sun φ of table direction k (midpoints of equal bands).
fn intensity_direction(k: u32) -> vec2<f32> {
    let i = k / INTENSITY_AZIMUTH_NODES;
    let a = k % INTENSITY_AZIMUTH_NODES;
    return vec2<f32>(
        1.0 - 2.0 * (f32(i) + 0.5) / f32(INTENSITY_MU_NODES),
        PI * (f32(a) + 0.5) / f32(INTENSITY_AZIMUTH_NODES),
    );
}

fn intensity_texel_from_h_mu_s(h: f32, mu_s: f32) -> vec2<f32> {
    let u = 0.5 * (1.0 + sign(mu_s) * sqrt(abs(mu_s)));
    let v = sqrt(clamp(h / thickness(), 0.0, 1.0));
    return vec2<f32>(u, v) * (vec2<f32>(INTENSITY_VOLUME_SIZE) - 1.0);
}

fn intensity_h_mu_s_from_texel(f: vec2<f32>) -> vec2<f32> {
    let s = 2.0 * f.x / f32(INTENSITY_VOLUME_SIZE.x - 1u) - 1.0;
    let v = f.y / f32(INTENSITY_VOLUME_SIZE.y - 1u);
    return vec2<f32>(v * v * thickness(), sign(s) * s * s);
}

// The view's azimuth from the sun as (cos φ, sin φ ≥ 0) where the view has zenith cosine mu,
// the sun mu_s and the two the cosine nu; any azimuth where either is vertical.
fn view_azimuth(mu: f32, mu_s: f32, nu: f32) -> vec2<f32> {
    let s = sqrt(max(1.0 - mu * mu, 0.0)) * sqrt(max(1.0 - mu_s * mu_s, 0.0));
    var c = 1.0;
    if s > 1e-6 {
        c = clamp((nu - mu * mu_s) / s, -1.0, 1.0);
    }
    return vec2<f32>(c, sqrt(max(1.0 - c * c, 0.0)));
}

// The phase functions (air, aerosol) between the view (zenith cosine mu, azimuth `azimuth` from
// view_azimuth) and table direction k with its mirror image, times their solid angle.
fn gather_weights(layer: u32, mu: f32, azimuth: vec2<f32>, k: u32) -> array<vec4<f32>, 2> {
    let d = intensity_direction(k);
    let a = mu * d.x;
    let b = sqrt(max(1.0 - mu * mu, 0.0)) * sqrt(max(1.0 - d.x * d.x, 0.0));
    let rho = batches[layer].rayleigh_depolarisation;
    var w = array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var side = 0; side < 2; side++) {
        let cross_term = select(-1.0, 1.0, side == 0) * azimuth.y * sin(d.y);
        let cos_theta = clamp(a + b * (azimuth.x * cos(d.y) + cross_term), -1.0, 1.0);
        w[0] += rayleigh_phase(cos_theta, rho);
        w[1] += aerosol_phase(cos_theta, layer);
    }
    w[0] *= INTENSITY_SOLID_ANGLE;
    w[1] *= INTENSITY_SOLID_ANGLE;
    return w;
}

fn intensity_taps(layer: u32, h: f32, mu_s: f32, k: u32) -> Taps {
    return taps(INTENSITY_VOLUME_SIZE, layer * INTENSITY_DIRECTIONS + k, intensity_texel_from_h_mu_s(h, mu_s));
}

// The higher orders of the sky pass: the volume's light gathered at (h, mu_s) towards the view
// (zenith cosine mu, view–sun cosine nu), per unit scattering coefficient of (air, aerosol).
fn higher_orders(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    let azimuth = view_azimuth(mu, mu_s, nu);
    var s = array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var k = 0u; k < INTENSITY_DIRECTIONS; k++) {
        let t = intensity_taps(layer, h, mu_s, k);
        let l = blend(intensity_volume_lut[t.i.x], intensity_volume_lut[t.i.y],
            intensity_volume_lut[t.i.z], intensity_volume_lut[t.i.w], t.w);
        let w = gather_weights(layer, mu, azimuth, k);
        s[0] += w[0] * l;
        s[1] += w[1] * l;
    }
    return s;
}

// The volume's skylight on the ground where the sun's zenith cosine is mu_s_g, per unit solar
// irradiance: the directions above the horizon (the first half), weighted by their cosine.
fn ground_skylight(layer: u32, mu_s_g: f32) -> vec4<f32> {
    var e = vec4<f32>(0.0);
    for (var k = 0u; k < INTENSITY_DIRECTIONS / 2u; k++) {
        let t = intensity_taps(layer, 0.0, mu_s_g, k);
        let l = blend(intensity_volume_lut[t.i.x], intensity_volume_lut[t.i.y],
            intensity_volume_lut[t.i.z], intensity_volume_lut[t.i.w], t.w);
        e += l * intensity_direction(k).x;
    }
    return e * (2.0 * INTENSITY_SOLID_ANGLE);
}
