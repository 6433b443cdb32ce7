// Pass: the view with a table-free single-scattering model (nishita, trapezoid, schuler,
// galaj-taylor): single scattering marched along each pixel's ray, lit at every sample through
// the transmittance towards the sun by the model's way, and the sunlit ground behind; from
// above the atmosphere the march starts where the ray enters it (entry point: views/sky.wgsl,
// or shared/moving_sky.wgsl for the moving sky).
// globals.model[0] holds (view samples, sun intervals, way: 0 midpoint or 1 trapezoid rule
// along the sun's ray, 2 Schuler's or 3 Gałaj's closed form on the exponential medium of
// shared/exponential.wgsl, 0), from the model's registry constants; the model's common files
// define higher_orders(layer, h, mu_s, mu, nu), the source of its higher orders per unit
// scattering coefficient of air and aerosol, and ground_skylight(layer, mu_s_g), their light on
// the ground (zero in shared/no_higher_orders.wgsl; Hillaire's Ψ_ms in
// shared/isotropic_higher_orders.wgsl for the -ms rows; the intensity volume in
// shared/intensity_volume.wgsl for nishita-96 and haber). Twin of
// model::methods::shared::single_scattering_sky; the way to the sun is in shared/sun_route.wgsl.

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
    var inscattered = vec4<f32>(0.0);
    var throughput = vec4<f32>(1.0);
    for (var s = 0u; s < n; s++) {
        let t = (f32(s) + 0.5) * dt;
        let at = altitude_along(h0, mu0, t);
        let mu_t = clamp((r0 * mu0 + t) / at.y, -1.0, 1.0);
        let mu_s_t = clamp((r0 * mu_s0 + t * nu) / at.y, -1.0, 1.0);
        let m = medium(b, at.x);
        let sun_t = sun_transmittance_by_way(layer, at.x, mu_s_t);
        let higher = higher_orders(layer, at.x, mu_s_t, mu_t, nu);
        let source = m.rayleigh_scattering * (phase_r * sun_t + higher[0])
            + m.aerosol_scattering * (phase_a * sun_t + higher[1]);
        inscattered += throughput * segment_weight(m.extinction, dt) * source;
        throughput *= exp(-m.extinction * dt);
    }
    var l = inscattered * b.solar_irradiance;
    if ground {
        let mu_s_g = clamp((r0 * mu_s0 + t_max * nu) / big_r, -1.0, 1.0);
        let sun_g = sun_transmittance_by_way(layer, 0.0, mu_s_g);
        let lit = sun_g * max(mu_s_g, 0.0) + ground_skylight(layer, mu_s_g);
        l += throughput * b.ground_albedo / PI * b.solar_irradiance * lit;
    }
    return l;
}
