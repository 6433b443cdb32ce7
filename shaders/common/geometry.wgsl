// Ray geometry in (h, mu) around a spherical planet; twins of model::geometry. r² − R² is
// always formed as h(2R + h) to stay accurate in f32 near the ground.

fn rho_squared(h: f32) -> f32 {
    return h * (2.0 * bottom_radius() + h);
}

fn hits_ground(h: f32, mu: f32) -> bool {
    let rm = (bottom_radius() + h) * mu;
    return mu < 0.0 && rm * rm - rho_squared(h) >= 0.0;
}

// Each root is formed without cancellation (see the twin's comments).
fn distance_to_top(h: f32, mu: f32) -> f32 {
    let r = bottom_radius() + h;
    let rm = r * mu;
    let c = (thickness() - h) * (top_radius() + r);
    let q = sqrt(max(rm * rm + c, 0.0));
    if rm > 0.0 {
        return max(c / (rm + q), 0.0);
    }
    return -rm + q;
}

fn distance_to_ground(h: f32, mu: f32) -> f32 {
    let rm = (bottom_radius() + h) * mu;
    let disc = max(rm * rm - rho_squared(h), 0.0);
    let denom = -rm + sqrt(disc);
    if denom > 0.0 {
        return rho_squared(h) / denom;
    }
    return 0.0;
}

// Distance to where the ray leaves the atmosphere: the ground if it hits it, else the top.
fn distance_to_boundary(h: f32, mu: f32) -> f32 {
    if hits_ground(h, mu) {
        return distance_to_ground(h, mu);
    }
    return distance_to_top(h, mu);
}

// (altitude, radius) at distance t along the ray (h, mu).
fn altitude_along(h: f32, mu: f32, t: f32) -> vec2<f32> {
    let r = bottom_radius() + h;
    let r_t = sqrt(max(r * r + t * t + 2.0 * r * mu * t, 0.0));
    let h_t = (rho_squared(h) + t * (t + 2.0 * r * mu)) / (r_t + bottom_radius());
    return vec2<f32>(h_t, r_t);
}

// (1 − e^(−σ·dt))/σ per lane.
fn segment_weight(extinction: vec4<f32>, dt: f32) -> vec4<f32> {
    let x = extinction * dt;
    let series = dt * (1.0 - 0.5 * x);
    let exact = (1.0 - exp(-x)) / max(extinction, vec4<f32>(1e-30));
    return select(exact, series, x < vec4<f32>(SMALL_OPTICAL_THICKNESS));
}

// +z up, +y north, +x east; angles in radians.
fn direction_from_angles(elevation: f32, azimuth: f32) -> vec3<f32> {
    return vec3<f32>(cos(elevation) * sin(azimuth), cos(elevation) * cos(azimuth), sin(elevation));
}

// Segment i of n over [t0, t1] with the given spacing.
fn march_segment(spacing: u32, t0: f32, t1: f32, i: u32, n: u32) -> vec2<f32> {
    let length = t1 - t0;
    let xa = f32(i) / f32(n);
    let xb = f32(i + 1u) / f32(n);
    if spacing == SPACING_QUADRATIC {
        return vec2<f32>(t0 + length * xa * xa, t0 + length * xb * xb);
    }
    if spacing == SPACING_QUADRATIC_TO_END {
        return vec2<f32>(t1 - length * (1.0 - xa) * (1.0 - xa), t1 - length * (1.0 - xb) * (1.0 - xb));
    }
    return vec2<f32>(t0 + length * xa, t0 + length * xb);
}
