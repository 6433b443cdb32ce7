//! The sun-zenith axis dense in twilight that Hillaire's (2020) Ψ_ms and ground-irradiance
//! tables and the intensity volumes share: piecewise linear in μ_s. Twin of
//! `shaders/shared/mu_s_axis.wgsl`.

/// Knots of the piecewise-linear μ_s axis of Hillaire's Ψ_ms and ground-irradiance tables and of
/// the intensity volumes (`super::intensity_volume`): texel
/// coordinate u ∈ [0, 1] against μ_s. Both quantities fall roughly exponentially once the sun is
/// below the horizon, which linear interpolation between texels 3.7° apart overestimates several
/// times over (the paper's uniform axis); 40 of the 63 intervals of a 64-texel axis therefore lie
/// between μ_s = −0.3 and 0.1 (0.57° apart), 4 below (where Ψ_ms is nearly nil) and 19 above
/// (2.7° apart, where it is smooth). The knots fall on texel centres of a 64-texel axis.
pub const MU_S_AXIS_U: [f64; 4] = [0.0, 4.0 / 63.0, 44.0 / 63.0, 1.0];
/// μ_s at the knots of [`MU_S_AXIS_U`].
pub const MU_S_AXIS_MU_S: [f64; 4] = [-1.0, -0.3, 0.1, 1.0];

/// Piece `k` of the μ_s axis whose knots `from` bracket `x`.
fn mu_s_axis_piece(from: &[f64; 4], x: f64) -> usize {
    if x < from[1] {
        0
    } else if x < from[2] {
        1
    } else {
        2
    }
}

/// Maps between the knots `from` and `to` of the μ_s axis, linearly on each piece.
fn mu_s_axis_map(from: &[f64; 4], to: &[f64; 4], x: f64) -> f64 {
    let x = x.clamp(from[0], from[3]);
    let k = mu_s_axis_piece(from, x);
    to[k] + (x - from[k]) / (from[k + 1] - from[k]) * (to[k + 1] - to[k])
}

/// Texel coordinate u ∈ [0, 1] of mu_s ∈ [−1, 1] on the μ_s axis (clamped).
pub fn mu_s_axis_coordinate(mu_s: f64) -> f64 {
    mu_s_axis_map(&MU_S_AXIS_MU_S, &MU_S_AXIS_U, mu_s)
}

/// mu_s at texel coordinate u ∈ [0, 1] of the μ_s axis (clamped).
pub fn mu_s_axis_mu_s(u: f64) -> f64 {
    mu_s_axis_map(&MU_S_AXIS_U, &MU_S_AXIS_MU_S, u)
}
