// Pass: the view without an atmosphere: black sky and the Lambertian ground lit by the sun
// straight from space (entry point: views/sky.wgsl). Twin of model::methods::empty::sky.

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let big_r = bottom_radius();
    let h = globals.camera_position.w;
    let up = normalize(globals.camera_position.xyz);
    let sun = globals.sun.xyz;
    let mu = dot(dir, up);
    var ground: bool;
    if ABOVE_ATMOSPHERE {
        ground = hits_ground(h, mu);
    } else {
        ground = sees_ground(h, mu);
    }
    if !ground {
        return vec4<f32>(0.0);
    }
    let d = distance_to_ground(h, mu);
    let mu_s_g = clamp(((big_r + h) * dot(sun, up) + d * dot(dir, sun)) / big_r, -1.0, 1.0);
    let b = batches[layer];
    return b.ground_albedo * b.solar_irradiance * (sun_visible_fraction(0.0, mu_s_g) * max(mu_s_g, 0.0) / PI);
}

// The sun's disk at full strength wherever the planet does not hide it.
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return vec4<f32>(sun_visible_fraction(h, mu_s));
}
