//! The scene's medium as the analytic transmittance models see it: closed forms of the optical
//! depth along a ray that hold for a density falling exponentially with altitude — Schuler's
//! (2012) approximation of the Chapman grazing-incidence function ([`schuler_chapman`]),
//! Gałaj et al.'s (2021) Taylor-series integral ([`galaj_taylor`]) and Leenman's (2025)
//! homogeneous-shell chord ([`homogeneous_shell`]).
//!
//! Air and aerosol each become one exponential, ρ₀·exp(−h/H), fitted to the scene's profile by
//! its first two moments: H is the altitude of the column's centroid and ρ₀ = column / H, which
//! keeps the vertical optical depth and the mean height of the scatterers (exact for an
//! exponential, and robust where the profile starts near zero at the ground, as a stratospheric
//! veil does). Ozone, a layer peaking near 22 km that no exponential resembles, becomes a thin
//! shell at the altitude of its column's centroid, crossed with the slant factor 1/μ at the shell
//! (the Dobson ozone air mass); the slant factor is capped at that of a horizontal path through
//! a layer as thick as the profile's spread. The view march of `schuler` and `galaj-taylor`
//! still reads the scene's own profile (only their way to the sun is analytic); Leenman's
//! `flat` and `raymarched` take their depths along the view from this medium too.

use super::{Lanes, Params};
use crate::geometry::rho_squared;
use std::f64::consts::PI;

/// One constituent as an exponential of altitude.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exponential {
    /// Scale height, m (> 0).
    pub scale_height_m: f64,
    /// The profile value at the ground (units of the profile: relative density for air, m⁻¹ per
    /// unit of the aerosol coefficients for aerosol), ≥ 0.
    pub at_ground: f64,
}

/// The medium of [`Params`] as the analytic models see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExponentialMedium {
    pub air: Exponential,
    pub aerosol: Exponential,
    /// Ozone column, relative ozone density × m (≥ 0).
    pub ozone_column_m: f64,
    /// Altitude of the ozone shell, m.
    pub ozone_altitude_m: f64,
    /// Smallest zenith cosine the slant factor through the shell uses, (0, 1].
    pub ozone_min_mu: f64,
}

/// Column, centroid altitude and spread (standard deviation of altitude) of profile component
/// `k`, by the trapezoid rule over the profile's samples.
pub fn moments(p: &Params, k: usize) -> (f64, f64, f64) {
    let n = p.profile.len();
    let h = |i: usize| p.thickness_m() * (i as f64 / (n - 1) as f64).powi(2);
    let (mut m0, mut m1, mut m2) = (0.0, 0.0, 0.0);
    for i in 0..n - 1 {
        let (h0, h1) = (h(i), h(i + 1));
        let (a, b) = (p.profile[i][k], p.profile[i + 1][k]);
        let dh = h1 - h0;
        m0 += 0.5 * (a + b) * dh;
        m1 += 0.5 * (a * h0 + b * h1) * dh;
        m2 += 0.5 * (a * h0 * h0 + b * h1 * h1) * dh;
    }
    if m0 <= 0.0 {
        return (0.0, 0.0, 0.0);
    }
    let mean = m1 / m0;
    (m0, mean, (m2 / m0 - mean * mean).max(0.0).sqrt())
}

impl ExponentialMedium {
    /// The fit to the profile of `p` (see the module's documentation).
    pub fn fit(p: &Params) -> ExponentialMedium {
        let exponential = |k| {
            let (column, centroid, _) = moments(p, k);
            if column <= 0.0 || centroid <= 0.0 {
                Exponential {
                    scale_height_m: 1.0,
                    at_ground: 0.0,
                }
            } else {
                Exponential {
                    scale_height_m: centroid,
                    at_ground: column / centroid,
                }
            }
        };
        let (ozone_column_m, ozone_altitude_m, spread) = moments(p, 1);
        let shell_r = p.bottom_radius_m + ozone_altitude_m;
        // A horizontal path through a layer of thickness 2w at radius r is 2·√(2·r·w) long,
        // the vertical one 2w: the slant factor is at most √(2r/w).
        let ozone_min_mu = if spread > 0.0 {
            (spread / (2.0 * shell_r)).sqrt().min(1.0)
        } else {
            1.0
        };
        ExponentialMedium {
            air: exponential(0),
            aerosol: exponential(2),
            ozone_column_m,
            ozone_altitude_m,
            ozone_min_mu,
        }
    }

