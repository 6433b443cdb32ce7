// Elek (2009): the mapping of the azimuth-free tables (mu, mu_s, h) and their trilinear
// look-ups. Twins of model::methods::elek (same mapping, same arithmetic in f32).

// The notes' cosine axis, ½(1 + sign(c)·|c|^⅓): dense where the cosine is near 0.
fn cosine_axis(c: f32) -> f32 {
    let x = clamp(c, -1.0, 1.0);
    return 0.5 * (1.0 + sign(x) * pow(abs(x), 1.0 / 3.0));
}

fn cosine_from_axis(v: f32) -> f32 {
    let x = clamp(2.0 * v - 1.0, -1.0, 1.0);
    return x * x * x;
}

// Fractional texel coordinates of (h, mu, mu_s); node-centred, altitude as √(h/H).
fn elek_texel(h: f32, mu: f32, mu_s: f32) -> vec3<f32> {
    return vec3<f32>(cosine_axis(mu), cosine_axis(mu_s), sqrt(clamp(h / thickness(), 0.0, 1.0)))
        * vec3<f32>(ELEK_SIZE - 1u);
}

// (h, mu, mu_s) of integer texel (x, y, z).
fn elek_h_mu_mu_s(x: u32, y: u32, z: u32) -> vec3<f32> {
    let f = vec3<f32>(f32(x), f32(y), f32(z)) / vec3<f32>(ELEK_SIZE - 1u);
    return vec3<f32>(f.z * f.z * thickness(), cosine_from_axis(f.x), cosine_from_axis(f.y));
}

// The texel's ray with the sun in the view's half-plane (azimuth 0).
fn elek_coords(x: u32, y: u32, z: u32) -> Coords {
    let a = elek_h_mu_mu_s(x, y, z);
    var c: Coords;
    c.h = a.x;
    c.mu = a.y;
    c.mu_s = a.z;
    c.nu = clamp(a.y * a.z + sqrt(max((1.0 - a.y * a.y) * (1.0 - a.z * a.z), 0.0)), -1.0, 1.0);
    c.ground = hits_ground(a.x, a.y);
    return c;
}

fn elek_index(layer: u32, x: u32, y: u32, z: u32) -> u32 {
    return ((layer * ELEK_SIZE.z + z) * ELEK_SIZE.y + y) * ELEK_SIZE.x + x;
}

// The 3D invocation of a pass over the tables: texel (x, y), slice z and layer.
fn volume_texel(id: vec3<u32>) -> vec4<u32> {
    return vec4<u32>(id.x, id.y, id.z % ELEK_SIZE.z, id.z / ELEK_SIZE.z);
}

// Trilinear taps: bilinear in the two slices around the altitude, then linear between them.
struct ElekTaps {
    a: Taps,
    b: Taps,
    wz: f32,
}

fn elek_taps(layer: u32, f: vec3<f32>) -> ElekTaps {
    let z = depth_taps(ELEK_SIZE.z, f.z);
    var t: ElekTaps;
    t.a = taps(ELEK_SIZE.xy, layer * ELEK_SIZE.z + u32(z.x), f.xy);
    t.b = taps(ELEK_SIZE.xy, layer * ELEK_SIZE.z + u32(z.y), f.xy);
    t.wz = z.z;
    return t;
}

// One reader per table: WGSL passes no storage buffer to a function.
fn read_delta_rayleigh(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(delta_rayleigh_lut[t.a.i.x], delta_rayleigh_lut[t.a.i.y], delta_rayleigh_lut[t.a.i.z], delta_rayleigh_lut[t.a.i.w], t.a.w),
        blend(delta_rayleigh_lut[t.b.i.x], delta_rayleigh_lut[t.b.i.y], delta_rayleigh_lut[t.b.i.z], delta_rayleigh_lut[t.b.i.w], t.b.w),
        t.wz);
}

fn read_delta_mie(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(delta_mie_lut[t.a.i.x], delta_mie_lut[t.a.i.y], delta_mie_lut[t.a.i.z], delta_mie_lut[t.a.i.w], t.a.w),
        blend(delta_mie_lut[t.b.i.x], delta_mie_lut[t.b.i.y], delta_mie_lut[t.b.i.z], delta_mie_lut[t.b.i.w], t.b.w),
        t.wz);
}

fn read_gathered_rayleigh(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(gathered_rayleigh_lut[t.a.i.x], gathered_rayleigh_lut[t.a.i.y], gathered_rayleigh_lut[t.a.i.z], gathered_rayleigh_lut[t.a.i.w], t.a.w),
        blend(gathered_rayleigh_lut[t.b.i.x], gathered_rayleigh_lut[t.b.i.y], gathered_rayleigh_lut[t.b.i.z], gathered_rayleigh_lut[t.b.i.w], t.b.w),
        t.wz);
}

fn read_gathered_mie(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(gathered_mie_lut[t.a.i.x], gathered_mie_lut[t.a.i.y], gathered_mie_lut[t.a.i.z], gathered_mie_lut[t.a.i.w], t.a.w),
        blend(gathered_mie_lut[t.b.i.x], gathered_mie_lut[t.b.i.y], gathered_mie_lut[t.b.i.z], gathered_mie_lut[t.b.i.w], t.b.w),
        t.wz);
}

fn read_rayleigh_scattering(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(rayleigh_scattering_lut[t.a.i.x], rayleigh_scattering_lut[t.a.i.y], rayleigh_scattering_lut[t.a.i.z], rayleigh_scattering_lut[t.a.i.w], t.a.w),
        blend(rayleigh_scattering_lut[t.b.i.x], rayleigh_scattering_lut[t.b.i.y], rayleigh_scattering_lut[t.b.i.z], rayleigh_scattering_lut[t.b.i.w], t.b.w),
        t.wz);
}

fn read_mie_scattering(t: ElekTaps) -> vec4<f32> {
    return mix(
        blend(mie_scattering_lut[t.a.i.x], mie_scattering_lut[t.a.i.y], mie_scattering_lut[t.a.i.z], mie_scattering_lut[t.a.i.w], t.a.w),
        blend(mie_scattering_lut[t.b.i.x], mie_scattering_lut[t.b.i.y], mie_scattering_lut[t.b.i.z], mie_scattering_lut[t.b.i.w], t.b.w),
        t.wz);
}

// The notes' modified Rayleigh phase, (a + b·nu)/(4π).
fn modified_rayleigh_phase(nu: f32) -> f32 {
    return (ELEK_MODIFIED_RAYLEIGH.x + ELEK_MODIFIED_RAYLEIGH.y * nu) / (4.0 * PI);
}
