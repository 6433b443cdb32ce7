// The entry point of every model's sky pass, appended after the pass's file, which defines
// `radiance(layer, dir)`: a batch's radiance of the sky and the ground along a world direction
// from the camera (drawn through `view_radiance`: views/radiance.wgsl, or for a march per pixel
// views/moving_sky_radiance.wgsl), and, in the model's common files, `sun_through_atmosphere(layer, h, mu_s)`:
// the transmittance along the sun's own ray (shared/sun_disk.wgsl for the table-based models).
// The sun's disk is added here, averaged over the pixel (twin of model::methods::render_with). Sums the
// batches into linear sRGB (Y = ∫ȳL dλ), scaled from sunlight at 1 AU to the scene's Earth–Sun
// distance, and writes coverage in alpha (0 outside the projection).
//
// With SKY_TILE > 1 (the frames of a view in motion, `Engine::set_sky_tile`) the radiance is
// computed at the corners of tiles of SKY_TILE × SKY_TILE pixels, shared through workgroup
// memory, and interpolated bilinearly inside a tile whose four corners see the same thing
// (sky, ground or nothing) and differ by less than SKY_TILE_CONTRAST. Any other tile (the
// horizon, the edge of a fisheye, a sharp gradient) is appended to `exact_tiles`, and a second,
// indirect dispatch (SKY_TILE_EXACT) computes those tiles pixel by pixel: a branch would not
// do, as a software GPU runs both sides of it for every lane. The sun's disk is never
// interpolated: its pixels are drawn by a third dispatch at SKY_TILE = 1.
//
// With POLARISATION the radiance passes the camera's polarising filter, or in the Polarisation
// display mode the radiance image holds the view's Stokes vector (views/polarisation.wgsl).
//
// The pass writes the view as displayed (views/tone.wgsl) beside its radiance, so a frame that
// redraws the sky runs no display pass. A frame in tiles interpolates the displayed colours of
// the corners and, unless WRITE_RADIANCE (the meter reads it), leaves the radiance image as the
// last frame at full resolution drew it: a software GPU spends most of a tiled frame writing
// 16-byte pixels. The engine then redraws the view at full resolution before the display or
// meter pass reads the radiance (Engine::read_radiance waits for it too). With glare, whose
// 1/θ² is steep near the sun, a tile is interpolated only where the corners' displayed colours
// are smooth as well.

override SKY_TILE: u32 = 1u;
override SKY_TILE_EXACT: bool = false;
override WRITE_RADIANCE: bool = true;

const TILE_CORNERS_PER_SIDE: u32 = WORKGROUP_SIZE + 1u;
var<workgroup> tile_corners: array<vec4<f32>, TILE_CORNERS>;
var<workgroup> tile_corners_shown: array<vec3<f32>, TILE_CORNERS>;

const CORNER_NOTHING: f32 = 0.0;
const CORNER_SKY: f32 = 1.0;
const CORNER_GROUND: f32 = 2.0;

// Writes pixel p's radiance l (unless WRITE_RADIANCE is off) and its displayed colour.
fn store(p: vec2<u32>, l: vec4<f32>) {
    if WRITE_RADIANCE {
        textureStore(radiance_out, p, l);
    }
    textureStore(display_out, p, displayed(p, l));
}

// A batch's radiance in linear sRGB (sunlight at 1 AU).
fn batch_srgb(layer: u32, l: vec4<f32>) -> vec3<f32> {
    return vec3<f32>(dot(batches[layer].to_srgb_r, l), dot(batches[layer].to_srgb_g, l),
        dot(batches[layer].to_srgb_b, l));
}

// A batch's weights of its lanes' radiances in the luminance Y (sunlight at 1 AU).
fn batch_y(layer: u32) -> vec4<f32> {
    return SRGB_TO_Y.x * batches[layer].to_srgb_r + SRGB_TO_Y.y * batches[layer].to_srgb_g
        + SRGB_TO_Y.z * batches[layer].to_srgb_b;
}

