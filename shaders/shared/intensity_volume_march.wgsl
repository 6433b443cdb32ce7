// The ray of an intensity-volume texel (model::methods::shared::intensity_volume::march): from
// (h, mu_s) along cell k's direction, the source the pass defines (order_source: the light
// scattered towards the ray per unit scattering coefficient of air and aerosol) marched in the
// multiple-scattering count of segments, quadratic towards the start, and the ground's
// order_ground(mu_s_g) behind it through the Lambertian albedo.

fn intensity_march(v: vec4<u32>) -> vec4<f32> {
    let layer = v.w;
    let at = intensity_h_mu_s_from_texel(vec2<f32>(f32(v.x), f32(v.y)));
    let h = at.x;
    let mu_s = at.y;
    let d = intensity_direction(v.z, mu_s);
    let mu = d.x;
    let nu = d.y;
    let r = bottom_radius() + h;
    let hit = hits_ground(h, mu);
    var t_max = distance_to_top(h, mu);
    if hit {
        t_max = distance_to_ground(h, mu);
    }
    let b = batches[layer];
    let n = globals.steps_a.y;
    var l = vec4<f32>(0.0);
    var throughput = vec4<f32>(1.0);
    for (var s = 0u; s < n; s++) {
        let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, s, n);
        let t = 0.5 * (seg.x + seg.y);
        let dt = seg.y - seg.x;
        let p = altitude_along(h, mu, t);
        let mu_t = clamp((r * mu + t) / p.y, -1.0, 1.0);
        let mu_s_t = clamp((r * mu_s + t * nu) / p.y, -1.0, 1.0);
        let m = medium(b, p.x);
        let j = order_source(layer, p.x, mu_s_t, mu_t, nu);
        l += throughput * segment_weight(m.extinction, dt) * (m.rayleigh_scattering * j[0] + m.aerosol_scattering * j[1]);
        throughput *= exp(-m.extinction * dt);
    }
    if hit {
        let mu_s_g = clamp((r * mu_s + t_max * nu) / bottom_radius(), -1.0, 1.0);
        l += throughput * b.ground_albedo / PI * order_ground(layer, mu_s_g);
    }
    return l;
}