    /// The path through the ozone shell (relative ozone density × m) from altitude `h` along
    /// zenith cosine `mu` out to space.
    pub fn ozone_path(&self, big_r: f64, h: f64, mu: f64) -> f64 {
        let (r, shell) = (big_r + h, big_r + self.ozone_altitude_m);
        let sin2 = (1.0 - mu * mu).max(0.0);
        let crossings = if r < shell {
            1.0
        } else if mu < 0.0 && r * r * sin2 < shell * shell {
            2.0
        } else {
            return 0.0;
        };
        let mu_shell = (1.0 - (r / shell).powi(2) * sin2).max(0.0).sqrt();
        crossings * self.ozone_column_m / mu_shell.max(self.ozone_min_mu)
    }

    /// Optical depth per lane of batch `layer` from altitude `h` along zenith cosine `mu` out
    /// of the atmosphere, with `column(h, mu, H)` the integral of exp(−h/H) along that ray
    /// (m): air and aerosol through `column`, ozone through its shell.
    pub fn optical_depth(
        &self,
        p: &Params,
        layer: usize,
        h: f64,
        mu: f64,
        column: impl Fn(f64, f64, f64) -> f64,
    ) -> Lanes {
        let aerosol = if self.aerosol.at_ground > 0.0 {
            column(h, mu, self.aerosol.scale_height_m)
        } else {
            0.0
        };
        let air = column(h, mu, self.air.scale_height_m);
        self.optical_depth_from_columns(p, layer, h, mu, (air, aerosol))
    }

    /// Optical depth per lane of batch `layer` from altitude `h` along zenith cosine `mu` out
    /// of the atmosphere, given the integrals of exp(−h/H) along that ray for air and aerosol
    /// (m, per unit ground density): ozone through its shell.
    pub fn optical_depth_from_columns(
        &self,
        p: &Params,
        layer: usize,
        h: f64,
        mu: f64,
        (air_column, aerosol_column): (f64, f64),
    ) -> Lanes {
        let b = &p.batches[layer];
        let air = self.air.at_ground * air_column;
        let aerosol = self.aerosol.at_ground * aerosol_column;
        let ozone = self.ozone_path(p.bottom_radius_m, h, mu);
        Lanes::from_fn(|i| {
            b.rayleigh_scattering[i] * air
                + b.ozone_absorption[i] * ozone
                + (b.aerosol_scattering[i] + b.aerosol_absorption[i]) * aerosol
        })
    }

    /// The values the GPU reads from the second and third rows of `globals.model`: (H and ρ₀
    /// of air, H and ρ₀ of aerosol), (ozone column, shell altitude, smallest μ, 0).
    pub fn constants(&self) -> [f64; 8] {
        [
            self.air.scale_height_m,
            self.air.at_ground,
            self.aerosol.scale_height_m,
            self.aerosol.at_ground,
            self.ozone_column_m,
            self.ozone_altitude_m,
            self.ozone_min_mu,
            0.0,
        ]
    }
}

/// The altitude (m) of the lowest point of the line through altitude `h` along zenith cosine
/// `mu` (negative where the line passes below the ground), without cancellation.
fn tangent_altitude(h: f64, mu: f64, big_r: f64) -> f64 {
    let r = big_r + h;
    let sin = (1.0 - mu * mu).max(0.0).sqrt();
    (rho_squared(h, big_r) - r * r * mu * mu) / (r * sin + big_r)
}

/// Schuler's (2012) Chapman function for zenith cosine `mu` ≥ 0 at x = r/H:
/// c / ((c − 1)·μ + 1) with c = √(πx/2), exact at the zenith (1) and at the horizon (√(πx/2),
/// the Chapman function's large-x limit).
fn chapman_upper(x: f64, mu: f64) -> f64 {
    let c = (PI * x / 2.0).sqrt();
    c / ((c - 1.0) * mu + 1.0)
}

