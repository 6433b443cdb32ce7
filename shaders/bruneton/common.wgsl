// Bruneton (2017): the mappings, look-ups and integration helpers the passes share. Twins of
// model::methods::bruneton (same mappings, same sample placement, same arithmetic in f32).
// 4D tables (mu_s, nu, mu, r) are stored as 3D tables with the nu slices side by side in x.

fn horizon_length() -> f32 {
    return sqrt(rho_squared(thickness()));
}

fn mu_s_axis(mu_s: f32) -> f32 {
    let d = distance_to_top(0.0, mu_s);
    let d_min = thickness();
    let d_max = horizon_length();
    let a = (d - d_min) / (d_max - d_min);
    let big_a = -2.0 * BRUNETON_MU_S_MIN * bottom_radius() / (d_max - d_min);
    return clamp(max(1.0 - a / big_a, 0.0) / (1.0 + a), 0.0, 1.0);
}

fn mu_s_from_axis(x: f32) -> f32 {
    let big_h = horizon_length();
    let d_min = thickness();
    let d_max = big_h;
    let big_a = -2.0 * BRUNETON_MU_S_MIN * bottom_radius() / (d_max - d_min);
    let a = (big_a - x * big_a) / (1.0 + x * big_a);
    let d = d_min + min(a, big_a) * (d_max - d_min);
    if d <= 0.0 {
        return 1.0;
    }
    return clamp((big_h * big_h - d * d) / (2.0 * bottom_radius() * d), -1.0, 1.0);
}

fn mu_texel(h: f32, mu: f32, ground: bool) -> f32 {
    let rho = sqrt(rho_squared(max(h, 0.0)));
    let half = f32(SCATTERING_MU / 2u - 1u);
    if ground {
        let d = distance_to_ground(h, mu);
        let d_min = max(h, 0.0);
        let d_max = rho;
        var x = 0.0;
        if d_max > d_min {
            x = clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
        }
        return half * (1.0 - x);
    }
    let d = distance_to_top(h, mu);
    let d_min = thickness() - h;
    let d_max = rho + horizon_length();
    let x = clamp((d - d_min) / max(d_max - d_min, 1e-9), 0.0, 1.0);
    return f32(SCATTERING_MU / 2u) + half * x;
}

fn r_texel(h: f32) -> f32 {
    let rho = sqrt(rho_squared(max(h, 0.0)));
    return min(rho / horizon_length(), 1.0) * f32(SCATTERING_R - 1u);
}

fn mu_s_texel(mu_s: f32) -> f32 {
    return mu_s_axis(mu_s) * f32(SCATTERING_MU_S - 1u);
}

fn nu_texel(nu: f32) -> f32 {
    return 0.5 * clamp(nu + 1.0, 0.0, 2.0) * f32(SCATTERING_NU - 1u);
}

fn scattering_texel(c: Coords) -> vec4<f32> {
    return vec4<f32>(mu_s_texel(c.mu_s), nu_texel(c.nu), mu_texel(c.h, c.mu, c.ground), r_texel(c.h));
}

