// Pass: the view with Leenman's (2025) analytic single scattering (flat, raymarched): the view
// ray cut into globals.model[0].x equal segments, each integrated in closed form as a slab whose
// optical depth (to the camera plus to the sun) changes linearly between its ends, every depth
// the homogeneous-shell chord on the exponential medium (shared/exponential.wgsl), and the
// sunlit ground behind; from above the atmosphere the ray starts where it enters (entry point:
// views/sky.wgsl; the sun's disk in shared/sun_route.wgsl). Twin of
// model::methods::shared::segments_sky.

// Homogeneous-shell columns to infinity from altitude h along zenith cosine mu: air, aerosol,
// ozone shell path (twin of Segments::columns).
fn shell_columns(h: f32, mu: f32) -> vec3<f32> {
    let fit = globals.model[1];
    return vec3<f32>(
        fit.y * homogeneous_shell(h, mu, fit.x),
        fit.w * homogeneous_shell(h, mu, fit.z),
        ozone_path(h, mu),
    );
}

// Optical depth per lane of columns c (twin of Segments::depth).
fn columns_depth(layer: u32, c: vec3<f32>) -> vec4<f32> {
    let b = batches[layer];
    return b.rayleigh_scattering * c.x + b.ozone_absorption * c.z
        + (b.aerosol_scattering + b.aerosol_absorption) * c.y;
}

// Columns between distances t_a < t_b along the ray from (h0, mu0): chords ahead where the ray
// climbs, behind where it descends, split at its lowest point (twin of Segments::between).
fn columns_between(h0: f32, mu0: f32, t_a: f32, t_b: f32) -> vec3<f32> {
    let r0 = bottom_radius() + h0;
    let a = altitude_along(h0, mu0, t_a);
    let b = altitude_along(h0, mu0, t_b);
    let mu_a = clamp((r0 * mu0 + t_a) / a.y, -1.0, 1.0);
    let mu_b = clamp((r0 * mu0 + t_b) / b.y, -1.0, 1.0);
    let lowest = -r0 * mu0;
    let zero = vec3<f32>(0.0);
    if lowest <= t_a {
        return max(shell_columns(a.x, mu_a) - shell_columns(b.x, mu_b), zero);
    }
    if lowest >= t_b {
        return max(shell_columns(b.x, -mu_b) - shell_columns(a.x, -mu_a), zero);
    }
    let through = shell_columns(altitude_along(h0, mu0, lowest).x, 0.0);
    return max(through - shell_columns(a.x, -mu_a), zero)
        + max(through - shell_columns(b.x, mu_b), zero);
}

// The sun's optical depth at distance t along the ray.
fn sun_depth_at(layer: u32, h0: f32, mu0: f32, mu_s0: f32, nu: f32, t: f32) -> vec4<f32> {
    let at = altitude_along(h0, mu0, t);
    let mu_s_t = clamp(((bottom_radius() + h0) * mu_s0 + t * nu) / at.y, -1.0, 1.0);
    return columns_depth(layer, shell_columns(at.x, mu_s_t));
}

// ∫₀¹ exp(−(a + (b − a)t)) dt per lane; twin of segments_sky::slab.
fn slab(a: vec4<f32>, b: vec4<f32>) -> vec4<f32> {
    let d = b - a;
    let small = abs(d) < vec4<f32>(SMALL_DEPTH_DIFFERENCE);
    let safe = select(d, vec4<f32>(1.0), small);
    return select((exp(-a) - exp(-b)) / safe, exp(-a) * (1.0 - 0.5 * d), small);
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let cc = camera_coords(dir);
    if !cc.hit {
        return vec4<f32>(0.0);
    }
    let h0 = cc.c.h;
    let mu0 = cc.c.mu;
    let mu_s0 = cc.c.mu_s;
    let nu = cc.c.nu;
    let ground = cc.c.ground;
    let b = batches[layer];
    let phase_r = rayleigh_phase(nu, b.rayleigh_depolarisation);
    let phase_a = aerosol_phase(nu, layer);
    let r0 = big_r + h0;
    var t_max = distance_to_top(h0, mu0);
    if ground {
        t_max = distance_to_ground(h0, mu0);
    }
    let n = u32(globals.model[0].x);
    let dt = t_max / f32(n);
    var sun_a = sun_depth_at(layer, h0, mu0, mu_s0, nu, 0.0);
    var depth = vec4<f32>(0.0);
    var l = vec4<f32>(0.0);
    for (var s = 1u; s <= n; s++) {
        let t_a = f32(s - 1u) * dt;
        let t_b = f32(s) * dt;
        let seg = columns_between(h0, mu0, t_a, t_b);
        let step = columns_depth(layer, seg);
        let sun_b = sun_depth_at(layer, h0, mu0, mu_s0, nu, t_b);
        let scattering = b.rayleigh_scattering * seg.x * phase_r
            + b.aerosol_scattering * seg.y * phase_a;
        l += b.solar_irradiance * scattering * slab(depth + sun_a, depth + step + sun_b);
        depth += step;
        sun_a = sun_b;
    }
    if ground {
        let mu_s_g = clamp((r0 * mu_s0 + t_max * nu) / altitude_along(h0, mu0, t_max).y, -1.0, 1.0);
        let sun_g = sun_transmittance_by_way(layer, 0.0, mu_s_g);
        l += exp(-depth) * b.ground_albedo / PI * b.solar_irradiance * sun_g * max(mu_s_g, 0.0);
    }
    return l;
}
