// Pass: the view with García Liñán (2023): the sky texture and the sunlit ground through the
// transmittance table; from above the atmosphere each pixel is marched with
// the model's integrand (entry point: views/sky.wgsl). Twin of
// model::methods::garcia_linan::sky.

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let top = top_radius();
    let h = globals.camera_position.w;
    let r = big_r + h;
    let sun = globals.sun.xyz;
    let e = batches[layer].solar_irradiance;
    let up = normalize(globals.camera_position.xyz);
    let mu = dot(dir, up);
    let mu_s = dot(sun, up);
    let nu = dot(dir, sun);
    if !ABOVE_ATMOSPHERE {
        let angles = sun_relative_angles(up, dir, sun);
        let phi = angles.x;
        let elevation = 0.5 * PI - angles.y;
        let s = sky_texture(layer, phi, elevation);
        if sees_ground(h, mu) {
            let d = distance_to_ground(h, mu);
            let mu_s_g = clamp((r * mu_s + d * nu) / big_r, -1.0, 1.0);
            let tr = transmittance_between(layer, h, mu, d);
            return s + tr * sunlit_ground(layer, mu_s_g);
        }
        return s;
    }
    let entry = entry_into_atmosphere(h, mu, mu_s, nu);
    if entry.z == 0.0 {
        return vec4<f32>(0.0);
    }
    let mu_e = entry.x;
    let mu_s_e = entry.y;
    let t_max = distance_to_boundary(thickness(), mu_e);
    let s = integrate_inscattering(layer, vec4<f32>(thickness(), mu_e, mu_s_e, nu), 0.0, t_max,
        globals.steps_b.y, SPACING_UNIFORM);
    var behind = vec4<f32>(0.0);
    if hits_ground(thickness(), mu_e) {
        let mu_s_g = clamp((top * mu_s_e + t_max * nu) / big_r, -1.0, 1.0);
        behind = sunlit_ground(layer, mu_s_g);
    }
    return s.radiance * e + s.transmittance * behind;
}