/// ∫ exp(−h'/H) along the ray from altitude `h` (m) with zenith cosine `mu` to infinity, m, by
/// Schuler's (2012) approximation of the Chapman function: H·exp(−h/H)·Ch(x, μ), x = (R + h)/H;
/// below the horizontal through the reflection about the lowest point, 2·Ch(x₀, 0)·exp(−h₀/H)
/// − Ch(x, −μ)·exp(−h/H), with h₀ and x₀ the lowest point's altitude and radius over H.
pub fn schuler_chapman(h: f64, mu: f64, scale_height_m: f64, big_r: f64) -> f64 {
    let big_h = scale_height_m;
    let x = (big_r + h) / big_h;
    if mu >= 0.0 {
        return big_h * (-h / big_h).exp() * chapman_upper(x, mu);
    }
    let h0 = tangent_altitude(h, mu, big_r).max(0.0);
    let x0 = (big_r + h0) / big_h;
    let through_lowest = 2.0 * (PI * x0 / 2.0).sqrt() * (-h0 / big_h).exp();
    big_h * (through_lowest - (-h / big_h).exp() * chapman_upper(x, -mu)).max(0.0)
}

/// ∫ exp(−h'/H) along the ray from altitude `h` (m) with zenith cosine `mu` to infinity, m, as
/// Leenman (2025) takes it after Jodie (2019): the density at `h` times the chord through a
/// homogeneous shell one scale height thick above the point — √(r²μ² + (r + H)² − r²) − rμ,
/// r = R + h (Rapp-Arrarás & Domingo-Santos's DR-1 form). Looking down, the chord through the
/// whole shell at the horizontal less the chord behind the point (Leenman's eq. 53): still the
/// density at `h`, and the planet in the way ignored.
pub fn homogeneous_shell(h: f64, mu: f64, scale_height_m: f64, big_r: f64) -> f64 {
    let (r, big_h) = (big_r + h, scale_height_m);
    // (r + H)² − r², formed without cancellation.
    let shell = big_h * (2.0 * r + big_h);
    // √(r²m² + s) − rm written as s / (√(r²m² + s) + rm), which keeps its digits in f32.
    let up = |m: f64| shell / ((r * r * m * m + shell).sqrt() + r * m);
    let chord = if mu >= 0.0 {
        up(mu)
    } else {
        2.0 * shell.sqrt() - up(-mu)
    };
    (-h / big_h).exp() * chord
}

/// Gałaj et al.'s (2021) parameters of the Taylor surrogate: the order between 1 and 2 (`a`)
/// and where along the ray it is expanded (`b`), from their grid search (both 0.45).
pub const GALAJ_TAYLOR_A: f64 = 0.45;
pub const GALAJ_TAYLOR_B: f64 = 0.45;

