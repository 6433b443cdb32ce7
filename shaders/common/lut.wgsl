// Lookup tables live in storage buffers of vec4 texels, indexed ((layer·depth + z)·height + y)·width
// + x exactly like model::methods::shared::Lut. Buffer loads are plain memory reads, far
// cheaper than texel fetches on software drivers, and the manual bilinear and trilinear
// interpolation below is the twin of Lut::bilinear / Lut::trilinear.
// Coordinates are fractional texel indices, clamped to the table.

struct Taps {
    // indices of the four texels (x0 y0, x1 y0, x0 y1, x1 y1) and the weights in x and y
    i: vec4<u32>,
    w: vec2<f32>,
}

// Bilinear taps in slice `slice` (= layer·depth + z) of a width × height table.
fn taps(size: vec2<u32>, slice: u32, f: vec2<f32>) -> Taps {
    let c = clamp(f, vec2<f32>(0.0), vec2<f32>(size) - 1.0);
    let i0 = vec2<u32>(floor(c));
    let i1 = min(i0 + 1u, size - 1u);
    let base = slice * size.x * size.y;
    var t: Taps;
    t.i = vec4<u32>(
        base + i0.y * size.x + i0.x,
        base + i0.y * size.x + i1.x,
        base + i1.y * size.x + i0.x,
        base + i1.y * size.x + i1.x,
    );
    t.w = c - floor(c);
    return t;
}

fn blend(a: vec4<f32>, b: vec4<f32>, c: vec4<f32>, d: vec4<f32>, w: vec2<f32>) -> vec4<f32> {
    return mix(mix(a, b, w.x), mix(c, d, w.x), w.y);
}

// The texels (i0, i1) around a fractional coordinate on an axis of `depth` texels, and the
// weight of i1 (the twin of shared::table::split).
fn depth_taps(depth: u32, fz: f32) -> vec3<f32> {
    let c = clamp(fz, 0.0, f32(depth - 1u));
    let z0 = floor(c);
    return vec3<f32>(z0, min(z0 + 1.0, f32(depth - 1u)), c - z0);
}
