// Pass: Gałaj et al.'s (2021) spline mesh of the integrand exp(−h/H) for air and aerosol (their
// fitted scale heights, globals.model[1]). Texel (i along the ray, j across): lanes (air in
// region I, air in region II, aerosol in region I, aerosol in region II); region I: lines above
// the ground, at distance t = i·√(R_top² − R²)/(N − 1) from the nearest point of a line
// d = R + j·(R_top − R)/(K − 1) from the centre; region II: lines meeting the ground, at
// altitude h = i·(R_top − R)/(N − 1) on a line d = j·R/K from the centre, times dt/dh.
// Every layer holds the same mesh. Twin of model::methods::galaj_spline::compute_mesh_lut.

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    let size = GALAJ_SPLINE_MESH_SIZE;
    if any(id.xy >= size) || id.z >= batch_count() {
        return;
    }
    let big_r = bottom_radius();
    let fit = globals.model[1];
    // Region I: √(d² + t²) − R without cancellation.
    let t = f32(id.x) * sqrt(thickness() * (top_radius() + big_r)) / f32(size.x - 1u);
    let above = f32(id.y) * thickness() / f32(size.y - 1u);
    let d2_minus_r2 = above * (2.0 * big_r + above);
    let h1 = (d2_minus_r2 + t * t) / (sqrt(d2_minus_r2 + big_r * big_r + t * t) + big_r);
    // Region II: dt/dh = r/√(r² − d²).
    let h2 = f32(id.x) * thickness() / f32(size.x - 1u);
    let r = big_r + h2;
    let d = f32(id.y) * big_r / f32(size.y);
    let jacobian = r / sqrt((r - d) * (r + d));
    galaj_spline_mesh_lut[(id.z * size.y + id.y) * size.x + id.x] = vec4<f32>(
        exp(-h1 / fit.x),
        exp(-h2 / fit.x) * jacobian,
        exp(-h1 / fit.z),
        exp(-h2 / fit.z) * jacobian,
    );
}
