// Pass: the view. Each pixel's ray is looked up in the sky-view table (sky), the aerial-
// perspective volume (near ground) or the sky view plus transmittance (far ground); from above
// the atmosphere it is ray-marched (Hillaire 2020 §6). The entry point is views/sky.wgsl.

fn ground_radiance(layer: u32, mu_s_g: f32) -> vec4<f32> {
    // Field loads, not the whole struct: on software drivers every load is a per-lane gather.
    let albedo = batches[layer].ground_albedo;
    let e = batches[layer].solar_irradiance;
    let sun_t = sun_transmittance(layer, 0.0, mu_s_g);
    let sky = ground_irradiance(layer, mu_s_g);
    return albedo / PI * e * (sun_t * max(mu_s_g, 0.0) + sky);
}

fn aerial_perspective(layer: u32, h: f32, phi: f32, theta: f32, d: f32) -> Inscattering {
    let f = aerial_perspective_texel_from_angles(h, phi, theta);
    let fz = aerial_perspective_slice_from_distance(d);
    let depth = AERIAL_PERSPECTIVE_SIZE.z;
    let z = depth_taps(depth, max(fz, 0.0));
    let a = taps(AERIAL_PERSPECTIVE_SIZE.xy, layer * depth + u32(z.x), f);
    let b = taps(AERIAL_PERSPECTIVE_SIZE.xy, layer * depth + u32(z.y), f);
    var result: Inscattering;
    result.radiance = mix(
        blend(aerial_perspective_inscattering_lut[a.i.x], aerial_perspective_inscattering_lut[a.i.y],
            aerial_perspective_inscattering_lut[a.i.z], aerial_perspective_inscattering_lut[a.i.w], a.w),
        blend(aerial_perspective_inscattering_lut[b.i.x], aerial_perspective_inscattering_lut[b.i.y],
            aerial_perspective_inscattering_lut[b.i.z], aerial_perspective_inscattering_lut[b.i.w], b.w),
        z.z);
    result.transmittance = mix(
        blend(aerial_perspective_transmittance_lut[a.i.x], aerial_perspective_transmittance_lut[a.i.y],
            aerial_perspective_transmittance_lut[a.i.z], aerial_perspective_transmittance_lut[a.i.w], a.w),
        blend(aerial_perspective_transmittance_lut[b.i.x], aerial_perspective_transmittance_lut[b.i.y],
            aerial_perspective_transmittance_lut[b.i.z], aerial_perspective_transmittance_lut[b.i.w], b.w),
        z.z);
    if fz < 0.0 {
        let k = fz + 1.0;
        result.radiance *= k;
        result.transmittance = mix(vec4<f32>(1.0), result.transmittance, k);
    }
    return result;
}

// Twin of hillaire::radiance.
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
        let theta = angles.y;
        if sees_ground(h, mu) {
            let d = distance_to_ground(h, mu);
            let mu_s_g = clamp((r * mu_s + d * nu) / big_r, -1.0, 1.0);
            let lg = ground_radiance(layer, mu_s_g);
            // Twin of hillaire::sky::ground_path.
            var s: Inscattering;
            let near = d < AERIAL_PERSPECTIVE_MAX_DISTANCE_M;
            if near {
                s = aerial_perspective(layer, h, phi, theta, d);
            } else {
                s.radiance = sky_view(layer, h, phi, theta, true);
            }
            if !near || h >= GROUND_TRANSMITTANCE_FROM_TABLE_ABOVE_M {
                let mu_g = clamp((r * mu + d) / big_r, -1.0, 1.0);
                let t_g = transmittance(layer, 0.0, -mu_g);
                let t_c = transmittance(layer, h, -mu);
                s.transmittance = min(t_g / max(t_c, vec4<f32>(1e-30)), vec4<f32>(1.0));
            }
            return s.radiance + s.transmittance * lg;
        }
        return sky_view(layer, h, phi, theta, false);
    }
    // Above the atmosphere: march from where the ray enters it.
    let entry = entry_into_atmosphere(h, mu, mu_s, nu);
    if entry.z == 0.0 {
        return vec4<f32>(0.0);
    }
    let mu_e = entry.x;
    let mu_s_e = entry.y;
    let ground = hits_ground(thickness(), mu_e);
    var t_max: f32;
    var spacing = SPACING_UNIFORM;
    if ground {
        t_max = distance_to_ground(thickness(), mu_e);
        spacing = SPACING_QUADRATIC_TO_END;
    } else {
        t_max = distance_to_top(thickness(), mu_e);
    }
    let s = integrate_inscattering(layer,
        vec4<f32>(thickness(), mu_e, mu_s_e, nu), 0.0, t_max, globals.steps_b.y, spacing);
    var behind = vec4<f32>(0.0);
    if ground {
        let mu_s_g = clamp((top * mu_s_e + t_max * nu) / big_r, -1.0, 1.0);
        behind = ground_radiance(layer, mu_s_g);
    }
    return s.radiance * e + s.transmittance * behind;
}