/// ∫ exp(−h'/H) along the ray from altitude `h` (m) with zenith cosine `mu` to the top of the
/// atmosphere (radius `top`), m, by Gałaj et al.'s (2021) Taylor-series integral with
/// parameters `a`, `b` ∈ [0, 1]. On the ray's line, at distance t from its point closest to
/// the planet's centre (impact parameter d), the altitude h(t) = √(d² + t²) − R is replaced by
/// its expansion h̃ about τ = b·t_top, of order 1 + a; the Jacobian dt/dh is taken as constant,
/// 1/h'(τ); so ∫ e^{−h/H} dt ≈ H/h'(τ)·[e^{−h̃}/H] between the ends. A ray that descends
/// before it rises is split at the lowest point (both halves from it). The planet is treated
/// as transparent below the lowest point of a ray that grazes it (only the sun's partly hidden
/// disk asks for one).
pub fn galaj_taylor(
    h: f64,
    mu: f64,
    scale_height_m: f64,
    big_r: f64,
    top: f64,
    (a, b): (f64, f64),
) -> f64 {
    let big_h = scale_height_m;
    let r = big_r + h;
    let t_p = r * mu;
    // d² − R² = (r² − R²) − t_p², kept from cancellation; a descending ray is taken to
    // pass above the ground (d ≥ R).
    let mut d2_minus_r2 = rho_squared(h, big_r) - t_p * t_p;
    if mu < 0.0 {
        d2_minus_r2 = d2_minus_r2.max(0.0);
    }
    let d2 = d2_minus_r2 + big_r * big_r;
    // top² − d² = (top² − R²) − (d² − R²).
    let t_top = ((top - big_r) * (top + big_r) - d2_minus_r2)
        .max(0.0)
        .sqrt();
    // The line's first point in the atmosphere: on the ground when it meets it (d < R).
    let t_min = (-d2_minus_r2).max(0.0).sqrt();
    let tau = t_min + b * (t_top - t_min);
    let s = (d2 + tau * tau).sqrt();
    let slope = tau / s;
    if slope <= 1e-12 {
        return 0.0;
    }
    let curvature = d2 / (s * s * s);
    let h_tau = (d2_minus_r2 + tau * tau) / (s + big_r);
    let h_tilde = |t: f64| {
        let dt = t - tau;
        0.5 * a * curvature * dt * dt + slope * dt + h_tau
    };
    let e = |t: f64| (-h_tilde(t) / big_h).exp();
    let bracket = if mu >= 0.0 {
        e(t_p) - e(t_top)
    } else {
        2.0 * e(0.0) - e(-t_p) - e(t_top)
    };
    (big_h / slope * bracket).max(0.0)
}

/// ∫ exp(−h'/H) along the ray from altitude `h` (m) with zenith cosine `mu` to the top of the
/// atmosphere (radius `top`), m, by adaptive quadrature (relative tolerance 1e-11): the exact
/// value the closed forms are measured against.
pub fn column_by_quadrature(h: f64, mu: f64, scale_height_m: f64, big_r: f64, top: f64) -> f64 {
    let d = crate::geometry::distance_to_top(h, mu, big_r, top);
    crate::quadrature::integrate_adaptive(
        |t| (-crate::geometry::altitude_along(h, mu, t, big_r).0 / scale_height_m).exp(),
        0.0,
        d,
        1e-11,
        1e-14,
    )
    .value
}

/// Mean relative error of [`galaj_taylor`] with parameters `ab` against `exact` (the integral
/// of exp(−h/H) along each ray, m) over `rays` (altitude m, zenith cosine, scale height m),
/// inside a planet of radius `big_r` whose atmosphere's top is at radius `top`.
pub fn galaj_taylor_mean_error(
    rays: &[(f64, f64, f64)],
    exact: &[f64],
    big_r: f64,
    top: f64,
    ab: (f64, f64),
) -> f64 {
    let sum: f64 = rays
        .iter()
        .zip(exact)
        .map(|(&(h, mu, hh), &e)| (galaj_taylor(h, mu, hh, big_r, top, ab) / e - 1.0).abs())
        .sum();
    sum / rays.len().max(1) as f64
}

