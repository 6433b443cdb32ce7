// Nishita et al.'s (1996) intensity volumes (model::methods::shared::intensity_volume): the
// scattered radiance per unit solar irradiance at each (μ_s, h) for INTENSITY_DIRECTIONS cells
// centred on the sun (bands of angle from it, INTENSITY_BAND_EDGE_COS, times bands of azimuth
// about it), each with its mirror image across the sun's vertical plane; and, as the higher
// orders of the table-free sky pass (shared/single_scattering_sky.wgsl), the light of
// intensity_volume_lut gathered towards the view and the skylight it sends onto the ground.
// Twin of the module's look-ups and gather.

// The texel (x: μ_s, y: h, z: direction, w: batch) of a Volume dispatch's invocation, whether
// it lies inside the volume, and its index in a volume's buffer.
fn intensity_volume_texel(invocation: vec3<u32>) -> vec4<u32> {
    let id = dispatched(invocation);
    return vec4<u32>(id.x, id.y, id.z % INTENSITY_DIRECTIONS, id.z / INTENSITY_DIRECTIONS);
}

fn inside_intensity_volume(v: vec4<u32>) -> bool {
    return all(v.xy < INTENSITY_VOLUME_SIZE) && v.w < batch_count();
}

fn intensity_index(v: vec4<u32>) -> u32 {
    return ((v.w * INTENSITY_DIRECTIONS + v.z) * INTENSITY_VOLUME_SIZE.y + v.y) * INTENSITY_VOLUME_SIZE.x + v.x;
}

// The bounds of cell k: the cosines of its band's edges (from the sun outwards), its azimuth
// band's first β and the bands' width in β; twin of intensity_volume::cell_bounds.
fn intensity_cell_bounds(k: u32) -> vec4<f32> {
    let band = k / INTENSITY_AZIMUTH_BANDS;
    let width = PI / f32(INTENSITY_AZIMUTH_BANDS);
    return vec4<f32>(INTENSITY_BAND_EDGE_COS[band], INTENSITY_BAND_EDGE_COS[band + 1u],
        width * f32(k % INTENSITY_AZIMUTH_BANDS), width);
}

fn sine_of(cosine: f32) -> f32 {
    return sqrt(max(1.0 - cosine * cosine, 0.0));
}

// The zenith cosine of the direction at angle α from the sun and azimuth beta about it.
fn zenith_cosine(cos_alpha: f32, beta: f32, mu_s: f32) -> f32 {
    return cos_alpha * mu_s + sine_of(cos_alpha) * cos(beta) * sine_of(mu_s);
}

// Cell k relative to the sun: the cosine of its centre's angle from the sun, its azimuth about
// the sun (0 towards the zenith) and the solid angle of one of its two mirror cells; twin of
// intensity_volume::cell.
fn intensity_cell(k: u32) -> vec3<f32> {
    let b = intensity_cell_bounds(k);
    return vec3<f32>(0.5 * (b.x + b.y), b.z + 0.5 * b.w, (b.x - b.y) * b.w);
}

// The zenith cosine and the view–sun cosine of cell k where the sun's zenith cosine is mu_s.
fn intensity_direction(k: u32, mu_s: f32) -> vec2<f32> {
    let cell = intensity_cell(k);
    return vec2<f32>(clamp(zenith_cosine(cell.x, cell.y, mu_s), -1.0, 1.0), cell.x);
}

// ∫ max(μ, 0) dΩ over one of cell k's mirror cells, by the midpoint rule on an
// INTENSITY_SUBCELLS² grid of its cos α and β; twin of intensity_volume::projected_solid_angle.
fn projected_solid_angle(k: u32, mu_s: f32) -> f32 {
    let b = intensity_cell_bounds(k);
    let n = f32(INTENSITY_SUBCELLS);
    var sum = 0.0;
    for (var i = 0u; i < INTENSITY_SUBCELLS; i++) {
        let cos_alpha = b.x + (b.y - b.x) * (f32(i) + 0.5) / n;
        for (var j = 0u; j < INTENSITY_SUBCELLS; j++) {
            sum += max(zenith_cosine(cos_alpha, b.z + b.w * (f32(j) + 0.5) / n, mu_s), 0.0);
        }
    }
    return sum * (b.x - b.y) * b.w / (n * n);
}

fn intensity_texel_from_h_mu_s(h: f32, mu_s: f32) -> vec2<f32> {
    let v = sqrt(clamp(h / thickness(), 0.0, 1.0));
    return vec2<f32>(mu_s_axis_coordinate(mu_s), v) * (vec2<f32>(INTENSITY_VOLUME_SIZE) - 1.0);
}

