// Pass (once per order n ≥ 2): order n of Haber et al.'s (2005) orders, the light of order n − 1
// (previous_intensity_lut) gathered along each texel's ray, the ground lit by its sky
// (shared/intensity_volume_march.wgsl); written as the last order and added to the volume. Twin
// of model::methods::shared::intensity_volume::compute_next. The gather and the skylight are
// shared/intensity_volume.wgsl's higher_orders and ground_skylight on previous_intensity_lut
// instead of intensity_volume_lut: WGSL passes no storage buffer to a function.

fn previous_texel(t: Taps) -> vec4<f32> {
    return blend(previous_intensity_lut[t.i.x], previous_intensity_lut[t.i.y],
        previous_intensity_lut[t.i.z], previous_intensity_lut[t.i.w], t.w);
}

fn order_source(layer: u32, h: f32, mu_s: f32, mu: f32, nu: f32) -> array<vec4<f32>, 2> {
    let view = view_in_sun_frame(mu, mu_s, nu);
    var s = array<vec4<f32>, 2>(vec4<f32>(0.0), vec4<f32>(0.0));
    var ws = s;
    for (var k = 0u; k < INTENSITY_DIRECTIONS; k++) {
        let l = previous_texel(intensity_taps(layer, h, mu_s, k));
        let w = gather_weights(layer, view, k);
        s[0] += w[0] * l;
        s[1] += w[1] * l;
        ws[0] += w[0];
        ws[1] += w[1];
    }
    return normalised_gather(s, ws);
}

fn order_ground(layer: u32, mu_s_g: f32) -> vec4<f32> {
    var e = vec4<f32>(0.0);
    for (var k = 0u; k < INTENSITY_DIRECTIONS; k++) {
        let weight = projected_solid_angle(k, mu_s_g);
        if weight > 0.0 {
            e += previous_texel(intensity_taps(layer, 0.0, mu_s_g, k)) * (2.0 * weight);
        }
    }
    return e;
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let v = intensity_volume_texel(invocation);
    if !inside_intensity_volume(v) {
        return;
    }
    let i = intensity_index(v);
    let l = intensity_march(v);
    delta_intensity_lut[i] = l;
    intensity_volume_lut[i] += l;
}
