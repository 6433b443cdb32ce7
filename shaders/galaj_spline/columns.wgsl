// Gałaj et al.'s (2021) spline columns: ∫ exp(−h'/H) along a ray for air and aerosol, by the
// Hermite spline over the mesh of galaj_spline/mesh.wgsl (Catmull–Rom tangents; across the
// lines at the ray's d, then integrated exactly along it), floored at zero. Defines the
// columns_to_top of the way to the sun (shared/sun_route.wgsl) for the galaj-spline rows, as
// shared/closed_form_columns.wgsl does for the closed forms. Twin of
// model::methods::galaj_spline::columns.

fn spline_mesh(i: u32, j: u32) -> vec4<f32> {
    return galaj_spline_mesh_lut[j * GALAJ_SPLINE_MESH_SIZE.x + i];
}

// The mesh at node i along the ray, interpolated across at fractional column y.
fn spline_node(i: u32, y: f32) -> vec4<f32> {
    let k = GALAJ_SPLINE_MESH_SIZE.y;
    let j = min(u32(max(floor(y), 0.0)), k - 2u);
    let s = clamp(y - f32(j), 0.0, 1.0);
    let a = max(j, 1u) - 1u;
    let b = min(j + 2u, k - 1u);
    let p0 = spline_mesh(i, j);
    let p1 = spline_mesh(i, j + 1u);
    let m0 = (p1 - spline_mesh(i, a)) / f32(j + 1u - a);
    let m1 = (spline_mesh(i, b) - p0) / f32(b - j);
    let s2 = s * s;
    let s3 = s2 * s;
    return (2.0 * s3 - 3.0 * s2 + 1.0) * p0 + (s3 - 2.0 * s2 + s) * m0
        + (-2.0 * s3 + 3.0 * s2) * p1 + (s3 - s2) * m1;
}

// ∫ over [0, s] of the Hermite segment (p0, m0, p1, m1) at unit spacing.
fn spline_segment(p0: vec4<f32>, m0: vec4<f32>, p1: vec4<f32>, m1: vec4<f32>, s: f32) -> vec4<f32> {
    let s2 = s * s;
    let s3 = s2 * s;
    let s4 = s3 * s;
    return p0 * (s - s3 + 0.5 * s4) + m0 * (0.5 * s2 - 2.0 / 3.0 * s3 + 0.25 * s4)
        + p1 * (s3 - 0.5 * s4) + m1 * (-s3 / 3.0 + 0.25 * s4);
}

// ∫ from a to b (mesh nodes along the ray, 0 ≤ a ≤ b ≤ N − 1) of the spline at column y, the
// node values read once each through a sliding window.
fn spline_integral(a: f32, b: f32, y: f32) -> vec4<f32> {
    let n = GALAJ_SPLINE_MESH_SIZE.x;
    var total = vec4<f32>(0.0);
    if b <= a {
        return total;
    }
    let first = min(u32(max(floor(a), 0.0)), n - 2u);
    let last = min(u32(max(ceil(b), 1.0)) - 1u, n - 2u);
    var before = spline_node(max(first, 1u) - 1u, y);
    var v0 = spline_node(first, y);
    var v1 = spline_node(first + 1u, y);
    for (var k = first; k <= last; k++) {
        let after = min(k + 2u, n - 1u);
        let v2 = spline_node(after, y);
        let m0 = (v1 - before) / f32(k + 1u - (max(k, 1u) - 1u));
        let m1 = (v2 - v0) / f32(after - k);
        let s0 = clamp(a - f32(k), 0.0, 1.0);
        let s1 = clamp(b - f32(k), 0.0, 1.0);
        total += spline_segment(v0, m0, v1, m1, s1) - spline_segment(v0, m0, v1, m1, s0);
        before = v0;
        v0 = v1;
        v1 = v2;
    }
    return total;
}

fn columns_to_top(way: u32, h: f32, mu: f32) -> vec2<f32> {
    let big_r = bottom_radius();
    let n = GALAJ_SPLINE_MESH_SIZE.x;
    let k = GALAJ_SPLINE_MESH_SIZE.y;
    let t_p = (big_r + h) * mu;
    var d2_minus_r2 = rho_squared(h) - t_p * t_p;
    if mu < 0.0 {
        d2_minus_r2 = max(d2_minus_r2, 0.0);
    }
    if d2_minus_r2 >= 0.0 {
        // Region I: from t_p (behind the nearest point when descending) to the top.
        let top2_minus_r2 = thickness() * (top_radius() + big_r);
        let step = sqrt(top2_minus_r2) / f32(n - 1u);
        let above = d2_minus_r2 / (sqrt(d2_minus_r2 + big_r * big_r) + big_r);
        let y = above / thickness() * f32(k - 1u);
        let t_top = sqrt(max(top2_minus_r2 - d2_minus_r2, 0.0));
        let x_p = abs(t_p) / step;
        var c = spline_integral(x_p, t_top / step, y);
        if mu < 0.0 {
            c += 2.0 * spline_integral(0.0, x_p, y);
        }
        return step * max(c.xz, vec2<f32>(0.0));
    }
    // Region II (rising, d < R): in altitude, from h to the top.
    let step = thickness() / f32(n - 1u);
    let d = sqrt(max(d2_minus_r2 + big_r * big_r, 0.0));
    let y = min(d / big_r * f32(k), f32(k - 1u));
    return step * max(spline_integral(h / step, f32(n - 1u), y).yw, vec2<f32>(0.0));
}