fn intensity_h_mu_s_from_texel(f: vec2<f32>) -> vec2<f32> {
    let x = f / (vec2<f32>(INTENSITY_VOLUME_SIZE) - 1.0);
    return vec2<f32>(x.y * x.y * thickness(), mu_s_axis_mu_s(x.x));
}

// The view (zenith cosine mu, view–sun cosine nu) in the sun's frame where the sun's zenith
// cosine is mu_s: (along the sun, towards the zenith along the great circle through both, across
// it); twin of the frame in intensity_volume::gathered.
fn view_in_sun_frame(mu: f32, mu_s: f32, nu: f32) -> vec3<f32> {
    let s = sine_of(mu);
    let s_s = sine_of(mu_s);
    var cos_phi = 1.0;
    if s * s_s > 1e-6 {
        cos_phi = clamp((nu - mu * mu_s) / (s * s_s), -1.0, 1.0);
    }
    return vec3<f32>(nu, mu * s_s - s * cos_phi * mu_s, s * sine_of(cos_phi));
}

// The phase functions (air, aerosol) between the view (`view` from view_in_sun_frame) and cell
// k with its mirror image, times the cell's solid angle.
fn gather_weights(layer: u32, view: vec3<f32>, k: u32) -> array<vec4<f32>, 2> {
    let cell = intensity_cell(k);
    let sin_alpha = sine_of(cell.x);
    let along = cell.x * view.x + sin_alpha * cos(cell.y) * view.y;
    let rho = batches[layer].rayleigh_depolarisation;
    var w = array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var side = 0; side < 2; side++) {
        let across = select(-1.0, 1.0, side == 0) * sin_alpha * sin(cell.y) * view.z;
        let cos_theta = clamp(along + across, -1.0, 1.0);
        w[0] += rayleigh_phase(cos_theta, rho) * cell.z;
        w[1] += aerosol_phase(cos_theta, layer) * cell.z;
    }
    return w;
}

// A gather's sums `s` over the sums of its weights `w`: each phase's quadrature normalised to
// its integral, 1 (intensity_volume::normalised); zero where every weight is.
fn normalised_gather(s: array<vec4<f32>, 2>, w: array<vec4<f32>, 2>) -> array<vec4<f32>, 2> {
    return array<vec4<f32>, 2>(
        select(vec4<f32>(0.0), s[0] / w[0], w[0] > vec4<f32>(0.0)),
        select(vec4<f32>(0.0), s[1] / w[1], w[1] > vec4<f32>(0.0)),
    );
}

fn intensity_taps(layer: u32, h: f32, mu_s: f32, k: u32) -> Taps {
    return taps(INTENSITY_VOLUME_SIZE, layer * INTENSITY_DIRECTIONS + k, intensity_texel_from_h_mu_s(h, mu_s));
}

// The higher orders of the sky pass: the volume's light gathered at (h, mu_s) towards the view
// (zenith cosine mu, view–sun cosine nu), per unit scattering coefficient of (air, aerosol).
fn higher_orders(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    let view = view_in_sun_frame(mu, mu_s, nu);
    var s = array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
    var ws = s;
    for (var k = 0u; k < INTENSITY_DIRECTIONS; k++) {
        let t = intensity_taps(layer, h, mu_s, k);
        let l = blend(intensity_volume_lut[t.i.x], intensity_volume_lut[t.i.y],
            intensity_volume_lut[t.i.z], intensity_volume_lut[t.i.w], t.w);
        let w = gather_weights(layer, view, k);
        s[0] += w[0] * l;
        s[1] += w[1] * l;
        ws[0] += w[0];
        ws[1] += w[1];
    }
    return normalised_gather(s, ws);
}

// The volume's skylight on the ground where the sun's zenith cosine is mu_s_g, per unit solar
// irradiance: each cell's light weighted by its part of the cosine-weighted hemisphere.
fn ground_skylight(layer: u32, mu_s_g: f32) -> vec4<f32> {
    var e = vec4<f32>(0.0);
    for (var k = 0u; k < INTENSITY_DIRECTIONS; k++) {
        let weight = projected_solid_angle(k, mu_s_g);
        if weight > 0.0 {
            let t = intensity_taps(layer, 0.0, mu_s_g, k);
            e += blend(intensity_volume_lut[t.i.x], intensity_volume_lut[t.i.y],
                intensity_volume_lut[t.i.z], intensity_volume_lut[t.i.w], t.w) * (2.0 * weight);
        }
    }
    return e;
}