// Linear sRGB of the sky and ground along `dir` seen at the view's point (x, y), with the sun's
// `disk` where it reaches, summed over the batches and scaled to the scene's Earth–Sun distance:
// through the camera's polarising filter where POLARISATION says so, or, for the Polarisation
// display mode, the Stokes vector (I_Y, Q_Y, U_Y) referred to up in the picture
// (views/polarisation.wgsl).
fn shade(x: f32, y: f32, dir: vec3<f32>, disk: DiskInPixel) -> vec3<f32> {
    var rgb = vec3<f32>(0.0);
    var stokes = vec3<f32>(0.0);
    var up = vec3<f32>(0.0);
    // Once per pixel, whatever the number of batches.
    if POLARISATION != POLARISATION_OFF {
        up = image_up(x, y, dir);
    }
    for (var layer = 0u; layer < batch_count(); layer++) {
        let sky = view_radiance(layer, dir);
        var l = sky;
        if SUN_DISK && disk.reaches {
            let sun = sun_through_atmosphere(layer, globals.camera_position.w, globals.sun.w);
            l += batches[layer].solar_irradiance * sun
                * disk_radiance(disk, batches[layer].wavelengths_nm);
        }
        if POLARISATION == POLARISATION_FILTER {
            l = through_polariser(layer, dir, up, l, sky);
        }
        if POLARISATION == POLARISATION_STOKES {
            let s = sky_stokes(layer, dir, up, sky);
            let w = batch_y(layer);
            stokes += vec3<f32>(dot(w, l), dot(w, s.q), dot(w, s.u));
        }
        rgb += batch_srgb(layer, l);
    }
    if POLARISATION == POLARISATION_STOKES {
        return globals.sunlight.x * stokes;
    }
    return globals.sunlight.x * rgb;
}

// The pixel centred at (x, y): linear sRGB with the sun's disk where SUN_DISK, coverage in alpha.
fn pixel(x: f32, y: f32) -> vec4<f32> {
    let ray = camera_ray(x, y);
    if ray.w == 0.0 {
        return vec4<f32>(0.0);
    }
    var disk = no_disk();
    if SUN_DISK {
        disk = sun_pixel(x, y);
    }
    return vec4<f32>(shade(x, y, ray.xyz, disk), 1.0);
}

// A tile corner at pixel-grid point (x, y): linear sRGB without the disk, and what the ray sees.
fn tile_corner(x: f32, y: f32) -> vec4<f32> {
    let ray = camera_ray(x, y);
    if ray.w == 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, CORNER_NOTHING);
    }
    let up = normalize(globals.camera_position.xyz);
    let ground = hits_ground(globals.camera_position.w, dot(ray.xyz, up));
    return vec4<f32>(shade(x, y, ray.xyz, no_disk()), select(CORNER_SKY, CORNER_GROUND, ground));
}

// Whether a tile may be interpolated from its corners.
fn tile_is_smooth(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>) -> bool {
    if a.w != b.w || a.w != c.w || a.w != d.w {
        return false;
    }
    return spread_is_small(a.rgb, b.rgb, c.rgb, d.rgb);
}

