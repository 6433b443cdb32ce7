// The sun-zenith axis that is dense in twilight, piecewise linear between the knots
// MU_S_AXIS_MU_S and MU_S_AXIS_U: Hillaire's Ψ_ms and ground-irradiance tables, and the
// intensity volumes. Twin of model::methods::hillaire::mu_s_axis_coordinate and mu_s_axis_mu_s.

fn mu_s_axis_map(knots: vec4<f32>, onto: vec4<f32>, x_in: f32) -> f32 {
    let x = clamp(x_in, knots.x, knots.w);
    let k = select(select(2u, 1u, x < knots.z), 0u, x < knots.y);
    return onto[k] + (x - knots[k]) / (knots[k + 1u] - knots[k]) * (onto[k + 1u] - onto[k]);
}

fn mu_s_axis_coordinate(mu_s: f32) -> f32 {
    return mu_s_axis_map(MU_S_AXIS_MU_S, MU_S_AXIS_U, mu_s);
}

fn mu_s_axis_mu_s(u: f32) -> f32 {
    return mu_s_axis_map(MU_S_AXIS_U, MU_S_AXIS_MU_S, u);
}

