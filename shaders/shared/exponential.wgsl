// The scene's medium as the analytic transmittance models see it: air and aerosol as fitted
// exponentials, ozone as a thin shell, and the closed forms of the optical depth along a ray
// to space — Schuler's (2012) Chapman function, Gałaj et al.'s (2021) Taylor integral and
// Leenman's (2025) homogeneous-shell chord.
// globals.model[1] = (H and ρ₀ of air, H and ρ₀ of aerosol), globals.model[2] = (ozone column,
// shell altitude, smallest μ through the shell, 0), from ExponentialMedium::constants.
// Twin of model::methods::shared::exponential.

// Path through the ozone shell from altitude h along zenith cosine mu out to space.
fn ozone_path(h: f32, mu: f32) -> f32 {
    let o = globals.model[2];
    let r = bottom_radius() + h;
    let shell = bottom_radius() + o.y;
    let sin2 = max(1.0 - mu * mu, 0.0);
    var crossings = 0.0;
    if r < shell {
        crossings = 1.0;
    } else if mu < 0.0 && r * r * sin2 < shell * shell {
        crossings = 2.0;
    } else {
        return 0.0;
    }
    let q = r / shell;
    let mu_shell = sqrt(max(1.0 - q * q * sin2, 0.0));
    return crossings * o.x / max(mu_shell, o.z);
}

// Altitude of the lowest point of the line through altitude h along zenith cosine mu.
fn tangent_altitude(h: f32, mu: f32) -> f32 {
    let r = bottom_radius() + h;
    let s = sqrt(max(1.0 - mu * mu, 0.0));
    return (rho_squared(h) - r * r * mu * mu) / (r * s + bottom_radius());
}

fn chapman_upper(x: f32, mu: f32) -> f32 {
    let c = sqrt(PI * x / 2.0);
    return c / ((c - 1.0) * mu + 1.0);
}

// ∫ exp(−h'/H) along the ray to infinity by Schuler's Chapman function (twin of
// exponential::schuler_chapman).
fn schuler_chapman(h: f32, mu: f32, big_h: f32) -> f32 {
    let x = (bottom_radius() + h) / big_h;
    if mu >= 0.0 {
        return big_h * exp(-h / big_h) * chapman_upper(x, mu);
    }
    let h0 = max(tangent_altitude(h, mu), 0.0);
    let x0 = (bottom_radius() + h0) / big_h;
    let through_lowest = 2.0 * sqrt(PI * x0 / 2.0) * exp(-h0 / big_h);
    return big_h * max(through_lowest - exp(-h / big_h) * chapman_upper(x, -mu), 0.0);
}

// ∫ exp(−h'/H) along the ray to the top by Gałaj's Taylor integral (twin of
// exponential::galaj_taylor).
fn galaj_taylor(h: f32, mu: f32, big_h: f32) -> f32 {
    let big_r = bottom_radius();
    let r = big_r + h;
    let t_p = r * mu;
    var d2_minus_r2 = rho_squared(h) - t_p * t_p;
    if mu < 0.0 {
        d2_minus_r2 = max(d2_minus_r2, 0.0);
    }
    let d2 = d2_minus_r2 + big_r * big_r;
    let t_top = sqrt(max(thickness() * (top_radius() + big_r) - d2_minus_r2, 0.0));
    let t_min = sqrt(max(-d2_minus_r2, 0.0));
    let tau = t_min + GALAJ_TAYLOR_B * (t_top - t_min);
    let s = sqrt(d2 + tau * tau);
    let slope = tau / s;
    if slope <= 1e-12 {
        return 0.0;
    }
    let curvature = d2 / (s * s * s);
    let h_tau = (d2_minus_r2 + tau * tau) / (s + big_r);
    let k = 0.5 * GALAJ_TAYLOR_A * curvature;
    let a_p = t_p - tau;
    let a_top = t_top - tau;
    let e_top = exp(-(k * a_top * a_top + slope * a_top + h_tau) / big_h);
    var bracket = 0.0;
    if mu >= 0.0 {
        bracket = exp(-(k * a_p * a_p + slope * a_p + h_tau) / big_h) - e_top;
    } else {
        let a_0 = -tau;
        let a_back = -t_p - tau;
        bracket = 2.0 * exp(-(k * a_0 * a_0 + slope * a_0 + h_tau) / big_h)
            - exp(-(k * a_back * a_back + slope * a_back + h_tau) / big_h) - e_top;
    }
    return max(big_h / slope * bracket, 0.0);
}

// Leenman's (2025) column: the density at h times the chord through a homogeneous shell one
// scale height thick (DR-1), continued through the horizontal looking down; twin of
// exponential::homogeneous_shell.
fn homogeneous_shell(h: f32, mu: f32, big_h: f32) -> f32 {
    let r = bottom_radius() + h;
    let shell = big_h * (2.0 * r + big_h);
    let m = abs(mu);
    let up = shell / (sqrt(r * r * m * m + shell) + r * m);
    var chord = up;
    if mu < 0.0 {
        chord = 2.0 * sqrt(shell) - up;
    }
    return exp(-h / big_h) * chord;
}

// Optical depth per lane from altitude h along zenith cosine mu out of the atmosphere, given
// the integrals of exp(−h/H) along that ray for air and aerosol (twin of
// ExponentialMedium::optical_depth_from_columns).
fn exponential_optical_depth(layer: u32, h: f32, mu: f32, columns: vec2<f32>) -> vec4<f32> {
    let fit = globals.model[1];
    let b = batches[layer];
    return b.rayleigh_scattering * (fit.y * columns.x) + b.ozone_absorption * ozone_path(h, mu)
        + (b.aerosol_scattering + b.aerosol_absorption) * (fit.w * columns.y);
}