/// Gałaj et al.'s (2021) grid search for the Taylor parameters: a and b over 0–1 in steps of
/// 0.01, each pair scored by [`galaj_taylor_mean_error`]. Returns the best (a, b) and its error.
pub fn galaj_grid_search(
    rays: &[(f64, f64, f64)],
    exact: &[f64],
    big_r: f64,
    top: f64,
) -> ((f64, f64), f64) {
    let mut best = ((GALAJ_TAYLOR_A, GALAJ_TAYLOR_B), f64::INFINITY);
    for i in 0..=100 {
        for j in 0..=100 {
            let ab = (f64::from(i) / 100.0, f64::from(j) / 100.0);
            let e = galaj_taylor_mean_error(rays, exact, big_r, top, ab);
            if e < best.1 {
                best = (ab, e);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;

    const R: f64 = 6_360_000.0;
    const TOP: f64 = 6_460_000.0;

    /// ∫ exp(−h/H) along the ray to the top, by adaptive quadrature.
    fn exact(h: f64, mu: f64, big_h: f64) -> f64 {
        column_by_quadrature(h, mu, big_h, R, TOP)
    }

    /// Both closed forms against quadrature for air and aerosol scale heights, from the ground
    /// to 50 km, zenith to below the horizontal. Schuler's rational form is exact at the zenith
    /// and the horizon and errs most between (−14 % near 88°). Gałaj's Taylor integral is within
    /// 2 % near the zenith, but its Jacobian, taken at a point 45 % of the way to the top, is far
    /// from the one near a grazing ray's start: for air it stays within 50 %, for aerosol's
    /// short scale height it overshoots without bound towards the horizon (4× at 80°, 200× at
    /// 88° from the ground), which bounds the model's domain to a high sun.
    #[test]
    fn the_closed_forms_follow_quadrature_within_their_stated_errors() {
        for big_h in [8_000.0, 1_200.0] {
            for h in [0.0, 1_000.0, 10_000.0, 50_000.0] {
                for zenith_deg in [0.0f64, 30.0, 60.0, 80.0, 88.0, 90.0, 93.0] {
                    let mu = f64::cos(zenith_deg.to_radians());
                    if crate::geometry::hits_ground(h, mu, R) {
                        continue;
                    }
                    let want = exact(h, mu, big_h);
                    if want < 1e-6 * big_h {
                        continue;
                    }
                    let schuler = schuler_chapman(h, mu, big_h, R) / want;
                    let bound = if zenith_deg <= 60.0 { 0.03 } else { 0.15 };
                    assert!(
                        (schuler - 1.0).abs() < bound,
                        "Schuler H {big_h} h {h} zenith {zenith_deg}: ratio {schuler}"
                    );
                    let taylor =
                        galaj_taylor(h, mu, big_h, R, TOP, (GALAJ_TAYLOR_A, GALAJ_TAYLOR_B)) / want;
                    let bound = match (big_h > 5_000.0, zenith_deg) {
                        (_, z) if z <= 30.0 => 0.025,
                        (true, _) => 0.5,
                        (false, z) if z <= 60.0 => 0.25,
                        (false, _) => f64::INFINITY,
                    };
                    assert!(
                        (taylor - 1.0).abs() < bound,
                        "Taylor H {big_h} h {h} zenith {zenith_deg}: ratio {taylor}"
                    );
                }
            }
        }
        // Leenman's homogeneous shell: exact at the zenith (H·e^{−h/H}), within 0.5 % to 60°
        // from it and 2 % at 80°, 13 % long at the horizon (√(2rH) against the Chapman
        // function's √(πrH/2)).
        for big_h in [8_000.0, 1_200.0] {
            for h in [0.0, 1_000.0, 10_000.0] {
                for (zenith_deg, bound) in [
                    (0.0f64, 1e-4),
                    (30.0, 0.005),
                    (60.0, 0.005),
                    (80.0, 0.02),
                    (90.0, 0.14),
                ] {
                    let mu = f64::cos(zenith_deg.to_radians());
                    let ratio = homogeneous_shell(h, mu, big_h, R) / exact(h, mu, big_h);
                    assert!(
                        (ratio - 1.0).abs() < bound,
                        "shell H {big_h} h {h} zenith {zenith_deg}: ratio {ratio}"
                    );
                }
            }
        }
        // Looking down it continues the upward chord through the horizontal.
        let (a, b) = (
            homogeneous_shell(1_000.0, 1e-9, 8_000.0, R),
            homogeneous_shell(1_000.0, -1e-9, 8_000.0, R),
        );
        assert!((a / b - 1.0).abs() < 1e-6);
        assert!(homogeneous_shell(1_000.0, -0.2, 8_000.0, R) > a);
        // The overshoot along a grazing ray is the method's, not a slip of this code.
        let grazing = galaj_taylor(0.0, 0.0, 1_200.0, R, TOP, (GALAJ_TAYLOR_A, GALAJ_TAYLOR_B));
        assert!(grazing / exact(0.0, 0.0, 1_200.0) > 100.0);
    }

    #[test]
    fn the_fit_keeps_the_column_and_puts_ozone_where_it_peaks() {
        let p = params();
        let e = ExponentialMedium::fit(&p);
        let (air, _, _) = moments(&p, 0);
        assert!((e.air.at_ground * e.air.scale_height_m / air - 1.0).abs() < 1e-12);
        assert!(
            (6_000.0..10_000.0).contains(&e.air.scale_height_m),
            "{:?}",
            e.air
        );
        assert!(
            (15_000.0..30_000.0).contains(&e.ozone_altitude_m),
            "{}",
            e.ozone_altitude_m
        );
        assert!(e.ozone_min_mu > 0.0 && e.ozone_min_mu < 0.2);
        // Straight up from the ground the shell is crossed once, vertically: the column.
        assert!((e.ozone_path(R, 0.0, 1.0) / e.ozone_column_m - 1.0).abs() < 1e-12);
        // Above the shell looking up nothing; looking down past it, twice.
        let above = e.ozone_altitude_m + 5_000.0;
        assert_eq!(e.ozone_path(R, above, 0.5), 0.0);
        assert!(e.ozone_path(R, above, -0.05) > 2.0 * e.ozone_column_m);
        // Near the horizon the slant factor is capped, not infinite.
        let grazing = e.ozone_path(R, e.ozone_altitude_m, 0.0);
        assert!(grazing.is_finite() && grazing <= e.ozone_column_m / e.ozone_min_mu + 1e-9);
    }

    /// The fitted medium's optical depth towards the zenith matches the scene's own vertical
    /// optical depth (what the fit keeps), through either closed form.
    #[test]
    fn the_vertical_optical_depth_of_the_fit_is_the_scenes() {
        let p = params();
        let e = ExponentialMedium::fit(&p);
        let scene = crate::methods::shared::single_scattering_sky::optical_depth(
            &p,
            0,
            0.0,
            1.0,
            4096,
            crate::methods::shared::single_scattering_sky::Rule::Midpoint,
        );
        let big_r = p.bottom_radius_m;
        let top = p.top_radius_m;
        let schuler = e.optical_depth(&p, 0, 0.0, 1.0, |h, mu, hh| {
            schuler_chapman(h, mu, hh, big_r)
        });
        let taylor = e.optical_depth(&p, 0, 0.0, 1.0, |h, mu, hh| {
            galaj_taylor(h, mu, hh, big_r, top, (GALAJ_TAYLOR_A, GALAJ_TAYLOR_B))
        });
        for i in 0..4 {
            assert!(
                (schuler[i] / scene[i] - 1.0).abs() < 0.02,
                "{schuler:?} {scene:?}"
            );
            assert!(
                (taylor[i] / scene[i] - 1.0).abs() < 0.02,
                "{taylor:?} {scene:?}"
            );
        }
    }

    /// On rays from the zenith to 60° the search finds a pair at least as good as the
    /// paper's, and both are within a few per cent; where the expansion point matters (b = 0
    /// puts it at the start of a ray from the ground, b = 1 at the top) the error differs.
    #[test]
    fn the_grid_search_scores_pairs_by_their_error() {
        let rays: Vec<(f64, f64, f64)> = [0.0, 2_000.0, 10_000.0]
            .iter()
            .flat_map(|&h| {
                [0.0f64, 20.0, 40.0, 60.0]
                    .map(|z| (h, z.to_radians().cos(), 8_000.0))
                    .to_vec()
            })
            .collect();
        let exact: Vec<f64> = rays.iter().map(|&(h, mu, hh)| exact(h, mu, hh)).collect();
        let ((a, b), best) = galaj_grid_search(&rays, &exact, R, TOP);
        let paper =
            galaj_taylor_mean_error(&rays, &exact, R, TOP, (GALAJ_TAYLOR_A, GALAJ_TAYLOR_B));
        assert!(
            best <= paper && paper < 0.02,
            "best {best} at ({a}, {b}), paper {paper}"
        );
        assert!((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b));
        let top_only = galaj_taylor_mean_error(&rays, &exact, R, TOP, (0.0, 1.0));
        assert!(
            top_only > 10.0 * best,
            "a = 0, b = 1: {top_only} against {best}"
        );
    }
}