// The point of integer texel (x, y, z); nu clamped to what mu and mu_s allow.
fn scattering_coords(x: u32, y: u32, z: u32) -> Coords {
    let big_r = bottom_radius();
    let big_h = horizon_length();
    let rho = big_h * f32(z) / f32(SCATTERING_R - 1u);
    let h = rho * rho / (sqrt(rho * rho + big_r * big_r) + big_r);
    let r = big_r + h;
    let half = f32(SCATTERING_MU / 2u - 1u);
    var c: Coords;
    c.h = h;
    c.ground = y < SCATTERING_MU / 2u;
    if c.ground {
        let xm = 1.0 - f32(y) / half;
        let d = h + xm * (rho - h);
        c.mu = -1.0;
        if d > 0.0 {
            c.mu = clamp(-(rho * rho + d * d) / (2.0 * r * d), -1.0, 1.0);
        }
    } else {
        let xm = f32(y - SCATTERING_MU / 2u) / half;
        let d_min = thickness() - h;
        let d = d_min + xm * (rho + big_h - d_min);
        c.mu = 1.0;
        if d > 0.0 {
            c.mu = clamp((big_h * big_h - rho * rho - d * d) / (2.0 * r * d), -1.0, 1.0);
        }
    }
    let slice = x / SCATTERING_MU_S;
    let j = x % SCATTERING_MU_S;
    c.mu_s = mu_s_from_axis(f32(j) / f32(SCATTERING_MU_S - 1u));
    let nu = -1.0 + 2.0 * f32(slice) / f32(SCATTERING_NU - 1u);
    let spread = sqrt(max((1.0 - c.mu * c.mu) * (1.0 - c.mu_s * c.mu_s), 0.0));
    c.nu = clamp(nu, c.mu * c.mu_s - spread, c.mu * c.mu_s + spread);
    return c;
}

fn scattering_index(layer: u32, x: u32, y: u32, z: u32) -> u32 {
    return ((layer * SCATTERING_SIZE.z + z) * SCATTERING_SIZE.y + y) * SCATTERING_SIZE.x + x;
}

// The cell of sixteen texels a look-up blends: trilinear in (mu_s, mu, r) in the two nu slices
// around nu, then linear in nu. Its texels are computed where they are read, so the readers
// below hold no array of sixteen indices: a GPU would keep a dynamically indexed array in slow
// per-invocation memory, which makes the sky pass several times slower.
struct ScatteringCell {
    // The index of the texel at the cell's lower corner.
    base: u32,
    // Index offsets to the upper texel along nu, r, mu and mu_s (0 where an axis is clamped).
    offset: vec4<u32>,
    // Weights of the upper texel along the same axes.
    t: vec4<f32>,
}

fn scattering_cell(layer: u32, t: vec4<f32>) -> ScatteringCell {
    let f_nu = clamp(t.y, 0.0, f32(SCATTERING_NU - 1u));
    let s0 = min(u32(floor(f_nu)), SCATTERING_NU - 2u);
    let j = depth_taps(SCATTERING_MU_S, t.x);
    let y = depth_taps(SCATTERING_SIZE.y, t.z);
    let z = depth_taps(SCATTERING_SIZE.z, t.w);
    var cell: ScatteringCell;
    cell.base = scattering_index(layer, s0 * SCATTERING_MU_S + u32(j.x), u32(y.x), u32(z.x));
    cell.offset = vec4<u32>(
        SCATTERING_MU_S,
        (u32(z.y) - u32(z.x)) * SCATTERING_SIZE.y * SCATTERING_SIZE.x,
        (u32(y.y) - u32(y.x)) * SCATTERING_SIZE.x,
        u32(j.y) - u32(j.x),
    );
    cell.t = vec4<f32>(f_nu - f32(s0), z.z, y.z, j.z);
    return cell;
}

struct Tap {
    index: u32,
    weight: f32,
}

// Corner k of the cell in (nu, r, mu) (bits in that order): the index of its lower mu_s texel
// and the weight of those three axes; the readers blend it with the texel above in mu_s.
fn cell_corner(cell: ScatteringCell, k: u32) -> Tap {
    let upper = vec3<u32>(k >> 2u, (k >> 1u) & 1u, k & 1u);
    let w = select(1.0 - cell.t.xyz, cell.t.xyz, upper == vec3<u32>(1u));
    return Tap(cell.base + dot(upper, cell.offset.xyz), w.x * w.y * w.z);
}

// One reader per table or pair of tables read together: WGSL passes no storage buffer to a
// function.
fn read_scattering_density(cell: ScatteringCell) -> vec4<f32> {
    var v = vec4<f32>(0.0);
    for (var k = 0u; k < 8u; k++) {
        let c = cell_corner(cell, k);
        v += (c.weight * (1.0 - cell.t.w)) * scattering_density_lut[c.index];
        v += (c.weight * cell.t.w) * scattering_density_lut[c.index + cell.offset.w];
    }
    return v;
}

