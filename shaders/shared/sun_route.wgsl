// The table-free models' way to the sun (globals.model[0].z: 0 midpoint or 1 trapezoid rule
// along the sun's ray over globals.model[0].y intervals, 2 Schuler's, 3 Gałaj's Taylor or
// 4 Leenman's homogeneous-shell closed form on the exponential medium of shared/exponential.wgsl
// (shared/closed_form_columns.wgsl), 5 Gałaj's spline (galaj_spline/columns.wgsl)) and the
// sun's disk through it. Twin of model::methods::shared::single_scattering_sky::SunRoute.

fn way_to_sun() -> u32 {
    return u32(globals.model[0].z + 0.5);
}

// Optical depth from altitude h along zenith cosine mu to the top by the model's rule over
// equal intervals; twin of single_scattering_sky::optical_depth.
fn optical_depth_to_top(layer: u32, h: f32, mu: f32) -> vec4<f32> {
    let n = u32(globals.model[0].y);
    let trapezoid = way_to_sun() == 1u;
    let dt = distance_to_top(h, mu) / f32(n);
    var samples = n;
    var offset = 0.5;
    if trapezoid {
        samples = n + 1u;
        offset = 0.0;
    }
    let b = batches[layer];
    var depth = vec4<f32>(0.0);
    for (var s = 0u; s < samples; s++) {
        let at = altitude_along(h, mu, (f32(s) + offset) * dt);
        var w = 1.0;
        if trapezoid && (s == 0u || s == n) {
            w = 0.5;
        }
        depth += w * medium(b, at.x).extinction * dt;
    }
    return depth;
}

// Optical depth from altitude h along zenith cosine mu to the top by the model's way; twin of
// SunRoute::optical_depth.
fn optical_depth_by_way(layer: u32, h: f32, mu: f32) -> vec4<f32> {
    let way = way_to_sun();
    if way >= 2u {
        return exponential_optical_depth(layer, h, mu, columns_to_top(way, h, mu));
    }
    return optical_depth_to_top(layer, h, mu);
}

// Transmittance towards the sun at zenith cosine mu_s by the model's way, times the visible
// fraction of its disk (0, and no integral, behind the planet); twin of SunRoute::transmittance.
// `sun_transmittance_by_way`, which the sky files call, is this (shared/sun_route_marched.wgsl)
// or, in the moving sky of the nested marches, its table (shared/sun_route_from_table.wgsl).
fn sun_transmittance_marched(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let visible = sun_visible_fraction(h, mu_s);
    if visible <= 0.0 {
        return vec4<f32>(0.0);
    }
    return exp(-optical_depth_by_way(layer, h, mu_s)) * visible;
}

// The sun's disk seen from any altitude: from where its ray enters the atmosphere when the
// camera is above it (twin of SunRoute::seen_from).
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    if h <= thickness() {
        return sun_transmittance_by_way(layer, h, mu_s);
    }
    let entry = entry_into_atmosphere(h, mu_s, mu_s, 1.0);
    if entry.z == 0.0 {
        return vec4<f32>(1.0);
    }
    return sun_transmittance_by_way(layer, thickness(), entry.x);
}
