// Manual bilinear and trilinear lookups with textureLoad: identical arithmetic to the f64 twin
// (model::methods::hillaire::Lut), and no dependence on filterable float formats.
// Coordinates are fractional texel indices, clamped to the table.

fn lut_bilinear(t: texture_2d_array<f32>, layer: u32, f: vec2<f32>) -> vec4<f32> {
    let size = textureDimensions(t);
    let c = clamp(f, vec2<f32>(0.0), vec2<f32>(size) - 1.0);
    let i0 = vec2<u32>(floor(c));
    let i1 = min(i0 + 1u, size - 1u);
    let w = c - floor(c);
    let a = mix(textureLoad(t, i0, layer, 0), textureLoad(t, vec2<u32>(i1.x, i0.y), layer, 0), w.x);
    let b = mix(textureLoad(t, vec2<u32>(i0.x, i1.y), layer, 0), textureLoad(t, i1, layer, 0), w.x);
    return mix(a, b, w.y);
}

// A volume of `depth` slices per layer, stacked along z.
fn lut_bilinear_3d(t: texture_3d<f32>, x0: u32, x1: u32, y0: u32, y1: u32, z: u32, w: vec2<f32>) -> vec4<f32> {
    let a = mix(textureLoad(t, vec3<u32>(x0, y0, z), 0), textureLoad(t, vec3<u32>(x1, y0, z), 0), w.x);
    let b = mix(textureLoad(t, vec3<u32>(x0, y1, z), 0), textureLoad(t, vec3<u32>(x1, y1, z), 0), w.x);
    return mix(a, b, w.y);
}

fn lut_trilinear(t: texture_3d<f32>, layer: u32, depth: u32, f: vec3<f32>) -> vec4<f32> {
    let size = vec3<u32>(textureDimensions(t).xy, depth);
    let c = clamp(f, vec3<f32>(0.0), vec3<f32>(size) - 1.0);
    let i0 = vec3<u32>(floor(c));
    let i1 = min(i0 + 1u, size - 1u);
    let w = c - floor(c);
    let a = lut_bilinear_3d(t, i0.x, i1.x, i0.y, i1.y, layer * depth + i0.z, w.xy);
    let b = lut_bilinear_3d(t, i0.x, i1.x, i0.y, i1.y, layer * depth + i1.z, w.xy);
    return mix(a, b, w.z);
}