// Whether four colours differ by at most SKY_TILE_CONTRAST per channel.
fn spread_is_small(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, d: vec3<f32>) -> bool {
    let hi = max(max(a, b), max(c, d));
    let lo = min(min(a, b), min(c, d));
    // Out-of-gamut colours have negative channels: the spread is measured against the larger
    // magnitude.
    return all(hi - lo <= SKY_TILE_CONTRAST * max(abs(hi), abs(lo)));
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(
    @builtin(global_invocation_id) invocation: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
) {
    if SKY_TILE <= 1u {
        let id = dispatched(invocation);
        if all(id.xy < globals.view.xy) {
            store(id.xy, pixel(f32(id.x) + 0.5, f32(id.y) + 0.5));
        }
        return;
    }
    if SKY_TILE_EXACT {
        // One listed tile per invocation.
        let n = group.x * WORKGROUP_SIZE * WORKGROUP_SIZE + local;
        if n < atomicLoad(&exact_tiles.count) {
            let t = exact_tiles.tiles[n];
            let first = vec2<u32>(t & 0xffffu, t >> 16u) * SKY_TILE;
            for (var j = 0u; j < SKY_TILE; j++) {
                for (var i = 0u; i < SKY_TILE; i++) {
                    let p = first + vec2<u32>(i, j);
                    if all(p < globals.view.xy) {
                        store(p, pixel(f32(p.x) + 0.5, f32(p.y) + 0.5));
                    }
                }
            }
        }
        return;
    }
    // The workgroup's block of WORKGROUP_SIZE × WORKGROUP_SIZE tiles; its corners first.
    let base = origin.xy + group.xy * (WORKGROUP_SIZE * SKY_TILE);
    for (var c = local; c < TILE_CORNERS; c += WORKGROUP_SIZE * WORKGROUP_SIZE) {
        let corner = vec2<u32>(c % TILE_CORNERS_PER_SIDE, c / TILE_CORNERS_PER_SIDE);
        let p = vec2<f32>(base + corner * SKY_TILE);
        let l = tile_corner(p.x, p.y);
        tile_corners[c] = l;
        tile_corners_shown[c] = select(shown(p.x, p.y, l.rgb), vec3<f32>(0.0), l.w == CORNER_NOTHING);
    }
    workgroupBarrier();
    let cell = vec2<u32>(local % WORKGROUP_SIZE, local / WORKGROUP_SIZE);
    let first = base + cell * SKY_TILE;
    if any(first >= globals.view.xy) {
        return;
    }
    let k = cell.y * TILE_CORNERS_PER_SIDE + cell.x;
    let a = tile_corners[k];
    let b = tile_corners[k + 1u];
    let c = tile_corners[k + TILE_CORNERS_PER_SIDE];
    let d = tile_corners[k + TILE_CORNERS_PER_SIDE + 1u];
    let sa = tile_corners_shown[k];
    let sb = tile_corners_shown[k + 1u];
    let sc = tile_corners_shown[k + TILE_CORNERS_PER_SIDE];
    let sd = tile_corners_shown[k + TILE_CORNERS_PER_SIDE + 1u];
    if !tile_is_smooth(a, b, c, d) || (GLARE && !spread_is_small(sa, sb, sc, sd)) {
        let n = atomicAdd(&exact_tiles.count, 1u);
        if n < arrayLength(&exact_tiles.tiles) {
            let t = first / SKY_TILE;
            exact_tiles.tiles[n] = t.x | (t.y << 16u);
            atomicMax(&exact_tiles.groups_x, n / (WORKGROUP_SIZE * WORKGROUP_SIZE) + 1u);
            atomicStore(&exact_tiles.groups_y, 1u);
            atomicStore(&exact_tiles.groups_z, 1u);
        }
        return;
    }
    let coverage = select(1.0, 0.0, a.w == CORNER_NOTHING);
    for (var j = 0u; j < SKY_TILE; j++) {
        for (var i = 0u; i < SKY_TILE; i++) {
            let p = first + vec2<u32>(i, j);
            if all(p < globals.view.xy) {
                let f = (vec2<f32>(f32(i), f32(j)) + 0.5) / f32(SKY_TILE);
                if WRITE_RADIANCE {
                    let rgb = mix(mix(a.rgb, b.rgb, f.x), mix(c.rgb, d.rgb, f.x), f.y);
                    textureStore(radiance_out, p, vec4<f32>(rgb, coverage));
                }
                let shown_rgb = mix(mix(sa, sb, f.x), mix(sc, sd, f.x), f.y);
                textureStore(display_out, p, dithered(p, shown_rgb));
            }
        }
    }
}
