// Pass: display. Linear radiance → exposure → tone map → sRGB (twin of model::display), or
// luminance in cd/m² on a log scale in false colour (twin of render::views::false_colour).

// Pipeline constants, one variant per display mode and tone map (see common/view.wgsl).
override DISPLAY_MODE: u32 = DISPLAY_COLOUR;
override TONE_MAP: u32 = TONE_MAP_EXPONENTIAL;

fn srgb_encode(linear: vec3<f32>) -> vec3<f32> {
    let c = clamp(linear, vec3<f32>(0.0), vec3<f32>(1.0));
    return select(1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055, 12.92 * c, c <= vec3<f32>(0.0031308));
}

fn tone_map(x: vec3<f32>) -> vec3<f32> {
    switch TONE_MAP {
        case TONE_MAP_FILMIC: {
            return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
        }
        case TONE_MAP_LINEAR: {
            return x;
        }
        default: {
            return 1.0 - exp(-x);
        }
    }
}

fn false_colour(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * f32(FALSE_COLOUR_STOP_COUNT - 1u);
    let i = min(u32(floor(x)), FALSE_COLOUR_STOP_COUNT - 2u);
    return mix(FALSE_COLOUR_STOPS[i], FALSE_COLOUR_STOPS[i + 1u], x - f32(i));
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= globals.view.xy) {
        return;
    }
    let l = textureLoad(radiance_in, id.xy, 0);
    var out = vec3<f32>(0.0);
    if l.a > 0.0 {
        if DISPLAY_MODE == DISPLAY_LUMINANCE {
            let y = dot(SRGB_TO_Y, l.rgb) * MAX_LUMINOUS_EFFICACY_LM_PER_W;
            let t = (log(max(y, 1e-30)) / log(10.0) - globals.display.y) / (globals.display.z - globals.display.y);
            out = false_colour(t);
        } else {
            out = srgb_encode(tone_map(max(l.rgb * globals.display.x, vec3<f32>(0.0))));
        }
    }
    textureStore(display_out, id.xy, vec4<f32>(out, 1.0));
}
