// Pass: the view with Leenman's (2025) analytic single scattering (flat, raymarched): the view
// ray cut into globals.model[0].x equal segments, each integrated in closed form as a slab whose
// optical depth (to the camera plus to the sun) changes linearly between its ends, every depth
// the homogeneous-shell chord on the exponential medium (shared/exponential.wgsl), and the
// sunlit ground behind; from above the atmosphere the ray starts where it enters (entry point:
// views/sky.wgsl; the sun's disk in shared/sun_route.wgsl). Twin of
// model::methods::shared::segments_sky.

// What the segment integral reads at a point of the view ray (twin of segments_sky::Point).
struct SlabPoint {
    // homogeneous-shell columns to infinity along the view: air, aerosol
    columns: vec2<f32>,
    view: vec4<f32>,
    sun: vec4<f32>,
}

fn slab_point(layer: u32, h: f32, mu: f32, mu_s: f32) -> SlabPoint {
    let fit = globals.model[1];
    var p: SlabPoint;
    p.columns = vec2<f32>(fit.y * homogeneous_shell(h, mu, fit.x), fit.w * homogeneous_shell(h, mu, fit.z));
    p.view = exponential_optical_depth(layer, h, mu, 4u);
    p.sun = exponential_optical_depth(layer, h, mu_s, 4u);
    return p;
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
    let phase_a = aerosol_phase(nu, b.aerosol_g);
    let r0 = big_r + h0;
    var t_max = distance_to_top(h0, mu0);
    if ground {
        t_max = distance_to_ground(h0, mu0);
    }
    let n = u32(globals.model[0].x);
    let dt = t_max / f32(n);
    var a_point = slab_point(layer, h0, mu0, mu_s0);
    var depth = vec4<f32>(0.0);
    var l = vec4<f32>(0.0);
    var mu_s_end = mu_s0;
    for (var s = 1u; s <= n; s++) {
        let t = f32(s) * dt;
        let at = altitude_along(h0, mu0, t);
        let mu_t = clamp((r0 * mu0 + t) / at.y, -1.0, 1.0);
        let mu_s_t = clamp((r0 * mu_s0 + t * nu) / at.y, -1.0, 1.0);
        let b_point = slab_point(layer, at.x, mu_t, mu_s_t);
        let step = max(a_point.view - b_point.view, vec4<f32>(0.0));
        let columns = max(a_point.columns - b_point.columns, vec2<f32>(0.0));
        let scattering = b.rayleigh_scattering * columns.x * phase_r
            + b.aerosol_scattering * columns.y * phase_a;
        l += b.solar_irradiance * scattering
            * slab(depth + a_point.sun, depth + step + b_point.sun);
        depth += step;
        a_point = b_point;
        mu_s_end = mu_s_t;
    }
    if ground {
        let sun_g = sun_transmittance_by_way(layer, 0.0, mu_s_end);
        l += exp(-depth) * b.ground_albedo / PI * b.solar_irradiance * sun_g * max(mu_s_end, 0.0);
    }
    return l;
}
