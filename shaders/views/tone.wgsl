// What the display shows of a pixel's linear radiance: exposure, white balance, tone map and
// sRGB (twin of model::display), or luminance in cd/m² on a log scale in false colour (twin of
// render::views::false_colour), or in the Polarisation mode the degree of polarisation in false
// colour, from 0 to 1 (the radiance image then holds the Stokes vector (I_Y, Q_Y, U_Y)). The display pass applies it to the radiance image; the sky pass
// applies it as it draws, so a frame that redraws the sky needs no display pass.

// Pipeline constants, one variant per display mode, tone map and glare (see common/view.wgsl):
// a software GPU would pay for the glare in every pixel behind a branch.
override DISPLAY_MODE: u32 = DISPLAY_COLOUR;
override TONE_MAP: u32 = TONE_MAP_EXPONENTIAL;
override GLARE: bool = false;

fn srgb_encode(linear: vec3<f32>) -> vec3<f32> {
    let c = clamp(linear, vec3<f32>(0.0), vec3<f32>(1.0));
    return select(1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3<f32>(0.0031308));
}

// AgX: linear in, linear out; twin of model::display::agx.
fn agx(rgb: vec3<f32>) -> vec3<f32> {
    let lo = AGX_LOG2_RANGE.x;
    let hi = AGX_LOG2_RANGE.y;
    let x = (clamp(log2(max(AGX_INSET * rgb, vec3<f32>(1e-10))), vec3<f32>(lo), vec3<f32>(hi)) - lo) / (hi - lo);
    var s = vec3<f32>(0.0);
    for (var i = 0u; i < 7u; i++) {
        s = s * x + AGX_SIGMOID[i];
    }
    return pow(max(AGX_OUTSET * s, vec3<f32>(0.0)), vec3<f32>(2.2));
}

// Khronos PBR Neutral; twin of model::display::pbr_neutral.
fn pbr_neutral(rgb: vec3<f32>) -> vec3<f32> {
    let x = min(rgb.r, min(rgb.g, rgb.b));
    let offset = select(0.04, x - 6.25 * x * x, x < 0.08);
    let c = rgb - offset;
    let peak = max(c.r, max(c.g, c.b));
    if peak < NEUTRAL_START {
        return c;
    }
    let d = 1.0 - NEUTRAL_START;
    let new_peak = 1.0 - d * d / (peak + d - NEUTRAL_START);
    let g = 1.0 - 1.0 / (NEUTRAL_DESATURATION * (peak - new_peak) + 1.0);
    let scaled = c * (new_peak / peak);
    return scaled + (vec3<f32>(new_peak) - scaled) * g;
}

// Twin of model::display::tone_map.
fn tone_map(x: vec3<f32>) -> vec3<f32> {
    switch TONE_MAP {
        case TONE_MAP_FILMIC: {
            return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
        }
        case TONE_MAP_AGX: {
            return agx(x);
        }
        case TONE_MAP_PBR_NEUTRAL: {
            return pbr_neutral(x);
        }
        case TONE_MAP_LINEAR: {
            return x;
        }
        default: {
            return 1.0 - exp(-x);
        }
    }
}

// Twin of model::display::hash32.
fn hash32(v: u32) -> u32 {
    var x = v;
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    return x ^ (x >> 16u);
}

// Triangular noise in (−1, 1) steps of 1/255 for pixel p; twin of model::display::dither.
fn dither(p: vec2<u32>) -> f32 {
    let a = hash32(p.x ^ hash32(p.y));
    let b = hash32(a);
    return f32(a >> 8u) / 16777216.0 + f32(b >> 8u) / 16777216.0 - 1.0;
}

// The veiling glare around the sun at the view's point (x, y) (a pixel's centre is at +0.5),
// 10·E/θ² (θ in degrees, at least 1°); twin of model::display::glare.
fn glare(x: f32, y: f32) -> vec3<f32> {
    let ray = camera_ray(x, y);
    if ray.w == 0.0 {
        return vec3<f32>(0.0);
    }
    let cos_theta = clamp(dot(normalize(ray.xyz), globals.sun.xyz), -1.0, 1.0);
    let theta_deg = max(degrees(acos(cos_theta)), GLARE_MIN_ANGLE_DEG);
    return globals.glare.xyz * (GLARE_K / (theta_deg * theta_deg));
}

fn false_colour(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * f32(FALSE_COLOUR_STOP_COUNT - 1u);
    let i = min(u32(floor(x)), FALSE_COLOUR_STOP_COUNT - 2u);
    return mix(FALSE_COLOUR_STOPS[i], FALSE_COLOUR_STOPS[i + 1u], x - f32(i));
}

// What the display shows of linear radiance rgb seen at the view's point (x, y), before
// dithering: glare, white balance, exposure, tone map and sRGB, or false colour.
fn shown(x: f32, y: f32, rgb: vec3<f32>) -> vec3<f32> {
    if DISPLAY_MODE == DISPLAY_POLARISATION {
        // The radiance image holds (I_Y, Q_Y, U_Y): the degree of polarisation, 0 to 1.
        return false_colour(select(0.0, length(rgb.yz) / rgb.x, rgb.x > 0.0));
    }
    if DISPLAY_MODE == DISPLAY_LUMINANCE {
        let y_cd = dot(SRGB_TO_Y, rgb) * MAX_LUMINOUS_EFFICACY_LM_PER_W;
        let t = (log(max(y_cd, 1e-30)) / log(10.0) - globals.display.y) / (globals.display.z - globals.display.y);
        return false_colour(t);
    }
    var l = rgb;
    if GLARE {
        l += glare(x, y);
    }
    let wb = globals.white_balance;
    let balanced = vec3<f32>(dot(wb[0].xyz, l), dot(wb[1].xyz, l), dot(wb[2].xyz, l));
    return srgb_encode(tone_map(max(balanced * globals.display.x, vec3<f32>(0.0))));
}

// Pixel p as written to the display image, its colour c (black outside the projection) dithered.
fn dithered(p: vec2<u32>, c: vec3<f32>) -> vec4<f32> {
    var out = c;
    if globals.display.w > 0.0 {
        out += dither(p) / 255.0;
    }
    return vec4<f32>(out, 1.0);
}

// Pixel p as displayed, from its linear radiance l (coverage in alpha).
fn displayed(p: vec2<u32>, l: vec4<f32>) -> vec4<f32> {
    var c = vec3<f32>(0.0);
    if l.a > 0.0 {
        c = shown(f32(p.x) + 0.5, f32(p.y) + 0.5, l.rgb);
    }
    return dithered(p, c);
}
