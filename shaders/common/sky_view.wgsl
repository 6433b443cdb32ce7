// The sky-view grid at the camera's altitude (Hillaire 2020 §5.3): azimuth from the sun ×
// view zenith, with the quadratic latitude mapping that puts texels near the horizon and the
// horizon between two rows. Hillaire's sky-view table and the moving sky of the marches per
// pixel (shared/moving_sky.wgsl) are both laid out on it. Twin of
// model::methods::hillaire::sky_view.

// β at the camera's altitude, the only altitude the sky view and aerial perspective are built
// for; computed once per frame in f64 (geometry::horizon_beta).
fn horizon_beta(h: f32) -> f32 {
    return globals.camera.w;
}

fn sky_view_texel_from_angles(h: f32, phi: f32, theta: f32) -> vec2<f32> {
    let beta = horizon_beta(h);
    let theta_h = PI - beta;
    var v: f32;
    if theta < theta_h {
        v = 0.5 * (1.0 - sqrt(max(1.0 - theta / theta_h, 0.0)));
    } else {
        v = 0.5 + 0.5 * sqrt(clamp((theta - theta_h) / beta, 0.0, 1.0));
    }
    let u = sqrt(clamp(phi / PI, 0.0, 1.0));
    return vec2<f32>(u, v) * vec2<f32>(SKY_VIEW_SIZE - 1u);
}

fn sky_view_angles_from_texel(h: f32, f: vec2<f32>) -> vec2<f32> {
    let beta = horizon_beta(h);
    let theta_h = PI - beta;
    let x = f / vec2<f32>(SKY_VIEW_SIZE - 1u);
    var theta: f32;
    if x.y < 0.5 {
        let c = 1.0 - 2.0 * x.y;
        theta = theta_h * (1.0 - c * c);
    } else {
        let c = 2.0 * x.y - 1.0;
        theta = theta_h + beta * c * c;
    }
    return vec2<f32>(PI * x.x * x.x, theta);
}

// The bilinear taps of (φ, θ) in batch `layer` of a table on the grid; `ground` picks the half
// of the table (never blended across the horizon).
fn sky_view_taps(layer: u32, h: f32, phi: f32, theta: f32, ground: bool) -> Taps {
    var f = sky_view_texel_from_angles(h, phi, theta);
    let half = f32(SKY_VIEW_SIZE.y / 2u);
    if ground {
        f.y = max(f.y, half);
    } else {
        f.y = min(f.y, half - 1.0);
    }
    return taps(SKY_VIEW_SIZE, layer, f);
}
