// The transmittance table every table-based model shares (Bruneton 2017 mapping); twins of
// model::methods::shared::transmittance.

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

// Transmittance straight up from the ground, T(0, 1): the table's first texel, where its
// mapping puts h = 0, mu = 1. One read where a look-up costs four and their blend; twin of
// shared::transmittance::ground_to_top.
fn transmittance_ground_to_top(layer: u32) -> vec4<f32> {
    return transmittance_lut[layer * TRANSMITTANCE_SIZE.x * TRANSMITTANCE_SIZE.y];
}

// The fraction of the sun's disk above the horizon seen from altitude h with the sun at zenith
// cosine mu_s (Earth's shadow with its penumbra); twin of shared::sun::visible_fraction.
fn sun_visible_fraction(h: f32, mu_s: f32) -> f32 {
    let sin_h = bottom_radius() / (bottom_radius() + h);
    let cos_h = -sqrt(max(1.0 - sin_h * sin_h, 0.0));
    let edge = sin_h * SUN_ANGULAR_RADIUS_RAD;
    return smoothstep(-edge, edge, mu_s - cos_h);
}

// Transmittance to the sun times the visible fraction of its disk above the horizon.
fn sun_transmittance(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return transmittance(layer, h, mu_s) * sun_visible_fraction(h, mu_s);
}

// Transmittance to the sun seen from altitude h (anywhere up to space) with the sun at zenith
// cosine mu_s, along the sun's own ray; twin of shared::transmittance::sun_seen_from.
fn sun_seen_from(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    if h <= thickness() {
        return sun_transmittance(layer, h, mu_s);
    }
    let entry = entry_into_atmosphere(h, mu_s, mu_s, 1.0);
    if entry.z == 0.0 {
        return vec4<f32>(1.0);
    }
    return sun_transmittance(layer, thickness(), entry.x);
}

// The Lambertian ground where the sun's zenith cosine is mu_s_g, lit by direct sunlight alone
// (models with no skylight term for surfaces). Twin of shared::transmittance::sunlit_ground.
fn sunlit_ground(layer: u32, mu_s_g: f32) -> vec4<f32> {
    let b = batches[layer];
    return b.ground_albedo / PI * b.solar_irradiance * sun_transmittance(layer, 0.0, mu_s_g) * max(mu_s_g, 0.0);
}

// Transmittance between the point at altitude h and the point at distance d along (h, mu), as
// ratios of table values in which every ray rises from where it starts. Twin of
// shared::transmittance::transmittance_between.
fn transmittance_between(layer: u32, h: f32, mu: f32, d: f32) -> vec4<f32> {
    let at = altitude_along(h, mu, d);
    let mu_d = clamp(((bottom_radius() + h) * mu + d) / at.y, -1.0, 1.0);
    var v: vec4<f32>;
    if mu_d < 0.0 {
        v = transmittance(layer, at.x, -mu_d) / max(transmittance(layer, h, -mu), vec4<f32>(1e-30));
    } else if mu < 0.0 {
        let low = transmittance(layer, lowest_altitude(h, mu), 0.0);
        v = low * low / max(transmittance(layer, h, -mu), vec4<f32>(1e-30))
            / max(transmittance(layer, at.x, mu_d), vec4<f32>(1e-30));
    } else {
        v = transmittance(layer, h, mu) / max(transmittance(layer, at.x, mu_d), vec4<f32>(1e-30));
    }
    return min(v, vec4<f32>(1.0));
}

// Altitude of the lowest point of the line (h, mu); twin of shared::transmittance::lowest_altitude.
fn lowest_altitude(h: f32, mu: f32) -> f32 {
    let big_r = bottom_radius();
    let r = big_r + h;
    let rho2 = rho_squared(h) - r * r * mu * mu;
    return max(rho2 / (sqrt(max(rho2 + big_r * big_r, 0.0)) + big_r), 0.0);
}