// The scattering sum and the single Mie, blended over the same cell.
struct Inscattered {
    scattering: vec4<f32>,
    single_mie: vec4<f32>,
}

fn read_scattering(cell: ScatteringCell) -> Inscattered {
    var v = Inscattered(vec4<f32>(0.0), vec4<f32>(0.0));
    for (var k = 0u; k < 8u; k++) {
        let c = cell_corner(cell, k);
        let w0 = c.weight * (1.0 - cell.t.w);
        let w1 = c.weight * cell.t.w;
        let upper = c.index + cell.offset.w;
        v.scattering += w0 * scattering_lut[c.index];
        v.scattering += w1 * scattering_lut[upper];
        v.single_mie += w0 * single_mie_lut[c.index];
        v.single_mie += w1 * single_mie_lut[upper];
    }
    return v;
}

// Whether the order loop's pass reads single scattering (order 2), whose deltas have a Mie
// part; at later orders that part is zero, and reading it would double the look-ups.
override FIRST_ORDER: bool = true;

// The order held by the delta tables arriving from the direction at fractional texel t with
// view–sun cosine nu: R·P_R(ν) + M·P_M(ν).
fn previous_order(b: Batch, layer: u32, t: vec4<f32>, nu: f32) -> vec4<f32> {
    let cell = scattering_cell(layer, t);
    var rayleigh = vec4<f32>(0.0);
    var mie = vec4<f32>(0.0);
    for (var k = 0u; k < 8u; k++) {
        let c = cell_corner(cell, k);
        let w0 = c.weight * (1.0 - cell.t.w);
        let w1 = c.weight * cell.t.w;
        let upper = c.index + cell.offset.w;
        rayleigh += w0 * delta_rayleigh_lut[c.index];
        rayleigh += w1 * delta_rayleigh_lut[upper];
        if FIRST_ORDER {
            mie += w0 * delta_mie_lut[c.index];
            mie += w1 * delta_mie_lut[upper];
        }
    }
    let radiance = rayleigh * rayleigh_phase(nu, b.rayleigh_depolarisation);
    if FIRST_ORDER {
        return radiance + mie * aerosol_phase(nu, layer);
    }
    return radiance;
}

// ---- irradiance tables: (mu_s, h), affine ----

fn irradiance_texel(h: f32, mu_s: f32) -> vec2<f32> {
    return vec2<f32>(0.5 * (mu_s + 1.0), clamp(h / thickness(), 0.0, 1.0)) * vec2<f32>(IRRADIANCE_SIZE - 1u);
}

fn irradiance_h_mu_s(f: vec2<f32>) -> vec2<f32> {
    let x = f / vec2<f32>(IRRADIANCE_SIZE - 1u);
    return vec2<f32>(x.y * thickness(), clamp(2.0 * x.x - 1.0, -1.0, 1.0));
}

fn read_delta_irradiance(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let t = taps(IRRADIANCE_SIZE, layer, irradiance_texel(h, mu_s));
    return blend(delta_irradiance_lut[t.i.x], delta_irradiance_lut[t.i.y], delta_irradiance_lut[t.i.z],
        delta_irradiance_lut[t.i.w], t.w);
}

fn read_irradiance(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    let t = taps(IRRADIANCE_SIZE, layer, irradiance_texel(h, mu_s));
    return blend(irradiance_lut[t.i.x], irradiance_lut[t.i.y], irradiance_lut[t.i.z], irradiance_lut[t.i.w], t.w);
}

// The 3D invocation of a pass over a scattering table: texel (x, y), slice z and layer.
fn volume_texel(id: vec3<u32>) -> vec4<u32> {
    return vec4<u32>(id.x, id.y, id.z % SCATTERING_SIZE.z, id.z / SCATTERING_SIZE.z);
}
