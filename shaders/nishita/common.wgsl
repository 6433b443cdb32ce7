// Nishita (1993): the nested march towards the sun, with no table, for the table-free
// single-scattering sky pass (shared/single_scattering_sky.wgsl). Twins of
// model::methods::nishita. globals.model holds the step counts: (view, sun, 0, 0).

// Transmittance from altitude h towards the sun at zenith cosine mu_s by a march of midpoint
// samples to the top, times the visible fraction of the disk (0, and no march, behind the
// planet).
fn sun_transmittance_of_model(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let visible = sun_visible_fraction(h, mu_s);
    if visible <= 0.0 {
        return vec4<f32>(0.0);
    }
    let n = u32(globals.model.y);
    let dt = distance_to_top(h, mu_s) / f32(n);
    let b = batches[layer];
    var depth = vec4<f32>(0.0);
    for (var s = 0u; s < n; s++) {
        let at = altitude_along(h, mu_s, (f32(s) + 0.5) * dt);
        depth += medium(b, at.x).extinction * dt;
    }
    return exp(-depth) * visible;
}
